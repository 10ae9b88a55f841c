// The array and modal-test formats of the record readers (io/record_samples.h): .npy and .mat arrays, UFF 58.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

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
  const auto value = [&](std::size_t i, std::size_t c) { return by_row ? at(i, c) : at(c, i); };
  // The time channel, when one is named: a row or column of the array itself (a .npy saved as np.vstack((t, y))
  // could not use its time, and --sample-rate on an irregular record gave smeared spectra without a word).
  std::optional<std::size_t> time_channel;
  std::vector<double> channel_time;
  if (!o.time_channel.empty()) {
    if (time) throw InputError(path + ": --time-channel names a time channel; a time vector is given too: one of them");
    if (o.sample_rate_hz) throw InputError(path + ": give --time-channel or --sample-rate, not both");
    char* end = nullptr;
    const long k = std::strtol(o.time_channel.c_str(), &end, 10);
    if (end != o.time_channel.c_str() + o.time_channel.size() || k < 1 || static_cast<std::size_t>(k) > channels ||
        channels < 2)
      throw InputError(path + ": --time-channel = '" + shown(o.time_channel) + "': must be a channel index in 1.." +
                       std::to_string(channels) + " of the " + std::to_string(channels) + " " + what +
                       " channels, leaving at least one signal" +
                       (channels < 2 ? " (this array has one channel: give --sample-rate)" : ""));
    time_channel = static_cast<std::size_t>(k - 1);
    for (std::size_t i = 0; i < samples; ++i) channel_time.push_back(value(i, *time_channel));
    time = &channel_time;
  }
  std::vector<std::string> names;
  std::vector<std::size_t> indices;
  for (std::size_t c = 0; c < channels; ++c)
    if (c != time_channel) names.push_back(std::to_string(c + 1)), indices.push_back(c);
  if (!o.channel.empty() && time_channel && o.channel == std::to_string(*time_channel + 1))
    throw InputError(path + ": --channel = --time-channel = " + o.channel +
                     ": the signal and its time are different "
                     "channels");
  const std::size_t channel = indices[choose_channel(names, o, path, what + " channels")];
  s.value_column = channels == 1 ? what : what + " channel " + std::to_string(channel + 1);
  // The time's own name in messages: its channel, or the MAT variable --time-variable named (a swapped pair was told
  // "time column time does not increase": the third pass's P134).
  s.time_column = time_channel               ? what + " channel " + std::to_string(*time_channel + 1)
                  : !o.time_variable.empty() ? "time variable '" + o.time_variable + "'"
                                             : "time";
  for (std::size_t i = 0; i < samples; ++i) out.v.push_back(value(i, channel));
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
                       (format == "mat" ? ", --time-variable NAME" : "") +
                       (channels >= 2 ? " or --time-channel K (the channel that holds the time)" : ""));
    // A rate makes the time base uniform by construction: there is nothing for --resample to interpolate (it was
    // accepted and did nothing).
    if (o.resample)
      throw InputError(path +
                       ": --resample interpolates a non-uniform time base; one made from --sample-rate is "
                       "uniform (give the record's own time instead: --time-channel or --time-variable)");
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
  // A units label that is no time unit at all ("m", "fortnight") was read as seconds (the fourth pass's Q231, Q232).
  if (!f.abscissa_unit.empty() && time_unit_of_label(f.abscissa_unit).empty())
    throw InputError(at + "abscissa units '" + f.abscissa_unit +
                     "': not a time unit (s, ms, us, min, h): a time record's abscissa is time in s");
  // The ordinate's specific data type against its units label: an acceleration (12) labelled m/s was fitted as a
  // velocity without a word (the fourth pass's Q528). UFF types 8, 11, 12: displacement, velocity, acceleration.
  const std::string stated = f.ordinate_type == 8    ? "displacement"
                             : f.ordinate_type == 11 ? "velocity"
                             : f.ordinate_type == 12 ? "acceleration"
                                                     : "";
  if (const std::string labelled = quantity_of(normalized_unit(f.unit));
      !stated.empty() && !labelled.empty() && stated != labelled)
    throw InputError(path + ":" + std::to_string(f.ordinate_line) + ": ordinate data type " +
                     std::to_string(f.ordinate_type) + " (" + stated + ") with units '" + f.unit + "', " +
                     (labelled == "acceleration" ? "an " : "a ") + labelled +
                     ": the header contradicts itself (which is the record?)");
  // A type that is no motion (13 excitation force, 9 reaction force, 15 pressure, 2 stress, 3 strain, 5
  // temperature, ...) is no response beamid fits: an excitation force was fitted as a motion (the fifth pass's R153).
  if (f.ordinate_type != 0 && f.ordinate_type != 1 && stated.empty())
    throw InputError(path + ":" + std::to_string(f.ordinate_line) + ": ordinate data type " +
                     std::to_string(f.ordinate_type) + (f.ordinate_type == 13 ? " (excitation force)" : "") +
                     ": a response record is 8 (displacement), 11 (velocity) or 12 (acceleration), or 0 or 1 "
                     "(unknown, general)");
  // A blank ordinate units label states no unit, as a blank LVM label does: a record exported in g was read as m/s^2
  // (the thirteenth pass's 4). The user says which.
  if (normalized_unit(f.unit).empty() && o.units == "auto")
    throw InputError(path + ":" + std::to_string(f.ordinate_line) +
                     ": the ordinate's units label is blank, so the record states no unit: give --units g for an "
                     "accelerometer in g, or --units as-is to take the values as SI (m, m/s, m/s^2)");
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
