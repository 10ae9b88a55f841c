// What a fit's data determine (fit/identification.h reports it with every fit): the Gauss-Newton information at the
// estimate in relative coordinates, its condition number and the combinations of parameters it leaves undetermined.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "fit/optimizer.h"
#include "fit/parameter_map.h"

namespace beamid::fit {

// What the data determine, from the Gauss-Newton information J^T J at the estimate in relative coordinates
// (ln q for every estimated q): its condition number kappa = sqrt(lambda_max / lambda_min) (that of J), and the
// weakest combination, the unit eigenvector of lambda_min, with the formal standard deviation s / sqrt(lambda_min)
// of a step along it (relative). kappa > 1e7 (lambda ratio beyond 1e-14, where the covariance is refused) means the
// record cannot separate that combination: for example EI and rho in a free decay, whose frequencies depend on EI/rho
// only.
//
// The verdict is about the parameters of interest (VerdictScope): a parameter its bound fixed is left out (the bound,
// not the data, set it), and the free nuisances (by default the damping terms) are marginalised, the information
// about the rest being the Schur complement I_AA - I_AB I_BB^+ I_BA, whose inverse is the covariance of the
// parameters of interest with the nuisances free. In a joint fit of four lengths one record's damping on its bound
// was named the weakest combination, hiding how well E and the clamp spring were determined (issue 31).
struct Identifiability {
  std::string status = "not computed";  // "ok", or why not (no residual vector, too few residuals, ...)
  double condition = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> keys;      // the parameters of interest the verdict is about (free ones only)
  std::vector<std::string> nuisance;  // free parameters marginalised (not of interest)
  std::vector<std::string> on_bound;  // parameters left out: their bound set them
  std::vector<double> weakest;        // per key, unit norm, the first component of magnitude >= 0.05 positive
  double weakest_sd = std::numeric_limits<double>::quiet_NaN();
  // "identifiable" (kappa <= 1e3), "ill-conditioned" (1e3 < kappa <= 1e7) or "not identifiable" (kappa > 1e7).
  std::string verdict;
  // Every eigen-direction of the information whose sqrt(lambda_max / lambda) exceeds 1e3, weakest first (the
  // first is `weakest`): a record can leave several combinations undetermined at once (a free decay: EI with l,
  // and the damping), and the weakest alone would hide the others.
  struct Direction {
    std::vector<double> components;  // per key, signed as `weakest`
    double ratio = 0;                // sqrt(lambda_max / lambda)
    double sd = 0;                   // formal standard deviation along it (relative)
  };
  std::vector<Direction> weak;
  // "0.71 ln EI - 0.71 ln rho": a combination (the weakest by default), components under 0.05 left out.
  std::string combination() const { return combination(weakest); }
  // " about EI, rho (gamma, cDI marginalised; kAcs on its bound, left out)": what the verdict is about, "" when it is
  // about every estimated parameter.
  std::string scope() const;
  std::string combination(const std::vector<double>& components) const;
};

// "0.71 ln EI - 0.71 ln rho": the direction v over `keys` as text, components under 0.05 left out, signed so that the
// first printed component is positive.
std::string combination_text(const std::vector<std::string>& keys, const std::vector<double>& v);

// What the verdict is about, per estimated coordinate (in the map's order); empty vectors: every one of interest,
// none on a bound. When no free parameter is of interest, the verdict is about every free one.
struct VerdictScope {
  std::vector<bool> of_interest;
  std::vector<bool> on_bound;
};

// From the covariance computation at the estimate (its J^T J and s^2, kept even when J^T J is singular) and the map
// of the estimated parameters at coordinates x. Status "ok", or the covariance's reason when J was not formed.
Identifiability identifiability_of(const Covariance& covariance, const ParameterMap& map, const Eigen::VectorXd& x,
                                   const VerdictScope& scope = {});

}  // namespace beamid::fit
