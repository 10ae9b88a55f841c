// The unit a record states for its values (an LVM Y_Unit_Label, a UFF ordinate label, a CSV column name's suffix or
// bracketed label), its conversion to SI, and the quantity it measures; and the unit a time column states. beamid
// models displacement in m, velocity in m/s and acceleration in m/s^2: a record in g, milli-g, millimetres or inches
// is converted on reading (ImportOptions::units "auto"), one that says it is a velocity is not fitted as a
// displacement, and one in volts or newtons is not fitted as a motion at all (api/fit_request.cc).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace beamid::io {

// A unit label as a file writes it ("g", "G", "g's", "mg", "m/s^2", "m/s2", "m/s²", "mm/s", "in/s", "ips", "cm", "µm",
// "V", "Volts", "N" ...) in beamid's spelling: g, mg, m, cm, mm, um, in, m/s, mm/s, in/s, m/s^2, mm/s^2, in/s^2, V, mV,
// N, lbf, Pa; the label itself (trimmed) when it is none of them.
std::string normalized_unit(std::string_view label);
// The unit a CSV column name states: a bracketed label ("accel (g)", "Acceleration [g]", "v (m/s²)") or a suffix after
// the last separator ("accel_g", "v_mm_s", "acc_m_s2", "acc_m_s^2", "x_cm", "vel_ips", "ch0_V"); "" when it states
// none.
std::string unit_of_column_name(std::string_view name);
// Why a column name's unit cannot be taken as stated: a bracket that does not close ("v (mm/s"), or two units that
// differ ("x (mm) (um)", "x_mm_um", "x_mm (um)"); "" when it can.
std::string column_unit_problem(std::string_view name);
// The unit a time column's name states in the same ways ("t_s", "t_ms", "Time [ms]", "time_msec", "T (mS)"): s, ms,
// us, ns, min or h; "" when it states none.
std::string time_unit_of_column_name(std::string_view name);
// The same for a label alone ("s", "sec", "ms", "mS", "msec", "usec", "minutes", ...; a UFF abscissa's units label).
std::string time_unit_of_label(std::string_view label);

struct SiConversion {
  std::string unit;  // the SI unit: m, m/s or m/s^2
  double factor;     // SI value = factor x the record's value
};
// The conversion of a motion unit to SI (g: 9.80665, mg: 9.80665e-3, mm: 1e-3, in: 0.0254 ...); nothing for an SI
// unit, a unit that is no motion, or an unknown one.
std::optional<SiConversion> si_conversion(const std::string& unit);
// "displacement", "velocity" or "acceleration" for a motion unit in any of the spellings above (m/s and in/s alike);
// "" for any other unit.
std::string quantity_of(const std::string& unit);
// Whether a known unit measures no motion (V, mV, N, kN, lbf, Pa): a record in it is a raw sensor signal.
bool is_non_motion_unit(const std::string& unit);
// Whether a unit (in beamid's spelling) measures a force (N, kN, lbf).
bool is_force_unit(const std::string& unit);
// Whether a unit (in beamid's spelling) is one beamid knows: SI, converted to SI, or no motion. A label a file states
// that is none of these is refused rather than taken as SI (nm, ft, degF, furlong/fortnight were read as m or m/s).
bool is_known_unit(const std::string& unit);
// The known units, for messages.
std::string known_units_list();

}  // namespace beamid::io
