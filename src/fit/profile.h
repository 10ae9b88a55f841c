// Profile-likelihood intervals (issue 34): for one estimated parameter q_k, the fit repeated with q_k fixed at values
// on either side of its estimate, every other estimated parameter refitted, so that the cost's rise along the profile
// is what the data say about q_k alone. For a least-squares cost with the noise level estimated from the residuals,
//   D(v) = (S(v) - S_min) / s^2,   s^2 = S_min / (m - p),
// S the minimum sum of squares with q_k = v, m residuals and p estimated parameters: with the noise level estimated,
// D is F(1, m - p), the square of Student's t with m - p degrees of freedom (chi^2 with one as m - p grows), so
// {v : D(v) <= t^2(0.8413)} is the 68.3 % interval and {v : D(v) <= t^2(0.975)} the 95 % one, 3.84 for many residuals
// (the likelihood-ratio intervals of Venzon and Moolgavkar 1988; Raue et al. 2009 for their use in identifiability;
// with 6 degrees of freedom the chi^2 level covered the truth on 89 % of 200 seeds: the thirty-first pass's adv71 P4).
// Where
// the cost is quadratic in q_k the profile is too, and the interval is the formal one, estimate +- z SE; where it is
// not (a bound near, a curved valley, a parameter the data hardly fix), the profile says what the formal error cannot:
// an asymmetric interval, or one that the data do not close within the bounds ("not bounded above by the data").
// The grid steps in ln q_k by half the formal relative standard error (a fiftieth of the log bound range where there is
// none), from the estimate outwards, each point started from its neighbour's estimate, until D exceeds the 95 % level,
// a bound is reached or kMaxProfileSteps points are taken on a side; a step that raises D by more than 2 is halved
// (up to kMaxProfileHalvings times), so that each crossing is bracketed by D at most 2 apart (a coarse step from an
// estimate on a bound put the 95 % end where D was 8-14: the thirty-first pass's adv71 P2); a crossing is interpolated
// linearly in the signed root sqrt(D), which is linear in q_k where the cost is quadratic.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fit/identification.h"

namespace beamid::fit {

inline constexpr int kMaxProfileSteps = 16;
inline constexpr int kMaxProfileHalvings = 8;
// A refit lower than the fit by more than this in D (a likelihood ratio e^{1/2}) is a lower minimum; less is the
// refit's own tolerance (an estimate on a bound refitted 0.0004-0.057 lower was called no global minimum: adv71 P3).
inline constexpr double kLowerMinimumD = 1.0;
// The levels of D for 68.27 % and 95 % with `dof` residual degrees of freedom: Student's t quantiles squared (exact for
// 1 and 2 degrees of freedom, the Cornish-Fisher expansion to 1/nu^4 beyond, within 1e-3 of the t quantile from 3).
double profile_level(double probability, int dof);

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
  double level68 = 1, level95 = 3.841458820694124;  // profile_level at the fit's degrees of freedom
  std::string status = "ok";                        // or why no profile was computed
  // "EI: 68 % [a, b], 95 % [c, d] (formal: estimate +- 1.96 SE [e, f])", with "not bounded above by the data within
  // its bounds" where a side stays open, and the lower minimum where one was found.
  std::string line() const;
};

// The profile of estimated key `key` about the fit `best` of (options, records) (fit::fit's result). InputError for
// a key not estimated, a per-record key (recordK.KEY), a fit that failed, a cost with no more residuals than
// parameters, or records weighted by their noise (record_weights "noise": each refit would re-estimate the weights,
// which keeps its cost near the number of residuals and flattens the profile: adv71 P1).
Profile profile(const FitOptions& options, const std::vector<Record>& records, const FitResult& best,
                const std::string& key);

}  // namespace beamid::fit
