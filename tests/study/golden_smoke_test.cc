// CI's tolerance check: the smoke study (studies/smoke.toml) is run from scratch and its per-case estimates are
// compared with the committed golden table tests/golden/smoke_cases.csv (made by `make golden` from a run that was
// reviewed; this test only reads it). A change that changes a fit's status or success, or moves an identifying fit's
// estimate by more than the tolerance below, fails.
//
// What is compared, and why. On one machine the study is bit-for-bit reproducible (the tables do not depend on
// threads), but not across machines: glibc's libm and FFTW choose code paths by the processor's vector units, so the
// last bits of every evaluation move, and a fit that does not identify (N = 4 and 8 here: the models misplace modes 2
// and 3 by several bins) lands wherever its optimizer's path takes it. Such a landing point is not a property of the
// code: the committed golden table of one machine put a spike-smooth N = 4 fit at EI = 0.456 where another machine
// put it at 0.982 (the bound). So every case is checked for success and for whether it failed, and the status and
// estimates of the fits that identify the beam (success = 1 in the golden table: spike and spike-smooth at N = 16) to
//   1e-3 relative for stiffness and inertia parameters, 1e-2 for damping parameters.
// Measured: running the smoke study with glibc's AVX2/FMA/AVX-512 variants switched off (GLIBC_TUNABLES) moves these
// fits by at most 8e-6 in EI and rho and 5.3e-4 in cDI and gamma (the optimizer's xtol stop along the shallow damping
// directions); the tolerances are 100x and 20x above that, and 20x below the study's success tolerances (2 %, 25 %),
// so they catch every change that matters to a conclusion.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "model/beam_parameters.h"
#include "study/run/runner.h"
#include "study/spec/study_spec.h"

namespace beamid::study {
namespace {
namespace fs = std::filesystem;

// CSV fields, honouring double quotes.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        out.back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

// Rows keyed by case_id: column name -> text.
std::map<std::string, std::map<std::string, std::string>> read_table(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  std::string line;
  std::getline(in, line);
  const auto header = fields(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto f = fields(line);
    EXPECT_EQ(f.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows[row["case_id"]] = row;
  }
  return rows;
}

TEST(GoldenSmoke, EstimatesMatchTheCommittedGoldenTable) {
  const StudySpec spec = load_study(std::string(BEAMID_SOURCE_DIR) + "/studies/smoke.toml");
  const fs::path out = fs::path(BEAMID_BINARY_DIR) / "golden-smoke";
  fs::remove_all(out);  // from scratch: nothing reused from an earlier build's store
  RunOptions o;
  o.output_dir = out.string();
  std::ostringstream log;
  ASSERT_TRUE(run_study(spec, o, log, false).tables) << log.str();
  const fs::path golden_path = fs::path(BEAMID_SOURCE_DIR) / "tests/golden/smoke_cases.csv";
  const auto golden = read_table(golden_path);
  const auto now = read_table(out / "cases.csv");
  ASSERT_FALSE(golden.empty());
  ASSERT_EQ(now.size(), golden.size()) << "the smoke study's cases changed: regenerate with `make golden` and review";
  int compared = 0;
  for (const auto& [id, g] : golden) {
    ASSERT_TRUE(now.count(id)) << "case " << id << " (" << g.at("cost") << ", N = " << g.at("elements")
                               << ") is no longer in the smoke study";
    const auto& n = now.at(id);
    const std::string what =
        g.at("cost") + ", N = " + g.at("elements") + ", noise " + g.at("noise") + ", replicate " + g.at("replicate");
    EXPECT_EQ(n.at("success"), g.at("success")) << what;
    // A fit that does not identify: whether it failed, not where it landed (nor whether that is on a bound).
    EXPECT_EQ(n.at("status") == "failed", g.at("status") == "failed") << what << ": status " << n.at("status");
    if (g.at("success") != "1") continue;
    EXPECT_EQ(n.at("status"), g.at("status")) << what;
    for (const auto& [column, text] : g) {
      if (column.rfind("estimate_", 0) != 0) continue;
      const std::string parameter = column.substr(std::string("estimate_").size());
      const double tolerance = model::find_parameter(parameter)->role == "damping" ? 1e-2 : 1e-3;
      const double want = std::stod(text), got = std::stod(n.at(column));
      ++compared;
      EXPECT_LE(std::abs(got - want), tolerance * std::abs(want))
          << what << ": " << column << " = " << got << ", golden " << want << " (relative change "
          << (got - want) / want << ", tolerance " << tolerance << ")";
    }
  }
  // The smoke study must keep fits that identify, or this test would compare no estimate at all.
  EXPECT_GE(compared, 16) << "the golden table has fewer than four identifying fits";
}

}  // namespace
}  // namespace beamid::study
