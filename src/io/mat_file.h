// MATLAB .mat files, version 5 (level 5, compressed or not) and 7.3 (HDF5), through Debian's libmatio: the only
// matio user is mat_file.cc, so that no matio type leaves it.
//
// A record is a real numeric variable (double, single or integer) of one or two dimensions: a vector, or a matrix
// with the samples along its longer dimension and the channels along the other (either way round). It is named by a
// dotted path from a top-level variable through struct fields ("test.accel.data"). The header is checked before
// matio opens the file: a v5 file starts with the text "MATLAB 5.0 MAT-file" and ends its 128-byte header with the
// endian indicator "IM" or "MI"; a v7.3 file is an HDF5 file with a 512-byte user block (signature at byte 512).
// Every violation is an InputError naming the file, the variable path and what was expected: a missing variable or
// field lists the ones there are.
#pragma once

#include <string>
#include <vector>

namespace beamid::io {

// Whether `bytes` start like a v5 or v7.3 MAT-file ("MATLAB" in the header text).
bool is_mat(const std::string& bytes);

struct MatArray {
  std::string version;  // "5" or "7.3"
  std::string path;     // the variable path read
  std::size_t rows = 0, columns = 0;
  std::vector<double> values;     // row-major
  double relative_precision = 0;  // one unit in the last place of the stored type: 1.2e-7 single, 4.4e-16 double
  double at(std::size_t i, std::size_t j) const { return values[i * columns + j]; }
};

// The variable at `variable` (a dotted path; empty: the file's only numeric variable). `bytes` are the file's
// first bytes (for the header check).
MatArray read_mat_variable(const std::string& file, const std::string& bytes, const std::string& variable);

}  // namespace beamid::io
