// The study runner's promises, on a miniature study (256-sample truth, N = 4 fits, a small landscape):
// the tables do not depend on the thread count; an interrupted run resumes to the same tables; shards merged give the
// same tables as one run; a case that cannot run is a row with its status, not a crash.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "io/provenance.h"
#include "study/plan/plan.h"
#include "study/run/record_schema.h"
#include "study/run/runner.h"
#include "study/tables/tables.h"

namespace beamid::study {
namespace {
namespace fs = std::filesystem;

const char* kMini = R"([study]
name = "mini"
question = "Does the runner keep its promises?"
seed = 11

[truth]
beam = "banks-aluminium"
samples = 256
force_x_m = 0.32
pulse_width_s = 0.004
output = "acceleration"

[fit]
estimate = ["EI", "rho"]
spikes = 2
max_frequency_hz = 120
max_evaluations = 200

[starts.near]
EI = 1.02
rho = 0.99

[methods.direct]
strategy = "direct"

[sweep]
elements = [4]
cost = ["time", "spike-smooth"]
noise = [0.0, 0.02]
replicates = 2
method = ["direct"]
start = ["near"]

[landscape]
elements = 4
noise = [0.0, 0.02]
cost = ["time", "spike-smooth"]
points = 9
pairs = [["EI", "rho"]]
grid_points = 5
zoom_range_factor = 1.05
zoom_points = 5
multistarts = 2
)";

std::map<std::string, std::string> tables(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), dir).string();
    // Timings (timings.csv, start_distance/timings.csv) are the only files that change from run to run.
    if (rel.rfind("store", 0) == 0 || fs::path(rel).filename() == "timings.csv") continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    files[rel] = text.str();
  }
  return files;
}

class StudyRunner : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("beamid-runner-test-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    spec_ = parse_study(kMini, "mini.toml", ".");
    RunOptions o;
    o.output_dir = (root_ / "one").string();
    o.jobs = 1;
    std::ostringstream log;
    const RunSummary s = run_study(spec_, o, log, false);
    ASSERT_TRUE(s.tables);
    reference_ = tables(root_ / "one");
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static StudySpec spec_;
  static std::map<std::string, std::string> reference_;
};
fs::path StudyRunner::root_;
StudySpec StudyRunner::spec_;
std::map<std::string, std::string> StudyRunner::reference_;

TEST_F(StudyRunner, WritesTheTablesAndARowPerCase) {
  for (const char* f : {"manifest.json", "cases.csv", "summary.csv", "summary.md", "convergence.csv", "spread.csv",
                        "landscape/smoothness.csv", "landscape/slice_time_EI.csv", "landscape/grid_time_EI_rho.dat",
                        "overlay.csv", "spectrum.csv", "report.md", "provenance.csv"})
    EXPECT_TRUE(reference_.count(f)) << f;
  // 2 costs x (1 noise-free + 2 replicates) = 6 cases, plus the header.
  const std::string& cases = reference_["cases.csv"];
  EXPECT_EQ(std::count(cases.begin(), cases.end(), '\n'), 7);
  EXPECT_NE(reference_["report.md"].find("Computed claims"), std::string::npos);
}

// Landscapes across noise levels: the noisy slice sees the sweep's replicate-0 record, so its cost differs from the
// clean slice's at every point (the noise adds sum sigma^2 g_i^2 > 0 to a least-squares cost, not a constant 0); a
// fine grid spans [v/1.05, 1.05 v] on both axes; the across table has one column per setting.
TEST_F(StudyRunner, LandscapesAcrossNoiseAndFineGrids) {
  for (const char* f : {"landscape/N4-noise0.02/slice_time_EI.csv", "landscape/zoom/N4-noise0/grid_time_EI_rho.dat",
                        "landscape/zoom/N4-noise0.02/grid_spike-smooth_EI_rho.dat", "landscape_across.md"})
    ASSERT_TRUE(reference_.count(f)) << f;
  const auto column = [](const std::string& csv, int k) {
    std::vector<double> v;
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::istringstream row(line);
      std::string cell;
      for (int i = 0; i <= k; ++i) std::getline(row, cell, ',');
      v.push_back(std::stod(cell));
    }
    return v;
  };
  const std::vector<double> clean = column(reference_["landscape/slice_time_EI.csv"], 2);
  const std::vector<double> noisy = column(reference_["landscape/N4-noise0.02/slice_time_EI.csv"], 2);
  ASSERT_EQ(clean.size(), 9u);
  ASSERT_EQ(noisy.size(), 9u);
  for (std::size_t j = 0; j < clean.size(); ++j) EXPECT_NE(clean[j], noisy[j]) << j;
  std::istringstream grid(reference_["landscape/zoom/N4-noise0/grid_time_EI_rho.dat"]);
  std::string line;
  double lo = INFINITY, hi = -INFINITY;
  while (std::getline(grid, line)) {
    if (line.empty() || line[0] == '#') continue;
    const double ratio = std::stod(line.substr(0, line.find(' ')));
    lo = std::min(lo, ratio), hi = std::max(hi, ratio);
  }
  EXPECT_NEAR(lo, 1 / 1.05, 1e-12);
  EXPECT_NEAR(hi, 1.05, 1e-12);
  const std::string& across = reference_["landscape_across.md"];
  EXPECT_NE(across.find("N = 4, noise 0 %"), std::string::npos) << across;
  EXPECT_NE(across.find("N = 4, noise 2 %"), std::string::npos) << across;
}

