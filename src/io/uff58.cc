#include "io/uff58.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "core/errors.h"
#include "io/text.h"

namespace beamid::io {
namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r"), last = s.find_last_not_of(" \t\r");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

// Reads the file line by line, keeping the line number and the byte offset.
class Cursor {
 public:
  explicit Cursor(const std::string& bytes) : bytes_(bytes) {}
  bool done() const { return position_ >= bytes_.size(); }
  int line() const { return line_; }  // of the next line
  std::size_t byte() const { return position_; }
  std::string next() {
    const auto end = bytes_.find('\n', position_);
    std::string text = bytes_.substr(position_, end == std::string::npos ? std::string::npos : end - position_);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    position_ = end == std::string::npos ? bytes_.size() : end + 1;
    ++line_;
    return text;
  }
  // Binary data: its bytes are not lines, but an editor counts the line feeds among them, and so do the messages.
  void skip_bytes(std::size_t count) {
    line_ += static_cast<int>(std::count(bytes_.begin() + static_cast<std::ptrdiff_t>(position_),
                                         bytes_.begin() + static_cast<std::ptrdiff_t>(position_ + count), '\n'));
    position_ += count;
  }

 private:
  const std::string& bytes_;
  std::size_t position_ = 0;
  int line_ = 1;
};

// The fixed-width field [begin, begin + width) of a header line as text (shorter lines read as blank).
std::string field(const std::string& line, std::size_t begin, std::size_t width) {
  return begin >= line.size() ? "" : trim(line.substr(begin, width));
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw InputError(path + ":" + std::to_string(line) + ": " + what + " (a UFF dataset 58 time record)");
}

long integer_field(const std::string& path, int line, const std::string& text, const std::string& what) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0') fail(path, line, what + " = '" + text + "': must be an integer");
  return v;
}

double number_field(const std::string& path, int line, std::string text, const std::string& what) {
  std::replace(text.begin(), text.end(), 'D', 'E');  // Fortran double-precision exponents
  std::replace(text.begin(), text.end(), 'd', 'e');
  const double v = decimal_number(text).value_or(std::nan(""));
  if (!std::isfinite(v)) fail(path, line, what + " = '" + text.substr(0, 40) + "': must be a finite number");
  return v;
}

}  // namespace

bool is_uff(const std::string& bytes) {
  Cursor c(bytes);
  for (int lines = 0; !c.done() && lines < 10; ++lines) {
    const std::string line = trim(c.next());
    if (line.empty()) continue;
    if (line != "-1" || c.done()) return false;
    const std::string id = field(c.next(), 0, 6);
    return !id.empty() && id.find_first_not_of("0123456789") == std::string::npos;
  }
  return false;
}

int uff_without_delimiter(const std::string& bytes) {
  Cursor c(bytes);
  for (int line = 1; !c.done() && line <= 10; ++line) {
    const std::string text = trim(c.next());
    if (text.empty()) continue;
    const std::string id = field(text, 0, 6);
    return trim(id) == "58" || text.rfind("58b", 0) == 0 ? line : 0;
  }
  return 0;
}

