// The two textual forms a study writes everywhere: numbers that round-trip ("%.17g": tables, store records and the
// canonical text that unit ids hash) and 64-bit hashes as 16 hex digits (unit ids, study-file hashes).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace beamid::study {

inline std::string full(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

inline std::string hex64(std::uint64_t value) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
  return buf;
}

}  // namespace beamid::study
