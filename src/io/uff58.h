// Universal File Format (UFF/UNV) dataset 58, "function at nodal DOF", as ASCII (58) and as the binary hybrid (58b),
// the time records that modal-test software exports (SDRC/I-DEAS layout, https://www.ceas3.uc.edu/sdrluff/).
//
// A dataset runs from a line "    -1" to the next. Its first line is "    58", or "    58b" followed by the byte
// order (1: little-endian, 2: big-endian), the floating-point format (2: IEEE 754), the number of ASCII header
// lines (11) and the number of data bytes. Then 11 fixed-column header records:
//   1-5   ID lines (80 characters; line 1 names the function);
//   6     function type (I5; 1 = time response), id, version, load case, response entity, node, direction, ...;
//   7     ordinate data type (I10; 2 = real single, 4 = real double, 5 and 6 complex), number of values (I10),
//         abscissa spacing (I10; 1 = even, 0 = uneven), abscissa minimum and increment (E13.5 each), z value;
//   8-11  abscissa, ordinate, ordinate denominator and z axis: data type, unit exponents, label and units label
//         (A20 each, the ordinate's units label, e.g. "g" or "m/s^2", is the record's unit).
// Then the values: ASCII single precision 6 per line (E13.5), double precision 4 per line (E20.12), or with uneven
// spacing (abscissa, ordinate) pairs; binary: n bytes of IEEE floats in the stated order. Other datasets in the file
// are skipped. Read here: real time responses (type 1); another function type or complex ordinates are named as such.
// Every violation is an InputError naming the file, the line (or byte offset) and what was expected.
#pragma once

#include <string>
#include <vector>

namespace beamid::io {

// Whether the text starts, after blank lines, with a "-1" delimiter line followed by a dataset number.
bool is_uff(const std::string& bytes);
// The 1-based line of a UFF dataset's ID line ("58", "58b ...") that opens the file without the "-1" delimiter before
// it, or 0: such a file was read as CSV and told its header '58' names no columns (the thirteenth pass's 12).
int uff_without_delimiter(const std::string& bytes);

struct UffFunction {
  int dataset_line = 0;   // line of its "-1" delimiter (1-based)
  std::string name;       // ID line 1 trimmed, or "node N dir D" when it is empty or NONE
  int function_type = 0;  // 1: time response
  bool complex = false;
  std::string unit;           // the ordinate's units label, trimmed
  int ordinate_type = 0;      // record 9's specific data type: 8 displacement, 11 velocity, 12 acceleration, ...
  int ordinate_line = 0;      // the line of record 9
  int abscissa_type = 0;      // record 8's specific data type: 0 unknown, 1 general, 17 time, 18 frequency, ...
  std::string abscissa_unit;  // record 8's units label, trimmed ("" for NONE)
  int abscissa_line = 0;      // the line of record 8
  bool even = true;           // abscissa spacing
  double x0 = 0, dx = 0;      // abscissa minimum and increment (even spacing)
  std::vector<double> x, y;   // x only with uneven spacing
  int first_value_line = 0;   // line of its first value (ASCII), 0 for binary
  std::size_t first_value_byte = 0;
};

// Every dataset 58 of the file, in file order.
std::vector<UffFunction> parse_uff58(const std::string& bytes, const std::string& path);

}  // namespace beamid::io
