// The textual forms beamid writes everywhere, in one place. Two number forms, both exact (17 significant digits read
// back as the same double), kept apart because outside tools rely on each:
//   full_precision  "%.16e", fixed width: the columns the commands print (the CLI contract) and the verification
//                   tables;
//   round_trip      "%.17g", shortest of the two for round numbers: the study tables, the study store and the
//                   canonical text that unit ids hash (changing it would change every id);
//   hex64        a 64-bit hash as 16 hex digits (unit ids, file hashes);
//   json_string  a JSON string literal;  csv_quoted  a CSV field in double quotes.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace beamid::io {

std::string full_precision(double value);
std::string round_trip(double value);
std::string hex64(std::uint64_t value);
std::string json_string(const std::string& text);
std::string csv_quoted(const std::string& text);

// The number a record's field holds: the whole text read by strtod as a decimal number (inf and nan included, for
// the callers' own finiteness checks), or nothing. strtod also reads hexadecimal ("0x10" as 16, "0x1p3" as 8), which
// no DAQ writes: a hex literal in a CSV column was taken as a sample (the tenth pass's NF_hex).
std::optional<double> decimal_number(const std::string& text);

// One CSV row of numbers in full_precision form.
void write_row(std::ostream& out, const std::vector<double>& values);

}  // namespace beamid::io
