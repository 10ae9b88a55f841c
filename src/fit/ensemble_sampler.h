// An affine-invariant ensemble MCMC sampler and its convergence diagnostics (issue 34 item 2): the sampler of a
// posterior for any cost, with or without a gradient.
//
// Sampler: Goodman and Weare's (2010) stretch move, in the parallel form of Foreman-Mackey et al. (2013, emcee):
// an ensemble's walkers are split in two halves; each walker X_k of one half proposes
//   Y = X_j + z (X_k - X_j),   z = ((a - 1) u + 1)^2 / a   (density ~ 1/sqrt(z) on [1/a, a]),
// with X_j a walker of the other half drawn uniformly, and accepts with probability min(1, z^(d-1) p(Y) / p(X_k)).
// The move is invariant under affine maps of the parameters, so a posterior whose parameters differ by orders of
// magnitude and are strongly correlated (EI and rho along a frequency's valley) is sampled as well as a round one.
// It needs no gradient: every least-squares cost of beamid has a log density, not every one a derivative.
//
// Diagnostics (Vehtari, Gelman, Simpson, Carpenter and Buerkner 2021): `chains` independent ensembles from
// independent starts, each split in halves, give the rank-normalised split R-hat of every parameter (the larger of
// the bulk's and the folded tail's). An ensemble's walkers are not independent chains, so an ensemble is one chain
// whose draws pool its walkers. The integrated autocorrelation time tau of a parameter is Sokal's (1997) windowed sum
// of the autocorrelation averaged over an ensemble's walkers (the estimator emcee recommends), with the window the
// smallest M >= 5 tau(M); the effective sample size is draws / tau. A run is converged when every R-hat < 1.01, every
// effective sample size >= 400 and the run is at least 50 tau long (the thresholds of Vehtari et al. and of emcee's
// documentation); otherwise its status names the first parameter and check that fails.
//
// Random numbers: std::mt19937_64 per ensemble, seeded by SplitMix64 of (seed, chain), uniforms and Gaussians as in
// signal/noise.h, so a seed gives the same draws with any standard library.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace beamid::fit {

// ln p(x) up to a constant; -infinity outside the support (a prior's bounds, a failed model evaluation).
using LogDensity = std::function<double(const Eigen::VectorXd&)>;

inline constexpr double kMaxRhat = 1.01;
inline constexpr double kMinEffectiveSamples = 400;
inline constexpr double kMinStepsPerTau = 50;
// Draws a walker's start may take: a start region where ln p is nowhere finite is refused, naming its center.
inline constexpr int kMaxStartTries = 1000;

struct SamplerOptions {
  int chains = 4;        // independent ensembles: R-hat compares them
  int walkers = 0;       // per ensemble, even; 0: the even number >= max(2 d + 2, 16)
  int steps = 2000;      // kept per walker, after the warm-up (4 parameters: tau about 45 steps, 50 tau asked)
  int warmup = 500;      // discarded per walker
  double stretch = 2.0;  // Goodman and Weare's a > 1
  std::uint64_t seed = 1;
  // InputError naming the option, its value and the constraint.
  void validate(int dimension) const;
  int walkers_for(int dimension) const;
};

struct SamplerResult {
  // Every kept draw: chains x steps x walkers rows (chain-major, then step, then walker), one column per parameter.
  Eigen::MatrixXd draws;
  std::vector<double> log_density;  // ln p of each kept draw
  Eigen::VectorXd mean, sd;
  Eigen::MatrixXd covariance;
  Eigen::VectorXd rhat, tau, effective_samples;  // per parameter
  double acceptance = 0;                         // over every proposal after the warm-up
  long evaluations = 0;                          // calls of ln p, the starts' and the warm-up's included
  int chains = 0, walkers = 0, steps = 0;
  bool converged = false;
  std::string status;  // "converged", or "not converged: ..." naming the parameter and the check
  // The q-quantile of parameter k over the kept draws (linear interpolation between order statistics).
  double quantile(int k, double q) const;
};

// One log density per chain, for chains run in parallel: each call returns a density of its own (a model's objective
// holds its workspace, so two threads do not share one).
using DensityFactory = std::function<LogDensity()>;

// Samples `log_density` over dimension center.size(): each walker starts at center + scale .* g (g standard normal),
// redrawn while ln p there is not finite. InputError for bad options, a center or scale of the wrong size or not
// finite, or a walker that finds no finite ln p in kMaxStartTries draws. `names` name the parameters in the status
// (x1, x2, ... when empty).
SamplerResult sample_ensemble(const LogDensity& log_density, const Eigen::VectorXd& center,
                              const Eigen::VectorXd& scale, const SamplerOptions& options,
                              const std::vector<std::string>& names = {});
// The same with each chain's density from `factory`, the chains run on up to `threads` threads: the draws do not
// depend on the thread count (each chain has its own stream and density).
SamplerResult sample_ensemble(const DensityFactory& factory, const Eigen::VectorXd& center,
                              const Eigen::VectorXd& scale, const SamplerOptions& options,
                              const std::vector<std::string>& names, int threads);

// The standard normal quantile Phi^-1(p), p in (0, 1): Acklam's rational approximation refined by one Halley step.
double normal_quantile(double p);

// The diagnostics alone, for draws already made; series[c][w] is walker w's kept values of one parameter in chain c
// (every walker of every chain the same length). Exposed for the tests.
double split_rhat(const std::vector<std::vector<std::vector<double>>>& series);
double autocorrelation_time(const std::vector<std::vector<double>>& walkers);

}  // namespace beamid::fit
