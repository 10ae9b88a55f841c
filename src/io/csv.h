// CSV output with full precision: every number as %.16e, i.e. 17 significant digits, enough to round-trip a double.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace beamid::io {

std::string full_precision(double value);

// One CSV row; numbers in full precision.
void write_row(std::ostream& out, const std::vector<double>& values);

}  // namespace beamid::io
