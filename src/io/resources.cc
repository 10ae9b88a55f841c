#include "io/resources.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/errors.h"

namespace beamid::io {

std::optional<double> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return std::nullopt;
}

double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<double>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

std::string bytes_text(double bytes) {
  char buf[32];
  if (bytes >= 1e9)
    std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
  else if (bytes >= 1e6)
    std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  else
    std::snprintf(buf, sizeof buf, "%.0f kB", bytes / 1e3);
  return buf;
}

std::string seconds_text(double s) {
  char buf[32];
  if (s < 90)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400)
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

void check_memory(const std::string& what, double bytes, std::ostream& warn) {
  const auto available = available_memory_bytes();
  if (!available) return;
  if (bytes > *available)
    throw InputError(what + ": needs about " + bytes_text(bytes) + " of memory; this machine has " +
                     bytes_text(*available) + " available");
  if (bytes > 0.25 * *available)
    // `what` names the command ("beamid simulate: ..."), or is a bare description that gets the program's name.
    warn << (what.rfind("beamid", 0) == 0 ? "" : "beamid: ") << what << ": needs about " << bytes_text(bytes)
         << " of memory (" << bytes_text(*available) << " available)\n";
}

}  // namespace beamid::io
