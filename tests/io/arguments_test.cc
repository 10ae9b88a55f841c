// Strict flag parsing: every malformed command line is a one-line InputError naming the flag and value.
#include "io/arguments.h"

#include <gtest/gtest.h>

#include "model/errors.h"

namespace beamid::io {
namespace {

const std::vector<FlagSpec> kSpec = {{"dt", true, ""}, {"samples", true, ""}, {"exact", false, ""}};

std::string error_of(const std::vector<std::string>& args, const std::string& get = "") {
  try {
    Arguments a("simulate", args, kSpec);
    if (get == "dt") a.number("dt");
    if (get == "samples") a.integer("samples");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Arguments, ParsesValuesAndSwitches) {
  const Arguments a("simulate", {"--dt", "1e-3", "--exact", "--samples", "4096"}, kSpec);
  EXPECT_DOUBLE_EQ(a.number("dt"), 1e-3);
  EXPECT_EQ(a.integer("samples"), 4096);
  EXPECT_TRUE(a.has("exact"));
  EXPECT_FALSE(Arguments("simulate", {}, kSpec).optional_number("dt"));
}

TEST(Arguments, Errors) {
  EXPECT_EQ(error_of({"--dtt", "1"}), "beamid simulate: unknown flag --dtt (valid flags: --dt, --samples, --exact)");
  EXPECT_EQ(error_of({"--dt"}), "beamid simulate: --dt needs a value");
  EXPECT_EQ(error_of({"--dt", "1", "--dt", "2"}), "beamid simulate: --dt given twice");
  EXPECT_EQ(error_of({"dt"}), "beamid simulate: unexpected argument 'dt' (flags start with --)");
  EXPECT_EQ(error_of({"--dt", "abc"}, "dt"), "beamid simulate: --dt = 'abc': must be a finite number");
  EXPECT_EQ(error_of({"--dt", "1e-3x"}, "dt"), "beamid simulate: --dt = '1e-3x': must be a finite number");
  EXPECT_EQ(error_of({"--dt", "inf"}, "dt"), "beamid simulate: --dt = 'inf': must be a finite number");
  EXPECT_EQ(error_of({"--samples", "4.5"}, "samples"), "beamid simulate: --samples = '4.5': must be an integer");
  EXPECT_EQ(error_of({}, "dt"), "beamid simulate: missing required flag --dt");
}

}  // namespace
}  // namespace beamid::io
