// The binary and modal-test formats labs write (issue 11 item 5): NumPy .npy (versions 1-3, both byte orders, C and
// Fortran order), MATLAB .mat v5 and v7.3 (written here by libmatio itself, including a struct), UFF dataset 58
// (ASCII and binary, beside a dataset of another type), and band-limited resampling. Each file is built in the test
// from known samples, so that what is read can be compared exactly; each malformed file must give an InputError that
// locates the fault (byte offset, line or variable path).
#include <gtest/gtest.h>
#include <matio.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <random>

#include "core/errors.h"
#include "io/time_series.h"
#include "record_files.h"

namespace beamid::io {
namespace {

// The test signal: a decaying 37 Hz sine plus a 3 Hz one, at 1 kHz.
double signal_at(double t) {
  return std::exp(-2 * t) * std::sin(2 * std::numbers::pi * 37 * t) + 0.3 * std::sin(2 * std::numbers::pi * 3 * t);
}

// An .npy file of `values` (row-major, `rows` x `columns`, columns 0 for a 1-D array) in format `major`.
std::string npy(const std::vector<double>& values, std::size_t rows, std::size_t columns, int major,
                const std::string& descr = "<f8", bool fortran = false) {
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': (" +
                       std::to_string(rows) + (columns ? ", " + std::to_string(columns) : ",") + "), }";
  const std::size_t preamble = major == 1 ? 10 : 12;
  while ((preamble + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += static_cast<char>(major);
  out += '\0';
  const std::size_t n = header.size();
  for (std::size_t b = 0; b < (major == 1 ? 2u : 4u); ++b) out += static_cast<char>((n >> (8 * b)) & 0xff);
  out += header;
  const std::size_t count = values.size();
  for (std::size_t k = 0; k < count; ++k) {
    // Fortran order writes column after column.
    const std::size_t c = columns ? columns : 1;
    const std::size_t index = fortran ? (k % rows) * c + k / rows : k;
    const double v = values[index];
    char bytes[8];
    std::size_t size = 8;
    if (descr.substr(1) == "f4") {
      const float f = static_cast<float>(v);
      std::memcpy(bytes, &f, 4);
      size = 4;
    } else if (descr.substr(1) == "f2") {  // half precision, for values it holds exactly (11 significant bits)
      std::uint16_t h = 0;
      if (v != 0) {
        int exponent = 0;
        const double mantissa = std::frexp(std::abs(v), &exponent);  // v = mantissa 2^exponent, mantissa in [0.5, 1)
        h = static_cast<std::uint16_t>((v < 0 ? 0x8000 : 0) | ((exponent + 14) << 10) |
                                       (static_cast<int>(std::ldexp(mantissa, 11)) - 1024));
      }
      std::memcpy(bytes, &h, 2);
      size = 2;
    } else if (descr.substr(1) == "i2") {
      const auto i = static_cast<std::int16_t>(v);
      std::memcpy(bytes, &i, 2);
      size = 2;
    } else {
      std::memcpy(bytes, &v, 8);
    }
    if (descr[0] == '>') std::reverse(bytes, bytes + size);  // this machine is little-endian (x86-64)
    out.append(bytes, size);
  }
  return out;
}

TEST(RecordFormats, NpyArraysOfEveryVersionOrderAndByteOrder) {
  const std::size_t n = 512;
  std::vector<double> two(2 * n), one(n);
  for (std::size_t i = 0; i < n; ++i) {
    one[i] = signal_at(static_cast<double>(i) * 1e-3);
    two[2 * i] = 100 + static_cast<double>(i);  // channel 1: a ramp
    two[2 * i + 1] = one[i];                    // channel 2: the signal
  }
  ImportOptions o;
  o.units = "as-is";  // an array states no unit (--units is required)
  o.sample_rate_hz = 1000;
  // Version 1, little-endian doubles, samples x channels: exact.
  o.channel = "2";
  // Without --units an array is refused: it states no unit (the seventh pass's F15 took one in g as m/s^2).
  ImportOptions unstated = o;
  unstated.units = "auto";
  EXPECT_NE(error_of(write("unstated.npy", npy(two, n, 2, 1)), unstated).find("a NumPy array states no unit"),
            std::string::npos);
  const TimeSeries a = read_time_series(write("two.npy", npy(two, n, 2, 1)), o);
  EXPECT_EQ(a.format, "npy");
  EXPECT_EQ(a.values, one);
  EXPECT_EQ(a.dt_s, 1e-3);
  // Version 2, big-endian singles, 1-D: the singles' rounding only (relative 6e-8 of the largest value, 1.3).
  o.channel.clear();
  const TimeSeries b = read_time_series(write("one.npy", npy(one, n, 0, 2, ">f4")), o);
  ASSERT_EQ(b.values.size(), n);
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(b.values[i], one[i], 1e-7) << i;
  // Version 3, Fortran order, channels x samples (2 x n, the samples along the longer dimension): exact.
  std::vector<double> transposed(2 * n);
  for (std::size_t i = 0; i < n; ++i) transposed[i] = two[2 * i], transposed[n + i] = two[2 * i + 1];
  o.channel = "2";
  const TimeSeries c = read_time_series(write("fortran.npy", npy(transposed, 2, n, 3, "<f8", true)), o);
  EXPECT_EQ(c.values, one);
  // Integers (a DAQ's raw counts) are read as numbers.
  std::vector<double> counts(n);
  for (std::size_t i = 0; i < n; ++i) counts[i] = std::round(1000 * one[i]);
  o.channel.clear();
  EXPECT_EQ(read_time_series(write("counts.npy", npy(counts, n, 0, 1, "<i2")), o).values, counts);
  // Half precision (NumPy's float16; refused as no number type: the thirtieth pass's adv68 P4): the counts over 1024,
  // which it holds exactly (11 significant bits), come back exactly.
  std::vector<double> halves(n);
  for (std::size_t i = 0; i < n; ++i) halves[i] = counts[i] / 1024;
  EXPECT_EQ(read_time_series(write("halves.npy", npy(halves, n, 0, 1, "<f2")), o).values, halves);
}

TEST(RecordFormats, AnArraysTimeChannelIsItsTimeBase) {
  // np.vstack((t, y)) saved as .npy: row 1 the time, row 2 the signal. With --time-channel 1 it is read as a CSV of
  // the same columns would be: the step from the time itself, the signal exact. An irregular time channel is refused
  // with the CSV's message (a --sample-rate on it gave smeared spectra without a word) unless --resample is given;
  // --resample with a --sample-rate, which is uniform by construction, is refused (it did nothing).
  const std::size_t n = 600;
  std::vector<double> rows(2 * n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    rows[i] = 0.5 + 2.5e-4 * static_cast<double>(i);  // 4 kHz from t = 0.5 s
    y[i] = signal_at(rows[i]);
    rows[n + i] = y[i];
  }
  ImportOptions o;
  o.units = "as-is";  // an array states no unit (--units is required)
  o.time_channel = "1";
  const TimeSeries a = read_time_series(write("timed.npy", npy(rows, 2, n, 1)), o);
  EXPECT_EQ(a.values, y);
  EXPECT_NEAR(a.dt_s, 2.5e-4, 1e-16);  // (t_last - t_0)/(n - 1) of doubles: round-off only
  EXPECT_NEAR(a.t0_s, 0.5, 1e-15);
  EXPECT_EQ(a.time_column, "array channel 1");
  // In float16 the times from 0.5 s are held only to 4.9e-4 s (2^-11 near 0.5 s), twice their step: the repeated times
  // are blamed on the type, not on a misordered line (the thirty-first pass's adv70 P5).
  EXPECT_NE(error_of(write("timed16.npy", npy(rows, 2, n, 1, "<f2")), o).find("the time channel's type holds it only"),
            std::string::npos)
      << error_of(write("timed16.npy", npy(rows, 2, n, 1, "<f2")), o);
  // The time and the signal are different channels; a rate and a time channel are not both taken.
  o.channel = "1";
  EXPECT_NE(error_of(write("timed.npy", npy(rows, 2, n, 1)), o).find("--channel = --time-channel = 1"),
            std::string::npos);
  o.channel.clear();
  o.sample_rate_hz = 4000;
  EXPECT_NE(error_of(write("timed.npy", npy(rows, 2, n, 1)), o).find("--time-channel or --sample-rate, not both"),
            std::string::npos);
  o.sample_rate_hz.reset();
  o.time_channel = "3";
  EXPECT_NE(error_of(write("timed.npy", npy(rows, 2, n, 1)), o).find("must be a channel index in 1..2"),
            std::string::npos);
  // Irregular: sample 300 late by a third of a step.
  std::vector<double> jittered = rows;
  jittered[300] += 2.5e-4 / 3;
  o.time_channel = "1";
  EXPECT_NE(error_of(write("jittered.npy", npy(jittered, 2, n, 1)), o).find("--resample"), std::string::npos)
      << error_of(write("jittered.npy", npy(jittered, 2, n, 1)), o);
  o.resample = true;
  EXPECT_EQ(read_time_series(write("jittered.npy", npy(jittered, 2, n, 1)), o).values.size(), n);
  o.time_channel.clear();
  o.sample_rate_hz = 4000;
  o.channel = "2";
  EXPECT_NE(error_of(write("timed.npy", npy(rows, 2, n, 1)), o).find("one made from --sample-rate is uniform"),
            std::string::npos);
}

TEST(RecordFormats, ResampleIsACubicSplineWithinItsErrorBound) {
  // A sinusoid at a tenth of the Nyquist frequency (200 Hz at 4 kHz) on a time base jittered by up to 30 % of a step:
  // read back on the uniform grid, it is within 5/384 (2 pi f dt)^4 = 1.3e-4 of the sinusoid away from the ends (the
  // spline's bound; the natural ends err more over a few samples), where linear interpolation errs by up to
  // (pi f dt)^2 / 2 = 1.2 % (the seventeenth pass's P4: a fit's cDI 6.5-13 % off).
  const std::size_t n = 2000;
  const double dt = 2.5e-4, f = 200, w = 2 * std::numbers::pi * f;
  std::vector<double> rows(2 * n);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (std::size_t i = 0; i < n; ++i) {
    rows[i] = dt * (static_cast<double>(i) + (i == 0 || i + 1 == n ? 0.0 : jitter(rng)));
    rows[n + i] = std::sin(w * rows[i]);
  }
  ImportOptions o;
  o.units = "as-is";
  o.time_channel = "1";
  o.resample = true;
  const TimeSeries r = read_time_series(write("spline.npy", npy(rows, 2, n, 1)), o);
  ASSERT_EQ(r.values.size(), n);
  double worst = 0;
  for (std::size_t i = 20; i + 20 < n; ++i)
    worst = std::max(worst, std::abs(r.values[i] - std::sin(w * (r.t0_s + static_cast<double>(i) * r.dt_s))));
  EXPECT_LT(worst, 5.0 / 384 * std::pow(w * dt * 1.3, 4));  // h up to 1.3 dt between jittered samples
  EXPECT_NE(r.notes.find("resampled by a cubic spline"), std::string::npos) << r.notes;
}

TEST(RecordFormats, MalformedNpyFilesNameTheByte) {
  // A header key stated twice ("'shape': (4,), 'shape': (2, 2)"): NumPy takes the last, and reading the first gave
  // spikes of a scrambled signal (the thirty-second pass's adv72 P1): refused by name.
  {
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (8,), 'shape': (4, 2), }";
    while ((10 + header.size() + 1) % 64 != 0) header += ' ';
    header += '\n';
    std::string file = std::string("\x93NUMPY\x01") + '\0' + static_cast<char>(header.size()) + '\0' + header;
    file += std::string(64, '\0');
    ImportOptions o;
    o.units = "as-is";
    o.sample_rate_hz = 1000;
    EXPECT_NE(error_of(write("twice.npy", file), o).find("header key 'shape' is stated 2 times"), std::string::npos)
        << error_of(write("twice.npy", file), o);
  }
  std::vector<double> v(64, 1.0);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::sin(0.3 * static_cast<double>(i));
  ImportOptions o;
  o.units = "as-is";  // an array states no unit (--units is required)
  o.sample_rate_hz = 100;
  const std::string good = npy(v, 64, 0, 1);
  std::string version = good;
  version[6] = 4;
  EXPECT_NE(error_of(write("v4.npy", version), o).find("byte 6: format version 4"), std::string::npos)
      << error_of(write("v4.npy", version), o);
  const std::string cut = good.substr(0, good.size() - 8);
  EXPECT_NE(error_of(write("cut.npy", cut), o).find("byte 128:"), std::string::npos)
      << error_of(write("cut.npy", cut), o);
  EXPECT_NE(error_of(write("cut.npy", cut), o).find("cut short"), std::string::npos);
  EXPECT_NE(error_of(write("complex.npy", npy(v, 32, 0, 1, "<c16")), o).find("descr = '<c16'"), std::string::npos);
  std::string long_header = good;
  long_header[8] = '\xff', long_header[9] = '\x7f';
  EXPECT_NE(error_of(write("long.npy", long_header), o).find("header length 32767 runs past"), std::string::npos);
  std::string cube = npy(v, 16, 4, 1);
  cube.replace(cube.find("(16, 4)"), 7, "(4,4,4)");
  EXPECT_NE(error_of(write("cube.npy", cube), o).find("one or two dimensions"), std::string::npos)
      << error_of(write("cube.npy", cube), o);
  EXPECT_NE(error_of(write("norate.npy", good)).find("give --sample-rate"), std::string::npos);
  std::vector<double> nan_inside = v;
  nan_inside[10] = std::nan("");
  EXPECT_NE(error_of(write("nan.npy", npy(nan_inside, 64, 0, 1)), o).find("sample 11"), std::string::npos);
}

// A MAT-file written by libmatio: `record` (samples x 2) and `t` at the top level, and the same record in a struct
// test.accel.data.
std::string write_mat(const std::string& name, mat_ft version, const std::vector<double>& column_major, std::size_t n,
                      const std::vector<double>& t) {
  const std::string path = testing::TempDir() + name;
  std::remove(path.c_str());
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, version);
  EXPECT_NE(mat, nullptr);
  size_t dims[2] = {n, 2};
  matvar_t* record =
      Mat_VarCreate("record", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, const_cast<double*>(column_major.data()), 0);
  Mat_VarWrite(mat, record, MAT_COMPRESSION_NONE);
  Mat_VarFree(record);
  size_t time_dims[2] = {1, n};
  matvar_t* time = Mat_VarCreate("t", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, time_dims, const_cast<double*>(t.data()), 0);
  Mat_VarWrite(mat, time, MAT_COMPRESSION_NONE);
  Mat_VarFree(time);
  size_t one[2] = {1, 1};
  const char* data_field[] = {"data"};
  const char* accel_field[] = {"accel"};
  matvar_t* accel = Mat_VarCreateStruct("accel", 2, one, data_field, 1);
  Mat_VarSetStructFieldByName(
      accel, "data", 0,
      Mat_VarCreate("data", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, const_cast<double*>(column_major.data()), 0));
  matvar_t* test = Mat_VarCreateStruct("test", 2, one, accel_field, 1);
  Mat_VarSetStructFieldByName(test, "accel", 0, accel);
  Mat_VarWrite(mat, test, MAT_COMPRESSION_NONE);
  Mat_VarFree(test);
  Mat_Close(mat);
  return path;
}

TEST(RecordFormats, MatFilesOfVersions5And73WithStructsAndTimeVectors) {
  const std::size_t n = 256;
  std::vector<double> column_major(2 * n), t(n), expected(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = 0.5 + static_cast<double>(i) * 1e-3;
    expected[i] = signal_at(t[i]);
    column_major[i] = static_cast<double>(i);  // column 1
    column_major[n + i] = expected[i];         // column 2
  }
  for (const auto& [version, label] : {std::pair{MAT_FT_MAT5, "5"}, std::pair{MAT_FT_MAT73, "7.3"}}) {
    const std::string path = write_mat(std::string("record") + label + ".mat", version, column_major, n, t);
    ImportOptions o;
    o.units = "as-is";  // an array states no unit (--units is required)
    o.variable = "test.accel.data";
    o.channel = "2";
    o.time_variable = "t";
    const TimeSeries s = read_time_series(path, o);
    EXPECT_EQ(s.format, std::string("mat v") + label);
    EXPECT_EQ(s.values, expected) << label;
    EXPECT_NEAR(s.dt_s, 1e-3, 1e-15) << label;
    EXPECT_NEAR(s.t0_s, 0.5, 1e-15) << label;
    // Two time sources are one too many, said as such (the fourth pass's Q197 blamed the variable's shape).
    ImportOptions both = o;
    both.time_channel = "1";
    EXPECT_NE(error_of(path, both).find("give --time-variable or --time-channel, not both"), std::string::npos)
        << error_of(path, both);
    o.variable = "record";
    o.time_variable.clear();
    o.sample_rate_hz = 1000;
    EXPECT_EQ(read_time_series(path, o).values, expected) << label;
    // What is not there is named with what is.
    o.variable = "test.accel.dat";
    EXPECT_NE(error_of(path, o).find("variable 'test.accel' has no field 'dat' (its fields: data)"), std::string::npos)
        << error_of(path, o);
    o.variable = "recrd";
    EXPECT_NE(error_of(path, o).find("not in the file, which holds record, t, test"), std::string::npos)
        << error_of(path, o);
    o.variable = "test";
    EXPECT_NE(error_of(path, o).find("is a struct"), std::string::npos) << error_of(path, o);
    o.variable.clear();
    EXPECT_NE(error_of(path, o).find("2 numeric variables"), std::string::npos) << error_of(path, o);
  }
}

TEST(RecordFormats, AFloat32TimeVectorIsUniformToItsPrecision) {
  // t = single(1 + (0:N-1) * 1e-4): float32 rounds each time by up to 6e-8 s, 600x the 1e-10 s (1e-6 dt) a double
  // vector is held to; the time base must be accepted to that precision, and dt come out right to it.
  const std::size_t n = 512;
  std::vector<float> t(n);
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = static_cast<float>(1.0 + static_cast<double>(i) * 1e-4);
    y[i] = signal_at(static_cast<double>(i) * 1e-4);
  }
  const std::string path = testing::TempDir() + "single_time.mat";
  std::remove(path.c_str());
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
  size_t dims[2] = {n, 1};
  matvar_t* time = Mat_VarCreate("t", MAT_C_SINGLE, MAT_T_SINGLE, 2, dims, t.data(), 0);
  matvar_t* record = Mat_VarCreate("y", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, y.data(), 0);
  Mat_VarWrite(mat, time, MAT_COMPRESSION_NONE);
  Mat_VarWrite(mat, record, MAT_COMPRESSION_NONE);
  Mat_VarFree(time);
  Mat_VarFree(record);
  Mat_Close(mat);
  ImportOptions o;
  o.units = "as-is";  // an array states no unit (--units is required)
  o.variable = "y";
  o.time_variable = "t";
  const TimeSeries s = read_time_series(path, o);
  EXPECT_EQ(s.values, y);
  EXPECT_NEAR(s.dt_s, 1e-4, 1e-9);
}

TEST(RecordFormats, MalformedMatFilesAreErrorsNotCrashes) {
  std::string header = "MATLAB 5.0 MAT-file, Platform: GLNXA64, Created on: test";
  header.resize(124, ' ');
  header += std::string("\x00\x01", 2) + "IM";
  ImportOptions o;
  o.units = "as-is";  // an array states no unit (--units is required)
  o.sample_rate_hz = 1000;
  // A header and nothing else, a header and garbage, a wrong endian indicator.
  EXPECT_NE(error_of(write("empty.mat", header), o).find("0 numeric variables"), std::string::npos)
      << error_of(write("empty.mat", header), o);
  const std::string garbage = header + std::string("\x0e\x00\x00\x00\xff\xff\xff\x7f", 8) + std::string(64, 'x');
  EXPECT_NE(error_of(write("garbage.mat", garbage), o), "no error");
  std::string endian = header;
  endian[126] = 'X';
  EXPECT_NE(error_of(write("endian.mat", endian), o).find("byte 126: endian indicator"), std::string::npos);
  // A valid file cut in half (libmatio read it as complete, zero-filled) and cut inside its last variable.
  std::vector<double> values(2 * 512), t(512);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sin(0.01 * static_cast<double>(i)) + 2;
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = 1e-3 * static_cast<double>(i);
  std::ifstream in(write_mat("whole.mat", MAT_FT_MAT5, values, 512, t), std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ImportOptions named;
  named.units = "as-is";  // an array states no unit (--units is required)
  named.variable = "record";
  named.sample_rate_hz = 1000;
  named.channel = "1";
  for (const std::size_t size : {whole.size() / 2, whole.size() - 8}) {
    const std::string m = error_of(write("cut.mat", whole.substr(0, size)), named);
    EXPECT_NE(m.find("bytes of data, but the file ends"), std::string::npos) << size << ": " << m;
    EXPECT_NE(m.find("truncated or corrupt"), std::string::npos) << m;
  }
  EXPECT_EQ(error_of(write("whole-again.mat", whole), named), "no error");
  // --variable on a file that is not a MAT-file.
  o.variable = "x";
  EXPECT_NE(error_of(write("plain.csv", "t_s,y\n0,1\n1,2\n"), o).find("not one"), std::string::npos);
}

// An array whose dimensions claim more or fewer values than its data element holds: libmatio read past the data
// (values that changed from call to call), cut it silently, or allocated the claimed size first (an 8 KB file that
// declared 2^31 - 1 samples took 8 GB: the twentieth adversarial pass's P1). Each is named as corrupt, uncompressed,
// inside a struct and inside a compressed element, and nothing the dimensions claim is allocated.
TEST(RecordFormats, MatArraysMustHoldWhatTheirDimensionsDeclare) {
  std::vector<double> values(2 * 512), t(512);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sin(0.01 * static_cast<double>(i)) + 2;
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = 1e-3 * static_cast<double>(i);
  std::ifstream in(write_mat("dims.mat", MAT_FT_MAT5, values, 512, t), std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ImportOptions o;
  o.units = "as-is";
  o.variable = "record";
  o.sample_rate_hz = 1000;
  o.channel = "1";
  const auto put = [](std::string& bytes, std::size_t at, std::uint32_t v) { std::memcpy(&bytes[at], &v, 4); };
  // The first variable (record, 512 x 2) starts at byte 128: its tag, its array flags (16 bytes), then its dimensions'
  // tag and the rows at byte 160 (x86-64 is little-endian, as the file says).
  std::uint32_t rows = 0;
  std::memcpy(&rows, &whole[160], 4);
  ASSERT_EQ(rows, 512u);
  for (const std::uint32_t claimed : {1024u, 256u, 0x7fffffffu}) {
    std::string forged = whole;
    put(forged, 160, claimed);
    const std::string m = error_of(write("forged.mat", forged), o);
    EXPECT_NE(m.find("variable 1 ('record') declares " + std::to_string(2ull * claimed) + " values"), std::string::npos)
        << m;
    EXPECT_NE(m.find("holds 8192 bytes of 8-byte values (1024)"), std::string::npos) << m;
  }
  // The struct test.accel.data, the last array of 512 x 2: its rows are the last 512 before a 2 in the file.
  const std::string pattern("\x00\x02\x00\x00\x02\x00\x00\x00", 8);
  std::size_t nested = whole.rfind(pattern);
  ASSERT_NE(nested, std::string::npos);
  nested -= 4;  // the dims tag's type and count, then rows: the rows word ends where the cols word (2) starts
  std::string inner = whole;
  put(inner, nested + 4, 1000);
  ImportOptions field = o;
  field.variable = "test.accel.data";
  EXPECT_NE(error_of(write("nested.mat", inner), field).find("variable 3 ('test') declares 2000 values"),
            std::string::npos)
      << error_of(write("nested.mat", inner), field);
  // The first variable compressed (its whole miMATRIX element deflated into an miCOMPRESSED one), as MATLAB's -v7
  // writes every variable: read when intact, refused with its dimensions forged.
  std::uint32_t count = 0;
  std::memcpy(&count, &whole[132], 4);
  const auto compressed_file = [&](std::string element) {
    uLongf size = compressBound(static_cast<uLong>(element.size()));
    std::string deflated(size, '\0');
    EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(deflated.data()), &size,
                        reinterpret_cast<const Bytef*>(element.data()), static_cast<uLong>(element.size()), 6),
              Z_OK);
    deflated.resize(size);
    std::string file = whole.substr(0, 128);
    const std::uint32_t tag[2] = {15, static_cast<std::uint32_t>(size)};
    file.append(reinterpret_cast<const char*>(tag), 8);
    return file + deflated;
  };
  const std::string element = whole.substr(128, 8 + count);
  EXPECT_EQ(error_of(write("deflated.mat", compressed_file(element)), o), "no error");
  std::string forged_element = element;
  put(forged_element, 32, 1024);
  const std::string m = error_of(write("deflated-forged.mat", compressed_file(forged_element)), o);
  EXPECT_NE(m.find("variable 1 ('record') declares 2048 values"), std::string::npos) << m;
  // A compressed element whose stream is cut: named, not inflated into garbage.
  std::string cut = compressed_file(element);
  cut.resize(cut.size() - 40);
  put(cut, 132, static_cast<std::uint32_t>(cut.size() - 136));
  EXPECT_NE(error_of(write("deflated-cut.mat", cut), o).find("does not inflate"), std::string::npos)
      << error_of(write("deflated-cut.mat", cut), o);
}

// A UFF file: a dataset 151 (a header, skipped), a time response as ASCII double precision with even spacing, and
// the same as binary 58b (little-endian doubles), then a frequency response (type 4) that is not a time record.
std::string uff_header(const std::string& id, int type, int count, double dx, const std::string& unit,
                       int data_type = 4) {
  char line[256];
  std::string h;
  h += id + std::string(80 - id.size(), ' ') + "\n";
  for (int k = 0; k < 4; ++k) h += "NONE\n";
  std::snprintf(line, sizeof line, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n", type, 1, 0, 0, "NONE", 12, 3, "NONE",
                1, 3);
  h += line;
  std::snprintf(line, sizeof line, "%10d%10d%10d%13.5e%13.5e%13.5e\n", data_type, count, 1, 0.0, dx, 0.0);
  h += line;
  std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", 17, 0, 0, 0, "Time", "s");
  h += line;
  std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", 12, 1, 0, 0, "Acceleration", unit.c_str());
  h += line;
  for (int k = 0; k < 2; ++k) {
    std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", 0, 0, 0, 0, "NONE", "NONE");
    h += line;
  }
  return h;
}

std::string uff_file(const std::vector<double>& y, double dx) {
  std::string f = "    -1\n   151\nmodel\ndescription\nprogram\ndate\n    -1\n";
  f += "    -1\n    58\n" + uff_header("tip accelerometer", 1, static_cast<int>(y.size()), dx, "g");
  char value[32];
  for (std::size_t i = 0; i < y.size(); ++i) {
    std::snprintf(value, sizeof value, "%20.11E", y[i]);
    f += value;
    if (i % 4 == 3 || i + 1 == y.size()) f += "\n";
  }
  f += "    -1\n";
  char binary_line[128];
  std::snprintf(binary_line, sizeof binary_line, "    58b%6d%6d%12d%12d%6d%6d%12d%12d\n", 1, 2, 11,
                static_cast<int>(8 * y.size()), 0, 0, 0, 0);
  f += std::string("    -1\n") + binary_line +
       uff_header("mid-span accelerometer", 1, static_cast<int>(y.size()), dx, "m/s^2");
  for (const double v : y) f.append(reinterpret_cast<const char*>(&v), 8);  // little-endian (x86-64)
  f += "\n    -1\n";
  f += "    -1\n    58\n" + uff_header("FRF 12:+Z/1:+Z", 4, 2, 1.0, "g/N") +
       "  1.00000000000E+00  2.00000000000E+00\n    -1\n";
  return f;
}

TEST(RecordFormats, UffDataset58AsciiAndBinary) {
  const std::size_t n = 300;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) y[i] = signal_at(static_cast<double>(i) * 1e-3);
  const std::string path = write("record.uff", uff_file(y, 1e-3));
  ImportOptions o;
  o.channel = "tip accelerometer";
  const TimeSeries ascii = read_time_series(path, o);
  EXPECT_EQ(ascii.format, "uff58");
  EXPECT_EQ(ascii.unit, "m/s^2") << "a record in g is converted";
  ASSERT_EQ(ascii.values.size(), n);
  // E20.11: 12 significant digits, then x 9.80665.
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(ascii.values[i], 9.80665 * y[i], 1e-10) << i;
  EXPECT_NEAR(ascii.dt_s, 1e-3, 1e-15);
  o.channel = "2";
  const TimeSeries binary = read_time_series(path, o);
  EXPECT_EQ(binary.value_column, "mid-span accelerometer");
  EXPECT_EQ(binary.values, y) << "binary doubles are exact";
  // The frequency response is not offered as a channel; choosing among the two time records is required.
  o.channel.clear();
  EXPECT_NE(error_of(path, o).find("2 time records (datasets 58) (tip accelerometer, mid-span accelerometer)"),
            std::string::npos)
      << error_of(path, o);
}