TEST_F(StudyRunner, TablesDoNotDependOnTheThreadCount) {
  RunOptions o;
  o.output_dir = (root_ / "two").string();
  o.jobs = 2;
  std::ostringstream log;
  ASSERT_TRUE(run_study(spec_, o, log, false).tables);
  EXPECT_EQ(tables(root_ / "two"), reference_);
}

TEST_F(StudyRunner, AnInterruptedRunResumesToTheSameTables) {
  fs::copy(root_ / "one", root_ / "resumed", fs::copy_options::recursive);
  // Lose three finished units and every table, as if the run had been killed.
  int removed = 0;
  for (const auto& e : fs::directory_iterator(root_ / "resumed" / "store"))
    if (removed < 3 && e.path().extension() == ".rec" && fs::file_size(e.path()) < 100000)
      fs::remove(e.path()), ++removed;
  fs::remove(root_ / "resumed" / "cases.csv");
  RunOptions o;
  o.output_dir = (root_ / "resumed").string();
  std::ostringstream log;
  const RunSummary s = run_study(spec_, o, log, false);
  EXPECT_LE(s.computed, 3);  // a removed truth is remade too, but it is not a unit
  EXPECT_GE(s.reused, s.units - 3);
  EXPECT_EQ(tables(root_ / "resumed"), reference_);
}

// Every record the runner stored, truths included, follows its kind's declared schema (record_schema.h): the writer
// and the reader agree on one list of fields.
TEST_F(StudyRunner, EveryStoredRecordFollowsItsDeclaredSchema) {
  const Plan plan = make_plan(spec_);
  const Store store((root_ / "one" / "store").string(), io::commit_label());
  std::map<UnitKind, int> kinds;
  for (const auto* units : {&plan.truths, &plan.units})
    for (const Unit& u : *units) {
      const auto r = store.load(u.id);
      ASSERT_TRUE(r) << u.id;
      EXPECT_EQ(schema_violation(*r, u, spec_.fit.estimate), "") << unit_kind_name(u.kind) << " " << u.id;
      ++kinds[u.kind];
    }
  // The mini study has truths, cases, slices, grids, multistart fits and the frequencies of its N.
  EXPECT_EQ(kinds.size(), 6u);
}

