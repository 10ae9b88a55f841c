#include "io/time_series.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <numbers>
#include <sstream>

#include "io/files.h"
#include "io/mat_file.h"
#include "io/npy.h"
#include "io/resources.h"
#include "io/uff58.h"
#include "model/errors.h"

namespace beamid::io {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g

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

// A field as an error message shows it: at most `limit` characters of message (a 2 MB field is not echoed whole),
// with bytes that are not printable ASCII as \xNN (so that a binary file's bytes never reach the terminal raw).
std::string shown(const std::string& text, std::size_t limit = 40) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  std::size_t i = 0;
  for (; i < text.size() && out.size() < limit; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f)
      out += text[i];
    else
      out += std::string("\\x") + kHex[byte >> 4] + kHex[byte & 15];
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size()) + " characters)";
  return out;
}

// The whole record file: a regular file of at most 1 GiB (the longest real record here is 4 MB; 1 GiB of text is
// about 50 million samples), checked against the memory that parsing it takes before it is parsed.
std::string read_text(const std::string& path) {
  std::string text = read_file(path, "cannot read the file (expected a record: CSV, LabVIEW .lvm, .npy, .mat or UFF)");
  // Parsing holds the text, a table of fields and the numbers: about 5 bytes per byte of file (measured: 800 MB
  // for a 186 MB CSV of 4e6 samples).
  check_memory(path + ": reading " + bytes_text(static_cast<double>(text.size())),
               5.0 * static_cast<double>(text.size()), std::cerr);
  return text;
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
  std::vector<std::string> units;  // per column ("" when unknown)
  int time_column = 0;             // -1: time from x0 + i delta (LVM X_Columns No)
  double x0 = 0, delta = 0;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> line_of;
  long declared_samples = 0;  // LVM "Samples" of the segment header (0: not given)
};

Table read_csv(std::istream& in, const std::string& path) {
  Table t;
  t.format = "csv";
  std::string line;
  if (!std::getline(in, line)) throw InputError(path + ": empty file (expected a header such as t_s,displacement_m)");
  t.names = split(line, ',');
  if (t.names.size() < 2)
    throw InputError(path + ":1: header '" + shown(trim(line)) +
                     "': must name at least two columns separated by commas (time in s, then one or more signals)");
  for (const auto& n : t.names) {
    // A unit in the name, "accel_g" or "accel (g)", is taken as the column's unit.
    const bool g = n.size() > 2 && (n.substr(n.size() - 2) == "_g" || n.find("(g)") != std::string::npos);
    t.units.push_back(g ? "g" : "");
  }
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) continue;
    t.rows.push_back(split(line, ','));
    t.line_of.push_back(number);
  }
  return t;
}

// LabVIEW measurement text: a file header and one segment header, each ending in ***End_of_Header***, then a line
// of column names and the data. Keys read: Separator, Decimal_Separator, X_Columns, Y_Unit_Label, X0, Delta_X.
Table read_lvm(std::istream& in, const std::string& path) {
  Table t;
  t.format = "lvm";
  std::string line;
  int number = 0, headers = 0;
  char separator = '\t';
  std::string x_columns = "One";
  std::vector<std::string> y_units;
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
      separator = value == "Tab" ? '\t' : ',';
    } else if (key == "Decimal_Separator" && value != ".") {
      throw InputError(path + ":" + std::to_string(number) + ": Decimal_Separator = '" + value +
                       "': only '.' is supported (re-export with a point as decimal separator)");
    } else if (key == "X_Columns") {
      if (value != "One" && value != "Multi" && value != "No")
        throw InputError(path + ":" + std::to_string(number) + ": X_Columns = '" + value +
                         "': must be One, Multi or No");
      x_columns = value;
    } else if (key == "Y_Unit_Label") {
      y_units.assign(fields.begin() + 1, fields.end());
    } else if (key == "X0" || key == "Delta_X") {
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(v))
        throw InputError(path + ":" + std::to_string(number) + ": " + key + " = '" + shown(value) +
                         "': must be a finite number");
      (key == "X0" ? t.x0 : t.delta) = v;
    } else if (key == "Samples" && !value.empty()) {
      char* end = nullptr;
      const long n = std::strtol(value.c_str(), &end, 10);
      if (end == value.c_str() + value.size() && n > 0) t.declared_samples = n;
    }
  }
  if (headers < 2) throw InputError(path + ": the header does not end (two ***End_of_Header*** lines expected)");
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
  int y = 0;
  for (std::size_t i = 0; i < t.names.size(); ++i) {
    const bool time = t.time_column == 0 && i == 0;
    t.units.push_back(time ? "s" : (y < static_cast<int>(y_units.size()) ? y_units[static_cast<std::size_t>(y)] : ""));
    if (!time) ++y;
  }
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) continue;
    const auto fields = split(line, separator);
    std::vector<std::string> row;
    for (int c : keep) row.push_back(c < static_cast<int>(fields.size()) ? fields[static_cast<std::size_t>(c)] : "");
    t.rows.push_back(row);
    t.line_of.push_back(number);
  }
  return t;
}