TEST(RecordFormats, MalformedUffFilesNameTheLineOrByte) {
  std::vector<double> y(40);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = signal_at(static_cast<double>(i) * 1e-3);
  const std::string good = uff_file(y, 1e-3);
  ImportOptions o;
  o.channel = "1";
  // A value that is not a number: its line (the 151 dataset takes lines 1-7, the 58's delimiter and number lines 8-9,
  // its header lines 10-20, so the first value is on line 21).
  std::string bad_value = good;
  const std::size_t first = bad_value.find("  0.00000000000E+00", bad_value.find("tip accelerometer"));
  bad_value.replace(first, 19, "  0.0000000000XE+00");
  const std::string value_error = error_of(write("value.uff", bad_value), o);
  EXPECT_NE(value_error.find("value.uff:21: value 1 (ordinate data type 4: fields of 20 characters) = "
                             "'0.0000000000XE+00': must be a finite number"),
            std::string::npos)
      << value_error;
  // The binary dataset cut short: its byte offset.
  const std::string cut = good.substr(0, good.find("mid-span accelerometer") + 700);
  o.channel = "2";
  const std::string cut_error = error_of(write("cut.uff", cut), o);
  EXPECT_NE(cut_error.find(": byte "), std::string::npos) << cut_error;
  EXPECT_NE(cut_error.find("cut short"), std::string::npos) << cut_error;
  // Fewer values than the header says.
  std::string short_count = good;
  short_count.replace(short_count.find("        40         1"), 20, "        41         1");
  o.channel = "1";
  EXPECT_NE(error_of(write("count.uff", short_count), o).find("header says 41 points"), std::string::npos)
      << error_of(write("count.uff", short_count), o);
  // Only a frequency response: no time record.
  const std::string frf =
      "    -1\n    58\n" + uff_header("FRF", 4, 2, 1.0, "g/N") + "  1.00000000000E+00  2.00000000000E+00\n    -1\n";
  EXPECT_NE(error_of(write("frf.uff", frf)).find("no real time record"), std::string::npos);
  // The abscissa (record 8, line 10 of the first dataset 58 here) is time in seconds: one in ms, or a frequency axis,
  // was read as seconds (spikes 1000x off: the second pass's N139, N143).
  const std::size_t abscissa = good.find("        17    0    0    0 Time                 s");
  ASSERT_NE(abscissa, std::string::npos);
  std::string in_ms = good;
  in_ms.replace(abscissa, 48, "        17    0    0    0 Time                 ms");
  EXPECT_NE(error_of(write("ms.uff", in_ms), o).find("ms.uff:17: abscissa units 'ms' are ms"), std::string::npos)
      << error_of(write("ms.uff", in_ms), o);
  std::string in_hz = good;
  in_hz.replace(abscissa, 48, "        18    0    0    0 Frequency            Hz");
  EXPECT_NE(error_of(write("hz.uff", in_hz), o).find("hz.uff:17: abscissa data type 18"), std::string::npos)
      << error_of(write("hz.uff", in_hz), o);
  // The fourth pass's Q231, Q232, Q528: an abscissa labelled in metres (no time unit) was read as seconds, and an
  // acceleration ordinate (type 12) labelled m/s fitted as a velocity.
  std::string in_m = good;
  in_m.replace(abscissa, 48, "        17    0    0    0 Length               m");
  EXPECT_NE(error_of(write("m.uff", in_m), o).find("m.uff:17: abscissa units 'm': not a time unit"), std::string::npos)
      << error_of(write("m.uff", in_m), o);
  std::string velocity_label = good;
  const std::size_t ordinate = good.find("        12    1    0    0 Acceleration         g   ");
  ASSERT_NE(ordinate, std::string::npos);  // channel 1's, the tip accelerometer's
  velocity_label.replace(ordinate, 50, "        12    1    0    0 Acceleration         m/s ");
  EXPECT_NE(error_of(write("v.uff", velocity_label), o).find("ordinate data type 12 (acceleration) with units 'm/s'"),
            std::string::npos)
      << error_of(write("v.uff", velocity_label), o);
  // A dataset without its opening '-1' line was read as CSV ("header '58': must name at least two columns"): named
  // as the UFF it is (the thirteenth pass's 12).
  const std::size_t dataset = good.find("\n    58");  // the first dataset 58's ID line, after its '-1'
  ASSERT_NE(dataset, std::string::npos);
  const std::string undelimited = good.substr(dataset + 1);
  EXPECT_NE(error_of(write("undelimited.uff", undelimited), o).find("undelimited.uff:1: a UFF dataset 58's ID line"),
            std::string::npos)
      << error_of(write("undelimited.uff", undelimited), o);
  // A blank ordinate units label states no unit (the thirteenth pass's 4: read as SI, 9.81x off for a record in g).
  std::string blank = good;
  blank.replace(ordinate, 50, "        12    1    0    0 Acceleration             ");
  ImportOptions automatic = o;
  automatic.units = "auto";
  EXPECT_NE(error_of(write("blank.uff", blank), automatic).find("the ordinate's units label is blank"),
            std::string::npos)
      << error_of(write("blank.uff", blank), automatic);
  // An excitation force (type 13) is no response (the fifth pass's R153).
  std::string force = good;
  force.replace(ordinate, 50, "        13    1    0    0 Force                N   ");
  EXPECT_NE(error_of(write("f.uff", force), o).find("ordinate data type 13 (excitation force): a response record is"),
            std::string::npos)
      << error_of(write("f.uff", force), o);
  // A binary file of no known kind says which formats are read.
  EXPECT_NE(error_of(write("mystery.bin", std::string("\x01\x02\x03\x04", 4) + std::string(100, 'a'))).find(".npy"),
            std::string::npos);
}

