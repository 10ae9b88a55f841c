#include "io/units.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace beamid::io {

namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g (CGPM 1901)
constexpr double kInch = 0.0254;              // m per inch (exact since 1959)
constexpr double kFoot = 0.3048;              // m per foot (exact since 1959)

std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\"'");
  if (first == std::string_view::npos) return "";
  return std::string(text.substr(first, text.find_last_not_of(" \t\"'") - first + 1));
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// The unit a label spells, in beamid's spelling, or "" (case-insensitive). A bare "v", "n" or "in" is volts, newtons
// or inches only in a label ("(V)", an LVM unit): as a name's suffix it is as likely a velocity ("tip_v"), an index
// ("x_n") or an input ("force_in").
std::string known_unit(std::string u, bool label) {
  u = lower(trimmed(u));
  // The micro sign (UTF-8 C2 B5) and Greek mu (CE BC) as u; the superscript two (C2 B2) as ^2.
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\xc2\xb5", "u"},
                                 {"\xce\xbc", "u"},
                                 {"\xc2\xb2", "^2"},
                                 {"**", "^"},
                                 {" ", ""}}) {
    for (auto at = u.find(from); at != std::string::npos; at = u.find(from, at + to.size()))
      u.replace(at, from.size(), to);
  }
  static const std::array<std::pair<const char*, const char*>, 50> spellings{{
      {"km", "km"},         {"yd", "yd"},        {"mil", "mil"},       {"mph", "mph"},       {"pm", "pm"},
      {"inch", "in"},       {"inches", "in"},    {"feet", "ft"},       {"foot", "ft"},       {"gal", "Gal"},
      {"g", "g"},           {"g's", "g"},        {"gs", "g"},          {"gn", "g"},          {"mg", "mg"},
      {"m", "m"},           {"cm", "cm"},        {"mm", "mm"},         {"um", "um"},         {"nm", "nm"},
      {"in", "in"},         {"ft", "ft"},        {"m/s", "m/s"},       {"ms^-1", "m/s"},     {"mm/s", "mm/s"},
      {"in/s", "in/s"},     {"ips", "in/s"},     {"ft/s", "ft/s"},     {"km/h", "km/h"},     {"m/s^2", "m/s^2"},
      {"m/s2", "m/s^2"},    {"ms^-2", "m/s^2"},  {"m/s/s", "m/s^2"},   {"mm/s^2", "mm/s^2"}, {"mm/s2", "mm/s^2"},
      {"in/s^2", "in/s^2"}, {"in/s2", "in/s^2"}, {"ft/s^2", "ft/s^2"}, {"ft/s2", "ft/s^2"},  {"v", "V"},
      {"volt", "V"},        {"volts", "V"},      {"mv", "mV"},         {"n", "N"},           {"newton", "N"},
      {"newtons", "N"},     {"lbf", "lbf"},      {"pa", "Pa"},         {"kn", "kN"},         {"um/s", "um/s"},
  }};
  if (!label && (u == "v" || u == "n" || u == "in")) return "";
  for (const auto& [spelling, unit] : spellings)
    if (u == spelling) return unit;
  return "";
}

// A bracketed label at the end of a name: "(g)", "[m/s^2]"; nothing when the name has none.
std::optional<std::string> bracketed(const std::string& name) {
  for (const auto& [open, close] : {std::pair{'(', ')'}, std::pair{'[', ']'}}) {
    const auto o = name.rfind(open), c = name.rfind(close);
    if (o != std::string::npos && c != std::string::npos && c > o) return name.substr(o + 1, c - o - 1);
  }
  return std::nullopt;
}

}  // namespace

std::string normalized_unit(std::string_view label) {
  const std::string unit = known_unit(std::string(label), true);
  return unit.empty() ? trimmed(label) : unit;
}

std::string unit_of_column_name(std::string_view column) {
  const std::string name = trimmed(column);
  if (const auto label = bracketed(name)) {
    // A bracket may hold a unit or a remark ("accel (tip)"); one that is written as a unit expression ('/' or '^')
    // is kept as stated even when beamid does not know it, so that it is refused rather than read as SI.
    const std::string unit = known_unit(*label, true);
    if (unit.empty() && label->find_first_of("/^") != std::string::npos) return trimmed(*label);
    return unit;
  }
  // A suffix after a separator, the longest that spells a unit: "acc_m_s2" is m/s^2 before s2 or m, "v_mm_s" mm/s.
  const std::string n = lower(name);
  for (std::size_t at = 0; (at = n.find('_', at)) != std::string::npos; ++at) {
    std::string suffix = n.substr(at + 1);
    std::replace(suffix.begin(), suffix.end(), '_', '/');  // m_s2 -> m/s2, mm_s -> mm/s, in_s -> in/s
    if (const std::string unit = known_unit(suffix, false); !unit.empty()) return unit;
  }
  return "";
}

