// The statistics behind the design's paired comparisons and reach curves (issue 35): the exact McNemar test against
// hand-computed binomial tails, Firth's logistic regression against its defining score equation and on separated
// outcomes, the bootstrap's determinism and uniformity, and the type-7 quantile.
#include "study/analysis/statistics.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace beamid::study {
namespace {

TEST(Statistics, McNemarIsTheTwoSidedBinomialTailOfTheDiscordantPairs) {
  // b = 1, c = 9: n = 10, P(X <= 1) = (1 + 10) / 1024, p = 22 / 1024 (hand-computed).
  EXPECT_NEAR(mcnemar_exact_p(1, 9), 22.0 / 1024, 1e-14);
  EXPECT_NEAR(mcnemar_exact_p(9, 1), 22.0 / 1024, 1e-14);
  // b = 0, c = 5: 2 / 32.
  EXPECT_NEAR(mcnemar_exact_p(0, 5), 2.0 / 32, 1e-14);
  // Balanced or no discordant pair: no evidence, p = 1 (the tail is clipped at 1).
  EXPECT_EQ(mcnemar_exact_p(4, 4), 1.0);
  EXPECT_EQ(mcnemar_exact_p(0, 0), 1.0);
  // Large n stays finite (lgamma): 300 vs 400 discordant pairs, |z| = 100 / sqrt(700) = 3.78, p about 1.7e-4.
  const double p = mcnemar_exact_p(300, 400);
  EXPECT_GT(p, 1e-4);
  EXPECT_LT(p, 3e-4);
}

// The score Firth's estimate solves, evaluated at (a, b): sum_i (y_i - p_i + h_i (1/2 - p_i)) (1, x_i).
Eigen::Vector2d firth_score(const std::vector<double>& x, const std::vector<int>& y, double a, double b) {
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  std::vector<double> p(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    p[i] = 1 / (1 + std::exp(-(a + b * x[i])));
    const Eigen::Vector2d xi(1, x[i]);
    information += p[i] * (1 - p[i]) * xi * xi.transpose();
  }
  const Eigen::Matrix2d inverse = information.inverse();
  Eigen::Vector2d score = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Eigen::Vector2d xi(1, x[i]);
    const double h = p[i] * (1 - p[i]) * xi.dot(inverse * xi);
    score += (y[i] - p[i] + h * (0.5 - p[i])) * xi;
  }
  return score;
}

TEST(Statistics, FirthLogisticSolvesItsScoreEquationAndRecoversACurve) {
  // 2,000 outcomes from P = 1 / (1 + exp(-(2 - 3 x))) at x uniform in [-2, 3]: the estimates within 4 standard
  // errors (about 0.1 for a and 0.12 for b at this size, from the information matrix), and the score at the estimate
  // zero to 1e-8 (the equation it solves).
  std::mt19937_64 engine(7);
  std::vector<double> x;
  std::vector<int> y;
  for (int i = 0; i < 2000; ++i) {
    const double xi = -2 + 5 * static_cast<double>(engine() >> 11) * 0x1.0p-53;
    const double u = static_cast<double>(engine() >> 11) * 0x1.0p-53;
    x.push_back(xi);
    y.push_back(u < 1 / (1 + std::exp(-(2 - 3 * xi))) ? 1 : 0);
  }
  const LogisticFit fit = firth_logistic(x, y);
  ASSERT_TRUE(fit.converged);
  EXPECT_NEAR(fit.intercept, 2, 0.4);
  EXPECT_NEAR(fit.slope, -3, 0.5);
  EXPECT_LT(firth_score(x, y, fit.intercept, fit.slope).norm(), 1e-8);
}

TEST(Statistics, FirthLogisticStaysFiniteOnSeparatedOutcomes) {
  // Every outcome at x <= 0 a success, every one at x >= 1 a failure: maximum likelihood has no finite estimate
  // (the slope runs to -infinity); Firth's does, with its crossing -a/b between the two groups.
  const std::vector<double> x = {-1, -1, 0, 0, 1, 1, 2, 2};
  const std::vector<int> y = {1, 1, 1, 1, 0, 0, 0, 0};
  const LogisticFit fit = firth_logistic(x, y);
  ASSERT_TRUE(fit.converged);
  EXPECT_LT(fit.slope, 0);
  EXPECT_TRUE(std::isfinite(fit.slope));
  EXPECT_GT(-fit.intercept / fit.slope, 0);
  EXPECT_LT(-fit.intercept / fit.slope, 1);
  // By symmetry of the design about x = 1/2, the crossing is at 1/2 (to the solver's tolerance).
  EXPECT_NEAR(-fit.intercept / fit.slope, 0.5, 1e-8);
  EXPECT_LT(firth_score(x, y, fit.intercept, fit.slope).norm(), 1e-8);
}

TEST(Statistics, BootstrapResamplesAreReproducibleAndUniform) {
  const auto a = bootstrap_resamples(11, 20, 500), b = bootstrap_resamples(11, 20, 500);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, bootstrap_resamples(12, 20, 500));
  // Every index is drawn 500 times in expectation over the 10,000 draws; a binomial sd of sqrt(10000 x 0.05 x 0.95)
  // = 21.8, so 5 sd is 109.
  std::vector<int> counts(20, 0);
  for (const auto& sample : a) {
    ASSERT_EQ(sample.size(), 20u);
    for (int index : sample) {
      ASSERT_GE(index, 0);
      ASSERT_LT(index, 20);
      ++counts[static_cast<std::size_t>(index)];
    }
  }
  for (int c : counts) EXPECT_NEAR(c, 500, 109);
}

TEST(Statistics, QuantileInterpolatesOrderStatisticsAndKeepsInfinitiesAtTheEnds) {
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);  // type 7: 1 + 0.5 x 3 = position 2.5
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0), 1);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 1), 4);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(quantile({-inf, 1, 2, 3, inf}, 0), -inf);
  EXPECT_EQ(quantile({-inf, 1, 2, 3, inf}, 1), inf);
  EXPECT_DOUBLE_EQ(quantile({-inf, 1, 2, 3, inf}, 0.5), 2);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

}  // namespace
}  // namespace beamid::study
