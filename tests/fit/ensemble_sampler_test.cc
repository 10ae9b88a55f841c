// The ensemble sampler against posteriors known in closed form, and its diagnostics on runs that must fail them.
#include "fit/ensemble_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "signal/noise.h"

namespace beamid::fit {
namespace {

TEST(NormalQuantile, InvertsTheNormalDistribution) {
  // Phi(x) = erfc(-x / sqrt 2) / 2; the refined quantile is within a few ulps of the inverse (1e-14 relative in p,
  // far into both tails, where Acklam's approximation alone is good to 1.2e-9).
  for (const double p : {1e-300, 1e-12, 1e-4, 0.02425, 0.1, 0.3, 0.5, 0.7, 0.975, 1 - 1e-4, 1 - 1e-12}) {
    const double x = normal_quantile(p);
    EXPECT_NEAR(0.5 * std::erfc(-x / std::numbers::sqrt2) / p, 1.0, 1e-13) << p;
  }
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-14);
  EXPECT_EQ(normal_quantile(0.5), 0.0);
}

// Chains of independent standard normal draws (4 chains x 8 walkers x 500 steps), each chain's mean moved by `shift`.
std::vector<std::vector<std::vector<double>>> normal_chains(double shift, std::uint64_t seed) {
  const std::vector<double> g = signal::gaussian_deviates(seed, 4 * 8 * 500);
  std::vector<std::vector<std::vector<double>>> series(4, std::vector<std::vector<double>>(8));
  std::size_t at = 0;
  for (int c = 0; c < 4; ++c)
    for (auto& walker : series[static_cast<std::size_t>(c)])
      for (int s = 0; s < 500; ++s) walker.push_back(g[at++] + shift * c);
  return series;
}

TEST(SplitRhat, IsOneForAgreeingChainsAndAboveTheThresholdForChainsThatDisagree) {
  // 16,000 independent draws: R-hat - 1 is of order 1 / n, far below 0.01. R-hat is about sqrt(1 + var(chain
  // means) / W): chains whose means step by 0.3 sd (var 0.1 W over the 8 split halves) give about 1.05, and must be
  // flagged; steps of 0.1 sd give 1.006, which the 1.01 threshold lets pass though a chain's mean has a standard error
  // of 0.016: R-hat measures the chains' disagreement against their spread, not its significance.
  EXPECT_LT(split_rhat(normal_chains(0.0, 7)), 1.002);
  EXPECT_GT(split_rhat(normal_chains(0.3, 7)), 1.03);
  EXPECT_LT(split_rhat(normal_chains(0.1, 7)), kMaxRhat);
  // The folded R-hat sees chains of one mean and different spreads, which the bulk's misses.
  auto spread = normal_chains(0.0, 8);
  for (auto& walker : spread[0])
    for (double& v : walker) v *= 1.5;
  EXPECT_GT(split_rhat(spread), kMaxRhat);
}

TEST(AutocorrelationTime, IsOneForIndependentDrawsAndTheKnownValueForAnAr1Series) {
  // For AR(1), x_t = phi x_{t-1} + e_t, rho(t) = phi^t and tau = (1 + phi) / (1 - phi) = 19 at phi = 0.9. The
  // estimator's window truncates the sum at M >= 5 tau, where phi^M < 1e-40; its error is statistical, about
  // tau sqrt(2 (2M + 1) / N) (Sokal 1997), 8 % here with 32 walkers of 20,000 steps: 15 % asked.
  const auto independent = normal_chains(0.0, 9)[0];
  EXPECT_NEAR(autocorrelation_time(independent), 1.0, 0.15);
  const std::vector<double> g = signal::gaussian_deviates(10, 32 * 20001);
  std::vector<std::vector<double>> walkers(32);
  std::size_t at = 0;
  for (auto& w : walkers) {
    double x = g[at++] / std::sqrt(1 - 0.81);  // started in the stationary distribution
    for (int s = 0; s < 20000; ++s) w.push_back(x = 0.9 * x + g[at++]);
  }
  EXPECT_NEAR(autocorrelation_time(walkers) / 19.0, 1.0, 0.15);
}

// A linear-Gaussian inverse problem: y = A theta + e, e ~ N(0, sigma^2 I), flat prior. The posterior is Gaussian with
// mean (A'A)^-1 A'y and covariance sigma^2 (A'A)^-1, known exactly. A is chosen ill-conditioned and badly scaled (the
// columns' scales 1 to 1e4, two of them 0.99 correlated), as EI, rho and the damping are.
struct LinearGaussian {
  Eigen::MatrixXd a;
  Eigen::VectorXd y, mean;
  Eigen::MatrixXd covariance;
  double sigma = 0.1;
  LinearGaussian() {
    const int m = 50;
    a.resize(m, 3), y.resize(m);
    const std::vector<double> g = signal::gaussian_deviates(11, m);
    for (int i = 0; i < m; ++i) {
      const double t = static_cast<double>(i) / (m - 1);
      a(i, 0) = 1.0, a(i, 1) = 1e-4 * (1.0 + 0.05 * t), a(i, 2) = 100 * t * t;
      y(i) = 2 + 1e-4 * 3e4 * (1 + 0.05 * t) + 100 * 0.5 * t * t + sigma * g[static_cast<std::size_t>(i)];
    }
    const Eigen::MatrixXd normal = a.transpose() * a;
    covariance = sigma * sigma * normal.inverse();
    mean = normal.ldlt().solve(a.transpose() * y);
  }
  double log_density(const Eigen::VectorXd& theta) const {
    return -(y - a * theta).squaredNorm() / (2 * sigma * sigma);
  }
};

TEST(EnsembleSampler, SamplesALinearGaussianPosteriorItsMeanCovarianceAndQuantiles) {
  const LinearGaussian problem;
  SamplerOptions o;
  o.steps = 2000, o.warmup = 500, o.seed = 3;
  // Started far from the mean (ten posterior sds off, with a scale a tenth of the posterior's): the warm-up must
  // bring the walkers there.
  const Eigen::VectorXd sd = problem.covariance.diagonal().cwiseSqrt();
  const SamplerResult r = sample_ensemble([&](const Eigen::VectorXd& x) { return problem.log_density(x); },
                                          problem.mean + 10 * sd, sd / 10, o, {"a", "b", "c"});
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(r.draws.rows(), 4 * 16 * 2000);
  // The stretch move's acceptance on a Gaussian in 3 dimensions is about 0.5 (Goodman and Weare 2010: 0.3-0.6).
  EXPECT_GT(r.acceptance, 0.3);
  EXPECT_LT(r.acceptance, 0.7);
  for (int k = 0; k < 3; ++k) {
    // The mean within 4.5 Monte-Carlo standard errors sd / sqrt(ESS); the sd within 4.5 of its own, sd / sqrt(2 ESS)
    // (the 4.5-sigma band is passed by chance with probability 1 - 7e-6 for each of the six checks).
    const double mcse = sd(k) / std::sqrt(r.effective_samples(k));
    EXPECT_NEAR(r.mean(k), problem.mean(k), 4.5 * mcse) << k;
    EXPECT_NEAR(r.sd(k) / sd(k), 1.0, 4.5 / std::sqrt(2 * r.effective_samples(k))) << k;
    // The 2.5 % and 97.5 % quantiles at mean -+ 1.96 sd: a tail quantile's standard error is about
    // sqrt(q (1 - q)) / (phi(z) sqrt(ESS)) = 2.7 sd / sqrt(ESS); 4.5 of them asked.
    const double band = 4.5 * 2.7 * sd(k) / std::sqrt(r.effective_samples(k));
    EXPECT_NEAR(r.quantile(k, 0.025), problem.mean(k) - 1.959963984540054 * sd(k), band) << k;
    EXPECT_NEAR(r.quantile(k, 0.975), problem.mean(k) + 1.959963984540054 * sd(k), band) << k;
  }
  // The correlation of the two nearly collinear columns' coefficients (about -0.99), to 0.01.
  const double exact = problem.covariance(0, 1) / (sd(0) * sd(1));
  EXPECT_LT(exact, -0.9);
  EXPECT_NEAR(r.covariance(0, 1) / (r.sd(0) * r.sd(1)), exact, 0.01);
}

TEST(EnsembleSampler, ARunTooShortOrStuckInTwoModesSaysItHasNotConverged) {
  const LinearGaussian problem;
  const Eigen::VectorXd sd = problem.covariance.diagonal().cwiseSqrt();
  const auto density = [&](const Eigen::VectorXd& x) { return problem.log_density(x); };
  SamplerOptions o;
  o.steps = 40, o.warmup = 0, o.seed = 4;  // 40 steps from a start 10 sds off: nowhere near the posterior
  const SamplerResult short_run = sample_ensemble(density, problem.mean + 10 * sd, sd / 10, o, {"a", "b", "c"});
  EXPECT_FALSE(short_run.converged);
  EXPECT_EQ(short_run.status.rfind("not converged: ", 0), 0u) << short_run.status;
  // Two modes 40 sds apart, the walkers started spread over both: a stretch move (z in [1/2, 2]) lands near its own
  // walker or in the valley between, never in the other mode, so each chain keeps the share of walkers its start put
  // in each mode; the chains' shares differ, and R-hat says so (1.09 and 1.14 with this seed).
  const auto two_modes = [](const Eigen::VectorXd& x) {
    const double a = -0.5 * (x.array() - 20).square().sum(), b = -0.5 * (x.array() + 20).square().sum();
    return std::max(a, b) + std::log1p(std::exp(-std::abs(a - b)));
  };
  o.steps = 1000, o.warmup = 200, o.seed = 5;
  const SamplerResult stuck = sample_ensemble(two_modes, Eigen::Vector2d(0, 0), Eigen::Vector2d(20, 20), o);
  EXPECT_FALSE(stuck.converged);
  EXPECT_NE(stuck.status.find("R-hat"), std::string::npos) << stuck.status;
}

TEST(EnsembleSampler, AProposalOutsideTheSupportIsRefusedAndASeedGivesTheSameDraws) {
  // A uniform prior on the box [0, 1]^2 (ln p = 0 inside, -inf outside): no draw leaves it, and its mean is the
  // centre, 0.5, its sd 1 / sqrt 12.
  const auto box = [](const Eigen::VectorXd& x) {
    return (x.array() >= 0).all() && (x.array() <= 1).all() ? 0.0 : -std::numeric_limits<double>::infinity();
  };
  SamplerOptions o;
  o.steps = 2000, o.seed = 6;
  const SamplerResult r = sample_ensemble(box, Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.3, 0.3), o);
  EXPECT_GE(r.draws.minCoeff(), 0.0);
  EXPECT_LE(r.draws.maxCoeff(), 1.0);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(r.mean(k), 0.5, 4.5 * r.sd(k) / std::sqrt(r.effective_samples(k)));
    EXPECT_NEAR(r.sd(k) * std::sqrt(12.0), 1.0, 0.05);  // sd's relative error 1 / sqrt(2 ESS) < 0.036
  }
  const SamplerResult again = sample_ensemble(box, Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.3, 0.3), o);
  EXPECT_EQ(again.draws, r.draws);
  // The chains on two threads, each with a density of its own: the same draws, bit for bit.
  const SamplerResult threaded = sample_ensemble([&box]() { return LogDensity(box); }, Eigen::Vector2d(0.5, 0.5),
                                                 Eigen::Vector2d(0.3, 0.3), o, {}, 2);
  EXPECT_EQ(threaded.draws, r.draws);
  // A start region where the density is nowhere finite, and bad options, are refused in one line.
  EXPECT_THROW(sample_ensemble(box, Eigen::Vector2d(5, 5), Eigen::Vector2d(1e-3, 1e-3), o), InputError);
  o.chains = 1;
  try {
    sample_ensemble(box, Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.3, 0.3), o);
    ADD_FAILURE() << "one chain was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("posterior chains = 1: must be in 2..64"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace beamid::fit