TEST(RecordFormats, ResamplingToARateKeepsTheBandAndRemovesWhatAliases) {
  // 2 s at 1 kHz of a 10 Hz tone and a 150 Hz tone. Resampled up to 2.5 kHz both are kept; down to 200 Hz the 150 Hz
  // tone lies above the new Nyquist frequency (100 Hz) and must be removed, not aliased to 50 Hz. Away from the ends
  // (32 periods of the lower rate, where the kernel is cut) the windowed sinc is accurate to its stop-band level,
  // about -70 dB for a Blackman window: asserted to 2e-3 of the tones' amplitude.
  const std::size_t n = 2000;
  std::string text = "t_s,y_m\n";
  char row[96];
  const auto tone = [](double t, bool high) {
    return std::sin(2 * std::numbers::pi * 10 * t) + (high ? 0.5 * std::sin(2 * std::numbers::pi * 150 * t) : 0.0);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * 1e-3;
    std::snprintf(row, sizeof row, "%.6f,%.17g\n", t, tone(t, true));
    text += row;
  }
  const std::string path = write("tones.csv", text);
  // Up-sampling is refused: it adds no information and correlates the samples (the twenty-first pass's P4).
  ImportOptions up;
  up.resample_rate_hz = 2500;
  EXPECT_NE(error_of(path, up).find("is above the record's 1000 Hz: resampling up adds no information"),
            std::string::npos)
      << error_of(path, up);
  up.resample_rate_hz = 1000;  // its own rate: nothing to resample (it cut 32 samples from each end, silently)
  EXPECT_NE(error_of(path, up).find("Hz is the record's own rate"), std::string::npos) << error_of(path, up);
  for (const double rate : {200.0}) {
    ImportOptions o;
    o.resample_rate_hz = rate;
    const TimeSeries s = read_time_series(path, o);
    EXPECT_NEAR(s.dt_s, 1 / rate, 1e-15);
    // Only where the kernel has its full support (32 periods of the lower rate each side): from the first multiple
    // of 1 / rate at least that far in, to that far before the end; every sample there is accurate, the first ones
    // included (cut short at the ends, the kernel let the 150 Hz tone through: the sixteenth pass's P1).
    const double half = 32 / std::min(1000.0, rate), first = std::ceil(half * rate - 1e-9) / rate;
    EXPECT_NEAR(s.t0_s, first, 1e-12);
    EXPECT_EQ(s.values.size(), static_cast<std::size_t>(std::floor((1.999 - half - first) * rate + 1e-9)) + 1);
    double worst = 0;
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      const double t = s.t0_s + static_cast<double>(i) / rate;
      worst = std::max(worst, std::abs(s.values[i] - tone(t, false)));
    }
    EXPECT_LT(worst, 2e-3) << rate;
    EXPECT_NE(s.notes.find("resampled from 1000 Hz"), std::string::npos) << s.notes;
  }
  ImportOptions o;
  o.resample_rate_hz = 2;  // 2 s at 2 Hz: 4 samples
  EXPECT_NE(error_of(path, o).find("at least 8 are needed"), std::string::npos);
}

