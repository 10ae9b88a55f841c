// Test helpers of the record readers: a file written to the test's temporary folder, and the error that reading it
// gives ("no error" when it reads).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/errors.h"
#include "io/time_series.h"

namespace beamid::io {

inline std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

inline std::string error_of(const std::string& path, const ImportOptions& o = {}) {
  try {
    read_time_series(path, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace beamid::io