double parse(const std::string& path, int line, const std::string& column, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    throw InputError(path + ":" + std::to_string(line) + ": " + column + " = '" + shown(text) + "': must be a number");
  if (!std::isfinite(v))
    throw InputError(path + ":" + std::to_string(line) + ": " + column + " = " + shown(text) + ": must be finite");
  return v;
}

}  // namespace

TimeSeries read_time_series(const std::string& path, const ImportOptions& o) {
  return parse_time_series(read_text(path), path, o);
}

namespace {

// One channel's samples with their times, as a reader found them, before the checks every format shares.
struct Samples {
  TimeSeries series;  // path, format, column names and the file's unit
  std::vector<double> t, v;
  bool time_in_file = false;   // t read from the file (checked for uniformity), else t0 + i dt
  double time_resolution = 0;  // the file's resolution of its times (a text column's last printed decimal)
  std::function<std::string(std::size_t)> where;  // sample i's place: "path:line" or "path: sample i"
  long declared_samples = 0;                      // LVM "Samples" of the segment header (0: not given)
};

// The channel a reader's names offer: by name, or by 1-based index; the only one when none is asked for.
std::size_t choose_channel(const std::vector<std::string>& names, const std::string& channel, const std::string& path,
                           const std::string& what) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  list = shown(list, 160);  // room for the names of a multi-channel record, not for a binary file's bytes
  if (channel.empty()) {
    if (names.size() != 1)
      throw InputError(path + ": " + std::to_string(names.size()) + " " + what + " (" + list +
                       "): choose one with --channel NAME or --channel INDEX");
    return 0;
  }
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == channel) return c;
  char* end = nullptr;
  const long index = std::strtol(channel.c_str(), &end, 10);
  if (end == channel.c_str() + channel.size() && index >= 1 && index <= static_cast<long>(names.size()))
    return static_cast<std::size_t>(index - 1);
  throw InputError(path + ": channel = '" + channel + "': must be one of " + list + " (or 1.." +
                   std::to_string(names.size()) + ")");
}

Samples text_samples(const std::string& text, const std::string& path, const ImportOptions& o) {
  // Text holds no control characters but tab, line feed and carriage return (and form feed, harmlessly).
  const auto binary = std::find_if(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f';
  });
  if (binary != text.end())
    throw InputError(path + ": byte " + std::to_string(binary - text.begin()) + " is 0x" +
                     "0123456789abcdef"[(static_cast<unsigned char>(*binary) >> 4) & 15] +
                     "0123456789abcdef"[static_cast<unsigned char>(*binary) & 15] +
                     ": a binary file of no format beamid reads (it reads CSV and LabVIEW .lvm text, NumPy .npy, "
                     "MATLAB .mat v5 and v7.3, and UFF dataset 58 ASCII or binary)");
  std::istringstream in(text);
  const bool lvm = path.size() > 4 && path.substr(path.size() - 4) == ".lvm";
  const Table table = lvm ? read_lvm(in, path) : read_csv(in, path);

  Samples out;
  TimeSeries& s = out.series;
  s.path = path;
  s.format = table.format;
  std::vector<int> signals;
  std::vector<std::string> names;
  for (int c = 0; c < static_cast<int>(table.names.size()); ++c)
    if (c != table.time_column) signals.push_back(c), names.push_back(table.names[static_cast<std::size_t>(c)]);
  const int column = signals[choose_channel(names, o.channel, path, "signal columns")];
  s.time_column = table.time_column >= 0 ? table.names[static_cast<std::size_t>(table.time_column)] : "time";
  s.value_column = table.names[static_cast<std::size_t>(column)];
  s.unit = table.units[static_cast<std::size_t>(column)];

  int time_decimals = 0;  // the finest printed resolution (trailing zeros may be dropped on some lines)
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const int line = table.line_of[r];
    if ((table.format == "csv" && row.size() != table.names.size()) || static_cast<int>(row.size()) <= column ||
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
  const std::vector<int> line_of = table.line_of;
  out.where = [path, line_of](std::size_t i) { return path + ":" + std::to_string(line_of.at(i)); };
  out.declared_samples = table.declared_samples;
  return out;
}

