// The text formats of the record readers (io/record_samples.h): CSV, LabVIEW .lvm and plain text tables.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/errors.h"
#include "io/record_samples.h"
#include "io/text.h"
#include "io/units.h"

namespace beamid::io {
namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r"), last = s.find_last_not_of(" \t\r");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, separator)) fields.push_back(trim(field));
  if (!line.empty() && line.back() == separator) fields.emplace_back();
  return fields;
}

// Decimals printed after the point (0 without one; exponent forms count as many as printed in the mantissa).
int decimals(const std::string& text) {
  const auto dot = text.find('.');
  if (dot == std::string::npos) return 0;
  const auto end = text.find_first_of("eE", dot);
  return static_cast<int>((end == std::string::npos ? text.size() : end) - dot - 1);
}

// The raw table of a file: column names, units and rows of text, with the line number of each row.
struct Table {
  std::string format;
  std::vector<std::string> names;
  std::vector<std::string> units;          // per column ("" when unknown)
  std::vector<std::string> unit_problems;  // per column: why its name's unit cannot be taken ("" when it can)
  int time_column = 0;                     // -1: time from x0 + i delta (LVM X_Columns No)
  double x0 = 0, delta = 0;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> line_of;
  long declared_samples = 0;  // LVM "Samples" of the segment header (0: not given)
  int names_line = 1;         // the line of the column names
};

// The word in a column's name that marks it as a spectrum rather than samples in time ("" when none): the real
// Impulse_test.lvm holds "Acceleration (FFT - (RMS))" in dB against frequency under a header that says X_Dimension
// Time, and its values read as a time series gave a "mode" at 1.6e-4 Hz without a word. Whole words only, any case.
std::string spectrum_word(const std::string& name) {
  static constexpr const char* words[] = {"fft", "psd", "asd", "spectrum", "spectra", "frf", "db", "autopower"};
  std::string word;
  for (std::size_t i = 0; i <= name.size(); ++i) {
    const unsigned char c = i < name.size() ? static_cast<unsigned char>(name[i]) : ' ';
    if (std::isalnum(c)) {
      word += static_cast<char>(std::tolower(c));
      continue;
    }
    for (const char* w : words)
      if (word == w) return name.substr(i - word.size(), word.size());
    word.clear();
  }
  return "";
}

// The words of a name, lower case, split at '_', ' ', '-', '.' and brackets ("freq_Hz" gives freq, hz).
std::vector<std::string> words_of(const std::string& name) {
  std::vector<std::string> words(1);
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      words.back() += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!words.back().empty())
      words.emplace_back();
  }
  if (words.back().empty()) words.pop_back();
  return words;
}

// Whether a column's name says it holds frequencies (a spectrum's axis: "freq_Hz", "bin", "frequency_hz") or times
// ("time_s", "t"): neither is a record's time column or signal, as their names say (the sixth pass's S070, S137,
// S477: a spectrum's axis was read as seconds, a time column as the vibration).
// Only the name before a first comma or semicolon: "v (tip), filtered 2 kHz" holds a remark, not frequencies (the
// seventh pass's L26); an angular frequency ("omega_rad_s") or a speed in rpm is a frequency too (Q104).
bool names_frequency(const std::string& name) {
  for (const std::string& w : words_of(name.substr(0, std::min(name.find_first_of(",;"), name.size()))))
    if (w == "hz" || w == "khz" || w == "freq" || w == "frequency" || w == "frequencies" || w == "bin" || w == "bins" ||
        w == "omega" || w == "rpm")
      return true;
  return false;
}
bool names_time(const std::string& name) {
  const std::vector<std::string> words = words_of(name);
  return !words.empty() && (words.front() == "t" || words.front() == "time" || words.front() == "timestamp");
}

