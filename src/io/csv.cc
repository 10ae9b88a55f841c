#include "io/csv.h"

#include <cstdio>

namespace beamid::io {

std::string full_precision(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.16e", value);
  return buffer;
}

void write_row(std::ostream& out, const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << full_precision(values[i]);
  out << '\n';
}

}  // namespace beamid::io