// An array of samples x channels (either way round: the samples run along the longer dimension) with its time base
// from --sample-rate, or from a time vector of the same length.
Samples array_samples(const std::string& path, const std::string& format, const std::string& what, std::size_t rows,
                      std::size_t columns, const std::function<double(std::size_t, std::size_t)>& at,
                      const std::vector<double>* time, double time_relative_precision, const ImportOptions& o) {
  Samples out;
  TimeSeries& s = out.series;
  s.path = path;
  s.format = format;
  const bool by_row = rows >= columns;  // samples along the rows: a channel is a column
  const std::size_t samples = by_row ? rows : columns, channels = by_row ? columns : rows;
  std::vector<std::string> names;
  for (std::size_t c = 0; c < channels; ++c) names.push_back(std::to_string(c + 1));
  const std::size_t channel = choose_channel(names, o.channel, path, what + " channels");
  s.value_column = channels == 1 ? what : what + " channel " + names[channel];
  s.time_column = "time";
  for (std::size_t i = 0; i < samples; ++i) out.v.push_back(by_row ? at(i, channel) : at(channel, i));
  if (time) {
    if (time->size() != samples)
      throw InputError(path + ": the time vector has " + std::to_string(time->size()) + " values: must have " +
                       std::to_string(samples) + ", one per sample of " + what);
    out.t = *time;
    out.time_in_file = true;
    // A stored time vector is as precise as its type: one unit in the last place of its largest value (float32:
    // 1.2e-7 of it, double: 4.4e-16), which covers the rounding of each time and of the end points dt comes from.
    double largest = 0;
    for (std::size_t i = 0; i < samples; ++i) {
      if (!std::isfinite(out.t[i]))
        throw InputError(path + ": time value " + std::to_string(i + 1) + " = " + format_value(out.t[i]) +
                         ": must be finite");
      largest = std::max(largest, std::abs(out.t[i]));
    }
    out.time_resolution = time_relative_precision * largest;
  } else {
    if (!o.sample_rate_hz)
      throw InputError(path + ": " + format + " holds no time base: give --sample-rate HZ" +
                       (format == "mat" ? " or --time-variable NAME" : ""));
    for (std::size_t i = 0; i < samples; ++i) out.t.push_back(static_cast<double>(i) / *o.sample_rate_hz);
  }
  out.where = [path](std::size_t i) { return path + ": sample " + std::to_string(i + 1); };
  for (std::size_t i = 0; i < out.v.size(); ++i)
    if (!std::isfinite(out.v[i]))
      throw InputError(out.where(i) + ": " + s.value_column + " = " + format_value(out.v[i]) + ": must be finite");
  return out;
}