namespace {

// A binary dataset's layout from its ID line (58b): byte order, floating-point format, header lines, data bytes.
struct BinaryLayout {
  long byte_order = 1, fp_format = 2, ascii_lines = 11, data_bytes = 0;
};

BinaryLayout binary_layout(const std::string& path, int id_line, const std::string& id_text) {
  BinaryLayout b;
  long &byte_order = b.byte_order, &fp_format = b.fp_format, &ascii_lines = b.ascii_lines, &data_bytes = b.data_bytes;
  byte_order = integer_field(path, id_line, field(id_text, 7, 6), "byte ordering");
  fp_format = integer_field(path, id_line, field(id_text, 13, 6), "floating-point format");
  ascii_lines = integer_field(path, id_line, field(id_text, 19, 12), "number of ASCII lines");
  data_bytes = integer_field(path, id_line, field(id_text, 31, 12), "number of data bytes");
  if (byte_order != 1 && byte_order != 2)
    fail(path, id_line, "byte ordering " + std::to_string(byte_order) + ": must be 1 (little) or 2 (big endian)");
  if (fp_format != 2) fail(path, id_line, "floating-point format " + std::to_string(fp_format) + ": must be 2 (IEEE)");
  if (ascii_lines != 11) fail(path, id_line, std::to_string(ascii_lines) + " ASCII header lines: must be 11");
  if (data_bytes < 0) fail(path, id_line, "number of data bytes " + std::to_string(data_bytes) + ": must be >= 0");
  return b;
}

// The eleven header lines of a dataset 58: the function's name, type, form, abscissa and unit into f; returns the
// ordinate data type and the number of points.
std::pair<long, long> read_header(Cursor& c, const std::string& path, int delimiter_line, UffFunction& f) {
  std::vector<std::string> header;
  std::vector<int> header_line;
  for (int r = 0; r < 11; ++r) {
    if (c.done())
      fail(path, c.line(),
           "the file ends inside the header of the dataset 58 at line " + std::to_string(delimiter_line));
    header_line.push_back(c.line());
    header.push_back(c.next());
  }
  f.name = trim(header[0]);
  f.function_type = static_cast<int>(integer_field(path, header_line[5], field(header[5], 0, 5), "function type"));
  const long response_node = field(header[5], 41, 10).empty()
                                 ? 0
                                 : integer_field(path, header_line[5], field(header[5], 41, 10), "response node");
  const long response_direction =
      field(header[5], 51, 4).empty()
          ? 0
          : integer_field(path, header_line[5], field(header[5], 51, 4), "response direction");
  if (f.name.empty() || f.name == "NONE")
    f.name = "node " + std::to_string(response_node) + " dir " + std::to_string(response_direction);
  const int form_line = header_line[6];
  const long data_type = integer_field(path, form_line, field(header[6], 0, 10), "ordinate data type");
  const long count = integer_field(path, form_line, field(header[6], 10, 10), "number of data values");
  const long spacing = integer_field(path, form_line, field(header[6], 20, 10), "abscissa spacing");
  if (data_type != 2 && data_type != 4 && data_type != 5 && data_type != 6)
    fail(path, form_line,
         "ordinate data type " + std::to_string(data_type) + ": must be 2, 4 (real) or 5, 6 (complex)");
  if (count < 1 || count > (1L << 28))
    fail(path, form_line, "number of data values " + std::to_string(count) + ": must be in 1..2^28");
  if (spacing != 0 && spacing != 1)
    fail(path, form_line, "abscissa spacing " + std::to_string(spacing) + ": must be 0 or 1");
  f.complex = data_type >= 5;
  f.even = spacing == 1;
  f.x0 = number_field(path, form_line, field(header[6], 30, 13), "abscissa minimum");
  f.dx = number_field(path, form_line, field(header[6], 43, 13), "abscissa increment");
  f.unit = field(header[8], 46, 21);
  f.ordinate_line = header_line[8];
  const std::string ordinate_type = field(header[8], 0, 10);
  f.ordinate_type = ordinate_type.empty()
                        ? 0
                        : static_cast<int>(integer_field(path, header_line[8], ordinate_type, "ordinate data type"));
  if (f.unit == "NONE") f.unit.clear();
  // Record 8, the abscissa: I10 specific data type, 3I5 unit exponents, then the axis label and units label as
  // record 9's (pyuff and the UFF specification: '%10i%5i%5i%5i %-20s %-20s').
  f.abscissa_line = header_line[7];
  const std::string abscissa_type = field(header[7], 0, 10);
  f.abscissa_type = abscissa_type.empty()
                        ? 0
                        : static_cast<int>(integer_field(path, header_line[7], abscissa_type, "abscissa data type"));
  f.abscissa_unit = field(header[7], 46, 21);
  if (f.abscissa_unit == "NONE") f.abscissa_unit.clear();
  return {data_type, count};
}

// A binary dataset's values (58b), then its closing delimiter.
void read_binary_values(Cursor& c, const std::string& bytes, const std::string& path, int id_line, int delimiter_line,
                        const BinaryLayout& layout, long data_type, long count, std::size_t per_point,
                        std::vector<double>& values) {
  const long data_bytes = layout.data_bytes, byte_order = layout.byte_order;
  const auto wanted = static_cast<std::size_t>(count) * per_point;
  const std::size_t item = data_type == 2 || data_type == 5 ? 4 : 8;
  if (static_cast<std::size_t>(data_bytes) != wanted * item)
    fail(path, id_line,
         std::to_string(data_bytes) + " data bytes: " + std::to_string(count) + " points of " +
             std::to_string(per_point) + " value(s) of " + std::to_string(item) + " bytes need " +
             std::to_string(wanted * item));
  if (c.byte() + static_cast<std::size_t>(data_bytes) > bytes.size())
    throw InputError(path + ": byte " + std::to_string(c.byte()) + ": the dataset 58b at line " +
                     std::to_string(delimiter_line) + " declares " + std::to_string(data_bytes) +
                     " data bytes; the file has " + std::to_string(bytes.size() - c.byte()) + " left (cut short?)");
  const bool swap = (byte_order == 1) != (std::endian::native == std::endian::little);
  for (std::size_t k = 0; k < wanted; ++k) {
    char buffer[8];
    std::memcpy(buffer, bytes.data() + c.byte() + k * item, item);
    if (swap) std::reverse(buffer, buffer + item);
    double v;
    if (item == 4) {
      float single;
      std::memcpy(&single, buffer, 4);
      v = single;
    } else {
      std::memcpy(&v, buffer, 8);
    }
    if (!std::isfinite(v))
      throw InputError(path + ": byte " + std::to_string(c.byte() + k * item) + ": value " + std::to_string(k + 1) +
                       " of the dataset 58b at line " + std::to_string(delimiter_line) + " is not finite");
    values.push_back(v);
  }
  c.skip_bytes(static_cast<std::size_t>(data_bytes));
  // The rest of the last data line, then the closing delimiter.
  bool closed = false;
  while (!c.done() && !closed) {
    const int at = c.line();
    const std::string rest = trim(c.next());
    closed = rest == "-1";
    if (!closed && !rest.empty()) fail(path, at, "'" + rest.substr(0, 40) + "' after the binary data: expected -1");
  }
  if (!closed)
    fail(path, c.line(),
         "the file ends inside the dataset 58b at line " + std::to_string(delimiter_line) + " (no closing -1)");
}

// An ASCII dataset's values in fixed-width fields, up to its closing delimiter.
void read_ascii_values(Cursor& c, const std::string& path, int delimiter_line, long data_type, long count,
                       std::size_t per_point, bool even, std::vector<double>& values) {
  const auto wanted = static_cast<std::size_t>(count) * per_point;
  // Fixed-width fields: E13.5 for single precision, E20.12 for double; uneven double pairs (E13.5, E20.12).
  bool closed = false;
  while (!c.done()) {
    const int at = c.line();
    const std::string line = c.next();
    if (trim(line) == "-1") {
      closed = true;
      break;
    }
    std::size_t begin = 0;
    for (int k = 0; begin < line.size(); ++k) {
      const bool single = data_type == 2 || data_type == 5;
      // Uneven double precision: each point is an E13.5 abscissa then E20.12 ordinate(s) (one real, two complex).
      const std::size_t width = single ? 13 : (!even && k % per_point == 0 ? 13 : 20);
      const std::string text = field(line, begin, width);
      if (!text.empty()) {
        if (values.size() == wanted)
          fail(path, at, "more values than the header's " + std::to_string(count) + " points");
        const std::string what =
            "value " + std::to_string(values.size() + 1) +
            (data_type == 5 || data_type == 6 ? " of a complex ordinate (data type " + std::to_string(data_type) +
                                                    "; a time record is real: type 2 or 4)"
                                              : " (ordinate data type " + std::to_string(data_type) + ": fields of " +
                                                    std::to_string(width) + " characters)");
        values.push_back(number_field(path, at, text, what));
      }
      begin += width;
    }
  }
  if (!closed)
    fail(path, c.line(),
         "the file ends inside the dataset 58 at line " + std::to_string(delimiter_line) + " (no closing -1)");
}

}  // namespace

