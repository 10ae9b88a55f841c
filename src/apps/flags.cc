#include "apps/flags.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>

#include "core/errors.h"

namespace beamid::apps {
namespace {

std::optional<double> parse_number(const std::string& value) {
  double result = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, result);
  if (value.empty() || ec != std::errc() || ptr != end || !std::isfinite(result)) return std::nullopt;
  return result;
}

std::optional<long long> parse_integer(const std::string& value) {
  long long result = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, result);
  if (value.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return result;
}

std::string range_text(long long min, long long max) {
  // The int limit stated as such: "an integer >= 0" was given for --seed 2147483648, which is one.
  if (max == std::numeric_limits<int>::max())
    return "must be an integer in " + std::to_string(min) + "..2147483647 (2^31 - 1)";
  return "must be an integer in " + std::to_string(min) + ".." + std::to_string(max);
}

// CLI11 reports "--flag: <what the validator returns>"; the validators return "'value': constraint", which the
// command line's error formatter (cli.cc) turns into "--flag = 'value': constraint".
CLI::Validator number_validator() {
  return CLI::Validator(
      [](std::string& v) { return parse_number(v) ? std::string() : "'" + v + "': must be a finite number"; }, "");
}
CLI::Validator integer_validator(long long min, long long max) {
  return CLI::Validator(
      [min, max](std::string& v) {
        const auto i = parse_integer(v);
        return i && *i >= min && *i <= max ? std::string() : "'" + v + "': " + range_text(min, max);
      },
      "");
}

}  // namespace

FlagSpec text_flag(std::string name, std::string help, bool required) {
  return {std::move(name), FlagKind::Text, std::move(help), required};
}
FlagSpec number_flag(std::string name, std::string help, bool required) {
  return {std::move(name), FlagKind::Number, std::move(help), required};
}
FlagSpec integer_flag(std::string name, std::string help, long long min, long long max, bool required) {
  return {std::move(name), FlagKind::Integer, std::move(help), required, min, max};
}
FlagSpec switch_flag(std::string name, std::string help) {
  return {std::move(name), FlagKind::Switch, std::move(help)};
}
FlagSpec positional(std::string name, std::string help) {
  return {std::move(name), FlagKind::Positional, std::move(help), true};
}

void add_flags(CLI::App& command, const std::vector<FlagSpec>& flags) {
  for (const FlagSpec& f : flags) {
    if (f.kind == FlagKind::Switch) {
      command.add_flag("--" + f.name)->description(f.help);
      continue;
    }
    CLI::Option* o = command.add_option(f.kind == FlagKind::Positional ? f.name : "--" + f.name, f.help);
    o->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::Throw);
    if (f.required) o->required();
    if (f.kind == FlagKind::Number) o->check(number_validator())->type_name("NUMBER");
    if (f.kind == FlagKind::Integer) {
      o->check(integer_validator(f.min, f.max));
      o->type_name(f.max == std::numeric_limits<int>::max()
                       ? "INTEGER>=" + std::to_string(f.min)
                       : "INTEGER:" + std::to_string(f.min) + ".." + std::to_string(f.max));
    }
    if (f.kind == FlagKind::Text || f.kind == FlagKind::Positional) o->type_name("TEXT");
  }
}

Flags::Flags(std::string command, const CLI::App& parsed, const std::vector<FlagSpec>& flags,
             std::vector<std::string> arguments)
    : command_(std::move(command)), arguments_(std::move(arguments)) {
  for (const FlagSpec& f : flags) {
    const CLI::Option* o = parsed.get_option(f.kind == FlagKind::Positional ? f.name : "--" + f.name);
    if (o->count() == 0) continue;
    values_[f.name] = f.kind == FlagKind::Switch ? std::string() : o->results().back();
    // An empty value names nothing (--output '' ended in "beamid: : cannot create folder (Invalid argument)").
    if ((f.kind == FlagKind::Text || f.kind == FlagKind::Positional) && values_[f.name].empty())
      fail((f.kind == FlagKind::Positional ? f.name : "--" + f.name) + " = '': must not be empty");
  }
}

void Flags::fail(const std::string& message) const { throw InputError("beamid " + command_ + ": " + message); }

std::string Flags::text(const std::string& flag) const {
  auto it = values_.find(flag);
  if (it == values_.end()) fail("--" + flag + " is required");
  return it->second;
}

std::string Flags::text_or(const std::string& flag, const std::string& fallback) const {
  return has(flag) ? text(flag) : fallback;
}

double Flags::number(const std::string& flag) const {
  const std::string value = text(flag);
  const auto v = parse_number(value);
  if (!v) fail("--" + flag + " = '" + value + "': must be a finite number");
  return *v;
}

std::optional<double> Flags::optional_number(const std::string& flag) const {
  if (!has(flag)) return std::nullopt;
  return number(flag);
}

int Flags::integer(const std::string& flag) const {
  const std::string value = text(flag);
  const auto v = parse_integer(value);
  if (!v || *v < std::numeric_limits<int>::min() || *v > std::numeric_limits<int>::max())
    fail("--" + flag + " = '" + value + "': must be an integer");
  return static_cast<int>(*v);
}

std::optional<int> Flags::optional_integer(const std::string& flag) const {
  if (!has(flag)) return std::nullopt;
  return integer(flag);
}

std::vector<std::string> Flags::texts(const std::string& flag) const {
  std::vector<std::string> items;
  if (!has(flag)) return items;
  const std::string value = text(flag);
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = value.find(',', begin);
    items.push_back(value.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    if (items.back().empty())
      fail("--" + flag + " = '" + value + "': must be a comma-separated list without empty items");
    if (comma == std::string::npos) return items;
    begin = comma + 1;
  }
}

std::vector<double> Flags::numbers(const std::string& flag) const {
  std::vector<double> values;
  for (const std::string& item : texts(flag)) {
    const auto v = parse_number(item);
    if (!v)
      fail("--" + flag + " = '" + text(flag) + "': must be a comma-separated list of finite numbers ('" + item +
           "' is not)");
    values.push_back(*v);
  }
  return values;
}

void Flags::require(bool ok, const std::string& flag, const std::string& constraint) const {
  if (!ok) fail("--" + flag + " = '" + text_or(flag, "") + "': " + constraint);
}

}  // namespace beamid::apps