Samples uff_samples(const std::string& bytes, const std::string& path, const ImportOptions& o) {
  const std::vector<UffFunction> functions = parse_uff58(bytes, path);
  std::vector<std::string> names;
  std::vector<std::size_t> records;
  std::string other;
  for (std::size_t k = 0; k < functions.size(); ++k) {
    if (functions[k].function_type == 1 && !functions[k].complex) {
      names.push_back(functions[k].name);
      records.push_back(k);
    } else {
      other += (other.empty() ? "" : "; ") + std::string("line ") + std::to_string(functions[k].dataset_line) +
               ": function type " + std::to_string(functions[k].function_type) +
               (functions[k].complex ? ", complex" : "");
    }
  }
  if (names.empty())
    throw InputError(path + ": no real time record (dataset 58 of function type 1) among its " +
                     std::to_string(functions.size()) + " dataset(s) 58" + (other.empty() ? "" : " (" + other + ")"));
  const UffFunction& f = functions[records[choose_channel(names, o.channel, path, "time records (datasets 58)")]];
  Samples out;
  out.series.path = path;
  out.series.format = "uff58";
  out.series.time_column = "time";
  out.series.value_column = f.name;
  out.series.unit = f.unit == "g" || f.unit == "G" ? "g" : f.unit;
  out.v = f.y;
  if (f.even) {
    if (!(f.dx > 0))
      throw InputError(path + ":" + std::to_string(f.dataset_line + 8) + ": abscissa increment " + format_value(f.dx) +
                       ": must be > 0");
    for (std::size_t i = 0; i < f.y.size(); ++i) out.t.push_back(f.x0 + static_cast<double>(i) * f.dx);
  } else {
    out.t = f.x;
    out.time_in_file = true;
    double largest = 0;
    for (double x : f.x) largest = std::max(largest, std::abs(x));
    out.time_resolution = 5e-6 * largest;  // E13.5: six significant digits
  }
  const int first_line = f.first_value_line;
  out.where = [path, first_line](std::size_t i) {
    return first_line > 0
               ? path + ": value " + std::to_string(i + 1) + " (from line " + std::to_string(first_line) + ")"
               : path + ": value " + std::to_string(i + 1);
  };
  return out;
}

// Band-limited resampling onto t0 + i / rate (time_series.h): y(tau) = sum_k x_k h(tau - t_k) / sum_k h(tau - t_k),
// h a Blackman-windowed sinc of cutoff fc = fs/2 when the rate rises (interpolation) and 0.45 rate when it falls (an
// anti-alias low-pass first), spanning +-32 periods of the lower rate: the Blackman window's transition band is then
// about 3/32 of the rate wide, 0.40-0.50 of the new rate when decimating. Dividing by the weights' sum keeps a constant
// constant, also at the record's ends.
void resample_to_rate(TimeSeries& s, double rate, const std::string& path) {
  const double fs = 1 / s.dt_s;
  const auto n = static_cast<double>(s.values.size());
  const double duration = (n - 1) * s.dt_s;
  const double count = std::floor(duration * rate + 1e-9) + 1;
  if (count < 8)
    throw InputError(path + ": --resample-rate " + format_value(rate) + " Hz leaves " + format_value(count) +
                     " samples of the " + format_value(duration) + " s record: at least 8 are needed");
  if (count > 1 << 28)
    throw InputError(path + ": --resample-rate " + format_value(rate) + " Hz would make " + format_value(count) +
                     " samples: at most 2^28");
  check_memory(path + ": resampling to " + format_value(count) + " samples", 8 * count, std::cerr);
  const double cutoff = rate < fs ? 0.45 * rate : 0.5 * fs;
  const double half = 32 / std::min(fs, rate);  // s
  std::vector<double> y(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double tau = static_cast<double>(i) / rate;
    const auto first = static_cast<long>(std::max(0.0, std::ceil((tau - half) * fs)));
    const auto last = static_cast<long>(std::min(n - 1, std::floor((tau + half) * fs)));
    double sum = 0, weights = 0;
    for (long k = first; k <= last; ++k) {
      const double u = tau - static_cast<double>(k) * s.dt_s;
      const double x = 2 * cutoff * u;
      const double sinc = std::abs(x) < 1e-12 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
      const double r = u / half;  // in [-1, 1]
      const double blackman = 0.42 + 0.5 * std::cos(std::numbers::pi * r) + 0.08 * std::cos(2 * std::numbers::pi * r);
      const double h = sinc * blackman;
      sum += h * s.values[static_cast<std::size_t>(k)];
      weights += h;
    }
    y[i] = sum / weights;
  }
  s.notes += "resampled from " + format_value(fs) + " Hz to " + format_value(rate) +
             " Hz by windowed-sinc interpolation" +
             (rate < fs ? " after a low-pass at " + format_value(cutoff) + " Hz" : "") + "; ";
  s.values = std::move(y);
  s.dt_s = 1 / rate;
}

