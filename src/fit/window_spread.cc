#include "fit/window_spread.h"

#include <cmath>
#include <limits>

#include "core/errors.h"

namespace beamid::fit {

WindowSpread window_spread(const FitOptions& options, const std::vector<Record>& records, const FitResult& full,
                           int windows) {
  if (windows < 2) throw InputError("windows = " + std::to_string(windows) + ": must be >= 2");
  for (const Record& r : records)
    if (r.experiment.samples / windows < kMinWindowSamples)
      throw InputError("windows = " + std::to_string(windows) + ": a window of record '" + r.name + "' would have " +
                       std::to_string(r.experiment.samples / windows) +
                       " samples: must be >= " + std::to_string(kMinWindowSamples));
  if (full.records.size() != records.size()) throw InputError("window_spread: the full fit is of other records");
  WindowSpread spread;
  spread.windows = windows;
  for (const ParameterEstimate& p : full.parameters) spread.keys.push_back(p.key);
  const std::size_t n = spread.keys.size();
  FitOptions o = options;
  o.strategy = o.strategy == kHybrid ? kHybrid : kDirect;  // the hybrid's refinement is part of its estimate
  o.starts = 1;
  std::vector<std::vector<double>> formal_errors;  // [window][parameter]
  std::vector<std::vector<bool>> on_bound;         // [window][parameter]: the window fit left it on a bound
  for (int k = 0; k < windows; ++k) {
    std::vector<Record> cut = records;
    for (std::size_t r = 0; r < cut.size(); ++r) {
      const int length = records[r].experiment.samples / windows;
      cut[r].experiment.samples = length;
      cut[r].data.assign(records[r].data.begin() + static_cast<std::ptrdiff_t>(k) * length,
                         records[r].data.begin() + static_cast<std::ptrdiff_t>(k + 1) * length);
      if (k > 0) cut[r].experiment.excitation = simulation::kFreeDecay;  // the state at the window's start is unknown
      cut[r].start = full.records[r].beam;                               // inside the bounds, always
    }
    std::vector<double> estimate(n, std::numeric_limits<double>::quiet_NaN()), formal = estimate;
    std::vector<bool> bound(n, false);
    std::string status;
    try {
      const FitResult r = fit(o, cut);
      status = r.status;
      if (status != "failed")
        for (std::size_t i = 0; i < n; ++i) {
          estimate[i] = r.parameters[i].estimate, formal[i] = r.parameters[i].standard_error;
          bound[i] = r.parameters[i].status == kAtLowerBound || r.parameters[i].status == kAtUpperBound;
        }
    } catch (const std::exception& error) {  // a window the cost cannot use (too few spikes in it, for example)
      status = std::string("failed: ") + error.what();
    }
    spread.estimates.push_back(estimate);
    formal_errors.push_back(formal);
    on_bound.push_back(bound);
    spread.statuses.push_back(status);
  }
  spread.mean.assign(n, std::numeric_limits<double>::quiet_NaN());
  spread.sd = spread.standard_error = spread.window_formal = spread.mean;
  // Only windows whose fit converged count: one stopped by the evaluation budget sits wherever the budget left it
  // (near its start, the full estimate), and eight such windows gave an sd of EI 300 times below its formal error,
  // a measure of the budget rather than the data (the second adversarial pass's N540).
  // A parameter's statistics leave out the windows where it sits on a bound (the bound set it, not the data).
  std::vector<bool>& counted = spread.counted;
  for (std::size_t k = 0; k < spread.estimates.size(); ++k) {
    counted.push_back(spread.statuses[k].rfind("converged", 0) == 0 && !spread.estimates[k].empty() &&
                      !std::isnan(spread.estimates[k].front()));
    spread.used += counted.back() ? 1 : 0;
  }
  // A window where a parameter ends on a bound is a constrained fit, and the bound biases its other estimates too (a
  // window's cDI on its lower bound moved its EI by 0.5 %, and a clean record's spread was called "model error or
  // drift", 3.3 times the windows' noise: the twenty-second pass's P6). Such windows still count for the parameters
  // off their bound (on a measured record a window driven onto a bound may be the model error the spread is there to
  // show, and leaving it out would shrink the spread); bound_bias says that the spread holds the bound's bias too.
  for (std::size_t k = 0; k < counted.size(); ++k)
    for (const bool b : on_bound[k]) spread.bound_bias = spread.bound_bias || (counted[k] && b);
  spread.used_per_parameter.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto counts = [&](std::size_t k) { return counted[k] && !on_bound[k][i]; };
    double sum = 0, squares = 0;
    int used = 0;
    for (std::size_t k = 0; k < spread.estimates.size(); ++k)
      if (counts(k)) sum += spread.estimates[k][i], ++used;
    spread.used_per_parameter[i] = used;
    if (used < 2) continue;
    const double mean = sum / used;
    for (std::size_t k = 0; k < spread.estimates.size(); ++k)
      if (counts(k)) squares += (spread.estimates[k][i] - mean) * (spread.estimates[k][i] - mean);
    spread.mean[i] = mean;
    spread.sd[i] = std::sqrt(squares / (used - 1));
    double formal_squares = 0;
    for (std::size_t k = 0; k < spread.estimates.size(); ++k)
      if (counts(k)) formal_squares += formal_errors[k][i] * formal_errors[k][i];
    spread.window_formal[i] = std::sqrt(formal_squares / used);
    spread.standard_error[i] = spread.sd[i] / std::sqrt(static_cast<double>(used));
  }
  return spread;
}

WindowSpread window_spread(const FitOptions& options, const std::vector<double>& data, const FitResult& full,
                           int windows) {
  return window_spread(options, {Record{"record1", options.start, options.experiment, data, {}, {}, {}}}, full,
                       windows);
}

}  // namespace beamid::fit
