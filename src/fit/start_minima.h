// Other minima the starts found: with --starts K every start ends somewhere, and the best is the estimate. Another
// start that ended almost as low (within kOtherMinimumVariances noise variances of the sum of squares) yet far from
// the estimate (beyond kOtherMinimumDistance standard errors in some parameter) says the cost has several minima the
// data hardly tell apart, which the standard errors, a description of the estimate's own basin, do not show. A thin
// beam's time fit of EI and kAG had minima at kAG 3.9e5, 7.7e5, 9.6e5 and 1.03e6 within 20 noise variances, and the
// fit printed one of them "converged" with a 1.7 % standard error (the twenty-first pass's adv51 P3).
#pragma once

#include <string>
#include <vector>

namespace beamid::fit {

// Where one start ended: its final sum of squares, its parameters' values (in the fit's order, physical units), and
// whether its final stage gave a usable estimate (converged or stopped by the budget, not failed).
struct StartEnd {
  double cost = 0;
  std::vector<double> values;
  bool usable = false;
};

// "Nearly as low": the likelihood ratio of two minima in white noise is exp(-delta / 2) with delta their sums of
// squares' difference in noise variances; 25 (a ratio of 4e-6) is well beyond any chi-square quantile of a dozen
// parameters at 99.9 %, so a minimum within it is one the data do not rule out.
inline constexpr double kOtherMinimumVariances = 25;
// "Far": beyond 3 standard errors the two minima are not one basin's scatter.
inline constexpr double kOtherMinimumDistance = 3;

// The nearest such other minimum as text ("space-filling start 3 ended only 4.2 noise variances higher, at kAG
// = 7.66e+05, 14 standard errors from the estimate"), or "" when there is none. `best` indexes `ends`; keys, estimate
// and standard_error are the estimate's, residual_variance the sum of squares' per degree of freedom at it.
std::string other_minimum(const std::vector<StartEnd>& ends, int best, const std::vector<std::string>& keys,
                          const std::vector<double>& estimate, const std::vector<double>& standard_error,
                          double residual_variance);

}  // namespace beamid::fit