// The checks and cuts every format shares (time_series.h): uniform time base or resampling, clipping, the window,
// the units and the rate.
TimeSeries finish(Samples in, const std::string& path, const ImportOptions& o) {
  TimeSeries s = std::move(in.series);
  std::vector<double>& t = in.t;
  std::vector<double>& v = in.v;
  if (in.declared_samples > 0 && static_cast<long>(v.size()) < in.declared_samples)
    throw InputError(path + ": " + std::to_string(v.size()) + " samples, but the header says Samples = " +
                     std::to_string(in.declared_samples) + ": the file is cut short");
  if (v.size() < 8) throw InputError(path + ": " + std::to_string(v.size()) + " samples: at least 8 are needed");
  // Uniform time base, to the printed resolution of the time column.
  const double t0 = t.front();
  const double dt = (t.back() - t0) / static_cast<double>(t.size() - 1);
  if (!(dt > 0)) throw InputError(path + ": time column " + s.time_column + " does not increase");
  const double tolerance = std::max(1e-6 * dt, in.time_resolution + 1e-9 * dt);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double expected = t0 + static_cast<double>(i) * dt;
    if (std::abs(t[i] - expected) > tolerance) {
      if (o.resample) break;
      throw InputError(in.where(i) + ": " + s.time_column + " = " + format_value(t[i]) +
                       ": non-uniform time base (expected " + format_value(expected) + " = t0 + " + std::to_string(i) +
                       " dt with dt = " + format_value(dt) + " s, to within " + format_value(tolerance) +
                       " s; --resample interpolates instead)");
    }
  }
  if (o.resample) {
    // Linear interpolation onto t0 + i dt (the time column must increase strictly).
    for (std::size_t i = 1; i < t.size(); ++i)
      if (!(t[i] > t[i - 1]))
        throw InputError(in.where(i) + ": " + s.time_column + " = " + format_value(t[i]) +
                         ": must increase to be resampled");
    std::vector<double> u(v.size());
    std::size_t j = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      const double ti = t0 + static_cast<double>(i) * dt;
      while (j + 2 < t.size() && t[j + 1] < ti) ++j;
      const double w = std::clamp((ti - t[j]) / (t[j + 1] - t[j]), 0.0, 1.0);
      u[i] = (1 - w) * v[j] + w * v[j + 1];
    }
    v = u;
    s.notes += "resampled linearly onto a uniform " + format_value(dt) + " s grid; ";
  }
  // Clipping: the largest |value| held by 3 or more consecutive samples.
  double peak = 0;
  for (double x : v) peak = std::max(peak, std::abs(x));
  if (peak == 0) throw InputError(path + ": " + s.value_column + " is 0 in every sample: there is nothing to analyse");
  if (peak > 1e150)
    throw InputError(path + ": " + s.value_column + " reaches " + format_value(peak) +
                     ": beyond 1e150, its spectrum would overflow (rescale the record)");
  const bool constant = std::all_of(v.begin(), v.end(), [&](double x) { return x == v.front(); });
  for (std::size_t i = 0; i + 2 < v.size() && peak > 0 && !constant; ++i)
    if (std::abs(v[i]) == peak && v[i + 1] == v[i] && v[i + 2] == v[i])
      throw InputError(in.where(i) + ": " + s.value_column + " = " + format_value(v[i]) +
                       " on 3 or more consecutive samples at the record's peak: the signal is "
                       "clipped (the DAQ range was exceeded), so its spectrum is distorted");

  // The window: from the sample nearest to start_s, round(duration / dt) samples (nearest, not "t >= start", so
  // that rounded DAQ times and a start given to a few digits pick the intended sample).
  const double start = o.start_s.value_or(t0);
  const double t_end = t0 + static_cast<double>(v.size() - 1) * dt;
  if (!(start >= t0 - 0.5 * dt && start <= t_end))
    throw InputError(path + ": start = " + format_value(start) + " s: must lie inside the record, [" +
                     format_value(t0) + ", " + format_value(t_end) + "] s");
  const double n_total = static_cast<double>(v.size());
  const double first_d = std::max(0.0, std::round((start - t0) / dt));
  const double count_d = o.duration_s ? std::round(*o.duration_s / dt) : n_total - first_d;
  const std::size_t first = static_cast<std::size_t>(std::min(first_d, n_total));
  const std::size_t last = static_cast<std::size_t>(std::clamp(first_d + count_d, first_d, n_total));
  if (last - first < 8 || (o.duration_s && first_d + count_d > n_total))
    throw InputError(path + ": the window of " + format_value(o.duration_s.value_or(n_total * dt)) + " s from " +
                     format_value(start) + " s holds " + std::to_string(last > first ? last - first : 0) +
                     " of the requested samples: at least 8 are needed, all inside the record, which spans [" +
                     format_value(t0) + ", " + format_value(t0 + (n_total - 1) * dt) + "] s");
  s.values.assign(v.begin() + static_cast<long>(first), v.begin() + static_cast<long>(last));
  s.t0_s = t0 + static_cast<double>(first) * dt;
  s.dt_s = dt;
  if (o.start_s || o.duration_s)
    s.notes += "window of " + std::to_string(s.values.size()) + " samples from t = " + format_value(s.t0_s) + " s; ";

  const bool in_g = o.units == "g" || (o.units == "auto" && s.unit == "g");
  if (in_g) {
    for (double& x : s.values) x *= kStandardGravity;
    s.unit = "m/s^2";
    s.notes += "converted from g to m/s^2 (x 9.80665); ";
  }
  if (o.resample_rate_hz) resample_to_rate(s, *o.resample_rate_hz, path);
  return s;
}

}  // namespace