Table read_csv(std::istream& in, const std::string& path) {
  Table t;
  t.format = "csv";
  std::string line;
  if (!std::getline(in, line)) throw InputError(path + ": empty file (expected a header such as t_s,displacement_m)");
  t.names = split(line, ',');
  if (t.names.size() < 2)
    throw InputError(path + ":1: header '" + shown(trim(line)) +
                     "': must name at least two columns separated by commas (time in s, then one or more signals)");
  // A file without a header would lose its first sample as "names" (issue 30): a first line of numbers is refused.
  bool numbers = true;
  for (const auto& n : t.names) {
    numbers = numbers && decimal_number(trim(n)).has_value();
  }
  if (numbers)
    throw InputError(path + ":1: '" + shown(trim(line)) +
                     "': the first line holds numbers, not column names: a CSV record starts with a header such as "
                     "t_s,displacement_m");
  // A comma inside a name's brackets ("x (mm, tip)") splits it in two: named as such, not counted as two signal
  // columns (the eighth pass's U_w01).
  for (std::size_t j = 0; j + 1 < t.names.size(); ++j) {
    const auto open = [](const std::string& n) {
      return std::count(n.begin(), n.end(), '(') + std::count(n.begin(), n.end(), '[') +
             std::count(n.begin(), n.end(), '{') - std::count(n.begin(), n.end(), ')') -
             std::count(n.begin(), n.end(), ']') - std::count(n.begin(), n.end(), '}');
    };
    if (open(t.names[j]) > 0 && open(t.names[j + 1]) < 0)
      throw InputError(path + ":1: columns " + std::to_string(j + 1) + " and " + std::to_string(j + 2) + " ('" +
                       shown(trim(t.names[j])) + "' and '" + shown(trim(t.names[j + 1])) +
                       "'): a comma inside a name's brackets splits it (CSV separates columns by commas): write the "
                       "remark with ';' (x (mm; tip)) or without the comma");
  }
  // Names as pandas and spreadsheets write them, "t_s","accel_g": the quotes are no part of the name. A quoted name
  // holding a comma was split at it: said, not read as two columns. A nameless column is not silently skipped.
  for (std::size_t j = 0; j < t.names.size(); ++j) {
    std::string name = trim(t.names[j]);
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = trim(name.substr(1, name.size() - 2));
    // A quote left in the name: half of a quoted name that held a comma (split at it), or a quote of its own
    // ("x (\")", inches as a double prime: the seventh pass's U016 was told of a comma it did not hold).
    const bool split_at_comma = !name.empty() && (name.front() == '"') != (name.back() == '"');
    if (name.find('"') != std::string::npos)
      throw InputError(path + ":1: column " + std::to_string(j + 1) + " '" + shown(name) + "': " +
                       (split_at_comma ? "a quoted name holding a comma is not read (beamid splits the header at every "
                                         "comma): rename the column without commas"
                                       : "a double quote inside a name is not read (is it inches? write 'in')"));
    if (name.empty())
      throw InputError(path + ":1: column " + std::to_string(j + 1) +
                       " has no name: every column of a record is "
                       "named (time in s first, then the signals)");
    t.names[j] = name;
  }
  // The time column is in seconds: one named in another unit ("t_ms", "Time [ms]", "time_msec") would be read 1000x
  // off (io/units.h).
  const std::string time = t.names.front();
  if (const std::string unit = time_unit_of_column_name(time); !unit.empty() && unit != "s")
    throw InputError(path + ":1: time column '" + shown(time) + "' is in " + unit +
                     ": beamid reads the time in seconds (convert it, e.g. t_s)");
  if (const std::string problem = column_unit_problem(time); !problem.empty())
    throw InputError(path + ":1: time column '" + shown(time) + "': " + problem);
  if (names_frequency(time))
    throw InputError(path + ":1: first column '" + shown(time) +
                     "': its name says frequency: beamid reads time series (time in s first), not spectra");
  // A unit in the name, "accel_g", "v_mm_s" or "accel (g)", is taken as the column's unit (io/units.h).
  for (const auto& n : t.names)
    t.units.push_back(unit_of_column_name(n)), t.unit_problems.push_back(column_unit_problem(n));
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) continue;
    t.rows.push_back(split(line, ','));
    t.line_of.push_back(number);
  }
  return t;
}

// The fields of a whitespace-separated line (tabs, spaces; a comma too, as some exports end fields with one).
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  for (const char c : line) {
    if (c == ' ' || c == '\t' || c == ',' || c == '\r') {
      if (!field.empty()) out.push_back(field), field.clear();
    } else {
      field += c;
    }
  }
  if (!field.empty()) out.push_back(field);
  return out;
}

