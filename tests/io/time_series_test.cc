// Reading data records: each malformed file gives an InputError naming the file, line, column and constraint.
#include "io/time_series.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/errors.h"
#include "record_files.h"

namespace beamid::io {
namespace {

std::string rows(int n, double dt) {
  std::string text = "t_s,displacement_m\n";
  for (int i = 0; i < n; ++i) text += std::to_string(i * dt) + "," + std::to_string(0.1 * i) + "\n";
  return text;
}

TEST(TimeSeries, ReadsAUniformRecord) {
  const auto s = read_time_series(write("good.csv", rows(10, 0.001)));
  EXPECT_EQ(s.values.size(), 10u);
  EXPECT_NEAR(s.dt_s, 0.001, 1e-15);
  EXPECT_EQ(s.value_column, "displacement_m");
}

TEST(TimeSeries, MalformedFilesAreLocated) {
  std::string text = rows(10, 0.001);
  const std::string with_nan = text.replace(text.find("0.003000,0.300000"), 17, "0.003000,nan");
  EXPECT_NE(error_of(write("nan.csv", with_nan)).find("nan.csv:5: displacement_m = nan: must be finite"),
            std::string::npos)
      << error_of(write("nan.csv", with_nan));
  text = rows(10, 0.001);
  const std::string jitter = text.replace(text.find("0.004000,"), 9, "0.004100,");
  EXPECT_NE(error_of(write("jitter.csv", jitter)).find("jitter.csv:6: t_s = 0.0041: non-uniform time base"),
            std::string::npos)
      << error_of(write("jitter.csv", jitter));
  EXPECT_NE(error_of(write("short.csv", rows(5, 0.001))).find("5 samples: at least 8 are needed"), std::string::npos);
  EXPECT_NE(error_of(write("word.csv", "t_s,y\n0,1\n0.1,abc\n")).find("word.csv:3: y = 'abc': must be a number"),
            std::string::npos);
  EXPECT_NE(error_of(write("one.csv", "t\n")).find("must name at least two columns"), std::string::npos);
  EXPECT_NE(error_of(write("three.csv", "t,a,b\n" + std::string(10, ' ') + "\n"))
                .find("2 signal columns (a, b): choose one with --channel"),
            std::string::npos);
  EXPECT_NE(error_of(testing::TempDir() + "absent.csv").find("cannot read the file"), std::string::npos);
  EXPECT_NE(error_of(testing::TempDir() + "absent.csv").find("(No such file or directory)"), std::string::npos);
}

TEST(TimeSeries, AMissingSampleACounterAndACoarseColumnAreNamed) {
  // A 1 kHz record printed to the millisecond, one sample (line 502) missing: it was read as uniform at dt = 1.00098
  // ms, every later sample a step off. The doubled step is named on its line.
  std::string missing = "t_s,displacement_m\n";
  for (int i = 0; i < 1024; ++i)
    if (i != 500)
      missing += std::to_string(i / 1000) + "." + std::string(i % 1000 < 100 ? (i % 1000 < 10 ? "00" : "0") : "") +
                 std::to_string(i % 1000) + "," + std::to_string(i % 7) + "\n";
  EXPECT_NE(error_of(write("missing.csv", missing)).find("missing.csv:502: t_s = 0.501: a step of 0.002"),
            std::string::npos)
      << error_of(write("missing.csv", missing));
  EXPECT_NE(error_of(write("missing.csv", missing)).find("(a missing sample?"), std::string::npos);
  // A column of sample indices is no time in seconds.
  std::string counter = "sample,displacement_m\n";
  for (int i = 0; i < 16; ++i) counter += std::to_string(i) + "," + std::to_string(i % 5) + "\n";
  EXPECT_NE(error_of(write("counter.csv", counter)).find("time column 'sample' counts samples (0, 1, ...)"),
            std::string::npos)
      << error_of(write("counter.csv", counter));
  // A step below 1 ns is a unit mistake (an LVM Delta_X of 1e-300 gave spikes at 3e297 Hz).
  std::string fast = "t_s,displacement_m\n";
  for (int i = 0; i < 10; ++i) fast += std::to_string(i) + "e-12," + std::to_string(i % 3) + "\n";
  EXPECT_NE(error_of(write("fast.csv", fast)).find("(a rate above 1 GHz)"), std::string::npos)
      << error_of(write("fast.csv", fast));
  // Quoted names as pandas writes them are names; a time column in ms under any spelling is refused.
  EXPECT_EQ(read_time_series(write("quoted.csv", "\"t_s\",\"accel_g\"\n" + rows(10, 0.001).substr(19))).unit, "m/s^2");
  for (const char* header : {"Time [ms]", "T_MS", "time_msec", "\"t_ms\""})
    EXPECT_NE(error_of(write("ms.csv", std::string(header) + ",x_m\n" + rows(10, 1.0).substr(19))).find("is in ms"),
              std::string::npos)
        << header;
  // --units g against a file that states millimetres.
  ImportOptions g;
  g.units = "g";
  EXPECT_NE(error_of(write("mm.csv", "t_s,x (mm)\n" + rows(10, 0.001).substr(19)), g)
                .find("--units g: the file states that x (mm) is in mm"),
            std::string::npos);
}

TEST(TimeSeries, ATimeBaseThatRepeatsJumpsOrRunsForDaysIsNamedWhereItIs) {
  // A duplicated line is blamed on itself (line 7 repeats line 6's time), not on the first line the mean step misses.
  std::string duplicated = rows(12, 0.001);
  const std::size_t line7 = [&] {  // the start of line 7 (the header is line 1)
    std::size_t at = 0;
    for (int k = 0; k < 6; ++k) at = duplicated.find('\n', at) + 1;
    return at;
  }();
  const std::size_t line8 = duplicated.find('\n', line7) + 1;
  duplicated.insert(line8, duplicated.substr(line7, line8 - line7));
  EXPECT_NE(error_of(write("dup.csv", duplicated)).find("dup.csv:8: t_s = 0.005: repeats the previous sample's time"),
            std::string::npos)
      << error_of(write("dup.csv", duplicated));
  // --resample does not interpolate across a gap of 998 median steps.
  std::string gap = "t_s,displacement_m\n";
  for (int i = 0; i < 12; ++i)
    gap += std::to_string(i * 0.001 + (i >= 6 ? 1.0 : 0.0)) + "," + std::to_string(i % 3) + "\n";
  ImportOptions resample;
  resample.resample = true;
  EXPECT_NE(error_of(write("gap.csv", gap), resample).find("gap.csv:8: t_s = 1.006: a gap of"), std::string::npos)
      << error_of(write("gap.csv", gap), resample);
  // A record of more than 1e6 s (an LVM Delta_X of 1e300 made one of 4e303 s) is a unit mistake.
  EXPECT_NE(error_of(write("days.csv", rows(10, 2e5))).find("the record lasts 1800000 s"), std::string::npos)
      << error_of(write("days.csv", rows(10, 2e5)));
  // Values below 1e-150 underflow (the pencil found 14.7 Hz in a 2.46 Hz decay scaled by 1e-200).
  std::string tiny = "t_s,displacement_m\n";
  for (int i = 0; i < 10; ++i) tiny += std::to_string(i * 0.001) + "," + std::to_string(i % 3) + "e-200\n";
  EXPECT_NE(error_of(write("tiny.csv", tiny)).find("reaches only 2e-200 m: below 1e-150"), std::string::npos)
      << error_of(write("tiny.csv", tiny));
}

// A LabVIEW export as NI writes it: tab-separated, two header blocks, times rounded to 6 decimals of a step that
// is not a round number (51200/31 Hz), the unit g, an empty Comment column.
std::string lvm(int n, const std::string& value_of_8 = "") {
  std::string text =
      "LabVIEW Measurement\t\nWriter_Version\t2\nSeparator\tTab\nDecimal_Separator\t.\nMulti_Headings\tYes\n"
      "X_Columns\tMulti\n***End_of_Header***\t\n\t\nChannels\t1\t\nSamples\t" +
      std::to_string(n) +
      "\t\nY_Unit_Label\tg\t\nX_Dimension\tTime\t\nX0\t0.0000000000000000E+0\t\nDelta_X\t0.000605\t\n"
      "***End_of_Header***\t\t\nX_Value\tAcceleration\tComment\n";
  const double dt = 31.0 / 51200;
  for (int i = 0; i < n; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.6f\t%.6f\n", i * dt, std::sin(0.3 * i));
    text += i == 8 && !value_of_8.empty()
                ? std::string(line).substr(0, std::string(line).find('\t') + 1) + value_of_8 + "\n"
                : std::string(line);
  }
  return text;
}

TEST(TimeSeries, ReadsLabViewTextWithRoundedTimesAndConvertsG) {
  const auto s = read_time_series(write("rec.lvm", lvm(100)));
  EXPECT_EQ(s.format, "lvm");
  EXPECT_EQ(s.value_column, "Acceleration");
  EXPECT_EQ(s.unit, "m/s^2");
  ASSERT_EQ(s.values.size(), 100u);
  // dt from the endpoints: the 6-decimal rounding of the last time (<= 5e-7 s) over 99 steps.
  EXPECT_NEAR(s.dt_s, 31.0 / 51200, 5e-7 / 99 + 1e-15);
  EXPECT_NEAR(s.values[3], 9.80665 * std::round(1e6 * std::sin(0.9)) / 1e6, 1e-12);
  // A window keeps t in [start, start + duration). --units as-is would take the g the file states as m/s^2: refused.
  ImportOptions o;
  o.start_s = 10 * 31.0 / 51200;
  o.duration_s = 20 * 31.0 / 51200;
  const auto w = read_time_series(write("rec.lvm", lvm(100)), o);
  EXPECT_EQ(w.unit, "m/s^2");
  ASSERT_EQ(w.values.size(), 20u);
  EXPECT_NEAR(w.values[0], 9.80665 * std::round(1e6 * std::sin(3.0)) / 1e6, 1e-12);
  o.units = "as-is";
  EXPECT_NE(error_of(write("rec.lvm", lvm(100)), o).find("--units as-is: the file states that Acceleration is in g"),
            std::string::npos);
  EXPECT_NEAR(w.t0_s, 10 * w.dt_s, 1e-12);
}

TEST(TimeSeries, AByteOrderMarkIsSkippedAndLatin1IsRefusedOnItsLine) {
  // The seventh pass's L12 (an LVM with a UTF-8 byte order mark was "not a LabVIEW file") and T65 (a CSV header
  // written in Latin-1, whose micro sign is the single byte 0xB5, was read as metres, 1e6 x off).
  const auto s = read_time_series(write("bom.lvm", "\xEF\xBB\xBF" + lvm(100)));
  EXPECT_EQ(s.format, "lvm");
  EXPECT_EQ(s.values.size(), 100u);
  std::string latin = "t_s,x (\xB5m)\n";
  for (int i = 0; i < 64; ++i) latin += std::to_string(i * 1e-3) + "," + std::to_string(0.1 * i) + "\n";
  const std::string error = error_of(write("latin1.csv", latin));
  EXPECT_NE(error.find("latin1.csv:1: byte 0xB5 is not UTF-8"), std::string::npos) << error;
}

TEST(TimeSeries, CountsDecimalCommasAndRemarksAreToldApart) {
  // The seventh pass's T28 and Q102: a time base of 0, 1, 2, ... is a sample count whatever the column's name (it
  // gave modes at 1 Hz sampling), unless the name says seconds; T10: decimal commas; L26: "kHz" in a remark after a
  // comma is no frequency column.
  std::string counted = "\n", seconds = "t_s,y (m)\n", commas = "\n", remark = "t_s\tv (tip), filtered 2 kHz\n";
  for (int i = 0; i < 64; ++i) {
    const std::string v = std::to_string(std::sin(0.3 * i));
    counted += std::to_string(i) + "\t" + v + "\n";
    seconds += std::to_string(i) + "," + v + "\n";
    std::string c = std::to_string(i * 1e-3) + "\t" + v;
    std::replace(c.begin(), c.end(), '.', ',');
    commas += c + "\n";
    remark += std::to_string(i * 1e-3) + "\t" + v + "\n";
  }
  ImportOptions g;
  g.units = "g";
  EXPECT_NE(error_of(write("counted.txt", counted), g).find("time column 'time' counts samples (0, 1, ...)"),
            std::string::npos)
      << error_of(write("counted.txt", counted), g);
  EXPECT_NEAR(read_time_series(write("seconds.csv", seconds)).dt_s, 1.0, 1e-12);
  EXPECT_NE(error_of(write("commas.txt", commas), g)
                .find("commas.txt:2: '0,000000\\x090,000000': numbers with a decimal comma"),
            std::string::npos)
      << error_of(write("commas.txt", commas), g);
  EXPECT_EQ(read_time_series(write("remark.txt", remark), g).values.size(), 64u);
}

TEST(TimeSeries, ALabViewChannelsNameStatesItsUnitAndASpectrumIsRefused) {
  // The fifth pass's R104: a channel named "disp (mm)" under an empty Y_Unit_Label was read as metres, 1e3 off.
  std::string text = lvm(100);
  text.replace(text.find("Y_Unit_Label\tg"), 14, "Y_Unit_Label\t");
  text.replace(text.find("\tAcceleration\t"), 14, "\tdisp (mm)\t");
  const auto mm = read_time_series(write("name_mm.lvm", text));
  EXPECT_EQ(mm.unit, "m");
  EXPECT_NEAR(mm.values[3], 1e-3 * std::round(1e6 * std::sin(0.9)) / 1e6, 1e-15);
  // A blank Y_Unit_Label under a name that states no unit states none: the user says which (a record in g was read
  // as m/s^2, 9.81x off: the twelfth pass's P8).
  std::string blank = lvm(100);
  blank.replace(blank.find("Y_Unit_Label\tg"), 14, "Y_Unit_Label\t");
  EXPECT_NE(error_of(write("blank_unit.lvm", blank))
                .find("column 'Acceleration': its Y_Unit_Label is blank and its name states no unit"),
            std::string::npos)
      << error_of(write("blank_unit.lvm", blank));
  // R105: a name and a Y_Unit_Label that disagree are refused on the names' line (16).
  text.replace(text.find("Y_Unit_Label\t"), 13, "Y_Unit_Label\tm");
  const std::string both = error_of(write("name_and_label.lvm", text));
  EXPECT_NE(both.find("name_and_label.lvm:16: column 'disp (mm)': its name states mm and the header's Y_Unit_Label "
                      "states m"),
            std::string::npos)
      << both;
  // A spectrum, named so (the real Impulse_test.lvm: dB against frequency under X_Dimension Time), or declared so by
  // X_Dimension, is not read as samples in time.
  std::string fft = lvm(100);
  fft.replace(fft.find("\tAcceleration\t"), 14, "\tAcceleration (FFT - (RMS))\t");
  EXPECT_NE(error_of(write("fft.lvm", fft)).find("its name says FFT: beamid reads time series"), std::string::npos)
      << error_of(write("fft.lvm", fft));
  std::string frequency = lvm(100);
  frequency.replace(frequency.find("X_Dimension\tTime"), 16, "X_Dimension\tFrequency");
  EXPECT_NE(error_of(write("f.lvm", frequency)).find("f.lvm:12: X_Dimension = 'Frequency' (channel 1): must be Time"),
            std::string::npos)
      << error_of(write("f.lvm", frequency));
  // The second channel's X_Dimension counts too (S094).
  std::string second = lvm(100);
  second.replace(second.find("X_Dimension\tTime"), 16, "X_Dimension\tTime\tFrequency");
  EXPECT_NE(error_of(write("f2.lvm", second)).find("X_Dimension = 'Frequency' (channel 2): must be Time"),
            std::string::npos)
      << error_of(write("f2.lvm", second));
  // A word inside another is no mark ("feedback" holds "db" only as letters of a word).
  std::string feedback = lvm(100);
  feedback.replace(feedback.find("\tAcceleration\t"), 14, "\tfeedback (g)\t");
  EXPECT_EQ(read_time_series(write("feedback.lvm", feedback)).unit, "m/s^2");
}

TEST(TimeSeries, AJumpInTheTimeBaseIsNamedOnItsOwnLine) {
  // The sixth pass's S107: every time from row 300 on shifted by 0.4 ms (a 1 ms record) was blamed on line 3, where
  // the mean step, biased by the jump, first missed the grid. Row 300 is line 302 (the header is line 1).
  std::string text = "t_s,displacement_m\n";
  for (int i = 0; i < 400; ++i)
    text += std::to_string(i * 0.001 + (i >= 300 ? 0.0004 : 0.0)) + "," + std::to_string(0.1 * (i % 7)) + "\n";
  const std::string error = error_of(write("jump.csv", text));
  EXPECT_NE(error.find("jump.csv:302: t_s = 0.3004: a step of"), std::string::npos) << error;
  EXPECT_NE(error.find("the time base jumps here"), std::string::npos) << error;
  // One sample off its time (the steps around it make up for each other) is still the grid check's to name.
  std::string off = "t_s,displacement_m\n";
  for (int i = 0; i < 400; ++i)
    off += std::to_string(i * 0.001 + (i == 300 ? 0.0004 : 0.0)) + "," + std::to_string(0.1 * (i % 7)) + "\n";
  EXPECT_NE(error_of(write("off.csv", off)).find("off.csv:302: t_s = 0.3004: non-uniform time base"), std::string::npos)
      << error_of(write("off.csv", off));
}

TEST(TimeSeries, APlainTextTableIsReadByColumnAndStatesNoUnitOfItsOwn) {
  // As a DAQ's "save as text" writes a record (the UnB impact tests: a blank line, then tab-separated time, an unused
  // channel, acceleration in g and force): 100 rows at dt = 0.000605 s.
  std::string text = "\n";
  for (int i = 0; i < 100; ++i) {
    char line[96];
    std::snprintf(line, sizeof line, "%.6f\t30.2\t%.6f\t%.6f\n", i * 0.000605, std::sin(0.3 * i), 0.0);
    text += line;
  }
  const std::string path = write("impact.txt", text);
  // It names no column, so it states no unit: taken as SI it would be 9.81 times off for a record in g.
  ImportOptions o;
  o.channel = "2";  // the second signal: the file's column 3
  EXPECT_NE(error_of(path, o).find("the table names no columns, so it states no unit: give --units g"),
            std::string::npos)
      << error_of(path, o);
  o.units = "g";
  const auto s = read_time_series(path, o);
  EXPECT_EQ(s.format, "text");
  EXPECT_EQ(s.value_column, "signal 2");  // as --channel counts the signals
  EXPECT_EQ(s.unit, "m/s^2");
  ASSERT_EQ(s.values.size(), 100u);
  EXPECT_NEAR(s.dt_s, 0.000605, 1e-12);
  EXPECT_NEAR(s.values[3], 9.80665 * std::round(1e6 * std::sin(0.9)) / 1e6, 1e-12);
  // With a line of names (tabs between names that hold spaces), a name's unit is read as a CSV column's.
  std::string named = "# exported by hand\ntime (s)\tdisp (mm)\n";
  for (int i = 0; i < 20; ++i) named += std::to_string(i * 0.001) + "  " + std::to_string(i % 3) + "\n";
  const auto mm = read_time_series(write("named.dat", named));
  EXPECT_EQ(mm.unit, "m");
  EXPECT_NEAR(mm.values[2], 2e-3, 1e-15);
  // A row with a field missing is refused on its line (line 2 of the file is its first row).
  std::string short_row = text;
  short_row.replace(short_row.find("\t0.000000\n", 200), 10, "\n");
  EXPECT_NE(error_of(write("short.txt", short_row), o).find("short.txt:"), std::string::npos)
      << error_of(write("short.txt", short_row), o);
  EXPECT_NE(error_of(write("short.txt", short_row), o).find("3 fields: must be 4"), std::string::npos)
      << error_of(write("short.txt", short_row), o);
}

TEST(TimeSeries, AColumnNamedAsFrequenciesOrTimesIsNoRecordOrSignal) {
  // The sixth pass's S070, S137, S477: a spectrum's axis "freq_Hz" was read as seconds, beamid's own fit-report
  // spectra file (bin, frequency_hz, data_magnitude) as a time record, and a second time column as the vibration.
  std::string spectrum = "freq_Hz,magnitude\n", spectra = "bin,frequency_hz,data_magnitude\n";
  std::string two_times = "t_s,time_s,v_m_s\n";
  for (int i = 0; i < 20; ++i) {
    spectrum += std::to_string(i) + "," + std::to_string(1.0 / (1 + i)) + "\n";
    spectra += std::to_string(i) + "," + std::to_string(0.5 * i) + "," + std::to_string(1.0 / (1 + i)) + "\n";
    two_times += std::to_string(0.001 * i) + "," + std::to_string(0.001 * i) + "," + std::to_string(i % 3) + "\n";
  }
  EXPECT_NE(error_of(write("spectrum.csv", spectrum)).find("first column 'freq_Hz': its name says frequency"),
            std::string::npos)
      << error_of(write("spectrum.csv", spectrum));
  ImportOptions o;
  o.channel = "2";
  EXPECT_NE(error_of(write("spectra.csv", spectra), o).find("its name says frequency"), std::string::npos)
      << error_of(write("spectra.csv", spectra), o);
  o.channel = "time_s";
  EXPECT_NE(error_of(write("times.csv", two_times), o).find("column 'time_s': its name says it holds times"),
            std::string::npos)
      << error_of(write("times.csv", two_times), o);
  o.channel = "v_m_s";
  EXPECT_EQ(read_time_series(write("times.csv", two_times), o).values.size(), 20u);
}

TEST(TimeSeries, ACoarseLabViewTimeColumnTakesTheHeadersStepWhenEveryTimeAgrees) {
  // The fourth pass's Q214: an X column rounded to 10 ms beside Delta_X = 0.001 gave the column's mean step,
  // 0.000997067 s, 0.3 % off, and every frequency with it. Every printed time agrees with the header's step to its
  // printed resolution, so that step is the record's, exactly.
  // n samples at 1 ms with Delta_X = 0.001 and the X column printed to 2 decimals.
  const auto coarse = [](int n) {
    std::string text = lvm(0);
    text.replace(text.find("Delta_X\t0.000605"), 17, "Delta_X\t0.001");
    for (int i = 0; i < n; ++i) {
      char line[64];
      std::snprintf(line, sizeof line, "%.2f\t%.6f\n", i * 1e-3, std::sin(0.3 * i));
      text += line;
    }
    return text;
  };
  const auto s = read_time_series(write("coarse.lvm", coarse(1024)));
  EXPECT_EQ(s.dt_s, 1e-3);
  EXPECT_NE(s.notes.find("the header's Delta_X"), std::string::npos) << s.notes;
  // 60 samples: the rounded last time makes the column's mean step 1.7 % off, which was refused as "the header and
  // the data disagree" (the fifth pass's R120), though every printed time agrees with Delta_X.
  EXPECT_EQ(read_time_series(write("short.lvm", coarse(60))).dt_s, 1e-3);
}

TEST(TimeSeries, LabViewChannelsOnOtherTimesAreNotOneRecord) {
  // X_Columns Multi: each channel has its own X column. Channel 1's times were used for channel 2 though its own were
  // 0.5 ms later (the fifth pass's R135); equal columns read as before.
  const auto two_channels = [](double offset_s) {
    std::string text = lvm(0);
    text.replace(text.find("X_Value\tAcceleration\tComment"), 28, "X_Value\tA\tX_Value\tB\tComment");
    text.replace(text.find("Delta_X\t0.000605"), 17, "Delta_X\t0.001");
    text.replace(text.find("Channels\t1"), 10, "Channels\t2");             // as many as the columns below (L10)
    text.replace(text.find("Y_Unit_Label\tg"), 14, "Y_Unit_Label\tg\tg");  // a unit for each (P8)
    for (int i = 0; i < 64; ++i) {
      char line[96];
      std::snprintf(line, sizeof line, "%.6f\t%.6f\t%.6f\t%.6f\n", i * 1e-3, std::sin(0.3 * i), i * 1e-3 + offset_s,
                    std::cos(0.3 * i));
      text += line;
    }
    return text;
  };
  ImportOptions o;
  o.channel = "B";
  EXPECT_EQ(read_time_series(write("multi.lvm", two_channels(0)), o).values.size(), 64u);
  EXPECT_NE(error_of(write("shifted.lvm", two_channels(5e-4)), o).find("X column 3 ('X_Value') = 0.000500 s differs"),
            std::string::npos)
      << error_of(write("shifted.lvm", two_channels(5e-4)), o);
  // A header's Channels that the data contradict (the seventh pass's L10: "Channels 2" over one channel was read).
  std::string wrong = two_channels(0);
  wrong.replace(wrong.find("Channels\t2"), 10, "Channels\t3");
  EXPECT_NE(error_of(write("channels.lvm", wrong), o).find(": Channels = 3: the data below have 2 channel column(s)"),
            std::string::npos)
      << error_of(write("channels.lvm", wrong), o);
}

TEST(TimeSeries, MalformedLabViewAndDaqFilesNameTheLine) {
  // Line 16 is the column-name line; data row 8 (0-based) is line 25.
  EXPECT_NE(error_of(write("nan.lvm", lvm(50, "NaN"))).find("nan.lvm:25: Acceleration = NaN: must be finite"),
            std::string::npos)
      << error_of(write("nan.lvm", lvm(50, "NaN")));
  EXPECT_NE(error_of(write("word.lvm", lvm(50, "1.2.3"))).find("word.lvm:25: Acceleration = '1.2.3': must be a number"),
            std::string::npos);
  EXPECT_NE(error_of(write("bad.lvm", "LabVIEW Measurement\nSeparator\tSemicolon\n"))
                .find("bad.lvm:2: Separator = 'Semicolon': must be Tab or Comma"),
            std::string::npos);
  EXPECT_NE(error_of(write("not.lvm", "time,value\n")).find("not.lvm:1: not a LabVIEW measurement file"),
            std::string::npos);
  // A hexadecimal literal, which strtod reads (0x10 as 16), is no sample (the tenth pass's NF_hex).
  EXPECT_NE(error_of(write("hex.csv", "t_s,x_m\n0,0.1\n0.1,0x10\n0.2,0.3\n"))
                .find("hex.csv:3: x_m = '0x10': must be a number"),
            std::string::npos)
      << error_of(write("hex.csv", "t_s,x_m\n0,0.1\n0.1,0x10\n0.2,0.3\n"));
  // A clipped record: the peak held for 3 samples.
  std::string clipped = "t_s,a\n";
  for (int i = 0; i < 20; ++i) clipped += std::to_string(0.01 * i) + "," + (i >= 5 && i < 8 ? "2.5" : "0.1") + "\n";
  EXPECT_NE(error_of(write("clip.csv", clipped))
                .find("clip.csv:7: a = 2.5 on 3 or more consecutive samples at the record's peak"),
            std::string::npos);
  // Clipped where a fast mode changes sign between samples (the nineteenth pass's P2): a 400 Hz decay at 1 kHz
  // clipped at 60 % of its peak meets the rail on single samples, never 3 in a row, and is refused as clipped; the
  // same decay unclipped is read.
  const auto fast_decay = [](double rail) {
    std::string text = "t_s,a_m_s2\n";
    for (int i = 0; i < 2000; ++i) {
      const double t = i * 1e-3;
      const double x = std::exp(-2 * t) * std::sin(2 * std::numbers::pi * 400 * t + 0.3);
      text += format_value(t) + "," + format_value(std::clamp(x, -rail, rail)) + "\n";
    }
    return text;
  };
  EXPECT_NE(error_of(write("scattered.csv", fast_decay(0.6))).find("separate stretches: the signal is clipped"),
            std::string::npos)
      << error_of(write("scattered.csv", fast_decay(0.6)));
  EXPECT_NO_THROW(read_time_series(write("unclipped.csv", fast_decay(2.0))));
  // A slow decay sampled fast on a 16-bit range holds its crest for several samples, entered and left by one quantum:
  // no rail (the twenty-fourth pass's adv56 P3 refused a 2.46 Hz mode at 10 kHz peaking at 80 % of full scale). The
  // same wave on a rail at 70 % of its amplitude arrives and leaves by 18 quanta a sample: clipped.
  const auto slow_wave = [](double rail) {
    const double quantum = 1.0 / 32768;  // 16 bits over [-1, 1]
    std::string text = "t_s,a_m_s2\n";
    for (int i = 0; i < 20000; ++i) {
      const double t = i * 1e-4;
      const double x =
          std::clamp(0.8 * std::exp(-0.3 * t) * std::sin(2 * std::numbers::pi * 2.46 * t + 0.3), -rail, rail);
      text += format_value(t) + "," + format_value(quantum * std::round(x / quantum)) + "\n";
    }
    return text;
  };
  EXPECT_NO_THROW(read_time_series(write("crest.csv", slow_wave(1.0))));
  // A rail on one side only, below the other side's peak (the twenty-fifth pass's adv58 P1): at -0.5 the decay's
  // negative half meets it in several stretches while its positive peak is 0.8.
  const auto one_sided = [](double rail) {
    std::string text = "t_s,a_m_s2\n";
    for (int i = 0; i < 4000; ++i) {
      const double t = i * 1e-3;
      const double x = 0.8 * std::exp(-0.3 * t) * std::sin(2 * std::numbers::pi * 2.46 * t + 0.3) +
                       0.05 * std::sin(2 * std::numbers::pi * 26.5 * t);
      text += format_value(t) + "," + format_value(std::max(x, rail)) + "\n";
    }
    return text;
  };
  EXPECT_NE(error_of(write("one_sided.csv", one_sided(-0.5)))
                .find("-0.5 on 3 or more consecutive samples at the "
                      "record's minimum"),
            std::string::npos)
      << error_of(write("one_sided.csv", one_sided(-0.5)));
  EXPECT_NO_THROW(read_time_series(write("two_sided.csv", one_sided(-2.0))));
  // A force channel at rest before and after its hit sits at its minimum, 0, on thousands of samples in two stretches:
  // its median, where it rests, no rail (the twenty-sixth pass's adv61 P2 refused simulate's own force column).
  std::string hit = "t_s,force_N\n";
  for (int i = 0; i < 4096; ++i) {
    const double f = i >= 100 && i < 104 ? std::pow(std::sin(std::numbers::pi * (i - 99) / 5.0), 2) : 0.0;
    hit += format_value(i * 1e-3) + "," + format_value(f) + "\n";
  }
  EXPECT_NO_THROW(read_time_series(write("hit.csv", hit)));
  // A pluck's pre-trigger lead-in holds the static deflection, its largest value, with noise of a few quanta that
  // meets the quantised maximum again and again (12 bits at 500 Hz), then decays: no rail, since between its visits
  // the signal never goes a tenth of the peak away (the twenty-seventh pass's adv63 P1 refused 6 of 12 seeds).
  std::string pluck = "t_s,x_m\n";
  const double q12 = 1.0 / 2048;
  for (int i = 0; i < 4396; ++i) {
    const double t = (i - 300) * 2e-3;
    const double x = i < 300 ? 1.0 + 2.6 * q12 * std::sin(1.7 * i) * std::sin(0.31 * i)
                             : std::exp(-0.2 * t) * std::cos(2 * std::numbers::pi * 2.46 * t);
    pluck += format_value(i * 2e-3) + "," + format_value(q12 * std::round(0.95 * x / q12)) + "\n";
  }
  EXPECT_NO_THROW(read_time_series(write("pluck.csv", pluck)));
  // A 10-bit record at 50 kHz holds a slow turning point's level for over 32 samples, entered and left by one
  // quantum: no dropout (adv58 P2 refused it as lost data).
  std::string fine_rate = "t_s,a_m_s2\n";
  for (int i = 0; i < 50000; ++i) {
    const double t = i * 2e-5, quantum = 1.0 / 512;
    const double x = std::exp(-0.3 * t) * std::sin(2 * std::numbers::pi * 2.46 * t + 0.3);
    fine_rate += format_value(t) + "," + format_value(quantum * std::round(x / quantum)) + "\n";
  }
  EXPECT_NO_THROW(read_time_series(write("fine_rate.csv", fine_rate)));
  // But a channel frozen at a crest for one whole period of a 30 Hz mode (667 samples at 20 kHz, 10 bits, zeta 0.05 %)
  // resumes within a quantum of the held value and is still lost data: a turning point holds a level for about 13
  // samples here, and the exemption stops at 4 times that (the twenty-sixth pass's adv60 P2 accepted 674 samples).
  std::vector<double> held(20000);
  const double quantum10 = 1.0 / 512, omega = 2 * std::numbers::pi * 30;
  for (std::size_t i = 0; i < held.size(); ++i) {
    const double t = static_cast<double>(i) / 20000;
    held[i] = quantum10 * std::round(std::exp(-0.0005 * omega * t) * std::sin(omega * t) / quantum10);
  }
  const std::size_t crest = 5000 + 167;  // t = 0.25 s + a quarter period: sin = 1
  for (std::size_t i = crest; i < crest + 667; ++i) held[i] = held[crest - 1];
  std::string frozen = "t_s,a_m_s2\n";
  for (std::size_t i = 0; i < held.size(); ++i)
    frozen += format_value(static_cast<double>(i) / 20000) + "," + format_value(held[i]) + "\n";
  EXPECT_NE(error_of(write("frozen.csv", frozen)).find("a dropout (lost data)"), std::string::npos)
      << error_of(write("frozen.csv", frozen));
  EXPECT_NE(error_of(write("rail.csv", slow_wave(0.56))).find("consecutive samples at the record's"), std::string::npos)
      << error_of(write("rail.csv", slow_wave(0.56)));
  // A dropout: 100 zeros at 0.5 s inside a 30 Hz decay sampled at 1 kHz (the ninth pass's #6), named on its first line
  // (header line 1, sample i on line i + 2). The same decay quantised to a 16-bit range, whose tail rounds to zero for
  // the record's last second, is no dropout, nor is a 0.25 Hz swing of 5 % of the peak under it, whose turning point at
  // 3 s holds one quantised value for about 44 samples: near such runs the signal stays within a few quanta of the
  // run's value (here about 9), far below 1 % of the peak.
  const auto record = [](int dropout, double quantum, double slow) {
    std::string text = "t_s,x_m\n";
    for (int i = 0; i < 4000; ++i) {
      const double t = i * 1e-3;
      double x = std::exp(-4 * t) * std::sin(2 * std::numbers::pi * 30 * t + 0.3) +
                 slow * std::sin(2 * std::numbers::pi * 0.25 * t);
      if (quantum > 0) x = quantum * std::round(x / quantum);
      if (i >= dropout && i < dropout + 100) x = 0;
      text += format_value(t) + "," + format_value(x) + "\n";
    }
    return text;
  };
  EXPECT_NE(error_of(write("dropout.csv", record(500, 0, 0)))
                .find("dropout.csv:502: x_m = 0 on 100 consecutive samples inside the record, with the vibration on "
                      "both sides: a dropout"),
            std::string::npos)
      << error_of(write("dropout.csv", record(500, 0, 0)));
  EXPECT_NO_THROW(read_time_series(write("tail.csv", record(-1000, 1.0 / 32768, 0))));
  EXPECT_NO_THROW(read_time_series(write("slow.csv", record(-1000, 1.0 / 32768, 0.05))));
  // Quantised to 8 bits (a quantum of 1/128 of the peak), the slow swing's turning point holds one value for about
  // 360 samples and leaves it by about 4 quanta, 2.8 % of the peak: quantisation, no dropout (the nineteenth pass's
  // P4). The 8-bit record's real dropout, zeros where the decay is still 0.135, is named as before.
  EXPECT_NO_THROW(read_time_series(write("coarse.csv", record(-1000, 1.0 / 128, 0.05))));
  EXPECT_NE(error_of(write("coarse_dropout.csv", record(500, 1.0 / 128, 0))).find("a dropout"), std::string::npos);
  // A record of 64 steps over its peak (7 bits over its range) whose slow mode (0.3 of the peak at 2.46 Hz) outlives
  // the fast ones holds its turning points for 47 samples: the refusal cannot tell that from lost data, and says so
  // (the twenty-seventh pass's adv62 P2 was told of a dropout alone).
  std::vector<double> crests(4096);
  double crest_peak = 0;
  for (std::size_t i = 0; i < crests.size(); ++i) {
    const double t = static_cast<double>(i) * 1e-3, pi = std::numbers::pi;
    crests[i] = 0.3 * std::sin(2 * pi * 2.46 * t + 0.3) + std::exp(-5 * t) * std::sin(2 * pi * 26.6 * t) +
                0.5 * std::exp(-8 * t) * std::sin(2 * pi * 81.7 * t);
    crest_peak = std::max(crest_peak, std::abs(crests[i]));
  }
  std::string slow_crests = "t_s,v_m_s\n";
  for (std::size_t i = 0; i < crests.size(); ++i)
    slow_crests += format_value(static_cast<double>(i) * 1e-3) + "," +
                   format_value(crest_peak / 64 * std::round(64 * crests[i] / crest_peak)) + "\n";
  EXPECT_NE(error_of(write("slow_crests.csv", slow_crests))
                .find("a dropout (lost data), whose spectrum is no beam's, or a slow turning point of a record "
                      "quantised this coarsely (its step is 1/"),
            std::string::npos)
      << error_of(write("slow_crests.csv", slow_crests));
  EXPECT_EQ(error_of(write("dropout.csv", record(500, 0, 0))).find("quantised"), std::string::npos);
  // Not where the run is jumped into: the 8-bit decay's zeros at 0.5 s are entered by about 5 quanta, no turning
  // point (the twenty-ninth pass's adv66 P5 was offered one for a run entered by 25).
  EXPECT_EQ(error_of(write("coarse_dropout.csv", record(500, 1.0 / 128, 0))).find("turning point"), std::string::npos)
      << error_of(write("coarse_dropout.csv", record(500, 1.0 / 128, 0)));
  // A hammer's force exactly 0 between two hits (half sines of 20 samples at 0.01 s and 2 s) rests there: no dropout
  // in a force unit, nor in a channel read as the excitation (--force-channel); a response so still would be lost
  // data (the twenty-seventh pass's adv62 P1 refused the force).
  const auto two_hits = [](const std::string& column) {
    std::string text = "t_s," + column + "\n";
    for (int i = 0; i < 4096; ++i) {
      double f = 0;
      if (i >= 10 && i < 30) f = std::sin(std::numbers::pi * (i - 10) / 20.0);
      if (i >= 2000 && i < 2020) f = 0.5 * std::sin(std::numbers::pi * (i - 2000) / 20.0);
      text += format_value(i * 1e-3) + "," + format_value(f) + "\n";
    }
    return text;
  };
  EXPECT_NO_THROW(read_time_series(write("hits_N.csv", two_hits("force (N)"))));
  // "force_N", simulate --force-column's own name, is in newtons too (the thirty-first pass's adv70 P4).
  EXPECT_NO_THROW(read_time_series(write("hits_force_N.csv", two_hits("force_N"))));
  // Two hits 3 samples long, sampled at 0.105, 0.914, 0.809, 0: a pulse the sampling barely resolves lands from its
  // crest in one step, at any phase (adv70 P3 refused this phase as clipped).
  std::string short_hits = "t_s,force_N\n";
  for (int i = 0; i < 4096; ++i) {
    const int k = i < 2000 ? i - 10 : i - 2010;
    const double f = k >= 0 && k < 3 ? std::vector<double>{0.105, 0.914, 0.809}[static_cast<std::size_t>(k)] : 0.0;
    short_hits += format_value(i * 1e-3) + "," + format_value(f) + "\n";
  }
  EXPECT_NO_THROW(read_time_series(write("short_hits.csv", short_hits)))
      << error_of(write("short_hits.csv", short_hits));
  EXPECT_NO_THROW(read_time_series(write("hits_lbf.csv", two_hits("hammer_lbf"))));
  ImportOptions excitation;
  excitation.excitation = true;
  EXPECT_NO_THROW(read_time_series(write("hits.csv", two_hits("hammer")), excitation));
  EXPECT_NE(error_of(write("hits.csv", two_hits("hammer"))).find("1971 consecutive samples at the record's minimum"),
            std::string::npos)
      << error_of(write("hits.csv", two_hits("hammer")));
  // Zeros inside a hit (a 200-sample half sine, samples 20-51 lost while it rises) are lost data, excitation or not
  // (the twenty-ninth pass's adv66 P1 took them as rest, and EI came out 7.7 % low).
  std::string inside_hit = "t_s,force_N\n";
  for (int i = 0; i < 4096; ++i) {
    double f = i < 200 ? std::sin(std::numbers::pi * i / 200.0) : 0.0;
    if (i >= 20 && i < 52) f = 0;
    inside_hit += format_value(i * 1e-4) + "," + format_value(f) + "\n";
  }
  EXPECT_NE(error_of(write("inside_hit.csv", inside_hit), excitation).find("on 32 consecutive samples"),
            std::string::npos)
      << error_of(write("inside_hit.csv", inside_hit), excitation);
  // A hit and its rebound on a 12-bit force channel (quantum 1/2048 of the peak): the force falls to a dip at 36 % of
  // the peak and rises again. Samples lost in the dip (35 read as 0, where the force falls by 0.02 a sample) are lost
  // data, not rest (the thirtieth pass's adv68 P1: EI 5.6 % low). At rest the channel's noise is a quantum: three
  // samples a quantum below rest are no rail (adv68 P2), and a quantum of noise just before the rest is no dropout's
  // edge (adv68 P3).
  const double q_hammer = 1.0 / 2048;
  const auto hammer = [&](bool lost_in_dip) {
    std::string text = "t_s,force_N\n";
    for (int i = 0; i < 4096; ++i) {
      double f = 0;
      if (i >= 10 && i < 130) f = std::sin(std::numbers::pi * (i - 10) / 120.0);
      if (i >= 90 && i < 210) f = std::max(f, 0.6 * std::sin(std::numbers::pi * (i - 90) / 120.0));
      if (lost_in_dip && i >= 100 && i < 135) f = 0;
      if (i >= 2000 && i < 2003) f = -q_hammer;  // noise at rest
      if (i == 2500) f = q_hammer;
      if (i >= 3000 && i < 3100) f = 0.5 * std::sin(std::numbers::pi * (i - 3000) / 100.0);
      text += format_value(i * 1e-4) + "," + format_value(q_hammer * std::round(f / q_hammer)) + "\n";
    }
    return text;
  };
  EXPECT_NO_THROW(read_time_series(write("hammer.csv", hammer(false)), excitation))
      << error_of(write("hammer.csv", hammer(false)), excitation);
  EXPECT_NE(error_of(write("hammer_lost.csv", hammer(true)), excitation).find("on 35 consecutive samples"),
            std::string::npos)
      << error_of(write("hammer_lost.csv", hammer(true)), excitation);
  EXPECT_NE(error_of(write("hits_m.csv", two_hits("x_m"))).find("a dropout (lost data)"), std::string::npos);
  // Channels by name and index; an unknown one lists the choices.
  const std::string two = "t_s,ax_g,ay_g\n0,1,2\n0.1,1,2\n0.2,1,2\n0.3,1,3\n0.4,1,2\n0.5,1,2\n0.6,1,2\n0.7,1,2\n";
  ImportOptions o;
  o.channel = "2";
  EXPECT_EQ(read_time_series(write("two.csv", two), o).value_column, "ay_g");
  EXPECT_NEAR(read_time_series(write("two.csv", two), o).values[3], 3 * 9.80665, 1e-12);
  o.channel = "az";
  EXPECT_NE(error_of(write("two.csv", two), o).find("channel = 'az': must be one of ax_g, ay_g (or 1..2)"),
            std::string::npos);
  // A column named like another's index is ambiguous (the name won without a word: the second pass's N044); a
  // column named like its own index is not.
  std::string numbered = two;
  numbered.replace(0, numbered.find('\n'), "t_s,2,1");
  o.channel = "2";
  EXPECT_NE(error_of(write("numbered.csv", numbered), o).find("channel = '2': ambiguous, the name of no. 1"),
            std::string::npos)
      << error_of(write("numbered.csv", numbered), o);
  numbered.replace(0, numbered.find('\n'), "t_s,1,2");
  EXPECT_EQ(read_time_series(write("numbered.csv", numbered), o).value_column, "2");
  // A window outside the record.
  ImportOptions late;
  late.channel = "2";  // (ax_g is constant, itself refused)
  late.start_s = 5;
  EXPECT_NE(error_of(write("two.csv", two), late).find("--start = '5' s: must lie inside the record, [0, 0.7] s"),
            std::string::npos)
      << error_of(write("two.csv", two), late);
  // A window that starts inside and runs past the end.
  ImportOptions long_window;
  long_window.channel = "2";
  long_window.start_s = 0.5;
  long_window.duration_s = 10;
  // It is told where the record ends and how long a window from its start can be (round(duration/dt) samples).
  EXPECT_NE(
      error_of(write("two.csv", two), long_window)
          .find("--duration = '10' s from 0.5 s runs past the record's end: the record spans [0, 0.7] s, so at most "
                "0.3 s from there"),
      std::string::npos)
      << error_of(write("two.csv", two), long_window);
}

TEST(TimeSeries, ResamplingOnRequest) {
  std::string jitter = "t_s,y\n";
  for (int i = 0; i < 20; ++i)
    jitter +=
        std::to_string(0.01 * i + (i == 7 ? 0.003 : 0)) + "," + std::to_string(2.0 * i + (i == 7 ? 0.6 : 0)) + "\n";
  EXPECT_NE(error_of(write("j.csv", jitter)).find("non-uniform time base"), std::string::npos);
  ImportOptions o;
  o.resample = true;
  const auto s = read_time_series(write("j.csv", jitter), o);
  // y = 200 t at every sample, the displaced one (t = 0.073, y = 14.6) too: the natural cubic spline reproduces a
  // straight line exactly (every second derivative 0), so y(0.07) = 14 on the uniform grid, to round-off.
  EXPECT_NEAR(s.values[7], 14, 1e-9);
  EXPECT_NEAR(s.values[10], 20, 1e-9);
  EXPECT_NE(s.notes.find("resampled"), std::string::npos);
}

TEST(TimeSeries, ReadsTheRealArtsRecord) {
  // studies/data/arts-steel-cantilever/timeseries_data.lvm (SOURCE.md there): 81 920 samples at 51200/31 Hz in g,
  // times printed to 6 decimals.
  const std::string path = std::string(BEAMID_SOURCE_DIR) + "/studies/data/arts-steel-cantilever/timeseries_data.lvm";
  const auto s = read_time_series(path);
  EXPECT_EQ(s.values.size(), 81920u);
  EXPECT_NEAR(1 / s.dt_s, 51200.0 / 31, 1e-3);  // the endpoints' 5e-7 s rounding over 81919 steps: 2e-5 Hz
  EXPECT_EQ(s.unit, "m/s^2");
  double peak = 0;
  for (double v : s.values) peak = std::max(peak, std::abs(v));
  EXPECT_NEAR(peak / 9.80665, 1.45, 0.05);  // the impact's peak, 1.45 g (SOURCE.md)
}

}  // namespace
}  // namespace beamid::io
