#include "io/units.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace beamid::io {

namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g

std::string lower_trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  std::string out(text.substr(first, last - first + 1));
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

}  // namespace

std::string normalized_unit(std::string_view label) {
  std::string u = lower_trimmed(label);
  // "µm" (UTF-8 micro sign) and "μm" (Greek mu) as um.
  for (const std::string micro : {"\xc2\xb5", "\xce\xbc"})
    if (u.rfind(micro, 0) == 0) u = "u" + u.substr(micro.size());
  static const std::array<std::pair<const char*, const char*>, 14> spellings{{{"g", "g"},
                                                                              {"m", "m"},
                                                                              {"mm", "mm"},
                                                                              {"um", "um"},
                                                                              {"m/s", "m/s"},
                                                                              {"mm/s", "mm/s"},
                                                                              {"m/s^2", "m/s^2"},
                                                                              {"m/s2", "m/s^2"},
                                                                              {"m/s**2", "m/s^2"},
                                                                              {"m s^-2", "m/s^2"},
                                                                              {"mm/s^2", "mm/s^2"},
                                                                              {"mm/s2", "mm/s^2"},
                                                                              {"m s^-1", "m/s"},
                                                                              {"mm/s**2", "mm/s^2"}}};
  for (const auto& [spelling, unit] : spellings)
    if (u == spelling) return unit;
  const auto first = label.find_first_not_of(" \t");
  if (first == std::string_view::npos) return "";
  return std::string(label.substr(first, label.find_last_not_of(" \t") - first + 1));
}

std::string unit_of_column_name(std::string_view name) {
  const std::string n = lower_trimmed(name);
  // "accel (g)", "v (m/s)": the label inside the last parentheses.
  const auto open = n.rfind('('), close = n.rfind(')');
  if (open != std::string::npos && close != std::string::npos && close > open) {
    const std::string unit = normalized_unit(n.substr(open + 1, close - open - 1));
    return si_conversion(unit) || !quantity_of(unit).empty() ? unit : "";
  }
  // Suffixes, the longest first ("_mm_s2" before "_m_s2" before "_s2" ...).
  static const std::array<std::pair<const char*, const char*>, 8> suffixes{{{"_mm_s2", "mm/s^2"},
                                                                            {"_m_s2", "m/s^2"},
                                                                            {"_mm_s", "mm/s"},
                                                                            {"_m_s", "m/s"},
                                                                            {"_mm", "mm"},
                                                                            {"_um", "um"},
                                                                            {"_m", "m"},
                                                                            {"_g", "g"}}};
  for (const auto& [suffix, unit] : suffixes) {
    const std::string_view s(suffix);
    if (n.size() > s.size() && n.compare(n.size() - s.size(), s.size(), s) == 0) return unit;
  }
  return "";
}

std::optional<SiConversion> si_conversion(const std::string& unit) {
  if (unit == "g") return SiConversion{"m/s^2", kStandardGravity};
  if (unit == "mm") return SiConversion{"m", 1e-3};
  if (unit == "um") return SiConversion{"m", 1e-6};
  if (unit == "mm/s") return SiConversion{"m/s", 1e-3};
  if (unit == "mm/s^2") return SiConversion{"m/s^2", 1e-3};
  return std::nullopt;
}

std::string quantity_of(const std::string& si_unit) {
  if (si_unit == "m") return "displacement";
  if (si_unit == "m/s") return "velocity";
  if (si_unit == "m/s^2") return "acceleration";
  return "";
}

}  // namespace beamid::io
