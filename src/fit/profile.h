// Profile-likelihood intervals (issue 34): for one estimated parameter q_k, the fit repeated with q_k fixed at values
// on either side of its estimate, every other estimated parameter refitted, so that the cost's rise along the profile
// is what the data say about q_k alone. For a least-squares cost with the noise level estimated from the residuals,
//   D(v) = (S(v) - S_min) / s^2,   s^2 = S_min / (m - p),
// S the minimum sum of squares with q_k = v, m residuals and p estimated parameters: D is asymptotically chi^2 with one
// degree of freedom, so {v : D(v) <= 1} is the 68.3 % interval and {v : D(v) <= 3.841} the 95 % one (the
// likelihood-ratio intervals of Venzon and Moolgavkar 1988; Raue et al. 2009 for their use in identifiability). Where
// the cost is quadratic in q_k the profile is too, and the interval is the formal one, estimate +- z SE; where it is
// not (a bound near, a curved valley, a parameter the data hardly fix), the profile says what the formal error cannot:
// an asymmetric interval, or one that the data do not close within the bounds ("not bounded above by the data").
// The grid steps in ln q_k by half the formal relative standard error (a fiftieth of the log bound range where there is
// none), from the estimate outwards, each point started from its neighbour's estimate, until D exceeds the 95 % level,
// a bound is reached or kMaxProfileSteps points are taken on a side; a crossing is interpolated linearly in the signed
// root sqrt(D), which is linear in q_k where the cost is quadratic.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fit/identification.h"

namespace beamid::fit {

inline constexpr int kMaxProfileSteps = 16;
// chi^2_1 quantiles: 68.27 % (one standard deviation) and 95 %.
inline constexpr double kProfileLevel68 = 1.0;
inline constexpr double kProfileLevel95 = 3.841458820694124;

struct ProfilePoint {
  double value = 0;                                             // q_k fixed here
  double cost = std::numeric_limits<double>::quiet_NaN();       // S(v), NaN when the refit failed
  double statistic = std::numeric_limits<double>::quiet_NaN();  // D(v)
  std::string status;                                           // the refit's status
};

struct Profile {
  std::string key;
  double estimate = 0, standard_error = 0;  // the full fit's (standard_error NaN at a bound)
  std::vector<ProfilePoint> points;         // ascending in value, the estimate included (D = 0)
  // The intervals' ends; NaN where the profile does not rise to the level within the bounds (then `open_below` /
  // `open_above` say which side).
  double lower68 = std::numeric_limits<double>::quiet_NaN(), upper68 = std::numeric_limits<double>::quiet_NaN();
  double lower95 = std::numeric_limits<double>::quiet_NaN(), upper95 = std::numeric_limits<double>::quiet_NaN();
  bool open_below = false, open_above = false;  // at 95 %
  // Where a refit found a lower cost than the fit's own: the fit's estimate is no global minimum (the profile's value
  // there is named), "" otherwise.
  std::string lower_minimum;
  std::string status = "ok";  // or why no profile was computed
  // "EI: 68 % [a, b], 95 % [c, d] (formal: estimate +- 1.96 SE [e, f])", with "not bounded above by the data within
  // its bounds" where a side stays open, and the lower minimum where one was found.
  std::string line() const;
};

// The profile of estimated key `key` about the fit `best` of (options, records) (fit::fit's result). InputError for
// a key not estimated, a per-record key (recordK.KEY), a fit that failed or a cost that is no sum of squares with
// more residuals than parameters.
Profile profile(const FitOptions& options, const std::vector<Record>& records, const FitResult& best,
                const std::string& key);

}  // namespace beamid::fit
