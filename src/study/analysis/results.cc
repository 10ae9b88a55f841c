#include "study/analysis/results.h"

#include <cmath>
#include <limits>

#include "core/errors.h"
#include "model/beam_parameters.h"
#include "study/run/record_schema.h"

namespace beamid::study {

int CaseRow::modes() const {
  return record.has("modes_in_data") ? static_cast<int>(record.number("modes_in_data")) : 0;
}

double CaseRow::max_abs_error(const std::vector<std::string>& keys) const {
  double m = 0;
  for (const auto& k : keys) {
    const double e = error(k);
    if (!std::isfinite(e)) return std::numeric_limits<double>::quiet_NaN();
    m = std::max(m, std::abs(e));
  }
  return m;
}

double tolerance(const StudySpec& spec, const std::string& key) {
  return model::parameter_role(key) == "damping" ? spec.fit.damping_tolerance : spec.fit.success_tolerance;
}

bool case_succeeded(const StudySpec& spec, const Record& record) {
  bool ok = record.text("status") != "failed";
  for (const auto& k : spec.fit.estimate)
    ok = ok && std::abs(record.number("relative_error." + k)) <= tolerance(spec, k);  // NaN: false
  return ok;
}

StudyResults load_results(const StudySpec& spec, const Plan& plan, const Store& store) {
  StudyResults results;
  results.spec = &spec;
  results.plan = &plan;
  int missing = 0, missing_truths = 0;
  const Unit* first_missing = nullptr;  // named in the message: the shard that holds it is the one to rerun
  for (const Unit& t : plan.truths) {
    if (auto r = load_unit(store, t, spec.fit.estimate))
      results.truths.push_back(std::move(*r));
    else
      ++missing, ++missing_truths, first_missing = first_missing ? first_missing : &t;
  }
  for (std::size_t k = 0; k < plan.units.size(); ++k) {
    const Unit& u = plan.units[k];
    auto r = load_unit(store, u, spec.fit.estimate);
    if (!r) {
      ++missing;
      first_missing = first_missing ? first_missing : &u;
      continue;
    }
    if (u.kind == UnitKind::Case) {
      const bool success = case_succeeded(spec, *r);
      results.cases.push_back({&u, std::move(*r), success});
    } else if (u.kind == UnitKind::Bound) {
      results.bounds.push_back({&u, std::move(*r)});
    } else if (u.kind == UnitKind::Start) {
      results.starts.push_back({&u, std::move(*r)});
    } else if (u.kind == UnitKind::Frequencies) {
      results.frequencies[u.elements] = std::move(*r);
    } else {
      results.landscape.push_back({&u, std::move(*r)});
    }
  }
  if (missing > 0) {
    // Which unit: its kind, id and position in the plan, so that the shard K/N that holds it (position mod N + 1)
    // can be told (the third pass's P391: "6 of 20 units ... missing" named none, and counted the truth as a unit).
    std::string first = unit_kind_name(first_missing->kind) + " " + first_missing->id;
    for (std::size_t k = 0; k < plan.units.size(); ++k)
      if (&plan.units[k] == first_missing) first += " (unit " + std::to_string(k + 1) + " of the plan)";
    throw InputError(store.directory() + ": " + std::to_string(missing - missing_truths) + " of " +
                     std::to_string(plan.units.size()) + " units" +
                     (missing_truths ? " and " + std::to_string(missing_truths) + " of " +
                                           std::to_string(plan.truths.size()) + " truth record(s)"
                                     : std::string()) +
                     " of study '" + spec.name + "' are missing (or were made by another build), the first " + first +
                     ": run the missing shards and name every shard's folder in --shards (unit k is shard ((k - 1) mod "
                     "N) + 1 of N)");
  }
  return results;
}

}  // namespace beamid::study
