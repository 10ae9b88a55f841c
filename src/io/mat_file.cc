#include "io/mat_file.h"

#include <matio.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <memory>

#include "core/errors.h"
#include "io/mat_layout.h"
#include "io/resources.h"

namespace beamid::io {
namespace {

const std::string kHdf5Signature = "\x89HDF\r\n\x1a\n";

// matio reports on stderr through its log unless given a function: its messages become part of our errors instead.
std::string& last_matio_message() {
  static thread_local std::string message;
  return message;
}
void keep_message(int, char* message) { last_matio_message() = message ? message : ""; }

struct Closer {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct Freer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using File = std::unique_ptr<mat_t, Closer>;
using Variable = std::unique_ptr<matvar_t, Freer>;

bool numeric(const matvar_t* v) {
  // A logical array (true/false flags, stored as uint8) is no signal: it was read as 0/1 and refused as "clipped".
  if (v->isLogical) return false;
  switch (v->class_type) {
    case MAT_C_DOUBLE:
    case MAT_C_SINGLE:
    case MAT_C_INT8:
    case MAT_C_UINT8:
    case MAT_C_INT16:
    case MAT_C_UINT16:
    case MAT_C_INT32:
    case MAT_C_UINT32:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

std::string class_name(const matvar_t* v) {
  if (v->isLogical) return "a logical array";
  switch (v->class_type) {
    case MAT_C_STRUCT:
      return "a struct";
    case MAT_C_CELL:
      return "a cell array";
    case MAT_C_CHAR:
      return "text";
    case MAT_C_SPARSE:
      return "a sparse matrix";
    case MAT_C_OBJECT:
      return "an object";
    case MAT_C_FUNCTION:
      return "a function handle";
    default:
      return "a numeric array";
  }
}

double element(const matvar_t* v, std::size_t k) {
  const void* d = v->data;
  switch (v->class_type) {
    case MAT_C_DOUBLE:
      return static_cast<const double*>(d)[k];
    case MAT_C_SINGLE:
      return static_cast<const float*>(d)[k];
    case MAT_C_INT8:
      return static_cast<const std::int8_t*>(d)[k];
    case MAT_C_UINT8:
      return static_cast<const std::uint8_t*>(d)[k];
    case MAT_C_INT16:
      return static_cast<const std::int16_t*>(d)[k];
    case MAT_C_UINT16:
      return static_cast<const std::uint16_t*>(d)[k];
    case MAT_C_INT32:
      return static_cast<const std::int32_t*>(d)[k];
    case MAT_C_UINT32:
      return static_cast<const std::uint32_t*>(d)[k];
    case MAT_C_INT64:
      return static_cast<double>(static_cast<const std::int64_t*>(d)[k]);
    case MAT_C_UINT64:
      return static_cast<double>(static_cast<const std::uint64_t*>(d)[k]);
    default:
      return 0;
  }
}

std::string field_names(matvar_t* v) {
  std::string names;
  const unsigned count = Mat_VarGetNumberOfFields(v);
  char* const* fields = Mat_VarGetStructFieldnames(v);
  for (unsigned i = 0; i < count && fields; ++i) names += (names.empty() ? "" : ", ") + std::string(fields[i]);
  return names.empty() ? "none" : names;
}

}  // namespace

bool is_mat(const std::string& bytes) {
  const bool v5 = bytes.compare(0, 6, "MATLAB") == 0;
  const bool v73 = bytes.size() >= 520 && bytes.compare(512, kHdf5Signature.size(), kHdf5Signature) == 0 &&
                   bytes.compare(0, 6, "MATLAB") == 0;
  return v5 || v73;
}

namespace {}  // namespace

MatArray read_mat_variable(const std::string& file, const std::string& bytes, const std::string& variable) {
  const std::string where = file + ": ";
  const bool hdf5 = bytes.size() >= 520 && bytes.compare(512, kHdf5Signature.size(), kHdf5Signature) == 0;
  if (!hdf5) {
    if (bytes.size() < 128 || bytes.compare(0, 19, "MATLAB 5.0 MAT-file") != 0)
      throw InputError(where +
                       "byte 0: not a MAT-file of version 5 (header 'MATLAB 5.0 MAT-file') or 7.3 (HDF5 "
                       "signature at byte 512)");
    const std::string endian = bytes.substr(126, 2);
    if (endian != "IM" && endian != "MI")
      throw InputError(where + "byte 126: endian indicator '" + endian + "': must be IM or MI (a v5 MAT-file)");
    check_v5_layout(where, bytes, endian == "IM");
  }
  Mat_LogInitFunc("beamid", keep_message);
  last_matio_message().clear();
  File mat(Mat_Open(file.c_str(), MAT_ACC_RDONLY));
  if (!mat) throw InputError(where + "libmatio cannot open it as a MAT-file (" + last_matio_message() + ")");
  MatArray out;
  out.version = Mat_GetVersion(mat.get()) == MAT_FT_MAT73 ? "7.3" : "5";

  // The top-level variables, for the default and for messages.
  std::vector<std::string> names;
  std::string numeric_name;
  int numeric_count = 0;
  std::uint64_t numeric_bytes = 0;
  for (int k = 0; k < 100000; ++k) {
    Variable info(Mat_VarReadNextInfo(mat.get()));
    if (!info) break;
    if (info->name) names.emplace_back(info->name);
    if (info->name && numeric(info.get())) ++numeric_count, numeric_name = info->name;
  }
  std::string listed;
  for (const auto& n : names) listed += (listed.empty() ? "" : ", ") + n;
  if (listed.empty()) listed = "none";
  std::string path = variable;
  if (path.empty()) {
    if (numeric_count != 1)
      throw InputError(where + std::to_string(numeric_count) + " numeric variables (the file holds " + listed +
                       "): choose one with --variable NAME (a dotted path reaches into structs)");
    path = numeric_name;
  }
  out.path = path;
  const std::string top = path.substr(0, path.find('.'));
  if (std::find(names.begin(), names.end(), top) == names.end())
    throw InputError(where + "variable '" + top + "': not in the file, which holds " + listed);
  Variable root(Mat_VarRead(mat.get(), top.c_str()));
  if (!root) throw InputError(where + "variable '" + top + "': libmatio cannot read it (" + last_matio_message() + ")");
  matvar_t* v = root.get();
  std::string reached = top;
  for (std::size_t begin = top.size(); begin < path.size();) {
    const std::size_t end = path.find('.', begin + 1);
    const std::string field = path.substr(begin + 1, end == std::string::npos ? std::string::npos : end - begin - 1);
    if (v->class_type != MAT_C_STRUCT)
      throw InputError(where + "variable '" + reached + "' is " + class_name(v) + ", not a struct: no field '" + field +
                       "'");
    matvar_t* next = Mat_VarGetStructFieldByName(v, field.c_str(), 0);
    if (!next)
      throw InputError(where + "variable '" + reached + "' has no field '" + field +
                       "' (its fields: " + field_names(v) + ")");
    v = next;
    reached += "." + field;
    begin = end == std::string::npos ? path.size() : end;
  }
  if (!numeric(v))
    throw InputError(where + "variable '" + path + "' is " + class_name(v) +
                     (v->class_type == MAT_C_STRUCT ? " (fields: " + field_names(v) + ")" : "") +
                     ": a record must be a real numeric vector or matrix");
  if (v->isComplex) throw InputError(where + "variable '" + path + "' is complex: a record must be real");
  if (v->rank != 2 || !v->dims)
    throw InputError(where + "variable '" + path + "' has " + std::to_string(v->rank) +
                     " dimensions: a record must be a vector or a matrix");
  out.rows = v->dims[0];
  out.columns = v->dims[1];
  if (out.rows == 0 || out.columns == 0 || !v->data) throw InputError(where + "variable '" + path + "' is empty");
  out.relative_precision = v->class_type == MAT_C_SINGLE ? 1.2e-7 : v->class_type == MAT_C_DOUBLE ? 4.4e-16 : 0;
  numeric_bytes = static_cast<std::uint64_t>(out.rows) * out.columns * sizeof(double);
  check_memory(where + "variable '" + path + "'", static_cast<double>(numeric_bytes), std::cerr);
  out.values.resize(out.rows * out.columns);
  // MATLAB stores columns one after another: element k is (k % rows, k / rows).
  for (std::size_t k = 0; k < out.values.size(); ++k)
    out.values[(k % out.rows) * out.columns + k / out.rows] = element(v, k);
  return out;
}

}  // namespace beamid::io
