// The units a record states and their conversion to SI (io/units.h): a record in g or millimetres is read in SI, and
// one that says what it measures is known to measure it.
#include "io/units.h"

#include <gtest/gtest.h>

#include <fstream>
#include <utility>

#include "core/errors.h"
#include "io/time_series.h"

namespace beamid::io {
namespace {

TEST(Units, ColumnNamesAndLabelsStateTheirUnit) {
  // beamid's own column names, a lab's, and labels as LVM and UFF files write them.
  EXPECT_EQ(unit_of_column_name("displacement_m"), "m");
  EXPECT_EQ(unit_of_column_name("velocity_m_s"), "m/s");
  EXPECT_EQ(unit_of_column_name("acceleration_m_s2"), "m/s^2");
  EXPECT_EQ(unit_of_column_name("tip_mm_s"), "mm/s");
  EXPECT_EQ(unit_of_column_name("accel_g"), "g");
  EXPECT_EQ(unit_of_column_name("x (mm)"), "mm");
  EXPECT_EQ(unit_of_column_name("v (m/s)"), "m/s");
  EXPECT_EQ(unit_of_column_name("Accel (G)"), "g");
  // Names that state no unit.
  for (const char* name : {"y", "sensor", "ch1", "beam", "tip_v", "x_n", "force_in", "t_s"})
    EXPECT_EQ(unit_of_column_name(name), "") << name;
  // Labels as DAQ exports and spreadsheets write them (the adversarial pass's N003-N016).
  EXPECT_EQ(unit_of_column_name("accel_mg"), "mg");
  EXPECT_EQ(unit_of_column_name("Acceleration [g]"), "g");
  EXPECT_EQ(unit_of_column_name("a (m/s\xc2\xb2)"), "m/s^2");
  EXPECT_EQ(unit_of_column_name("acc_m_s^2"), "m/s^2");
  EXPECT_EQ(unit_of_column_name("x (cm)"), "cm");
  EXPECT_EQ(unit_of_column_name("v (in/s)"), "in/s");
  EXPECT_EQ(unit_of_column_name("vel_ips"), "in/s");
  EXPECT_EQ(unit_of_column_name("ch0 (V)"), "V");
  EXPECT_EQ(unit_of_column_name("\"accel_g\""), "g");
  EXPECT_EQ(normalized_unit("g's"), "g");
  EXPECT_EQ(normalized_unit("Volts"), "V");
  // Time columns.
  for (const auto& [name, unit] :
       {std::pair{"t_s", "s"}, std::pair{"t_ms", "ms"}, std::pair{"Time [ms]", "ms"}, std::pair{"T_MS", "ms"},
        std::pair{"time_msec", "ms"}, std::pair{"Time (mS)", "ms"}, std::pair{"time", ""}})
    EXPECT_EQ(time_unit_of_column_name(name), unit) << name;
  EXPECT_EQ(normalized_unit(" m/s2 "), "m/s^2");
  EXPECT_EQ(normalized_unit("\xc2\xb5m"), "um");  // the micro sign
  EXPECT_EQ(normalized_unit("kg"), "kg");         // an unknown label is kept as written
}

TEST(Units, ConversionsToSiAndQuantities) {
  // g is standard gravity, 9.80665 m/s^2 (CGPM 1901); the metric prefixes are exact.
  EXPECT_EQ(si_conversion("g")->factor, 9.80665);
  EXPECT_EQ(si_conversion("mm/s")->unit, "m/s");
  EXPECT_EQ(si_conversion("mm/s")->factor, 1e-3);
  EXPECT_EQ(si_conversion("um")->factor, 1e-6);
  EXPECT_FALSE(si_conversion("m/s^2"));
  EXPECT_FALSE(si_conversion("V"));
  EXPECT_EQ(quantity_of("m"), "displacement");
  EXPECT_EQ(quantity_of("m/s"), "velocity");
  EXPECT_EQ(quantity_of("m/s^2"), "acceleration");
  EXPECT_EQ(quantity_of("g"), "acceleration");  // the quantity of any motion unit, converted or not
  EXPECT_EQ(quantity_of("in/s"), "velocity");
  EXPECT_EQ(quantity_of("V"), "");
  EXPECT_TRUE(is_non_motion_unit("V"));
  EXPECT_EQ(si_conversion("mg")->factor, 9.80665e-3);
  EXPECT_EQ(si_conversion("in/s")->factor, 0.0254);  // the inch is 25.4 mm exactly
  // The third pass's labels that were read as SI (P003-P016): nm, ft (0.3048 m exactly), km/h, g_n; a unit beamid
  // does not know is not "known", so a file stating it is refused (time_series.cc), and a bracketed unit expression
  // is kept as stated while a bracketed remark is no unit.
  EXPECT_EQ(si_conversion(unit_of_column_name("x_nm"))->factor, 1e-9);
  EXPECT_EQ(si_conversion(unit_of_column_name("x (ft)"))->factor, 0.3048);
  EXPECT_EQ(si_conversion(unit_of_column_name("v_km_h"))->unit, "m/s");
  EXPECT_EQ(unit_of_column_name("a (gn)"), "g");
  EXPECT_EQ(unit_of_column_name("v (furlong/fortnight)"), "furlong/fortnight");
  EXPECT_FALSE(is_known_unit("furlong/fortnight"));
  EXPECT_FALSE(is_known_unit(normalized_unit("degF")));
  EXPECT_EQ(unit_of_column_name("accel (tip)"), "");
  // The fourth pass's (Q017-Q053): the international mile (1609.344 m), the yard (0.9144 m), the gal (1 cm/s^2).
  EXPECT_DOUBLE_EQ(si_conversion(unit_of_column_name("ux_mph"))->factor, 0.44704);
  EXPECT_DOUBLE_EQ(si_conversion(unit_of_column_name("x (yd)"))->factor, 0.9144);
  EXPECT_EQ(si_conversion(unit_of_column_name("a (Gal)"))->unit, "m/s^2");
  EXPECT_TRUE(is_known_unit("m/s^2") && is_known_unit("mm") && is_known_unit("V"));
  // The fifth pass's (adv33 #2): a capital M is mega, not milli ("x (Mm)" was read as mm, 1e9 times off), a time
  // unit in a value column is no motion ("v (ms)" was read as m/s), and both are kept as stated so that they are
  // refused; shouted capitals and spelled-out words still read.
  EXPECT_EQ(unit_of_column_name("x (Mm)"), "Mm");
  EXPECT_EQ(unit_of_column_name("x_Mm"), "Mm");
  EXPECT_EQ(unit_of_column_name("v (ms)"), "ms");
  EXPECT_EQ(unit_of_column_name("ux_ms"), "ms");
  EXPECT_EQ(unit_of_column_name("v (furlong)"), "furlong");
  EXPECT_FALSE(is_known_unit("Mm") || is_known_unit("ms") || is_known_unit("furlong"));
  EXPECT_EQ(unit_of_column_name("X (MM)"), "mm");
  EXPECT_EQ(unit_of_column_name("x (millimetres)"), "mm");
  EXPECT_EQ(unit_of_column_name("x (Meters)"), "m");
  EXPECT_EQ(unit_of_column_name("v (Mph)"), "mph");
  // Names whose unit cannot be taken as stated: an unclosed bracket, two units that differ.
  EXPECT_NE(column_unit_problem("v (mm/s"), "");
  EXPECT_NE(column_unit_problem("x (mm) (um)"), "");
  EXPECT_NE(column_unit_problem("x_mm_um"), "");
  EXPECT_NE(column_unit_problem("x_mm (um)"), "");
  // "_in" alone: inches or an input, said (a displacement in inches was read as metres: the thirteenth pass's 1);
  // stated as a unit, or beside another, it is no question.
  EXPECT_NE(column_unit_problem("x_in").find("ends in '_in'"), std::string::npos);
  EXPECT_NE(column_unit_problem("Displacement_IN").find("ends in '_in'"), std::string::npos);
  EXPECT_EQ(column_unit_problem("x (in)"), "");
  EXPECT_EQ(column_unit_problem("v_in_s"), "");
  // Nested brackets pair up: the real Impulse_test.lvm's "Acceleration (FFT - (RMS))" closes (a backward scan called
  // it unclosed); a nested unit is read, and a bracket that closes with the wrong kind is still unclosed.
  EXPECT_EQ(column_unit_problem("Acceleration (FFT - (RMS))"), "");
  EXPECT_EQ(unit_of_column_name("Acceleration (FFT - (RMS))"), "");
  EXPECT_EQ(unit_of_column_name("x (tip (mm))"), "mm");
  EXPECT_NE(column_unit_problem("x (mm]"), "");
  // The sixth pass: one unit in two brackets is one unit (S003, S007: "two units" before), a remark inside the unit's
  // bracket is a remark (S004: read as SI), a peak or RMS qualifier leaves the unit (S028, S029), and units beamid
  // does not convert are refused rather than read as SI (S035-S060).
  for (const auto& [name, unit] :
       {std::pair{"a (m/(s^2))", "m/s^2"}, std::pair{"v ([mm/s])", "mm/s"}, std::pair{"v ((mm/s))", "mm/s"},
        std::pair{"x ((mm))", "mm"}, std::pair{"x (mm [tip])", "mm"}, std::pair{"a (g pk)", "g"},
        std::pair{"x (pk-pk mm)", "mm"}, std::pair{"v (mm/s rms)", "mm/s"}}) {
    EXPECT_EQ(unit_of_column_name(name), unit) << name;
    EXPECT_EQ(column_unit_problem(name), "") << name;
  }
  for (const char* name : {"a (\xc2\xb5g)", "x (\xc2\xb5in)", "x (dm)", "x (\xc3\x85)", "v (counts)"})
    EXPECT_FALSE(is_known_unit(unit_of_column_name(name))) << name << ": " << unit_of_column_name(name);
  for (const char* name : {"a (\xc2\xb5g)", "x (dm)", "v (counts)"}) EXPECT_NE(unit_of_column_name(name), "") << name;
  // The seventh pass: a remark after ';' or ',' in the unit's bracket (U004, U005), superscript exponents (U042): read
  // as the unit; a scale factor (U024), knots, g0 and a degree sign (U049, U063, U095), and two units side by side
  // (U028, "m m" is m^2, which the spaces' removal made mm): kept as stated, so that they are refused, not read as SI.
  for (const auto& [name, unit] :
       {std::pair{"x (mm; tip)", "mm"}, std::pair{"x (tip; mm)", "mm"}, std::pair{"x (tip, mm)", "mm"},
        std::pair{"v (mm\xc2\xb7s\xe2\x81\xbb\xc2\xb9)", "mm/s"},
        std::pair{"a (m\xc2\xb7s\xe2\x81\xbb\xc2\xb2)", "m/s^2"}, std::pair{"v (mm/s [tip])", "mm/s"},
        std::pair{"a (m/(s^2) [raw])", "m/s^2"}, std::pair{"x (mm: laser)", "mm"}, std::pair{"x (mm | tip)", "mm"},
        std::pair{"x (mm - tip)", "mm"}, std::pair{"x (mm\xc2\xb7tip)", "mm"}, std::pair{"a (g_n)", "g"},
        std::pair{"x (mm [sensor 1])", "mm"}})
    EXPECT_EQ(unit_of_column_name(name), unit) << name;
  for (const char* name : {"x (1e-3 m)", "x (10^-3 m)", "v (knots)", "a (g0)",
                           "a (\xc2\xb0"
                           "C)",
                           "x (m m)", "x (mm; um)", "x (mm2)", "x (mm*mm)", "x (mm~tip)", "x (mm#1)", "x (mm.)",
                           "x (mm/ laser)", "x (mm\xc2\xb2)", "a (g\xc2\xb7s)"}) {
    EXPECT_NE(unit_of_column_name(name), "") << name;
    EXPECT_FALSE(is_known_unit(unit_of_column_name(name))) << name << ": " << unit_of_column_name(name);
  }
  EXPECT_EQ(unit_of_column_name("x (1)"), "");  // a bare number is a remark (a channel's index), not a scale
  // The fifth pass's: a remark after the unit (R005, R043), and time columns labelled after a remark, spelled out,
  // or in no time unit (R061-R074).
  EXPECT_EQ(unit_of_column_name("x (mm) (raw)"), "mm");
  EXPECT_EQ(unit_of_column_name("a (g) [tip]"), "g");
  EXPECT_EQ(unit_of_column_name("acc_g_raw"), "g");
  EXPECT_EQ(time_unit_of_column_name("t (ms) [rel]"), "ms");
  EXPECT_EQ(time_unit_of_column_name("t_ms_abs"), "ms");
  EXPECT_EQ(time_unit_of_column_name("time (milliseconds)"), "ms");
  EXPECT_EQ(time_unit_of_column_name("t (Hz)"), "Hz");
  EXPECT_EQ(time_unit_of_column_name("t (m)"), "m");
  EXPECT_EQ(time_unit_of_column_name("time"), "");
  EXPECT_NE(column_unit_problem("t [ms"), "");
  // Spelled-out units, SI exponents, other brackets, a trailing unit after a space, "per", and a unit over a time
  // unit beamid does not convert (the fifth pass's R001-R053): read as stated, or kept so that they are refused.
  EXPECT_EQ(unit_of_column_name("x (micrometres)"), "um");
  EXPECT_EQ(unit_of_column_name("x (centimeters)"), "cm");
  EXPECT_EQ(unit_of_column_name("v (mm s-1)"), "mm/s");
  EXPECT_EQ(unit_of_column_name("a (mm.s-2)"), "mm/s^2");
  EXPECT_EQ(unit_of_column_name("v {mm/s}"), "mm/s");
  EXPECT_EQ(unit_of_column_name("x <mm>"), "mm");
  EXPECT_EQ(unit_of_column_name("v mm/s"), "mm/s");
  EXPECT_EQ(unit_of_column_name("v_cm_s"), "cm/s");
  EXPECT_EQ(unit_of_column_name("v_kmh"), "km/h");
  EXPECT_EQ(unit_of_column_name("v_mm_per_s"), "mm/s");
  EXPECT_EQ(unit_of_column_name("v_m_min"), "m/min");
  EXPECT_FALSE(is_known_unit("m/min"));
  EXPECT_NE(column_unit_problem("x mm)"), "");
  EXPECT_DOUBLE_EQ(si_conversion("cm/s")->factor, 0.01);
  for (const char* fine : {"x (mm)", "acc_m_s2", "v_mm_s", "accel (tip) (g)", "tip_mm_s", "sensor", "x (mm) [tip]"})
    EXPECT_EQ(column_unit_problem(fine), "") << fine;
}

TEST(Units, ARecordInMillimetresPerSecondIsReadInMetresPerSecond) {
  // The adversarial pass's velocity_mm_s record was read as m/s, 1000 times too large, without a word.
  const std::string path = testing::TempDir() + "mm_s.csv";
  {
    std::ofstream out(path);
    out << "t_s,velocity_mm_s\n";
    for (int i = 0; i < 16; ++i) out << 0.001 * i << "," << (i % 5) - 2 << "\n";
  }
  const TimeSeries s = read_time_series(path);
  EXPECT_EQ(s.unit, "m/s");
  EXPECT_EQ(s.values[0], -2e-3);  // -2 mm/s
  EXPECT_NE(s.notes.find("converted from mm/s to m/s (x 0.001)"), std::string::npos) << s.notes;
  // --units as-is takes the numbers as they are; a unit the file states that beamid converts contradicts it, as it
  // does --units g (mm/s taken as m/s is 1000 times off). A unit it does not convert (V, or SI) is kept as the label.
  ImportOptions as_is;
  as_is.units = "as-is";
  try {
    read_time_series(path, as_is);
    ADD_FAILURE() << "mm/s taken as-is";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "--units as-is: the file states that velocity_mm_s is in mm/s, which beamid converts to m/s"),
              std::string::npos)
        << e.what();
  }
  const std::string volts = testing::TempDir() + "volts.csv";
  {
    std::ofstream out(volts);
    out << "t_s,signal (V)\n";
    for (int i = 0; i < 16; ++i) out << 0.001 * i << "," << (i % 5) - 2 << "\n";
  }
  const TimeSeries raw = read_time_series(volts, as_is);
  EXPECT_EQ(raw.values[0], -2.0);
  EXPECT_EQ(raw.unit, "V");
}

}  // namespace
}  // namespace beamid::io
