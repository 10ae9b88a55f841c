// The posterior of a fit's estimated parameters (issue 34 item 2): samples of p(q | data) by the ensemble sampler
// (fit/ensemble_sampler.h), their means, sds, 95 % credible intervals and correlations, the chains' R-hat and
// effective sample sizes, and the model's evidence p(data) by Laplace's approximation and by importance sampling.
//
// Likelihood. The least-squares costs are Gaussian likelihoods whose level the residuals give (costs/cost.h: time,
// white or prewhitened by a named noise model, freq-band and freq-ml): residuals r(q) of m independent N(0, s^2)
// terms. The noise level s is not known; with Jeffreys' prior 1/s it integrates out in closed form,
//   p(data | q) = int (2 pi s^2)^(-m/2) exp(-S(q) / (2 s^2)) ds / s = Gamma(m/2) / 2 (pi S(q))^(-m/2),
// S(q) = |r(q)|^2 the cost: a Student-like likelihood that weighs the cost's rise by the residuals' own level, as
// the formal standard errors do (s^2 = S / (m - p)); for many residuals its curvature at the minimum is the formal
// covariance times m / (m - p). The spike and modal costs weigh their terms by convention, not by the noise, and have
// no likelihood: refused, as is a noise model estimated from the fit's residuals (the posterior would need the
// estimate it was fitted with) and records weighted by their noise (each record would need its own level).
//
// Prior: uniform on each parameter's bounds (the fit's --bounds), in the parameter itself, whatever the fit's
// scaling; the sampler runs in the fit's coordinates (ln q under log scaling), so the density there takes the
// Jacobian dq/dx.
//
// Evidence, to compare model classes on one record (a rigid against a spring clamp; with or without an attachment):
//   Laplace:   ln Z = ln L(q^) + ln pi(q^) + (p/2) ln 2 pi + ln det(C)/2, C = the formal covariance (m - p) / m;
//              NaN when an estimate is on a bound (no interior maximum) or the covariance is unavailable.
//   sampled:   importance sampling from a multivariate Student t (5 degrees of freedom: tails heavier than the
//              posterior's) with the draws' mean and twice their covariance, in the sampler's coordinates:
//              Z = mean_i L(x_i) pi(x_i) / g(x_i), its standard error from the weights' spread (delta method in ln Z).
// Both carry the same constant ln Gamma(m/2) - ln 2 - (m/2) ln pi: evidences compare models of one record only.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "fit/ensemble_sampler.h"
#include "fit/identification.h"

namespace beamid::fit {

inline constexpr int kEvidenceDegreesOfFreedom = 5;

struct PosteriorOptions {
  SamplerOptions sampler;
  int threads = 1;              // chains in parallel (the draws do not depend on it)
  int importance_draws = 4000;  // the sampled evidence's model evaluations; 0: not computed
  void validate(int dimension) const;
};

struct PosteriorParameter {
  std::string key;
  double estimate = 0, standard_error = 0;  // the fit's
  double mean = 0, sd = 0, median = 0, lower95 = 0, upper95 = 0;
  double rhat = 0, effective_samples = 0;
};

struct Posterior {
  std::vector<PosteriorParameter> parameters;
  Eigen::MatrixXd correlation;
  SamplerResult samples;  // the draws in the parameters' own values (not the sampler's coordinates)
  int residuals = 0;
  double log_evidence_laplace = std::numeric_limits<double>::quiet_NaN();
  double log_evidence_sampled = std::numeric_limits<double>::quiet_NaN();
  double log_evidence_sampled_se = std::numeric_limits<double>::quiet_NaN();
  std::string evidence_note;  // why an evidence is NaN, or ""
  double wall_time_s = 0;
  std::string status;  // the sampler's: "converged" or "not converged: ..."
  bool converged() const { return status == "converged"; }
  // "EI: mean 0.491 sd 0.0021, 95 % [0.487, 0.495] (fit 0.491 +- 0.0020), R-hat 1.002, ESS 2400"
  std::string line(std::size_t k) const;
};

// Why a fit with these options has no posterior, or "" (the cost, the noise model, the weights): checked before the
// fit runs.
std::string posterior_problem(const FitOptions& options, const std::vector<Record>& records);

// The posterior about the fit `best` of (options, records): the walkers start about its estimate, a formal standard
// error apart (a hundredth of the bound range where there is none). InputError where posterior_problem says why,
// and for a failed fit.
Posterior posterior(const FitOptions& options, const std::vector<Record>& records, const FitResult& best,
                    const PosteriorOptions& posterior_options);

}  // namespace beamid::fit