TEST(RecordFormats, TimesTooLargeForTheirStepSayHowWellTheStepIsKnown) {
  // 2,000 samples at 1 ms with times near 1e11 s, printed to 17 digits: a double there resolves 1.5e-5 s, so the step
  // is known from the span (2 s) to about 2e-5 of itself, and every frequency with it (the twenty-first pass's P5:
  // modal-id's frequency moved 1.4e-6 beside an uncertainty of 1e-14). Said; the same record from t = 0 is not.
  std::string offset = "t_s,y_m\n", plain = offset;
  char row[96];
  for (int i = 0; i < 2000; ++i) {
    const double y = std::sin(2 * std::numbers::pi * 10 * i * 1e-3);
    std::snprintf(row, sizeof row, "%.17g,%.17g\n", 1e11 + i * 1e-3, y);
    offset += row;
    std::snprintf(row, sizeof row, "%.17g,%.17g\n", i * 1e-3, y);
    plain += row;
  }
  const TimeSeries late = read_time_series(write("late.csv", offset), {});
  EXPECT_NE(late.notes.find("the time column's values near 1e+11 s resolve only"), std::string::npos) << late.notes;
  EXPECT_NE(late.notes.find("so the step is known to within"), std::string::npos) << late.notes;
  const TimeSeries early = read_time_series(write("early.csv", plain), {});
  EXPECT_EQ(early.notes.find("resolve only"), std::string::npos) << early.notes;
}