// A line whose space- or tab-separated tokens are numbers written with a decimal comma ("0,0010000000 -0,1234"), as
// a European locale's export writes them: read with the comma as a separator, it had "3 signal columns" or a time
// "printed to 1 s" (the seventh pass's T10, T62). Two or more such tokens, each digits, one comma, digits.
bool decimal_commas(const std::string& line) {
  int found = 0, tokens = 0;
  std::string token;
  const auto judge = [&] {
    if (token.empty()) return;
    ++tokens;
    std::size_t i = token[0] == '-' || token[0] == '+' ? 1 : 0;
    const std::size_t comma = token.find(',');
    const bool digits_before =
        comma != std::string::npos && comma > i &&
        std::all_of(token.begin() + static_cast<long>(i), token.begin() + static_cast<long>(comma),
                    [](unsigned char c) { return std::isdigit(c); });
    const std::string after = comma == std::string::npos ? "" : token.substr(comma + 1);
    const auto exponent = after.find_first_of("eE");
    const std::string mantissa = after.substr(0, exponent);
    if (digits_before && !mantissa.empty() &&
        std::all_of(mantissa.begin(), mantissa.end(), [](unsigned char c) { return std::isdigit(c); }))
      ++found;
    token.clear();
  };
  for (const char c : line) {
    if (c == ' ' || c == '\t' || c == '\r')
      judge();
    else
      token += c;
  }
  judge();
  return found >= 2 && found == tokens;
}

[[noreturn]] void refuse_decimal_commas(const std::string& path, int line, const std::string& text) {
  throw InputError(path + ":" + std::to_string(line) + ": '" + shown(text, 60) +
                   "': numbers with a decimal comma; beamid reads a point as the decimal separator (export with a "
                   "point, or replace the commas)");
}

bool all_numbers(const std::vector<std::string>& fields) {
  for (const auto& cell : fields)
    if (!decimal_number(cell)) return false;
  return !fields.empty();
}

// A plain text table (.txt, .dat, .tsv, .asc): numbers separated by tabs or spaces, time in s in the first column,
// blank lines and lines starting with # or % skipped, with or without a line of column names first. As a DAQ's
// "save as text" writes it: the UnB impact records (studies/data/unb-steel-tipmass) are a blank line, then rows of
// time, an unused channel, acceleration and hammer force. Without names its columns are "column K" (K counted in
// the file), chosen by --channel as any record's (the signals counted 1-based, or the name), and it states no unit:
// the caller must give one (text_samples).
Table read_plain(std::istream& in, const std::string& path) {
  Table t;
  t.format = "text";
  std::string line;
  int number = 0;
  std::vector<std::string> first;
  while (first.empty() && std::getline(in, line)) {
    ++number;
    const std::string l = trim(line);
    if (l.empty() || l[0] == '#' || l[0] == '%') continue;
    if (decimal_commas(l)) refuse_decimal_commas(path, number, l);
    first = fields_of(l);
  }
  if (first.empty()) throw InputError(path + ": no rows (expected a table of numbers: time in s, then the signals)");
  const bool named = !all_numbers(first);
  if (named) {
    // Names separated by tabs where there are tabs ("Accel (g)" holds a space), else by spaces.
    t.names = line.find('\t') != std::string::npos ? split(trim(line), '\t') : first;
    for (auto& n : t.names) n = trim(n);
    t.names_line = number;
    // Names split at spaces (no tabs) that cut a bracket ("t_s x (mm)" gave the columns x and (mm): the ninth pass's
    // sp1): the names must not hold spaces there.
    for (const std::string& n : t.names)
      if (!n.empty() && (n.front() == '(' || n.front() == '[' || n.front() == '{'))
        throw InputError(path + ":" + std::to_string(number) + ": '" + shown(trim(line), 60) +
                         "': the names are separated by spaces, and '" + shown(n) +
                         "' is a unit or remark cut from its name: separate the names by tabs, or write them "
                         "without spaces (x_mm)");
  } else {
    // The first column is the time, the others the signals, named as --channel counts them ("signal 2" is
    // --channel 2; they were "column 3" for --channel 2, and --channel 'column 2' picked another: the seventh pass's
    // T55).
    for (std::size_t k = 0; k < first.size(); ++k) t.names.push_back(k == 0 ? "time" : "signal " + std::to_string(k));
    t.names_line = 0;
    t.rows.push_back(first);
    t.line_of.push_back(number);
  }
  if (t.names.size() < 2)
    throw InputError(path + ":" + std::to_string(number) + ": '" + shown(trim(line)) +
                     "': 1 column: a record is a time column in s and at least one signal");
  for (const auto& n : t.names)
    t.units.push_back(named ? unit_of_column_name(n) : ""),
        t.unit_problems.push_back(named ? column_unit_problem(n) : "");
  if (named) {
    if (names_frequency(t.names.front()))
      throw InputError(path + ":" + std::to_string(number) + ": first column '" + shown(t.names.front()) +
                       "': its name says frequency: beamid reads time series (time in s first), not spectra");
    if (const std::string unit = time_unit_of_column_name(t.names.front()); !unit.empty() && unit != "s")
      throw InputError(path + ":" + std::to_string(number) + ": time column '" + shown(t.names.front()) + "' is in " +
                       unit + ": beamid reads the time in seconds (convert it)");
  }
  while (std::getline(in, line)) {
    ++number;
    const std::string l = trim(line);
    if (l.empty() || l[0] == '#' || l[0] == '%') continue;
    if (t.rows.empty() && decimal_commas(l)) refuse_decimal_commas(path, number, l);  // the first row after names
    t.rows.push_back(fields_of(l));
    t.line_of.push_back(number);
  }
  return t;
}