// Issue 30: two records swapped inside a finished store (each intact, under the other's name) were reused and changed
// the tables. Each record carries its unit's id inside its checked content, so both are named, moved aside and
// recomputed, and the tables come out as before. A record under its own name that lacks a declared field (a record
// of another kind, say) is treated the same way.
TEST_F(StudyRunner, SwappedOrMisshapenRecordsAreMovedAsideAndRecomputed) {
  fs::copy(root_ / "one", root_ / "swapped", fs::copy_options::recursive);
  const Plan plan = make_plan(spec_);
  std::vector<std::string> cases;
  for (const Unit& u : plan.units)
    if (u.kind == UnitKind::Case) cases.push_back(u.id);
  ASSERT_GE(cases.size(), 3u);
  const fs::path store = root_ / "swapped" / "store";
  const auto file = [&](const std::string& id) { return store / (id + ".rec"); };
  fs::rename(file(cases[0]), store / "held");
  fs::rename(file(cases[1]), file(cases[0]));
  fs::rename(store / "held", file(cases[1]));
  // A landscape unit's record, valid and checked, stored under the third case's own id.
  Record other = *Store(store.string(), io::commit_label()).load(plan.units.back().id);
  Store(store.string(), io::commit_label()).save(cases[2], other);
  RunOptions o;
  o.output_dir = (root_ / "swapped").string();
  std::ostringstream log;
  const RunSummary s = run_study(spec_, o, log, false);
  EXPECT_EQ(s.computed, 3) << log.str();
  EXPECT_NE(log.str().find("(renamed or swapped)"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("field 'termination' is missing"), std::string::npos) << log.str();
  EXPECT_EQ(tables(root_ / "swapped"), reference_);
  EXPECT_TRUE(fs::exists(store / "damaged" / (cases[0] + ".rec")));
}

// Issue 30 (a second pass): a unit's id does not include the study seed (so that ids stay stable), and a study rerun
// with another seed into the same folder reused every record of the first seed. The records carry a hash of their
// seeds (record_schema.h), so every unit is recomputed, and the tables are those of a fresh run with the new seed.
TEST_F(StudyRunner, ARerunWithAnotherSeedRecomputesEveryUnit) {
  fs::copy(root_ / "one", root_ / "reseeded", fs::copy_options::recursive);
  std::string text = kMini;
  text.replace(text.find("seed = 11"), 9, "seed = 12");
  const StudySpec reseeded = parse_study(text, "mini.toml", ".");
  RunOptions o;
  o.output_dir = (root_ / "reseeded").string();
  std::ostringstream log;
  const RunSummary s = run_study(reseeded, o, log, false);
  EXPECT_EQ(s.reused, 0) << log.str();
  EXPECT_EQ(s.computed, s.units);
  RunOptions fresh;
  fresh.output_dir = (root_ / "seed12").string();
  std::ostringstream fresh_log;
  ASSERT_TRUE(run_study(reseeded, fresh, fresh_log, false).tables);
  EXPECT_EQ(tables(root_ / "reseeded"), tables(root_ / "seed12"));
  EXPECT_NE(tables(root_ / "seed12"), reference_);
}

TEST_F(StudyRunner, AnotherStudyFileOfTheSameNameDoesNotTakeOverTheResultsFolder) {
  // The sixth pass's S420: b.toml, of a.toml's [study] name with another seed, ran into a.toml's results folder,
  // replaced its tables and moved its finished records aside. Refused, naming the owner; a.toml itself reruns there.
  const fs::path a = root_ / "a.toml", b = root_ / "b.toml";
  std::string other = kMini;
  other.replace(other.find("seed = 11"), 9, "seed = 12");
  std::ofstream(a) << kMini;
  std::ofstream(b) << other;
  RunOptions o;
  o.output_dir = (root_ / "named").string();
  std::ostringstream log;
  ASSERT_TRUE(run_study(parse_study(kMini, a.string(), root_.string()), o, log, false).tables);
  try {
    run_study(parse_study(other, b.string(), root_.string()), o, log, false);
    ADD_FAILURE() << "b.toml ran into a.toml's folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds the results of another study file, " + a.string()), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(run_study(parse_study(kMini, a.string(), root_.string()), o, log, false).computed, 0);
}

// Issue 30: a study rerun without a section left that section's old tables beside the new ones. The tables an
// earlier run wrote and this one does not are removed: the folder equals a fresh run's.
TEST_F(StudyRunner, ARerunWithoutASectionRemovesItsOldTables) {
  fs::copy(root_ / "one", root_ / "shrunk", fs::copy_options::recursive);
  std::string text = kMini;
  text.replace(text.find("[landscape]"), std::string::npos, "");
  const StudySpec without = parse_study(text, "mini.toml", ".");
  RunOptions o;
  o.output_dir = (root_ / "shrunk").string();
  std::ostringstream log;
  ASSERT_TRUE(run_study(without, o, log, false).tables);
  RunOptions fresh;
  fresh.output_dir = (root_ / "fresh-without").string();
  ASSERT_TRUE(run_study(without, fresh, log, false).tables);
  const auto shrunk = tables(root_ / "shrunk"), expected = tables(root_ / "fresh-without");
  EXPECT_LT(shrunk.size(), reference_.size());
  EXPECT_EQ(shrunk, expected);
  // The list of written tables removes only what a run wrote: a line added to it (a store record, a user's file) is
  // refused by its check, and nothing is removed (the eleventh pass's TT3 deleted both).
  fs::copy(root_ / "one", root_ / "edited", fs::copy_options::recursive);
  std::ofstream(root_ / "edited" / "mine.txt") << "a user's notes\n";
  std::ofstream(root_ / "edited" / "store" / "tables.txt", std::ios::app) << "mine.txt\n";
  o.output_dir = (root_ / "edited").string();
  ASSERT_TRUE(run_study(without, o, log, false).tables);
  EXPECT_TRUE(fs::exists(root_ / "edited" / "mine.txt"));
  EXPECT_NE(log.str().find("tables.txt: fails its check"), std::string::npos);
}

TEST_F(StudyRunner, ShardsMergeIntoTheTablesOfOneRun) {
  for (int k = 1; k <= 2; ++k) {
    RunOptions o;
    o.output_dir = (root_ / ("shard" + std::to_string(k))).string();
    o.shard_index = k;
    o.shard_count = 2;
    std::ostringstream log;
    EXPECT_FALSE(run_study(spec_, o, log, false).tables);  // half the units: no tables yet
  }
  EXPECT_THROW(write_tables_from_store(spec_, (root_ / "shard1").string()), InputError);
  fs::create_directories(root_ / "merged" / "store");
  for (int k = 1; k <= 2; ++k)
    for (const auto& e : fs::directory_iterator(root_ / ("shard" + std::to_string(k)) / "store"))
      fs::copy_file(e.path(), root_ / "merged" / "store" / e.path().filename(), fs::copy_options::overwrite_existing);
  write_tables_from_store(spec_, (root_ / "merged").string());
  EXPECT_EQ(tables(root_ / "merged"), reference_);
}

TEST_F(StudyRunner, ACaseThatCannotRunIsARowWithItsStatus) {
  // 40 spikes do not exist in a 256-sample record: the spike-smooth cases cannot be set up.
  std::string text = kMini;
  text.replace(text.find("spikes = 2"), 10, "spikes = 40");
  text.replace(text.find("[landscape]"), std::string::npos, "");
  const StudySpec spec = parse_study(text, "mini.toml", ".");
  RunOptions o;
  o.output_dir = (root_ / "failing").string();
  std::ostringstream log;
  const RunSummary s = run_study(spec, o, log, false);
  EXPECT_TRUE(s.tables);
  EXPECT_EQ(s.failed, 3);  // the three spike-smooth cases
  std::ifstream in(root_ / "failing" / "cases.csv");
  std::string line;
  int failed_rows = 0;
  while (std::getline(in, line))
    if (line.find(",spike-smooth,") != std::string::npos) {
      EXPECT_NE(line.find(",failed,0,"), std::string::npos) << line;
      EXPECT_NE(line.find("spikes"), std::string::npos) << line;  // the reason is in the row
      ++failed_rows;
    }
  EXPECT_EQ(failed_rows, 3);
  // Run again, every unit reused: the summary counts the failed cases the tables hold, not only those computed now
  // (a resumed study said 0 beside 2 failed rows: the twentieth pass's P8).
  std::ostringstream again;
  const RunSummary resumed = run_study(spec, o, again, false);
  EXPECT_EQ(resumed.computed, 0);
  EXPECT_EQ(resumed.failed, 3);
  // The failed cases' records follow the declared schema too (their fields are set to "not run" values first).
  const Plan plan = make_plan(spec);
  const Store store((root_ / "failing" / "store").string(), io::commit_label());
  for (const Unit& u : plan.units) {
    const auto r = store.load(u.id);
    ASSERT_TRUE(r) << u.id;
    EXPECT_EQ(schema_violation(*r, u, spec.fit.estimate), "") << u.id;
  }
}

// Issue 30: a sweep of 1e8 units planned into 7 GB and then ended in bad_alloc; one above core::kMaxStudyUnits is
// refused before it is planned, with its size.
TEST(StudyValidation, ASweepTooLargeToPlanIsRefusedBeforePlanning) {
  std::string text = kMini;
  text.replace(text.find("replicates = 2"), 14, "replicates = 100000");
  text.replace(text.find("elements = [4]"), 14, "elements = [4, 5, 6, 7, 8, 9]");
  const StudySpec spec = parse_study(text, "mini.toml", ".");
  try {
    make_plan(spec);
    FAIL() << "the sweep was planned";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mini.toml: [sweep] makes 1200012 cases"), std::string::npos) << e.what();
  }
}

TEST(StudyValidation, EveryUnitIsCheckedBeforeAnyRuns) {
  // The beam length cannot be estimated (the Galerkin forms are built for one length): the study file parses, but
  // the plan is refused before any truth is simulated, naming the file, the unit and the reason.
  std::string text = kMini;
  text.replace(text.find("estimate = [\"EI\", \"rho\"]"), 24, "estimate = [\"EI\", \"l\"]");
  text.replace(text.find("rho = 0.99"), 10, "l = 0.99");
  text.replace(text.find("pairs = [[\"EI\", \"rho\"]]"), 23, "pairs = [[\"EI\", \"l\"]]");
  const StudySpec spec = parse_study(text, "mini.toml", ".");
  RunOptions o;
  o.output_dir = (fs::temp_directory_path() / ("beamid-validation-" + std::to_string(::getpid()))).string();
  std::ostringstream log;
  try {
    run_study(spec, o, log, false);
    FAIL() << "an inadmissible plan ran";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("mini.toml: case ", 0), 0u) << m;
    EXPECT_NE(m.find("(N = 4, cost time, method direct)"), std::string::npos) << m;
    EXPECT_NE(m.find("l"), std::string::npos) << m;
  }
  EXPECT_FALSE(fs::exists(fs::path(o.output_dir) / "store")) << "nothing may be written before validation";
  fs::remove_all(o.output_dir);
}