std::string time_unit_of_column_name(std::string_view column) {
  const std::string name = trimmed(column);
  if (const auto inside = bracketed(name)) return time_unit_of_label(*inside);
  if (const auto at = name.rfind('_'); at != std::string::npos) return time_unit_of_label(name.substr(at + 1));
  return "";
}

std::string time_unit_of_label(std::string_view text) {
  const std::string label = lower(trimmed(text));
  for (const auto& [spelling, unit] : std::array<std::pair<const char*, const char*>, 14>{{{"s", "s"},
                                                                                           {"sec", "s"},
                                                                                           {"seconds", "s"},
                                                                                           {"ms", "ms"},
                                                                                           {"msec", "ms"},
                                                                                           {"us", "us"},
                                                                                           {"usec", "us"},
                                                                                           {"\xc2\xb5s", "us"},
                                                                                           {"ns", "ns"},
                                                                                           {"min", "min"},
                                                                                           {"mins", "min"},
                                                                                           {"minutes", "min"},
                                                                                           {"h", "h"},
                                                                                           {"hours", "h"}}})
    if (label == spelling) return unit;
  return "";
}

std::optional<SiConversion> si_conversion(const std::string& unit) {
  if (unit == "g") return SiConversion{"m/s^2", kStandardGravity};
  if (unit == "mg") return SiConversion{"m/s^2", 1e-3 * kStandardGravity};
  if (unit == "cm") return SiConversion{"m", 1e-2};
  if (unit == "mm") return SiConversion{"m", 1e-3};
  if (unit == "um") return SiConversion{"m", 1e-6};
  if (unit == "in") return SiConversion{"m", kInch};
  if (unit == "mm/s") return SiConversion{"m/s", 1e-3};
  if (unit == "in/s") return SiConversion{"m/s", kInch};
  if (unit == "mm/s^2") return SiConversion{"m/s^2", 1e-3};
  if (unit == "in/s^2") return SiConversion{"m/s^2", kInch};
  if (unit == "nm") return SiConversion{"m", 1e-9};
  if (unit == "pm") return SiConversion{"m", 1e-12};
  if (unit == "km") return SiConversion{"m", 1e3};
  if (unit == "yd") return SiConversion{"m", 3 * kFoot};
  if (unit == "mil") return SiConversion{"m", 1e-3 * kInch};
  if (unit == "mph") return SiConversion{"m/s", 1609.344 / 3600};  // the international mile, 1760 yd
  if (unit == "Gal") return SiConversion{"m/s^2", 1e-2};           // the gal, 1 cm/s^2
  if (unit == "ft") return SiConversion{"m", kFoot};
  if (unit == "ft/s") return SiConversion{"m/s", kFoot};
  if (unit == "ft/s^2") return SiConversion{"m/s^2", kFoot};
  if (unit == "km/h") return SiConversion{"m/s", 1 / 3.6};
  if (unit == "um/s") return SiConversion{"m/s", 1e-6};
  return std::nullopt;
}

std::string quantity_of(const std::string& unit) {
  const auto si = si_conversion(unit);
  const std::string base = si ? si->unit : unit;
  if (base == "m") return "displacement";
  if (base == "m/s") return "velocity";
  if (base == "m/s^2") return "acceleration";
  return "";
}

bool is_non_motion_unit(const std::string& unit) {
  return unit == "V" || unit == "mV" || unit == "N" || unit == "kN" || unit == "lbf" || unit == "Pa";
}

bool is_known_unit(const std::string& unit) {
  return unit == "m" || unit == "m/s" || unit == "m/s^2" || si_conversion(unit) || is_non_motion_unit(unit);
}

std::string known_units_list() {
  return "m, km, cm, mm, um, nm, pm, in, mil, ft, yd; m/s, mm/s, um/s, in/s, ft/s, km/h, mph; m/s^2, mm/s^2, in/s^2, "
         "ft/s^2, Gal, g, mg; V, mV, N, kN, lbf, Pa";
}

}  // namespace beamid::io
