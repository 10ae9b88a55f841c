#include "io/arguments.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "model/errors.h"

namespace beamid::io {

Arguments::Arguments(std::string command, const std::vector<std::string>& args, std::vector<FlagSpec> spec)
    : command_(std::move(command)), spec_(std::move(spec)) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg.rfind("--", 0) != 0) fail("unexpected argument '" + arg + "' (flags start with --)");
    const std::string name = arg.substr(2);
    const FlagSpec* flag = nullptr;
    for (const auto& s : spec_)
      if (s.name == name) flag = &s;
    if (flag == nullptr) {
      std::string valid;
      for (const auto& s : spec_) valid += (valid.empty() ? "--" : ", --") + s.name;
      fail("unknown flag " + arg + " (valid flags: " + valid + ")");
    }
    if (values_.count(name)) fail(arg + " given twice");
    if (!flag->takes_value) {
      values_[name] = "";
      continue;
    }
    if (i + 1 >= args.size()) fail(arg + " needs a value");
    values_[name] = args[++i];
  }
}

void Arguments::fail(const std::string& message) const { throw InputError("beamid " + command_ + ": " + message); }

bool Arguments::has(const std::string& flag) const { return values_.count(flag) > 0; }

std::string Arguments::text(const std::string& flag) const {
  auto it = values_.find(flag);
  if (it == values_.end()) fail("missing required flag --" + flag);
  return it->second;
}

std::string Arguments::text_or(const std::string& flag, const std::string& fallback) const {
  return has(flag) ? text(flag) : fallback;
}

double Arguments::number(const std::string& flag) const {
  const std::string value = text(flag);
  double result = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, result);
  if (value.empty() || ec != std::errc() || ptr != end || !std::isfinite(result))
    fail("--" + flag + " = '" + value + "': must be a finite number");
  return result;
}

std::optional<double> Arguments::optional_number(const std::string& flag) const {
  if (!has(flag)) return std::nullopt;
  return number(flag);
}

int Arguments::integer(const std::string& flag) const {
  const std::string value = text(flag);
  long long result = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, result);
  if (value.empty() || ec != std::errc() || ptr != end || result < std::numeric_limits<int>::min() ||
      result > std::numeric_limits<int>::max())
    fail("--" + flag + " = '" + value + "': must be an integer");
  return static_cast<int>(result);
}

std::optional<int> Arguments::optional_integer(const std::string& flag) const {
  if (!has(flag)) return std::nullopt;
  return integer(flag);
}

void Arguments::require(bool ok, const std::string& flag, const std::string& constraint) const {
  if (!ok) fail("--" + flag + " = '" + text_or(flag, "") + "': " + constraint);
}

std::string Arguments::usage() const {
  std::string out;
  for (const auto& s : spec_) {
    std::string left = "  --" + s.name + (s.takes_value ? " VALUE" : "");
    if (left.size() < 28) left.resize(28, ' ');
    out += left + " " + s.help + "\n";
  }
  return out;
}

}  // namespace beamid::io
