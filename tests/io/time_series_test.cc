// Reading data records: each malformed file gives an InputError naming the file, line, column and constraint.
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "io/time_series.h"
#include "model/errors.h"

namespace beamid::io {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string rows(int n, double dt) {
  std::string text = "t_s,displacement_m\n";
  for (int i = 0; i < n; ++i) text += std::to_string(i * dt) + "," + std::to_string(0.1 * i) + "\n";
  return text;
}

std::string error_of(const std::string& path) {
  try {
    read_time_series(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
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
  EXPECT_NE(error_of(write("nan.csv", with_nan)).find("nan.csv:5: displacement_m = nan: must be finite"), std::string::npos)
      << error_of(write("nan.csv", with_nan));
  text = rows(10, 0.001);
  const std::string jitter = text.replace(text.find("0.004000,"), 9, "0.004100,");
  EXPECT_NE(error_of(write("jitter.csv", jitter)).find("jitter.csv:6: t_s = 0.0041: non-uniform time base"), std::string::npos)
      << error_of(write("jitter.csv", jitter));
  EXPECT_NE(error_of(write("short.csv", rows(5, 0.001))).find("5 samples: at least 8 are needed"), std::string::npos);
  EXPECT_NE(error_of(write("word.csv", "t_s,y\n0,1\n0.1,abc\n")).find("word.csv:3: y = 'abc': must be a number"), std::string::npos);
  EXPECT_NE(error_of(write("three.csv", "t,a,b\n")).find("must name exactly two columns"), std::string::npos);
  EXPECT_NE(error_of(testing::TempDir() + "absent.csv").find("cannot read the file"), std::string::npos);
}

}  // namespace
}  // namespace beamid::io