// A Y column's unit: its Y_Unit_Label, else the unit its name states ("disp (mm)", read as a CSV column's name; an
// empty label beside that name was read as metres, 1e3 off: the fifth pass's R104). A name and a label that
// disagree are a problem to name, not a choice to make (R105).
void set_lvm_units(Table& t, const std::vector<std::string>& y_units) {
  int y = 0;
  for (std::size_t i = 0; i < t.names.size(); ++i) {
    const bool time = t.time_column == 0 && i == 0;
    if (time) {
      t.units.push_back("s"), t.unit_problems.push_back("");
      continue;
    }
    const std::string label =
        y < static_cast<int>(y_units.size()) ? normalized_unit(y_units[static_cast<std::size_t>(y)]) : "";
    ++y;
    const std::string named = unit_of_column_name(t.names[i]);
    std::string problem = column_unit_problem(t.names[i]);
    if (problem.empty() && !label.empty() && !named.empty() && named != label)
      problem = "its name states " + named + " and the header's Y_Unit_Label states " + label + ": they must agree";
    t.units.push_back(label.empty() ? named : label), t.unit_problems.push_back(problem);
  }
}

// An LVM header's X0 or Delta_X on its line: a finite number, and a step that advances (Delta_X = 0 or -0.001 was
// accepted beside an X column: the fourth pass's Q218, Q219).
double time_base_number(const std::string& key, const std::string& value, const std::string& path, int number) {
  const std::optional<double> read = decimal_number(value);
  const double v = read.value_or(std::nan(""));
  if (!std::isfinite(v))
    throw InputError(path + ":" + std::to_string(number) + ": " + key + " = '" + shown(value) +
                     "': must be a finite number");
  if (key == "Delta_X" && !(v > 0))
    throw InputError(path + ":" + std::to_string(number) + ": Delta_X = " + format_value(v) + ": must be > 0 s");
  return v;
}

// With X_Columns Multi every channel's X column must be the first's: channel 1's times were used for every channel
// without a check (the fifth pass's R135). Equal to the coarser of the two printed resolutions.
void check_x_columns(const std::vector<std::string>& fields, const std::vector<std::string>& names,
                     const std::string& path, int number) {
  for (std::size_t c = 2; c < fields.size() && c < names.size(); c += 2) {
    const std::string &first = fields[0], &other = fields[c];
    if (trim(other).empty() || other == first) continue;
    const double a = std::strtod(first.c_str(), nullptr), b = std::strtod(other.c_str(), nullptr);
    const double resolution = std::pow(10.0, -std::min(decimals(first), decimals(other)));
    if (!(std::abs(a - b) <= 0.5 * resolution * (1 + 1e-9)))
      throw InputError(path + ":" + std::to_string(number) + ": X column " + std::to_string(c + 1) + " ('" +
                       shown(names[c]) + "') = " + shown(trim(other)) + " s differs from the first X column's " +
                       shown(trim(first)) +
                       " s: channels sampled at other times are not one record (save each to its own file)");
  }
}

// LabVIEW measurement text: a file header and one segment header, each ending in ***End_of_Header***, then a line
// of column names and the data. Keys read: Separator, Decimal_Separator, X_Columns, Y_Unit_Label, X0, Delta_X.
// A positive integer header value ("Samples", "Channels"), or 0.
long positive_count(const std::string& value) {
  char* end = nullptr;
  const long n = std::strtol(value.c_str(), &end, 10);
  return !value.empty() && end == value.c_str() + value.size() && n > 0 ? n : 0;
}

// What an LVM header states that the reader uses.
struct LvmHeader {
  char separator = '\t';
  std::string x_columns = "One";
  long declared_channels = 0;  // the segment header's Channels (0: not given)
  int channels_line = 0;
  std::vector<std::string> y_units;
};

