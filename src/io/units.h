// The unit a record states for its values (an LVM Y_Unit_Label, a UFF ordinate label, a CSV column name's suffix),
// its conversion to SI, and the quantity it measures. beamid models displacement in m, velocity in m/s and
// acceleration in m/s^2: a record in g or in millimetres is converted on reading (ImportOptions::units "auto"), and
// one that says it is a velocity is not fitted as a displacement (api/fit_request.cc).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace beamid::io {

// A unit label as a file writes it ("g", "G", "m/s^2", "m/s2", "mm/s", "m", "um", "µm", ...) in beamid's spelling: one
// of g, m, mm, um, m/s, mm/s, m/s^2, mm/s^2; the label itself (trimmed) when it is none of them.
std::string normalized_unit(std::string_view label);
// The unit a CSV column name states: a suffix "_g", "_m", "_mm", "_um", "_m_s", "_mm_s", "_m_s2", "_mm_s2" or a
// parenthesised label "accel (g)", "x (mm)", "v (m/s)"; "" when it states none.
std::string unit_of_column_name(std::string_view name);

struct SiConversion {
  std::string unit;  // the SI unit: m, m/s or m/s^2
  double factor;     // SI value = factor x the record's value
};
// The conversion of a unit to SI (g: 9.80665, mm: 1e-3, um: 1e-6 ...); nothing for an SI or unknown unit.
std::optional<SiConversion> si_conversion(const std::string& unit);
// "displacement", "velocity" or "acceleration" for m, m/s, m/s^2; "" for any other unit.
std::string quantity_of(const std::string& si_unit);

}  // namespace beamid::io