TimeSeries parse_time_series(const std::string& bytes, const std::string& path, const ImportOptions& o) {
  if (o.units != "auto" && o.units != "g" && o.units != "as-is")
    throw InputError("units = '" + o.units + "': must be one of auto, g, as-is");
  if (o.duration_s && !(*o.duration_s > 0))
    throw InputError("duration = " + format_value(*o.duration_s) + ": must be > 0");
  if (o.sample_rate_hz && !(*o.sample_rate_hz > 0 && std::isfinite(*o.sample_rate_hz)))
    throw InputError("sample rate = " + format_value(*o.sample_rate_hz) + " Hz: must be > 0");
  if (o.resample_rate_hz && !(*o.resample_rate_hz > 0 && std::isfinite(*o.resample_rate_hz)))
    throw InputError("resample rate = " + format_value(*o.resample_rate_hz) + " Hz: must be > 0");
  // The format from the content: NumPy's magic, a MAT-file's header text, UFF's "-1" delimiter; else text by the
  // file's ending (.lvm, else CSV).
  const bool npy = is_npy(bytes), mat = !npy && is_mat(bytes), uff = !npy && !mat && is_uff(bytes);
  if (!mat && (!o.variable.empty() || !o.time_variable.empty()))
    throw InputError(path + ": --variable and --time-variable name variables of a MAT-file; this is not one");
  if (!npy && !mat && o.sample_rate_hz)
    throw InputError(path + ": --sample-rate is for records without a time base (.npy, .mat); this file has one");
  if (npy) {
    const NpyArray a = parse_npy(bytes, path);
    const std::size_t rows = a.shape[0], columns = a.shape.size() == 2 ? a.shape[1] : 1;
    return finish(array_samples(
                      path, "npy", "array", rows, columns, [&a](std::size_t i, std::size_t j) { return a.at(i, j); },
                      nullptr, 0, o),
                  path, o);
  }
  if (mat) {
    const MatArray a = read_mat_variable(path, bytes, o.variable);
    std::vector<double> time;
    double time_precision = 0;
    if (!o.time_variable.empty()) {
      if (o.sample_rate_hz) throw InputError(path + ": give --time-variable or --sample-rate, not both");
      const MatArray t = read_mat_variable(path, bytes, o.time_variable);
      if (t.rows != 1 && t.columns != 1)
        throw InputError(path + ": time variable '" + t.path + "' is " + std::to_string(t.rows) + " x " +
                         std::to_string(t.columns) + ": must be a vector");
      time = t.values;
      time_precision = t.relative_precision;
    }
    Samples samples = array_samples(
        path, "mat", a.path, a.rows, a.columns, [&a](std::size_t i, std::size_t j) { return a.at(i, j); },
        o.time_variable.empty() ? nullptr : &time, time_precision, o);
    samples.series.format = "mat v" + a.version;
    return finish(std::move(samples), path, o);
  }
  if (uff) return finish(uff_samples(bytes, path, o), path, o);
  return finish(text_samples(bytes, path, o), path, o);
}

}  // namespace beamid::io