// The header up to its second ***End_of_Header*** line (the time base and sample count go into t), `number` the last
// line read.
LvmHeader read_lvm_header(std::istream& in, const std::string& path, int& number, Table& t) {
  LvmHeader h;
  std::string line;
  int headers = 0;
  if (!std::getline(in, line) || line.rfind("LabVIEW Measurement", 0) != 0)
    throw InputError(path +
                     ":1: not a LabVIEW measurement file (the first line must start with 'LabVIEW Measurement')");
  number = 1;
  while (headers < 2 && std::getline(in, line)) {
    ++number;
    const std::string l = trim(line);
    if (l.rfind("***End_of_Header***", 0) == 0) {
      ++headers;
      continue;
    }
    const auto fields = split(l, '\t');
    if (fields.empty()) continue;
    const std::string& key = fields[0];
    const std::string value = fields.size() > 1 ? fields[1] : "";
    if (key == "Separator") {
      if (value != "Tab" && value != "Comma")
        throw InputError(path + ":" + std::to_string(number) + ": Separator = '" + value + "': must be Tab or Comma");
      h.separator = value == "Tab" ? '\t' : ',';
    } else if (key == "Decimal_Separator" && value != ".") {
      throw InputError(path + ":" + std::to_string(number) + ": Decimal_Separator = '" + value +
                       "': only '.' is supported (re-export with a point as decimal separator)");
    } else if (key == "X_Columns") {
      if (value != "One" && value != "Multi" && value != "No")
        throw InputError(path + ":" + std::to_string(number) + ": X_Columns = '" + value +
                         "': must be One, Multi or No");
      h.x_columns = value;
    } else if (key == "X_Dimension") {
      // One field per channel: each must be Time (a second channel marked Frequency was read as a time series:
      // the sixth pass's S094).
      for (std::size_t f = 1; f < fields.size(); ++f)
        if (!fields[f].empty() && fields[f] != "Time")
          throw InputError(path + ":" + std::to_string(number) + ": X_Dimension = '" + fields[f] + "' (channel " +
                           std::to_string(f) +
                           "): must be Time (beamid reads time series; a spectrum's peaks are what `beamid spikes` "
                           "finds in a time record)");
    } else if (key == "Y_Unit_Label") {
      h.y_units.assign(fields.begin() + 1, fields.end());
    } else if (key == "X0" || key == "Delta_X") {
      (key == "X0" ? t.x0 : t.delta) = time_base_number(key, value, path, number);
    } else if (key == "Samples") {
      if (const long n = positive_count(value)) t.declared_samples = n;
    } else if (key == "Channels") {
      h.declared_channels = positive_count(value), h.channels_line = number;
      // A count that is no positive number says nothing the data can be checked against (the eighth pass's L_lc0).
      if (h.declared_channels == 0)
        throw InputError(path + ":" + std::to_string(number) + ": Channels = '" + value +
                         "': must be a positive whole number (the segment's channel count)");
    }
  }
  if (headers < 2) throw InputError(path + ": the header does not end (two ***End_of_Header*** lines expected)");
  return h;
}

Table read_lvm(std::istream& in, const std::string& path) {
  Table t;
  t.format = "lvm";
  std::string line;
  int number = 0;
  const LvmHeader h = read_lvm_header(in, path, number, t);
  const char separator = h.separator;
  const std::string& x_columns = h.x_columns;
  // The column-name line.
  while (std::getline(in, line)) {
    ++number;
    if (!trim(line).empty()) break;
  }
  auto names = split(line, separator);
  while (!names.empty() && (names.back().empty() || names.back() == "Comment")) names.pop_back();
  if (names.empty()) throw InputError(path + ":" + std::to_string(number) + ": expected the column names");
  if (names.size() < 2 && x_columns != "No")
    throw InputError(path + ":" + std::to_string(number) + ": column names '" + shown(trim(line)) +
                     "': 1 column with " + (separator == ',' ? "Separator Comma" : "Separator Tab") +
                     ": must be a time column and at least one signal (does the header's Separator match the data?)");
  // Keep the time column (the first X column) and the Y columns; with X_Columns Multi every Y has its own X column,
  // and only the first is kept (they are equal for a single-rate task).
  std::vector<int> keep;
  for (int c = 0; c < static_cast<int>(names.size()); ++c) {
    const bool is_x = x_columns == "Multi" ? c % 2 == 0 : (x_columns == "One" && c == 0);
    if (!is_x || c == 0) keep.push_back(c);
  }
  t.time_column = x_columns == "No" ? -1 : 0;
  if (t.time_column < 0 && !(t.delta > 0)) throw InputError(path + ": X_Columns = No needs Delta_X > 0 in the header");
  std::vector<std::string> kept_names;
  for (int c : keep) kept_names.push_back(names[static_cast<std::size_t>(c)]);
  t.names = kept_names;
  t.names_line = number;
  // The segment header's channel count against the Y columns (a "Channels 2" over one channel was read without a
  // word, while a Samples count that disagrees is refused: the seventh pass's L10).
  const long y_columns = static_cast<long>(kept_names.size()) - (t.time_column >= 0 ? 1 : 0);
  if (h.declared_channels > 0 && h.declared_channels != y_columns)
    throw InputError(path + ":" + std::to_string(h.channels_line) +
                     ": Channels = " + std::to_string(h.declared_channels) + ": the data below have " +
                     std::to_string(y_columns) + " channel column(s) (line " + std::to_string(number) +
                     "): the header and the data disagree (an edited or a cut file?)");
  set_lvm_units(t, h.y_units);
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) continue;
    // A second segment (its own header, ending in ***End_of_Header***) was reported as a non-number in X_Value.
    if (line.rfind("***End_of_Header***", 0) == 0 || line.rfind("Channels", 0) == 0)
      throw InputError(path + ":" + std::to_string(number) +
                       ": a second segment begins here: beamid reads LVM files of one segment (save each segment, or "
                       "each run, to its own file)");
    const auto fields = split(line, separator);
    if (x_columns == "Multi") check_x_columns(fields, names, path, number);
    std::vector<std::string> row;
    for (int c : keep) row.push_back(c < static_cast<int>(fields.size()) ? fields[static_cast<std::size_t>(c)] : "");
    t.rows.push_back(row);
    t.line_of.push_back(number);
  }
  return t;
}

