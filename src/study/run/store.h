// The study's work store: one small text file per finished unit (results/<study>/store/<id>.rec), written atomically
// (a temporary file renamed into place), so an interrupted study loses at most the units that were running and a
// resumed one skips everything already stored. A record is "key<TAB>value" lines; lists of numbers are space
// separated in 17 significant digits. Each record carries the code version that made it; a record from another
// build is ignored (recomputed), so a resumed study never mixes results of different code.
// Every record checks itself: its last line is "#check<TAB><length of the lines before><TAB><their FNV-1a 64 hash>",
// and the lines include the unit's id ("unit"), which is itself a hash of everything that determines the unit's
// result (plan.h), so a record is bound to its unit and to the inputs that made it. A record that is cut short,
// altered or unreadable, that belongs to another unit (renamed or swapped), or that fails the caller's schema check
// (record_schema.h) is named on the log, moved aside to store/damaged/ and recomputed, so no damage to the store can
// crash or stop a study, nor be reused.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace beamid::study {

class Record {
 public:
  void set(const std::string& key, const std::string& value);
  void set(const std::string& key, double value);
  void set(const std::string& key, const std::vector<double>& values);
  bool has(const std::string& key) const { return fields_.count(key) != 0; }
  const std::string& text(const std::string& key) const;  // InputError naming the key when absent
  double number(const std::string& key) const;
  std::vector<double> numbers(const std::string& key) const;
  const std::map<std::string, std::string>& fields() const { return fields_; }

  std::string serialise() const;  // the lines, without the check line (Store adds it)
  // InputError naming source:line for a malformed line.
  static Record parse(const std::string& text, const std::string& source);

 private:
  std::map<std::string, std::string> fields_;
};

// A text followed by its check line, and the text back when its check line holds (else nothing, and why): the form
// every record has, and every file beside the store that must not be trusted when edited (the list of written tables).
std::string with_check_line(const std::string& body);
std::optional<std::string> checked_body(const std::string& text, std::string& why);

class Store {
 public:
  // Creates the folder if needed. Damaged records are reported on `log` (one line each; std::cerr when null).
  Store(std::string directory, std::string code_version, std::ostream* log = nullptr);
  const std::string& directory() const { return directory_; }
  // Why a record read back does not fit the caller's expectations, or "" when it does.
  using RecordCheck = std::function<std::string(const Record&)>;
  // The stored record of unit `id`, if there is one made by this code version that passes its check, is unit id's
  // and passes `check` (a damaged one is moved aside and reported).
  std::optional<Record> load(const std::string& id, const RecordCheck& check = {}) const;
  // Stamps the unit's id and the code version and writes atomically.
  void save(const std::string& id, Record record) const;
  // Copies every sound record file of another store folder into this one (for merging shards). A damaged record, one
  // under another unit's name, or one that `belongs` refuses (it returns why: a record of no unit of the study being
  // merged, or made from other inputs) is left behind and listed ("path: why"), so that a merge can say which shard
  // record it could not use.
  struct Absorbed {
    int copied = 0;
    int foreign = 0;  // left behind by `belongs`
    std::vector<std::string> left_behind;
  };
  using Belongs = std::function<std::string(const std::string& id, const Record& record)>;
  Absorbed absorb(const std::string& other_directory, const Belongs& belongs = {}) const;

 private:
  std::string directory_;
  std::string code_version_;
  std::ostream* log_;
};

}  // namespace beamid::study