// Start-distance curves for every experiment (start_distance.experiments = "all"): one radius row per run and
// experiment, each with its own modes in the data (a sin^2 pulse of width tau excites up to about 2/tau, so the 2 ms
// pulse shows more of the thin beam's modes than the 50 ms one) and its own predicted basin; the first experiment's
// units keep the ids they have with experiments = "first".
TEST(StudyRunnerExperiments, StartDistanceCurvesForEveryExperiment) {
  std::string text = std::string(kMini);
  text = text.substr(0, text.find("[landscape]"));
  text.replace(text.find("elements = [4]\n"), 15, "elements = [4]\npulse_width_s = [0.002, 0.05]\n");
  const std::string sd =
      "\n[start_distance]\nelements = 4\noffsets = [0.001, 0.01]\ndirections = 2\n"
      "runs = [\"time/direct\"]\n";
  const StudySpec first = parse_study(text + sd, "mini.toml", ".");
  const StudySpec all = parse_study(text + sd + "experiments = \"all\"\n", "mini.toml", ".");
  const Plan plan_first = make_plan(first), plan_all = make_plan(all);
  std::vector<std::string> ids_first, ids_all;
  for (const Unit& u : plan_first.units)
    if (u.kind == UnitKind::Start) ids_first.push_back(u.id);
  for (const Unit& u : plan_all.units)
    if (u.kind == UnitKind::Start) ids_all.push_back(u.id);
  ASSERT_EQ(ids_first.size(), 5u);  // the truth start and 2 offsets x 2 directions
  ASSERT_EQ(ids_all.size(), 10u);
  EXPECT_TRUE(std::equal(ids_first.begin(), ids_first.end(), ids_all.begin()));
  const fs::path dir = fs::temp_directory_path() / ("beamid-experiments-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  RunOptions o;
  o.output_dir = dir.string();
  o.jobs = 1;
  std::ostringstream log;
  ASSERT_TRUE(run_study(all, o, log, false).tables);
  {  // the start-distance records follow the declared schema
    const Plan plan = make_plan(all);
    const Store store((dir / "store").string(), io::commit_label());
    std::set<UnitKind> kinds;
    for (const Unit& u : plan.units) {
      const auto r = store.load(u.id);
      ASSERT_TRUE(r) << u.id;
      EXPECT_EQ(schema_violation(*r, u, all.fit.estimate), "") << u.id;
      kinds.insert(u.kind);
    }
    EXPECT_TRUE(kinds.count(UnitKind::Start));
  }
  const auto files = tables(dir);
  fs::remove_all(dir);
  std::istringstream radius(files.at("start_distance/radius.csv"));
  std::string line;
  std::getline(radius, line);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(radius, line)) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].size(), 18u);
  EXPECT_EQ(rows[0][13], "0");  // experiment
  EXPECT_EQ(rows[1][13], "1");
  EXPECT_GT(std::stoi(rows[0][16]), std::stoi(rows[1][16]));  // modes in the data
  EXPECT_GE(std::stoi(rows[1][16]), 2);
  EXPECT_EQ(rows[0][17], "2");  // fitted modes: fit.spikes = 2 in both
  // The predicted basins differ with the experiment's modes only through the fitted ones (the same two here), so
  // they are equal; each is finite.
  EXPECT_EQ(rows[0][7], rows[1][7]);
  EXPECT_GT(std::stod(rows[0][7]), 0.0);
  EXPECT_NE(files.at("start_distance.md").find("| modes in data (fitted) | pulse |"), std::string::npos);
}

}  // namespace
}  // namespace beamid::study