// An LVM with an X column and a header Delta_X: the two must agree to 1 % (a Delta_X of 0.002 beside a column stepping
// 0.001 was settled silently in the column's favour: the second pass's N080). Where the column resolves single steps
// it is the record's time base, checked as any column (Delta_X itself is printed to a few digits: the steel record's
// 0.000605 is 0.075 % below its column's step, 0.00060545). Where it is printed too coarsely to (3 decimals at
// 0.6 ms: "repeats the previous sample's time", N079) the time base is t_0 + i step with the header's Delta_X, the
// sampling interval the DAQ states, when every printed time agrees with it to its printed resolution (a column
// rounded to 10 ms beside Delta_X = 0.001 gave the column's mean step, 0.3 % off, and every frequency with it: the
// fourth pass's Q214); else with the column's mean step (t_last - t_0)/(n - 1) when every printed time agrees with
// that; else the record is refused on the first line that agrees with neither. The notes say which step was used.
void use_mean_step_when_coarse(Samples& out, const Table& table, const std::string& path, int time_decimals) {
  const double delta = table.delta, t0 = out.t.front(), resolution = out.time_resolution;
  const double n = static_cast<double>(out.t.size());
  const double mean_step = (out.t.back() - t0) / (n - 1);
  // The first sample whose printed time is more than its resolution from t_0 + i step (n when none is).
  const auto first_off = [&](double step) {
    std::size_t i = 0;
    while (i < out.t.size() && std::abs(out.t[i] - (t0 + static_cast<double>(i) * step)) <= resolution * (1 + 1e-9))
      ++i;
    return i;
  };
  // A coarse column's mean step is uncertain by its resolution / (n - 1), which on a short record exceeds 1 %: one
  // that agrees with Delta_X at every printed time is no disagreement (the fifth pass's R120).
  const bool coarse = resolution > 0.5 * mean_step;
  const bool header = coarse && first_off(delta) == out.t.size();
  if (!header && !(std::abs(mean_step - delta) <= 1e-2 * delta))
    throw InputError(path + ":" + std::to_string(table.line_of.back()) + ": the X column steps " +
                     format_value(mean_step) + " s on average but the header's Delta_X is " + format_value(delta) +
                     " s: the header and the data disagree (which one is the record's?)");
  if (!coarse) return;  // the column resolves its steps: they are checked as any column's
  const double step = header ? delta : mean_step;
  if (const std::size_t i = first_off(step); i < out.t.size())
    throw InputError(path + ":" + std::to_string(table.line_of[i]) + ": X = " + format_value(out.t[i]) +
                     " s is more than its printed resolution " + format_value(resolution) +
                     " s from a uniform time base of step " + format_value(step) +
                     " s (the X column's mean; Delta_X = " + format_value(delta) +
                     " agrees with it no better): the record is not uniformly sampled, or a sample is missing");
  for (std::size_t i = 0; i < out.t.size(); ++i) out.t[i] = t0 + static_cast<double>(i) * step;
  out.time_in_file = false;
  out.time_resolution = 0;
  out.series.notes += "uniform time base of step " + format_value(step) + " s, " +
                      (header ? std::string("the header's Delta_X, which every printed time agrees with")
                              : "the X column's mean step from its ends (Delta_X = " + format_value(delta) +
                                    " s agrees to 1 %, but not with every printed time)") +
                      "; the X column, printed to " + std::to_string(time_decimals) +
                      " decimals, does not resolve single steps; ";
}

