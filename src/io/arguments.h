// Strict "--flag value" parsing for the beamid subcommands: an unknown flag, a missing or malformed value, or a
// repeated flag is an InputError whose one-line message names the command, the flag, the value and the constraint,
// e.g. "beamid simulate: --dt = 'abc': must be a number".
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace beamid::io {

struct FlagSpec {
  std::string name;        // without the leading "--"
  bool takes_value = true; // false: a switch such as --exact
  std::string help;        // one line for --help
};

class Arguments {
 public:
  // args excludes the program and command names. Throws InputError as described above.
  Arguments(std::string command, const std::vector<std::string>& args, std::vector<FlagSpec> spec);

  const std::string& command() const { return command_; }
  bool has(const std::string& flag) const;
  // The raw text; InputError when absent.
  std::string text(const std::string& flag) const;
  std::string text_or(const std::string& flag, const std::string& fallback) const;
  // Parsed numbers: the whole text must be a finite number (an integer for integer()).
  double number(const std::string& flag) const;
  std::optional<double> optional_number(const std::string& flag) const;
  int integer(const std::string& flag) const;
  std::optional<int> optional_integer(const std::string& flag) const;
  // InputError naming the flag unless `ok`.
  void require(bool ok, const std::string& flag, const std::string& constraint) const;
  // "--flag" usage lines for --help.
  std::string usage() const;

 private:
  [[noreturn]] void fail(const std::string& message) const;
  std::string command_;
  std::vector<FlagSpec> spec_;
  std::map<std::string, std::string> values_;
};

}  // namespace beamid::io
