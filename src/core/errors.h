// The two kinds of failure a program reports.
// InputError: caused by what a user gave (a file, a flag, a value). The message is one line that names where (file:line
// or flag), the key, the value and the violated constraint, for example: "beam.toml:7: beam.EI = -1: must be > 0".
// Programs print it and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace beamid {

// The message as one line of printable text: a line break, a tab or another control character that came in with a
// user's input (a key, a field, a library's parse message quoting the input) is written as an escape ("\\n", "\\x01"),
// so that an error is always exactly one line; a message longer than 1,600 bytes keeps about its first 1,000 and last
// 500 (cut between UTF-8 characters) and says how many bytes it cut between them.
std::string one_line(const std::string& message);

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

// OutputError: a result that could not be written for a reason of the machine's, not the input's (a full disk, a
// folder made read-only, a quota). The message names the path and the OS's reason; programs exit 1 ("the results
// could not be written"), not 2 (bad input): a full disk gave exit 2 (the twentieth adversarial pass's P3).
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

// NumericalError: a computation that could not be carried out for admissible input (a singular matrix, an
// eigensolver or integrator that did not converge). Inside a study it becomes a row with a status, never a crash.
class NumericalError : public std::runtime_error {
 public:
  explicit NumericalError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

// Shortest round-trip text of a double, for error messages ("-1", "0.491", "1e-300", "nan").
std::string format_value(double value);
// A derived quantity (a bound computed from other values) to `digits` significant digits, as printf's %g: "425.3",
// "1.074e+10". Values a user gave are quoted with format_value, exactly.
std::string format_rounded(double value, int digits = 4);

}  // namespace beamid
