// CI's tolerance check: the smoke study (studies/smoke.toml) is run from scratch and its per-case estimates are
// compared with the committed golden table tests/golden/smoke_cases.csv (made by `make golden` from a run that was
// reviewed; this test only reads it). A change that moves any estimate by more than the tolerance below, or changes a
// fit's status, fails.
//
// Tolerance: 1e-4 relative on every estimate. On one machine the study is bit-for-bit reproducible (the tables do
// not depend on threads), so any difference is a change in the code or the libraries. Converged fits move by
// ~1e-10 between optimisation levels (Release -O2 against the sanitizer build's -O1); 1e-4 is far above that and
// 200x below the study's 2 % success tolerance, so it catches every change that matters to a study's conclusions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "study/runner.h"
#include "study/study_spec.h"

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
  const double tolerance = 1e-4;
  for (const auto& [id, g] : golden) {
    ASSERT_TRUE(now.count(id)) << "case " << id << " (" << g.at("cost") << ", N = " << g.at("elements")
                               << ") is no longer in the smoke study";
    const auto& n = now.at(id);
    const std::string what =
        g.at("cost") + ", N = " + g.at("elements") + ", noise " + g.at("noise") + ", replicate " + g.at("replicate");
    EXPECT_EQ(n.at("status"), g.at("status")) << what;
    EXPECT_EQ(n.at("success"), g.at("success")) << what;
    for (const auto& [column, text] : g) {
      if (column.rfind("estimate_", 0) != 0) continue;
      const double want = std::stod(text), got = std::stod(n.at(column));
      if (std::isnan(want)) {
        EXPECT_TRUE(std::isnan(got)) << what << ": " << column;
        continue;
      }
      EXPECT_LE(std::abs(got - want), tolerance * std::abs(want))
          << what << ": " << column << " = " << got << ", golden " << want << " (relative change "
          << (got - want) / want << ")";
    }
  }
}

}  // namespace
}  // namespace beamid::study
