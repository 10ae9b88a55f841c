// The plan's cost estimate (study/run/estimate.h): a unit the previous run timed counts at its own time, one it did
// not at the median of its kind, cost and N there (else of its kind), one of a kind never timed at
// kSecondsPerUntimedUnit; a missing or foreign timings file times nothing, and no line of it is fatal.
#include "study/run/estimate.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace beamid::study {
namespace {
namespace fs = std::filesystem;

Unit unit(UnitKind kind, const std::string& id, const std::string& cost, int elements) {
  Unit u;
  u.kind = kind;
  u.id = id;
  u.cost = cost;
  u.elements = elements;
  return u;
}

TEST(PlanEstimate, UnitsAreTimedByIdThenByTheirKindsMedianThenByTheDefault) {
  const fs::path path = fs::temp_directory_path() / ("beamid-estimate-" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream out(path);
    out << "unit_id,kind,cost,elements,noise,wall_time_s\n"
        << "aaaa,truth,,,,6.5\n"
        << "bbbb,case,spike,16,0.01,2\n"
        << "cccc,case,spike,16,0.01,4\n"
        << "dddd,case,spike,16,0.01,9\n"
        << "eeee,case,time,8,0.01,0.5\n"
        << "not,a,line\n"                // skipped
        << "ffff,case,time,8,0.01,x\n";  // skipped
  }
  const Unit truth = unit(UnitKind::Truth, "aaaa", "", 48);        // its own time: 6.5
  const Unit timed = unit(UnitKind::Case, "cccc", "spike", 16);    // its own time: 4
  const Unit spike = unit(UnitKind::Case, "zzzz", "spike", 16);    // the median of spike N = 16: 4
  const Unit other_n = unit(UnitKind::Case, "yyyy", "spike", 12);  // the median of every case: (2, 4, 9, 0.5) -> 3
  const Unit never = unit(UnitKind::Grid, "xxxx", "time", 8);      // no grid timed: the default
  const PlanEstimate e = estimate_plan({&truth, &timed, &spike, &other_n, &never}, path.string(), 48);
  EXPECT_EQ(e.units, 5);
  EXPECT_EQ(e.by_id, 2);
  EXPECT_EQ(e.by_median, 2);
  EXPECT_EQ(e.untimed, 1);
  EXPECT_DOUBLE_EQ(e.compute_s, 6.5 + 4 + 4 + 3 + kSecondsPerUntimedUnit);
  ASSERT_FALSE(e.groups.empty());
  EXPECT_EQ(e.groups.front().label, "case spike N = 16");  // 8 s, the largest
  EXPECT_EQ(e.groups.front().units, 2);
  const std::string text = plan_text(e, 2, path.string());
  EXPECT_NE(text.find("plan: 5 unit(s) to run"), std::string::npos) << text;
  EXPECT_NE(text.find("1 never timed"), std::string::npos) << text;
  fs::remove(path);
  const PlanEstimate none = estimate_plan({&truth, &spike}, path.string(), 48);  // the file is gone
  EXPECT_EQ(none.untimed, 2);
  EXPECT_DOUBLE_EQ(none.compute_s, 2 * kSecondsPerUntimedUnit);
  // At N_truth = 400 an untimed truth record costs its evaluations (3 x 3.2 s x 8 = 77 s, measured 71 s), not 1 s;
  // a fit at N = 200 about 100 of its 3.2 s evaluations (the twentieth pass's P7).
  const Unit large = unit(UnitKind::Case, "wwww", "time", 200);
  const PlanEstimate big = estimate_plan({&truth, &large}, path.string(), 400);
  EXPECT_NEAR(big.compute_s, 3 * 3.2 * 8 + 100 * 3.2, 1e-9);
}

}  // namespace
}  // namespace beamid::study
