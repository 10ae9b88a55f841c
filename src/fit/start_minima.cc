// Other minima the starts found: see start_minima.h.
#include "fit/start_minima.h"

#include <cmath>
#include <cstddef>

#include "core/errors.h"

namespace beamid::fit {

std::string other_minimum(const std::vector<StartEnd>& ends, int best, const std::vector<std::string>& keys,
                          const std::vector<double>& estimate, const std::vector<double>& standard_error,
                          double residual_variance) {
  if (best < 0 || static_cast<std::size_t>(best) >= ends.size() || !(residual_variance > 0)) return "";
  const double best_cost = ends[static_cast<std::size_t>(best)].cost;
  std::string nearest;
  double nearest_delta = kOtherMinimumVariances;
  for (std::size_t s = 0; s < ends.size(); ++s) {
    const StartEnd& end = ends[s];
    if (static_cast<int>(s) == best || !end.usable || end.values.size() != keys.size()) continue;
    const double delta = (end.cost - best_cost) / residual_variance;
    if (!(delta >= 0 && delta < nearest_delta)) continue;
    // The parameter farthest from the estimate, in its standard errors.
    std::size_t far = keys.size();
    double distance = kOtherMinimumDistance;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      // Apart by more than round-off (a noise-free record's standard errors are round-off, and two starts ending
      // at the same value to 12 digits were "far": the twenty-fifth pass's adv59 P3).
      const double apart = std::abs(end.values[i] - estimate[i]);
      const double d = apart / standard_error[i];
      if (std::isfinite(d) && d > distance && apart > 1e-9 * std::abs(estimate[i])) far = i, distance = d;
    }
    if (far == keys.size()) continue;
    nearest_delta = delta;
    // Numbered as the fit report's "best:" is: 0 the given start, then the space-filling ones.
    nearest = (s == 0 ? std::string("the given start") : "space-filling start " + std::to_string(s)) + " ended only " +
              format_rounded(delta, 2) + " noise variances higher, at " + keys[far] + " = " +
              format_rounded(end.values[far], 4) + ", " + format_rounded(distance, 2) +
              " standard errors from the estimate";
  }
  return nearest;
}

}  // namespace beamid::fit