double parse(const std::string& path, int line, const std::string& column, const std::string& text) {
  const std::optional<double> read = decimal_number(text);
  if (!read)
    throw InputError(path + ":" + std::to_string(line) + ": " + column + " = '" + shown(text) + "': must be a number");
  const double v = *read;
  if (!std::isfinite(v))
    throw InputError(path + ":" + std::to_string(line) + ": " + column + " = " + shown(text) + ": must be finite");
  return v;
}

}  // namespace

std::optional<std::string> binary_text_problem(std::string_view text, const std::string& path) {
  // Text holds no control characters but tab, line feed and carriage return (and form feed, harmlessly).
  const auto binary = std::find_if(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f';
  });
  if (binary == text.end()) return std::nullopt;
  return path + ": byte " + std::to_string(binary - text.begin()) + " is 0x" +
         "0123456789abcdef"[(static_cast<unsigned char>(*binary) >> 4) & 15] +
         "0123456789abcdef"[static_cast<unsigned char>(*binary) & 15] +
         ": a binary file of no format beamid reads (it reads CSV, LabVIEW .lvm and plain table text, NumPy .npy, "
         "MATLAB .mat v5 "
         "and v7.3, and UFF dataset 58 ASCII or binary)";
}

bool is_plain_text_path(const std::string& path) {
  std::string lower = path;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* ending : {".txt", ".dat", ".tsv", ".asc"})
    if (lower.ends_with(ending)) return true;
  return false;
}

namespace {

// The length of the valid UTF-8 sequence at text[i] (1 for ASCII), or 0 when the bytes there are not UTF-8.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || (n == 2 && c < 0xc2) || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((byte(i + k) >> 6) != 0x2) return 0;
  return n;
}

// Names and units are read as UTF-8: a header written in Latin-1 or Windows-1252 (Windows DAQ software's "ANSI")
// spells the micro sign as the single byte 0xB5, which matched no unit, and "x (\xb5m)" was read as metres, 1e6 x
// off (the seventh pass's T65). Refused on its line, with the byte.
void check_utf8(std::string_view text, const std::string& path) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_length(text, i);
    if (n > 0) {
      i += n;
      continue;
    }
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(i), '\n');
    const auto u = static_cast<unsigned char>(text[i]);
    throw InputError(path + ":" + std::to_string(line) + ": byte 0x" + "0123456789ABCDEF"[u >> 4] +
                     "0123456789ABCDEF"[u & 15] +
                     " is not UTF-8: the file is likely Latin-1 or Windows-1252 (where 0xB5 is the micro sign, 0xB0 "
                     "the degree sign), whose "
                     "names and units beamid would misread; save it as UTF-8");
  }
}

}  // namespace

