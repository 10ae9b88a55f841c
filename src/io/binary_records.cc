// The array and modal-test formats of the record readers (io/record_samples.h): .npy and .mat arrays, UFF 58.
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "io/record_samples.h"
#include "io/uff58.h"
#include "io/units.h"

namespace beamid::io {

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
  const std::size_t channel = choose_channel(names, o, path, what + " channels");
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
  const UffFunction& f = functions[records[choose_channel(names, o, path, "time records (datasets 58)")]];
  // The abscissa is time in seconds: a frequency (18) or other axis, or a time in ms, was read as seconds (spikes
  // 1000x off: the second pass's N139, N143). Types 0 (unknown) and 1 (general) are taken as time, as writers use them.
  const std::string at = path + ":" + std::to_string(f.abscissa_line) + ": ";
  if (f.abscissa_type != 0 && f.abscissa_type != 1 && f.abscissa_type != 17)
    throw InputError(at + "abscissa data type " + std::to_string(f.abscissa_type) +
                     ": must be 17 (time), or 0 or 1 (unknown, general) for a time record" +
                     (f.abscissa_type == 18 ? " (18 is frequency: a spectrum, not a record)" : ""));
  if (const std::string unit = time_unit_of_label(f.abscissa_unit); !unit.empty() && unit != "s")
    throw InputError(at + "abscissa units '" + f.abscissa_unit + "' are " + unit +
                     ": beamid reads the time in seconds (rewrite the abscissa in s)");
  Samples out;
  out.series.path = path;
  out.series.format = "uff58";
  out.series.time_column = "time";
  out.series.value_column = f.name;
  out.series.unit = normalized_unit(f.unit);
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

}  // namespace beamid::io
