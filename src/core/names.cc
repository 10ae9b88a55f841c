#include "core/names.h"

#include "core/errors.h"

namespace beamid::core {

bool NameSet::contains(const std::string& name) const {
  for (const auto& e : entries_)
    if (e.name == name) return true;
  return false;
}

std::vector<std::string> NameSet::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.name);
  return out;
}

std::string NameSet::list() const {
  std::string s;
  for (const auto& e : entries_) s += (s.empty() ? "" : ", ") + e.name;
  return s;
}

std::string NameSet::alternatives() const {
  std::string s;
  for (const auto& e : entries_) s += (s.empty() ? "" : " | ") + e.name;
  return s;
}

std::optional<std::string> NameSet::violation(const std::string& key, const std::string& value) const {
  if (contains(value)) return std::nullopt;
  return key + " = '" + value + "': must be one of " + list();
}

std::string NameSet::require(const std::string& key, const std::string& value) const {
  if (auto error = violation(key, value)) throw InputError(*error);
  return value;
}

}  // namespace beamid::core
