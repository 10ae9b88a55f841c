// Strict reading of one TOML table (toml++), shared by the beam and study files: every key must be consumed by a
// getter, `finish` names any other; every error is one line "file:line: prefix.key = value: constraint".
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "model/errors.h"

namespace beamid::model {

class TableReader {
 public:
  TableReader(const toml::table& table, std::string prefix, const std::string& source)
      : table_(table), prefix_(std::move(prefix)), source_(source) {}

  std::string where(const toml::node* node) const {
    const auto& s = node ? node->source() : table_.source();
    return source_ + ":" + std::to_string(s.begin.line);
  }
  [[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& constraint) const {
    throw InputError(where(table_.get(key)) + ": " + prefix_ + key + " = " + value + ": " + constraint);
  }
  const toml::node* get(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }
  bool has(const std::string& key) const { return table_.contains(key); }

  double number(const std::string& key, std::optional<double> fallback, const std::function<bool(double)>& ok,
                const std::string& constraint) {
    const toml::node* node = get(key);
    if (node == nullptr) {
      if (!fallback) throw InputError(where(nullptr) + ": [" + table_name() + "] is missing key '" + key + "'");
      return *fallback;
    }
    const auto v = node->value<double>();
    if (!node->is_number() || !v) fail(key, text(*node), "must be a number");
    if (!std::isfinite(*v) || !ok(*v)) fail(key, format_value(*v), constraint);
    return *v;
  }
  int integer(const std::string& key, std::optional<int> fallback, int min, int max) {
    const toml::node* node = get(key);
    if (node == nullptr) {
      if (!fallback) throw InputError(where(nullptr) + ": [" + table_name() + "] is missing key '" + key + "'");
      return *fallback;
    }
    const auto v = node->value<std::int64_t>();
    if (!node->is_integer() || !v) fail(key, text(*node), "must be an integer");
    if (*v < min || *v > max) fail(key, std::to_string(*v), range_text(min, max));
    return static_cast<int>(*v);
  }
  std::string string(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& allowed = {}) {
    const toml::node* node = get(key);
    if (node == nullptr) {
      if (!fallback) throw InputError(where(nullptr) + ": [" + table_name() + "] is missing key '" + key + "'");
      return *fallback;
    }
    const auto v = node->value<std::string>();
    if (!v) fail(key, text(*node), "must be a string");
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), *v) == allowed.end())
      fail(key, "'" + *v + "'", "must be one of " + join(allowed));
    return *v;
  }
  const toml::array* array(const std::string& key, bool required) {
    const toml::node* node = get(key);
    if (node == nullptr) {
      if (required) throw InputError(where(nullptr) + ": [" + table_name() + "] is missing key '" + key + "'");
      return nullptr;
    }
    const toml::array* a = node->as_array();
    if (a == nullptr) fail(key, text(*node), "must be an array");
    if (a->empty()) fail(key, "[]", "must not be empty");
    return a;
  }
  std::vector<std::string> strings(const std::string& key, bool required, const std::vector<std::string>& allowed) {
    std::vector<std::string> out;
    const toml::array* a = array(key, required);
    if (a == nullptr) return out;
    for (const toml::node& item : *a) {
      const auto v = item.value<std::string>();
      if (!v) element_fail(key, item, text(item), "must be a string");
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), *v) == allowed.end())
        element_fail(key, item, "'" + *v + "'", "must be one of " + join(allowed));
      if (std::find(out.begin(), out.end(), *v) != out.end()) element_fail(key, item, "'" + *v + "'", "is repeated");
      out.push_back(*v);
    }
    return out;
  }
  std::vector<double> numbers(const std::string& key, const std::function<bool(double)>& ok,
                              const std::string& constraint) {
    std::vector<double> out;
    const toml::array* a = array(key, false);
    if (a == nullptr) return out;
    for (const toml::node& item : *a) {
      const auto v = item.value<double>();
      if (!item.is_number() || !v) element_fail(key, item, text(item), "must be a number");
      if (!std::isfinite(*v) || !ok(*v)) element_fail(key, item, format_value(*v), constraint);
      if (std::find(out.begin(), out.end(), *v) != out.end()) element_fail(key, item, format_value(*v), "is repeated");
      out.push_back(*v);
    }
    return out;
  }
  std::vector<int> integers(const std::string& key, bool required, int min, int max) {
    std::vector<int> out;
    const toml::array* a = array(key, required);
    if (a == nullptr) return out;
    for (const toml::node& item : *a) {
      const auto v = item.value<std::int64_t>();
      if (!item.is_integer() || !v) element_fail(key, item, text(item), "must be an integer");
      if (*v < min || *v > max) element_fail(key, item, std::to_string(*v), range_text(min, max));
      if (std::find(out.begin(), out.end(), static_cast<int>(*v)) != out.end())
        element_fail(key, item, std::to_string(*v), "is repeated");
      out.push_back(static_cast<int>(*v));
    }
    return out;
  }
  // Every key present but not read is an error naming it and the valid keys.
  void finish(const std::vector<std::string>& valid) const {
    for (auto&& [key, node] : table_) {
      const std::string k(key.str());
      if (!used_.count(k))
        throw InputError(source_ + ":" + std::to_string(key.source().begin.line) + ": unknown key " + prefix_ + k +
                         ": valid keys are " + join(valid));
    }
  }
  static std::string join(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
  }
  static std::string text(const toml::node& node) {
    std::ostringstream os;
    if (node.is_string())
      os << "'" << *node.value<std::string>() << "'";
    else if (node.is_table())
      os << "{...}";
    else if (node.is_array())
      os << "[...]";
    else
      node.visit([&os](auto&& v) { os << v; });
    return os.str();
  }

 private:
  std::string table_name() const { return prefix_.empty() ? "" : prefix_.substr(0, prefix_.size() - 1); }
  static std::string range_text(int min, int max) {
    return max == std::numeric_limits<int>::max() ? "must be >= " + std::to_string(min)
                                                  : "must be in " + std::to_string(min) + ".." + std::to_string(max);
  }
  [[noreturn]] void element_fail(const std::string& key, const toml::node& item, const std::string& value,
                                 const std::string& constraint) const {
    throw InputError(source_ + ":" + std::to_string(item.source().begin.line) + ": " + prefix_ + key +
                     " element " + value + ": " + constraint);
  }
  const toml::table& table_;
  std::string prefix_;
  const std::string& source_;
  std::set<std::string> used_;
};


}  // namespace beamid::model
