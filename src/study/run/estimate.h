// What a study run will cost before it starts (issue 32 item 1): the units to run, timed by a previous run's
// timings.csv in the output folder (the committed results/<study>/timings.csv for `make study`), and the expected
// wall time on the given threads and as Slurm shards. A unit the previous run timed is counted at its own time (its
// id is a hash of its settings, so a rerun of the same study has the same ids); one it did not, at the median of its
// kind, cost and order N there, else of its kind; one of a kind never timed at kSecondsPerUntimedUnit.
#pragma once

#include <string>
#include <vector>

#include "study/plan/plan.h"

namespace beamid::study {

// A unit at N = 16 takes about 1 s on this machine (the paper study's 762 units took 6.5 min on 2 threads).
inline constexpr double kSecondsPerUntimedUnit = 1.0;
// At a larger N an untimed unit is counted at least at its model evaluations' cost (core::kSecondsPerEvaluationAtN200,
// growing as N^3): a truth record about kTruthEvaluations of them (the exact closed form, then the first one's CVODE
// cross-check: measured 71 s at N_truth = 400, where one evaluation takes 26 s), a fit about kFitEvaluations (the
// modal and spike-smooth fits' medians are 20-170, (3.5)'s up to 1,250). A study at N_truth = 400 planned "about 11 s"
// just after saying one evaluation takes 26 s (the twentieth adversarial pass's P7).
inline constexpr double kTruthEvaluations = 3;
inline constexpr double kFitEvaluations = 100;

struct PlanEstimate {
  int units = 0;
  int by_id = 0, by_median = 0, untimed = 0;  // how each unit's time was found
  double compute_s = 0;                       // summed over the units
  struct Group {                              // the units of one kind, cost and N, with their summed time
    std::string label;                        // "case spike N = 16"
    int units = 0;
    double compute_s = 0;
  };
  std::vector<Group> groups;  // the largest first
};

// The estimate for `units` from the timings file at `timings_path` (absent or unreadable: every unit untimed; a line
// it cannot read is skipped: the file is a previous output, not an input).
// `truth_elements` is N_truth (a truth unit's own `elements` is not set).
PlanEstimate estimate_plan(const std::vector<const Unit*>& units, const std::string& timings_path, int truth_elements);

// "plan: 60 unit(s) to run, about 3 min of compute: 3 s wall on 2 thread(s) ... (largest: ...)", one line.
std::string plan_text(const PlanEstimate& estimate, int jobs, const std::string& timings_path);

}  // namespace beamid::study
