#include "study/run/store.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>

#include "core/errors.h"
#include "io/files.h"
#include "io/text.h"
#include "signal/noise.h"

namespace beamid::study {
namespace fs = std::filesystem;

void Record::set(const std::string& key, const std::string& value) {
  std::string v = value;
  for (char& c : v)
    if (c == '\n' || c == '\t' || c == '\r') c = ' ';
  fields_[key] = v;
}
void Record::set(const std::string& key, double value) { fields_[key] = io::round_trip(value); }
void Record::set(const std::string& key, const std::vector<double>& values) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? " " : "") + io::round_trip(values[i]);
  fields_[key] = s;
}

const std::string& Record::text(const std::string& key) const {
  auto it = fields_.find(key);
  if (it == fields_.end()) throw InputError("study record: missing field '" + key + "'");
  return it->second;
}

namespace {

// A number as written by io::round_trip (including inf, -inf and nan). strtod, not stod: stod throws on the
// subnormal numbers that round_trip writes exactly. Anything else is an InputError naming the field, so that a
// damaged record is recomputed, never half read.
double parse_number(const std::string& token, const std::string& key) {
  if (token == "inf") return std::numeric_limits<double>::infinity();
  if (token == "-inf") return -std::numeric_limits<double>::infinity();
  if (token == "nan" || token == "-nan") return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size())
    throw InputError("study record: field '" + key + "' = '" + token.substr(0, 40) + "': must be a number");
  return v;
}

}  // namespace

double Record::number(const std::string& key) const { return parse_number(text(key), key); }

std::vector<double> Record::numbers(const std::string& key) const {
  std::vector<double> out;
  std::istringstream in(text(key));
  std::string token;
  while (in >> token) out.push_back(parse_number(token, key));
  return out;
}

std::string Record::serialise() const {
  std::string s;
  for (const auto& [k, v] : fields_) s += k + "\t" + v + "\n";
  return s;
}

