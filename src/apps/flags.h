// The command line's flags, parsed by CLI11 (the only CLI11 user is src/apps/): each command states its flags once
// as FlagSpecs (kind, help, integer range, required), which become CLI11 options with validators, the generated
// --help, and errors in the project's one-line form
//   beamid <command>: --<flag> = '<value>': <constraint>
// After parsing, a command reads its values through Flags (typed accessors that name the flag in any error).
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace beamid::apps {

enum class FlagKind {
  Text,       // --flag VALUE, any text
  Number,     // --flag VALUE, a finite number
  Integer,    // --flag VALUE, an integer in [min, max]
  Switch,     // --flag
  Positional  // VALUE (the name is the metavariable, e.g. "STUDY.toml")
};

struct FlagSpec {
  std::string name;  // without the leading "--"
  FlagKind kind = FlagKind::Text;
  std::string help;
  bool required = false;
  long long min = std::numeric_limits<int>::min(), max = std::numeric_limits<int>::max();  // Integer only
};
// Constructors for the usual kinds.
FlagSpec text_flag(std::string name, std::string help, bool required = false);
FlagSpec number_flag(std::string name, std::string help, bool required = false);
FlagSpec integer_flag(std::string name, std::string help, long long min, long long max, bool required = false);
FlagSpec switch_flag(std::string name, std::string help);
FlagSpec positional(std::string name, std::string help);

// Adds the flags to a CLI11 (sub)command.
void add_flags(CLI::App& command, const std::vector<FlagSpec>& flags);

// The values of one parsed command.
class Flags {
 public:
  // `arguments`: the command line after the command's name (what a report quotes).
  Flags(std::string command, const CLI::App& parsed, const std::vector<FlagSpec>& flags,
        std::vector<std::string> arguments);
  // For tests and programs: values given directly ("" for a switch).
  Flags(std::string command, std::map<std::string, std::string> values)
      : command_(std::move(command)), values_(std::move(values)) {}

  const std::string& command() const { return command_; }
  const std::vector<std::string>& arguments() const { return arguments_; }
  bool has(const std::string& flag) const { return values_.count(flag) > 0; }
  // The raw text; InputError when absent.
  std::string text(const std::string& flag) const;
  std::string text_or(const std::string& flag, const std::string& fallback) const;
  double number(const std::string& flag) const;
  std::optional<double> optional_number(const std::string& flag) const;
  int integer(const std::string& flag) const;
  std::optional<int> optional_integer(const std::string& flag) const;
  // A comma-separated list ("a,b" or "0.3,0.5"); empty when absent. An empty item, or an item that is not a finite
  // number, is an InputError naming the flag and the item.
  std::vector<std::string> texts(const std::string& flag) const;
  std::vector<double> numbers(const std::string& flag) const;
  // InputError "beamid <command>: --flag = 'value': constraint" unless ok.
  void require(bool ok, const std::string& flag, const std::string& constraint) const;
  // A file flag whose content is given inline instead of read from the named file (the Python package's beam
  // dicts: --beam names "<beam dict>" and its TOML text comes with it); nothing when the file is to be read.
  void set_inline(const std::string& flag, std::string content) { inline_[flag] = std::move(content); }
  const std::string* inline_content(const std::string& flag) const {
    const auto it = inline_.find(flag);
    return it == inline_.end() ? nullptr : &it->second;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const;
  std::string command_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> arguments_;
  std::map<std::string, std::string> inline_;
};

}  // namespace beamid::apps
