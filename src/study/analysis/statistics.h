// The statistics every study table states: medians, moments, and a success rate with its Wilson interval. Pure
// functions of numbers (no study types), so that metrics, start-distance curves and claims share one definition.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace beamid::study {

// Median of the finite values (NaN when there is none).
double median(std::vector<double> values);

struct Stats {
  int count = 0;                   // finite values
  double mean, std, rmse, median;  // NaN when undefined (std needs two values)
  // The Monte-Carlo standard error of the mean, std / sqrt(count) (comparison.md section 4; NaN under two values).
  double mcse() const;
};
Stats stats(const std::vector<double>& values);

// The 95 % Wilson score interval of a success rate k/n (../shared/docs/comparison.md section 4):
//   centre = (p + z^2/(2n)) / (1 + z^2/n),  half-width = z sqrt(p(1-p)/n + z^2/(4n^2)) / (1 + z^2/n),  z = 1.96,
// which, unlike p +- z sqrt(p(1-p)/n), is not empty at 0/n or n/n. {NaN, NaN} for n = 0.
std::pair<double, double> wilson_interval(int successes, int cases);
// "0/132 (95 % interval 0-2.83 %)", a count with its interval, as the report states every rate.
std::string count_with_interval(int successes, int cases);

// The exact two-sided McNemar test of paired successes (comparison.md section 4: methods fitted on the same records
// from the same starts): of the n = b + c discordant pairs (b: the first method alone succeeds, c: the second alone),
// under "no difference" each is the first's with probability 1/2, so p = min(1, 2 P(Binomial(n, 1/2) <= min(b, c))).
// 1 when there is no discordant pair.
double mcnemar_exact_p(int b, int c);

// Logistic regression of binary outcomes y_i on one covariate x_i, P(y = 1) = 1 / (1 + exp(-(a + b x))), by Firth's
// penalised likelihood (Firth 1993, Biometrika 80:27; Heinze and Schemper 2002 for separation): the score
// U = sum_i (y_i - p_i + h_i (1/2 - p_i)) (1, x_i), h_i the hat values of the weighted design, solved by Newton steps
// on the information X'WX. Unlike maximum likelihood, its estimates stay finite when the outcomes are separated
// (every start below some offset succeeds and every one above fails), which the reach curves of few records often
// are. converged false when 200 steps do not bring the step below 1e-10 or the outcomes are all of one kind.
struct LogisticFit {
  double intercept = 0, slope = 0;
  bool converged = false;
};
LogisticFit firth_logistic(const std::vector<double>& x, const std::vector<int>& y);

// `resamples` bootstrap resamples of n units, each n indices drawn uniformly with replacement from 0..n-1: the
// engine is std::mt19937_64 (its sequence is fixed by the standard) and an index is floor(u n) with
// u = (x >> 11) 2^-53, so that the same seed gives the same resamples with any standard library.
std::vector<std::vector<int>> bootstrap_resamples(std::uint64_t seed, int n, int resamples);

// The q-quantile (0 <= q <= 1) of the values by linear interpolation between order statistics (type 7 of Hyndman
// and Fan 1996, R's default); infinite values sort at their ends. NaN when there is none.
double quantile(std::vector<double> values, double q);

}  // namespace beamid::study
