// A closed set of names for one kind of choice (costs, strategies, optimizers, excitations, outputs), each with a
// one-line description. Each kind has one registry, beside the code that implements it (costs/cost.h,
// fit/identification.h, fit/optimizer.h, simulation/experiment.h); the command line, the study reader and the tables
// take the valid names, the lists in their errors and the alternatives in their help from it, so a name is written
// once.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace beamid::core {

class NameSet {
 public:
  struct Entry {
    std::string name;
    std::string description;
  };
  explicit NameSet(std::vector<Entry> entries) : entries_(std::move(entries)) {}

  const std::vector<Entry>& entries() const { return entries_; }
  bool contains(const std::string& name) const;
  std::vector<std::string> names() const;
  std::string list() const;          // "time, spike, spike-smooth" (for errors)
  std::string alternatives() const;  // "time | spike | spike-smooth" (for help)
  // "key = 'value': must be one of a, b, c" when value is not a name; nothing otherwise.
  std::optional<std::string> violation(const std::string& key, const std::string& value) const;
  // The value itself when it is a name of the set; else InputError "key = 'value': must be one of a, b, c". For the
  // code that maps a name to what it selects (an adapter's enum, a constructor): an unknown name is never a default.
  std::string require(const std::string& key, const std::string& value) const;

 private:
  std::vector<Entry> entries_;
};

}  // namespace beamid::core
