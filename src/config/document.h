// The configuration layer: strict reading of TOML files (beam, geometry, study and real-study files) behind a facade
// with no toml++ type in it, so that nothing outside src/config/ depends on the TOML library.
//
// Every error is one line "file:line: prefix.key = value: constraint" (InputError), e.g.
//   studies/paper.toml:14: fit.success_tolerance = -0.01: must be > 0
// A Table remembers which keys were read; `finish` names any other key with the list of valid ones, so a misspelled
// key is an error, never a silently ignored setting.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace beamid::config {

struct DocumentData;  // the parsed TOML tree (document.cc)

class Table;

// One value of a document with its source line.
class Node {
 public:
  int line() const;
  // The value as written for messages: 'text' for strings, {...} for tables, [...] for arrays, else the literal.
  std::string text() const;
  bool is_string() const;
  bool is_number() const;  // integer or floating point
  bool is_integer() const;
  bool is_boolean() const;
  bool is_table() const;
  bool is_array() const;
  std::optional<std::string> string() const;
  std::optional<double> number() const;  // integers convert exactly
  std::optional<std::int64_t> integer() const;
  std::optional<bool> boolean() const;
  std::vector<Node> elements() const;  // of an array (empty otherwise)
  // This node as a table whose messages name keys "prefix.key" (InputError "file:line: what must be a table ([what])"
  // when it is not one).
  Table table(const std::string& prefix, const std::string& what) const;

 private:
  friend class Table;
  friend class Document;
  Node(std::shared_ptr<const DocumentData> document, const void* node) : document_(std::move(document)), node_(node) {}
  std::shared_ptr<const DocumentData> document_;
  const void* node_;  // a toml::node of document_
};

class Table {
 public:
  const std::string& source() const;
  // "file:line" of a key (or of the table itself when the key is absent).
  std::string where(const std::string& key) const;
  std::string where() const;
  [[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& constraint) const;

  bool has(const std::string& key) const;
  // The raw value of a key (marking it read), or nothing.
  std::optional<Node> get(const std::string& key);
  // Every key with its line, in file order.
  std::vector<std::pair<std::string, Node>> entries() const;
  int key_line(const std::string& key) const;

  // Typed reads: a missing key takes `fallback`, or is an error "[table] is missing key 'k'" without one.
  double number(const std::string& key, std::optional<double> fallback, const std::function<bool(double)>& ok,
                const std::string& constraint);
  int integer(const std::string& key, std::optional<int> fallback, int min, int max);
  std::string string(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& allowed = {});
  bool boolean(const std::string& key, bool fallback);
  // Arrays: never empty when present; elements distinct.
  std::optional<std::vector<Node>> array(const std::string& key, bool required);
  std::vector<std::string> strings(const std::string& key, bool required, const std::vector<std::string>& allowed);
  std::vector<double> numbers(const std::string& key, const std::function<bool(double)>& ok,
                              const std::string& constraint);
  std::vector<int> integers(const std::string& key, bool required, int min, int max);
  // A sub-table (marking it read): nothing when absent; InputError "file:line: name must be a table ([name])" when
  // it is something else.
  std::optional<Table> table(const std::string& key);
  // Every key present but not read is an error naming it and the valid keys.
  void finish(const std::vector<std::string>& valid) const;
  // For a document root: every key must name one of `valid` tables.
  void only_tables(const std::vector<std::string>& valid) const;
  // Every key must be one of `valid`, read or not: called before the reads, an unknown key (a misspelling) is named
  // before a missing one is ("missing key 'EI'" hid the EJ = 1.05 beside it).
  void only_keys(const std::vector<std::string>& valid) const;
  // The element `item` of array `key` violates `constraint`.
  [[noreturn]] void element_fail(const std::string& key, const Node& item, const std::string& value,
                                 const std::string& constraint) const;

  static std::string join(const std::vector<std::string>& names);

 private:
  friend class Node;
  friend class Document;
  Table(std::shared_ptr<const DocumentData> document, const void* table, std::string prefix);
  std::string table_name() const;
  std::shared_ptr<const DocumentData> document_;
  const void* table_;  // a toml::table of document_
  std::string prefix_;
  std::shared_ptr<std::vector<std::string>> used_;  // shared by copies, so a copied table still counts its reads
};

class Document {
 public:
  // InputError "source:line: TOML syntax error: ..." on bad syntax.
  static Document parse(const std::string& text, const std::string& source);
  // Reads the file first (io::read_file: a folder, a device or a file over 16 MB is refused before any read):
  // InputError "path: <cannot_read>" when it cannot be read.
  static Document load(const std::string& path, const std::string& cannot_read);
  Table root() const;
  // A top-level table: InputError "source:1: missing table [name]" when absent and required.
  std::optional<Table> table(const std::string& name, bool required) const;
  Table required(const std::string& name) const { return *table(name, true); }
  const std::string& text() const;  // the bytes read (for hashes)
  const std::string& source() const;

 private:
  explicit Document(std::shared_ptr<const DocumentData> data) : data_(std::move(data)) {}
  std::shared_ptr<const DocumentData> data_;
};

// Beam and study files are a few kB; a file larger than this is not one.
inline constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{16} << 20;

// "3.3.0": the TOML library's version, for provenance.
std::string toml_library_version();

}  // namespace beamid::config