Samples text_samples(const std::string& given, const std::string& path, const ImportOptions& o) {
  // A UTF-8 byte order mark (Notepad writes one) is no part of the first line: an LVM file with one was "not a
  // LabVIEW measurement file" (the seventh pass's L12).
  const bool bom = given.starts_with("\xEF\xBB\xBF");
  const std::string stripped = bom ? given.substr(3) : std::string();
  const std::string& text = bom ? stripped : given;
  if (auto problem = binary_text_problem(text, path)) throw InputError(*problem);
  check_utf8(text, path);
  // Lines ended by a bare carriage return (classic Mac OS) read as one line of a thousand columns (the third pass's
  // P064); one bare CR among LF lines merged two lines into "3 fields: must be 2" (the sixth pass's S099). Said as
  // such, with its line.
  for (std::size_t cr = text.find('\r'); cr != std::string::npos; cr = text.find('\r', cr + 1)) {
    if (cr + 1 < text.size() && text[cr + 1] == '\n') continue;
    if (cr + 1 == text.size()) break;  // a last line ended by CR alone is read as it is
    if (text.find('\n') == std::string::npos)
      throw InputError(path +
                       ": its lines end in a bare carriage return (CR, as classic Mac OS wrote): convert them to "
                       "line feeds (LF) or CR LF");
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(cr), '\n');
    throw InputError(path + ":" + std::to_string(line) +
                     ": a bare carriage return (CR) ends this line where the others end in a line feed: mixed line "
                     "endings join two lines; convert the file's line endings to LF or CR LF");
  }
  std::istringstream in(text);
  const Table table = path.ends_with(".lvm")     ? read_lvm(in, path)
                      : is_plain_text_path(path) ? read_plain(in, path)
                                                 : read_csv(in, path);

  Samples out;
  TimeSeries& s = out.series;
  s.path = path;
  s.format = table.format;
  std::vector<int> signals;
  std::vector<std::string> names;
  for (int c = 0; c < static_cast<int>(table.names.size()); ++c)
    if (c != table.time_column) signals.push_back(c), names.push_back(table.names[static_cast<std::size_t>(c)]);
  const int column = signals[choose_channel(names, o, path, "signal columns")];
  s.time_column = table.time_column >= 0 ? table.names[static_cast<std::size_t>(table.time_column)] : "time";
  s.value_column = table.names[static_cast<std::size_t>(column)];
  s.unit = table.units[static_cast<std::size_t>(column)];
  if (names_frequency(s.value_column) || names_time(s.value_column))
    throw InputError(path + ":" + std::to_string(table.names_line) + ": column '" + shown(s.value_column) +
                     "': its name says it holds " + (names_time(s.value_column) ? "times" : "frequencies") +
                     ", not the vibration: choose the signal column with --channel");
  if (const std::string word = spectrum_word(s.value_column); !word.empty())
    throw InputError(path + ":" + std::to_string(table.names_line) + ": column '" + shown(s.value_column) +
                     "': its name says " + word +
                     ": beamid reads time series, not spectra (a spectrum's peaks are what `beamid spikes` finds in "
                     "a time record; rename the column if it does hold samples in time)");
  // A table without names states no unit: the user says which (its values were taken as SI).
  if (table.format == "text" && table.names_line == 0 && o.units == "auto")
    throw InputError(path + ": column '" + s.value_column +
                     "': the table names no columns, so it states no unit: give --units g for an accelerometer in g, "
                     "or --units as-is to take the values as SI (m, m/s, m/s^2)");
  // An LVM states its unit in Y_Unit_Label; a blank label (and no unit in the column's name) states none, and a record
  // in g was read as m/s^2, 9.81x off, as a table without names had been (the twelfth pass's P8).
  if (table.format == "lvm" && o.units == "auto" && column < static_cast<int>(table.units.size()) &&
      table.units[static_cast<std::size_t>(column)].empty())
    throw InputError(path + ": column '" + s.value_column +
                     "': its Y_Unit_Label is blank and its name states no unit: give --units g for an accelerometer "
                     "in g, or --units as-is to take the values as SI (m, m/s, m/s^2)");
  if (o.units == "auto" && column < static_cast<int>(table.unit_problems.size()) &&
      !table.unit_problems[static_cast<std::size_t>(column)].empty())
    throw InputError(path + ":" + std::to_string(table.names_line) + ": column '" + shown(s.value_column) +
                     "': " + table.unit_problems[static_cast<std::size_t>(column)] + " (or give --units as-is)");

  int time_decimals = 0;  // the finest printed resolution (trailing zeros may be dropped on some lines)
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const int line = table.line_of[r];
    if ((table.format != "lvm" && row.size() != table.names.size()) || static_cast<int>(row.size()) <= column ||
        (table.time_column >= 0 && row.empty()))
      throw InputError(path + ":" + std::to_string(line) + ": " + std::to_string(row.size()) + " fields: must be " +
                       std::to_string(table.names.size()) + " (" + s.time_column + ", ..., " + s.value_column + ")");
    if (table.time_column >= 0) {
      const std::string& field = row[static_cast<std::size_t>(table.time_column)];
      out.t.push_back(parse(path, line, s.time_column, field));
      time_decimals = std::max(time_decimals, decimals(field));
    } else {
      out.t.push_back(table.x0 + static_cast<double>(r) * table.delta);
    }
    out.v.push_back(parse(path, line, s.value_column, row[static_cast<std::size_t>(column)]));
  }
  out.time_in_file = table.time_column >= 0;
  out.time_resolution = out.time_in_file ? std::pow(10.0, -time_decimals) : 0;
  if (table.format == "lvm" && out.time_in_file && table.delta > 0 && out.t.size() >= 2)
    use_mean_step_when_coarse(out, table, path, time_decimals);
  const std::vector<int> line_of = table.line_of;
  out.where = [path, line_of](std::size_t i) { return path + ":" + std::to_string(line_of.at(i)); };
  out.declared_samples = table.declared_samples;
  return out;
}

}  // namespace beamid::io
