// Reading a sampled record from CSV, as written by `beamid simulate`: a header line naming the columns, then rows
// "t, y" (time in seconds first, one signal column). Checked: every field a finite number, at least 8 samples, and
// a uniform time base t_i = t_0 + i dt (|t_i - t_0 - i dt| <= 1e-6 dt, dt = (t_last - t_0)/(n - 1)); a violation is
// an InputError naming the file, line, column, value and constraint.
#pragma once

#include <string>
#include <vector>

namespace beamid::io {

struct TimeSeries {
  std::string path;
  std::string time_column, value_column;  // header names
  double t0_s = 0;
  double dt_s = 0;
  std::vector<double> values;
};

TimeSeries read_time_series(const std::string& path);

}  // namespace beamid::io