std::vector<UffFunction> parse_uff58(const std::string& bytes, const std::string& path) {
  std::vector<UffFunction> functions;
  Cursor c(bytes);
  while (!c.done()) {
    const int delimiter_line = c.line();
    const std::string delimiter = trim(c.next());
    if (delimiter.empty()) continue;
    if (delimiter != "-1")
      fail(path, delimiter_line, "'" + delimiter.substr(0, 40) + "': expected a -1 delimiter line");
    if (c.done()) break;
    const int id_line = c.line();
    const std::string id_text = c.next();
    const std::string id = field(id_text, 0, 6);
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
      fail(path, id_line, "dataset number '" + trim(id_text).substr(0, 40) + "': must be an integer");
    const bool binary = id_text.size() > 6 && std::tolower(static_cast<unsigned char>(id_text[6])) == 'b';
    if (id != "58") {  // another dataset: skipped to its closing delimiter
      while (!c.done() && trim(c.next()) != "-1") {
      }
      continue;
    }
    UffFunction f;
    f.dataset_line = delimiter_line;
    const BinaryLayout layout = binary ? binary_layout(path, id_line, id_text) : BinaryLayout{};
    const auto [data_type, count] = read_header(c, path, delimiter_line, f);
    // Values per point: the ordinate (2 if complex) and, with uneven spacing, the abscissa.
    const std::size_t per_point = (f.complex ? 2 : 1) + (f.even ? 0 : 1);
    const auto wanted = static_cast<std::size_t>(count) * per_point;
    std::vector<double> values;
    values.reserve(std::min<std::size_t>(wanted, bytes.size()));
    if (binary) {
      f.first_value_byte = c.byte();
      read_binary_values(c, bytes, path, id_line, delimiter_line, layout, data_type, count, per_point, values);
    } else {
      f.first_value_line = c.line();
      read_ascii_values(c, path, delimiter_line, data_type, count, per_point, f.even, values);
    }
    if (values.size() != wanted)
      fail(path, delimiter_line,
           "the dataset holds " + std::to_string(values.size()) + " values: its header says " + std::to_string(count) +
               " points of " + std::to_string(per_point) +
               (f.complex ? " (ordinate data type " + std::to_string(data_type) +
                                " is complex, two values a point; a time record is real: type 2 or 4)"
                          : std::string()));
    for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
      if (!f.even) f.x.push_back(values[k * per_point]);
      f.y.push_back(values[k * per_point + (f.even ? 0 : 1)]);  // the real part of a complex ordinate
    }
    functions.push_back(std::move(f));
  }
  return functions;
}

}  // namespace beamid::io
