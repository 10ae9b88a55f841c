#include "io/time_series.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "model/errors.h"

namespace beamid::io {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) {
    const auto first = field.find_first_not_of(" \t\r"), last = field.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
  }
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

}  // namespace

TimeSeries read_time_series(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the file");
  TimeSeries s;
  s.path = path;
  std::string line;
  if (!std::getline(in, line)) throw InputError(path + ": empty file (expected a header such as t_s,displacement_m)");
  const auto header = split(line);
  if (header.size() != 2)
    throw InputError(path + ":1: header '" + line + "': must name exactly two columns (time in s, then the signal)");
  s.time_column = header[0];
  s.value_column = header[1];
  std::vector<double> t;
  std::vector<int> line_of;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = split(line);
    if (fields.size() != 2)
      throw InputError(path + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) +
                       " fields: must be 2 (" + s.time_column + "," + s.value_column + ")");
    double v[2];
    for (int c = 0; c < 2; ++c) {
      const std::string& text = fields[static_cast<std::size_t>(c)];
      char* end = nullptr;
      v[c] = std::strtod(text.c_str(), &end);
      const std::string& column = c == 0 ? s.time_column : s.value_column;
      if (text.empty() || end != text.c_str() + text.size())
        throw InputError(path + ":" + std::to_string(number) + ": " + column + " = '" + text + "': must be a number");
      if (!std::isfinite(v[c]))
        throw InputError(path + ":" + std::to_string(number) + ": " + column + " = " + text + ": must be finite");
    }
    t.push_back(v[0]);
    s.values.push_back(v[1]);
    line_of.push_back(number);
  }
  if (s.values.size() < 8)
    throw InputError(path + ": " + std::to_string(s.values.size()) + " samples: at least 8 are needed");
  s.t0_s = t.front();
  s.dt_s = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  if (!(s.dt_s > 0)) throw InputError(path + ": time column " + s.time_column + " does not increase");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double expected = s.t0_s + static_cast<double>(i) * s.dt_s;
    if (std::abs(t[i] - expected) > 1e-6 * s.dt_s)
      throw InputError(path + ":" + std::to_string(line_of[i]) + ": " + s.time_column + " = " + format_value(t[i]) +
                       ": non-uniform time base (expected " + format_value(expected) + " = t0 + " +
                       std::to_string(i) + " dt with dt = " + format_value(s.dt_s) + " s)");
  }
  return s;
}

}  // namespace beamid::io
