#include "study/store.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/errors.h"
#include "study/text.h"

namespace beamid::study {
namespace fs = std::filesystem;

void Record::set(const std::string& key, const std::string& value) {
  std::string v = value;
  for (char& c : v)
    if (c == '\n' || c == '\t' || c == '\r') c = ' ';
  fields_[key] = v;
}
void Record::set(const std::string& key, double value) { fields_[key] = full(value); }
void Record::set(const std::string& key, const std::vector<double>& values) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? " " : "") + full(values[i]);
  fields_[key] = s;
}

const std::string& Record::text(const std::string& key) const {
  auto it = fields_.find(key);
  if (it == fields_.end()) throw InputError("study record: missing field '" + key + "'");
  return it->second;
}

double Record::number(const std::string& key) const {
  const std::string& t = text(key);
  if (t == "inf") return std::numeric_limits<double>::infinity();
  if (t == "-inf") return -std::numeric_limits<double>::infinity();
  if (t == "nan" || t == "-nan") return std::numeric_limits<double>::quiet_NaN();
  return std::stod(t);
}

std::vector<double> Record::numbers(const std::string& key) const {
  std::vector<double> out;
  std::istringstream in(text(key));
  std::string token;
  while (in >> token) {
    if (token == "inf") out.push_back(std::numeric_limits<double>::infinity());
    else if (token == "-inf") out.push_back(-std::numeric_limits<double>::infinity());
    else if (token == "nan" || token == "-nan") out.push_back(std::numeric_limits<double>::quiet_NaN());
    else out.push_back(std::stod(token));
  }
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

Store::Store(std::string directory, std::string code_version)
    : directory_(std::move(directory)), code_version_(std::move(code_version)) {
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec) throw InputError(directory_ + ": cannot create the study store folder: " + ec.message());
}

std::optional<Record> Store::load(const std::string& id) const {
  const fs::path path = fs::path(directory_) / (id + ".rec");
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  try {
    Record r = Record::parse(text.str(), path.string());
    if (!r.has("code") || r.text("code") != code_version_) return std::nullopt;
    return r;
  } catch (const InputError&) {
    return std::nullopt;  // a damaged record is recomputed
  }
}

void Store::save(const std::string& id, Record record) const {
  record.set("code", code_version_);
  const fs::path final_path = fs::path(directory_) / (id + ".rec");
  const fs::path tmp = fs::path(directory_) / (id + ".rec.tmp");
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << record.serialise();
    out.flush();
    if (!out) throw InputError(tmp.string() + ": cannot write a study record");
  }
  fs::rename(tmp, final_path);
}

int Store::absorb(const std::string& other) const {
  if (!fs::is_directory(other)) throw InputError(other + ": not a study store folder");
  int count = 0;
  for (const auto& entry : fs::directory_iterator(other)) {
    if (entry.path().extension() != ".rec") continue;
    const fs::path target = fs::path(directory_) / entry.path().filename();
    const fs::path tmp = fs::path(directory_) / (entry.path().filename().string() + ".tmp");
    fs::copy_file(entry.path(), tmp, fs::copy_options::overwrite_existing);
    fs::rename(tmp, target);
    ++count;
  }
  return count;
}

}  // namespace beamid::study