TEST(RecordFormats, ResamplingBelowARecordsContentIsRefusedOrSaid) {
  // Decays of two modes, 4 s at 2 kHz (the ninth pass's #2; 20 s for the 10 Hz case). Resampled to 10 Hz, below both 23
  // and 141 Hz, only the low-pass's residue is left: refused (its pencil gave 1.02 and 4.51 Hz "modes"). Resampled to
  // 100 Hz, 31 Hz is kept and 173 Hz removed: read, with the pass band (0.40 x 100 Hz) set so that a pole at the
  // filter's edge is said. A 10 Hz decay resampled to 100 Hz removes nothing that stands out: no note (its pass band is
  // set all the same).
  const auto decay = [](double f1, double f2, double a2, int samples = 8000) {
    std::string text = "t_s,a_m_s2\n";
    char row[96];
    for (int i = 0; i < samples; ++i) {
      const double t = i / 2000.0;
      const double v = std::exp(-2 * t) * std::sin(2 * std::numbers::pi * f1 * t) +
                       a2 * std::exp(-6 * t) * std::sin(2 * std::numbers::pi * f2 * t);
      std::snprintf(row, sizeof row, "%.6f,%.17g\n", t, v);
      text += row;
    }
    return text;
  };
  ImportOptions o;
  o.resample_rate_hz = 10;
  // (20 s: at 10 Hz the low-pass's 3.2 s at each end are left out, and 4 s would leave too few samples.) With the
  // ends left out, where the cut-short kernel had let the decay through, almost nothing is left (5e-15 % of the
  // power), and the refusal says so (with the leaking ends, it had been refused for the residue's spectrum).
  const std::string refused = error_of(write("w23.csv", decay(23, 141, 0.5, 40000)), o);
  EXPECT_NE(refused.find("--resample-rate 10 Hz: its low-pass at 4.5 Hz leaves"), std::string::npos) << refused;
  EXPECT_NE(refused.find("the record's content lies above it"), std::string::npos) << refused;
  o.resample_rate_hz = 100;
  const TimeSeries kept = read_time_series(write("rs.csv", decay(31, 173, 2)), o);
  EXPECT_EQ(kept.pass_band_hz, 40);
  EXPECT_NE(kept.notes.find("the record's peak at 173 Hz lies above the pass band (40 Hz)"), std::string::npos)
      << kept.notes;
  const TimeSeries clean = read_time_series(write("ten.csv", decay(10, 30, 0)), o);
  EXPECT_EQ(clean.pass_band_hz, 40);
  EXPECT_EQ(clean.notes.find("pass band"), std::string::npos) << clean.notes;
}

}  // namespace
}  // namespace beamid::io
