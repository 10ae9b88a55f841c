// The number forms of the Markdown tables and report text (CSV tables use io::round_trip): three significant
// digits, percentages, and noise levels. A non-finite value prints as "-".
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace beamid::study {

inline std::string g3(double v) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
// A relative value as a percentage with 3 significant digits: "1.5 %".
inline std::string pct(double fraction) {
  if (!std::isfinite(fraction)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g %%", 100 * fraction);
  return buf;
}
// With its sign: "+1.5 %", "-3 %".
inline std::string signed_pct(double fraction) {
  if (!std::isfinite(fraction)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.3g %%", 100 * fraction);
  return buf;
}
// Four significant digits (the real-data tables, whose frequencies need them).
inline std::string g4(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}
inline std::string noise_label(double level) { return level == 0 ? "0" : g3(100 * level) + "%"; }

}  // namespace beamid::study