Record Record::parse(const std::string& text, const std::string& source) {
  Record r;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const auto tab = line.find('\t');
    if (tab == std::string::npos || tab == 0)
      throw InputError(source + ":" + std::to_string(number) + ": malformed record line (expected key<TAB>value)");
    r.fields_[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return r;
}

namespace {

constexpr const char* kCheck = "#check\t";
// Records larger than this are not records (the largest, a truth of 2^22 samples, is about 100 MB).
constexpr std::uintmax_t kMaxRecordBytes = std::uintmax_t{512} << 20;

std::string check_line(const std::string& body) {
  return kCheck + std::to_string(body.size()) + "\t" + io::hex64(core::fnv1a64(body)) + "\n";
}

std::mutex& log_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

std::string with_check_line(const std::string& body) { return body + check_line(body); }

std::optional<std::string> checked_body(const std::string& text, std::string& why) {
  const auto at = text.rfind(kCheck);
  if (at == std::string::npos) {
    why = "no check line (cut short, or not a record)";
    return std::nullopt;
  }
  const std::string body = text.substr(0, at);
  if (text.substr(at) != check_line(body)) {
    why = "check line does not match the record (cut short or altered)";
    return std::nullopt;
  }
  return body;
}

Store::Store(std::string directory, std::string code_version, std::ostream* log)
    : directory_(std::move(directory)), code_version_(std::move(code_version)), log_(log) {
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec)
    throw InputError("--output: " + directory_ + ": cannot create the study store folder: " + ec.message() +
                     " (is --output a folder beamid may create?)");
}

namespace {

// Why the record read back as unit id's is not that unit's, or "".
std::string binding_violation(const Record& r, const std::string& id) {
  if (!r.has("unit")) return "no unit id";
  if (r.text("unit") != id)
    return "it is the record of unit " + r.text("unit").substr(0, 40) + ", not of " + id + " (renamed or swapped)";
  return "";
}

}  // namespace

std::optional<Record> Store::load(const std::string& id, const RecordCheck& check) const {
  const fs::path path = fs::path(directory_) / (id + ".rec");
  std::error_code ec;
  // The entry itself, not what a symbolic link points to: a link to itself made exists() fail (ELOOP), so the unit
  // was recomputed and its save then refused to replace the link, stopping the study (the seventh pass's S15).
  const fs::file_type type = fs::symlink_status(path, ec).type();
  if (ec || type == fs::file_type::not_found) return std::nullopt;
  std::string why;
  if (type != fs::file_type::regular) why = "is not a regular file (a symbolic link, a folder, a pipe or a device)";
  if (why.empty()) try {
      const std::string text = io::read_file(path, "cannot read the study record", kMaxRecordBytes);
      if (const auto body = checked_body(text, why)) {
        Record r = Record::parse(*body, path.string());
        if (r.has("code") && r.text("code") != code_version_) return std::nullopt;  // another build's: recomputed
        why = r.has("code") ? binding_violation(r, id) : "no code version";
        if (why.empty() && check) why = check(r);
        if (why.empty()) return r;
      } else if (text.find(kCheck) == std::string::npos) {
        // A record of an earlier build, written before records had check lines: not damage, just not ours. Only a
        // whole one, of complete lines beyond the first: a record cut inside its first line ("code\t55c6710cfb00-d")
        // reads as another build's code and was recomputed without a word (the fourth pass's Q393).
        const bool whole = !text.empty() && text.back() == '\n' && std::count(text.begin(), text.end(), '\n') >= 2;
        try {
          const Record r = Record::parse(text, path.string());
          if (whole && r.has("code") && r.text("code") != code_version_) return std::nullopt;
        } catch (const InputError&) {
        }
      }
    } catch (const InputError& e) {
      why = e.what();
    }
  // Damaged: moved aside (kept for inspection) and recomputed. Where damaged/ cannot be a folder (a file of that
  // name), beside the record as <id>.rec.damaged; the message says where it went, or that it could not be kept (it
  // claimed a move to damaged/ that had not happened, the record gone: the fourteenth pass's P9).
  const fs::path aside_dir = fs::path(directory_) / "damaged";
  fs::create_directories(aside_dir, ec);
  const auto free_name = [&ec](const fs::path& base) {
    fs::path name = base;
    for (int k = 1; fs::exists(name, ec) || fs::is_symlink(name, ec); ++k)
      name = base.string() + "." + std::to_string(k);
    return name;
  };
  fs::path aside = free_name(aside_dir / (id + ".rec"));
  std::error_code moved;
  fs::rename(path, aside, moved);
  if (moved) {
    aside = free_name(fs::path(directory_) / (id + ".rec.damaged"));
    moved.clear();
    fs::rename(path, aside, moved);
  }
  std::string where = "moved to " + aside.string();
  if (moved) {
    fs::remove_all(path, ec);
    where = "removed, as it could not be moved aside (" + moved.message() + ")";
  }
  std::lock_guard<std::mutex> lock(log_mutex());
  (log_ ? *log_ : std::cerr) << "beamid study: store: " << path.string() << ": " << why << ": " << where
                             << "; the unit is recomputed\n";
  return std::nullopt;
}

void Store::save(const std::string& id, Record record) const {
  record.set("unit", id);
  record.set("code", code_version_);
  const std::string body = record.serialise();
  io::write_file_atomic(fs::path(directory_) / (id + ".rec"), with_check_line(body));
}

Store::Absorbed Store::absorb(const std::string& other, const Belongs& belongs) const {
  if (!io::is_existing_folder(other)) throw InputError(other + ": not a study store folder");
  Absorbed absorbed;
  std::error_code ec;
  fs::directory_iterator folder(other, ec);
  if (ec) throw InputError(other + ": cannot list the study store folder (" + ec.message() + ")");
  for (const auto& entry : folder) {
    if (entry.path().extension() != ".rec") continue;
    // A record that is a folder, a link or a pipe is no record: left behind and named (a pipe would be waited on).
    if (entry.is_symlink() || !entry.is_regular_file()) {
      absorbed.left_behind.push_back(entry.path().string() +
                                     (entry.is_symlink() ? ": a symbolic link, not a record file"
                                                         : ": not a regular file (a folder, a pipe or a device)"));
      continue;
    }
    const fs::path target = fs::path(directory_) / entry.path().filename();
    const std::string text = io::read_file(entry.path(), "a study record", kMaxRecordBytes);
    std::string why;
    // A damaged shard record, or one under another unit's name, is left behind (and listed): the merge names it.
    const auto body = checked_body(text, why);
    if (body) {
      try {
        // A record of another build would replace one of this build in the output, and then be recomputed (a merge
        // that went on to fail had already replaced a valid record: the twenty-first pass's P2): left behind.
        const Record r = Record::parse(*body, entry.path().string());
        why = r.has("code") && r.text("code") != code_version_
                  ? "a record of another build (code " + r.text("code").substr(0, 40) + ", this is " + code_version_ +
                        "): run that shard again with this build"
                  : binding_violation(r, entry.path().stem().string());
      } catch (const InputError& e) {
        why = e.what();
      }
    }
    if (!body || !why.empty()) {
      absorbed.left_behind.push_back(entry.path().string() + ": " + why);
      continue;
    }
    if (belongs) {
      why = belongs(entry.path().stem().string(), Record::parse(*body, entry.path().string()));
      if (!why.empty()) {
        absorbed.left_behind.push_back(entry.path().string() + ": " + why);
        ++absorbed.foreign;
        continue;
      }
    }
    io::write_file_atomic(target, text);
    ++absorbed.copied;
  }
  std::sort(absorbed.left_behind.begin(), absorbed.left_behind.end());  // directory order is the file system's
  return absorbed;
}

}  // namespace beamid::study
