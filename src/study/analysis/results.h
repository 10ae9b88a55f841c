// A finished study as data: every unit's record, loaded once from the store in plan order, with each case judged
// against the study's success tolerances. The metrics (metrics.h), tables and claims are functions of this alone,
// so a single run, a resumed run and merged shards give the same bytes.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "study/plan/plan.h"
#include "study/run/store.h"
#include "study/spec/study_spec.h"

namespace beamid::study {

// One finished fit with its settings.
struct CaseRow {
  const Unit* unit = nullptr;
  Record record;
  bool success = false;  // not failed, and every estimate within its tolerance

  bool failed() const { return record.text("status") == "failed"; }
  double error(const std::string& key) const { return record.number("relative_error." + key); }
  int modes() const;  // modes in the data (0 when unknown)
  // max_k |relative error of k| (NaN when one is not finite).
  double max_abs_error(const std::vector<std::string>& keys) const;
};

// A landscape unit (slice, grid or multistart) with its record.
struct LandscapeRow {
  const Unit* unit = nullptr;
  Record record;
};

struct StudyResults {
  const StudySpec* spec = nullptr;
  const Plan* plan = nullptr;
  std::vector<Record> truths;           // as plan.truths
  std::vector<CaseRow> cases;           // plan order
  std::vector<LandscapeRow> landscape;  // plan order
  std::vector<LandscapeRow> starts;     // start-distance fits (kind "start"), plan order
  std::vector<LandscapeRow> bounds;     // Cramér-Rao bounds (kind "bound"), plan order
  std::map<int, Record> frequencies;    // N -> its "frequencies" unit (exact_hz, galerkin_hz)
};

// The success tolerance of a parameter: fit.damping_tolerance for damping parameters, fit.success_tolerance else.
double tolerance(const StudySpec& spec, const std::string& key);

// Loads every unit of the plan (InputError naming the store and the missing count when some are absent).
StudyResults load_results(const StudySpec& spec, const Plan& plan, const Store& store);

// Judges one case record: status not "failed" and |relative error| <= tolerance for every estimated key (NaN fails).
bool case_succeeded(const StudySpec& spec, const Record& record);

}  // namespace beamid::study
