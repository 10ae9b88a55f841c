// NumPy's .npy format, versions 1.0, 2.0 and 3.0 (numpy.lib.format): the magic "\x93NUMPY", major and minor version
// bytes, the header length (2 bytes little-endian in 1.0, 4 in 2.0 and 3.0), an ASCII (3.0: UTF-8) Python dict
// literal {'descr': '<f8', 'fortran_order': False, 'shape': (n, c), } padded with spaces to a multiple of 64 bytes,
// then the array's bytes. Read here: real numbers of either byte order, floating (f4, f8) or integer (i1, i2, i4, i8,
// u1, u2, u4, u8), in C or Fortran order, of one or two dimensions. Every violation is an InputError naming the file,
// the byte offset and what was expected.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace beamid::io {

// "\x93NUMPY": whether `bytes` start like an .npy file.
bool is_npy(const std::string& bytes);

struct NpyArray {
  std::vector<std::size_t> shape;  // one or two dimensions
  std::string descr;               // as in the header, e.g. "<f8"
  std::vector<double> values;      // in C (row-major) order, whatever the file's order
  // Element (i, j) of a two-dimensional array (i of a one-dimensional one with j = 0).
  double at(std::size_t i, std::size_t j) const { return values[shape.size() == 1 ? i : i * shape[1] + j]; }
};

NpyArray parse_npy(const std::string& bytes, const std::string& path);

}  // namespace beamid::io
