// The statistics every study table states: medians, moments, and a success rate with its Wilson interval. Pure
// functions of numbers (no study types), so that metrics, start-distance curves and claims share one definition.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace beamid::study {

// Median of the finite values (NaN when there is none).
double median(std::vector<double> values);

struct Stats {
  int count = 0;                   // finite values
  double mean, std, rmse, median;  // NaN when undefined (std needs two values)
};
Stats stats(const std::vector<double>& values);

// The 95 % Wilson score interval of a success rate k/n (../shared/docs/comparison.md section 4):
//   centre = (p + z^2/(2n)) / (1 + z^2/n),  half-width = z sqrt(p(1-p)/n + z^2/(4n^2)) / (1 + z^2/n),  z = 1.96,
// which, unlike p +- z sqrt(p(1-p)/n), is not empty at 0/n or n/n. {NaN, NaN} for n = 0.
std::pair<double, double> wilson_interval(int successes, int cases);
// "0/132 (95 % interval 0-2.83 %)", a count with its interval, as the report states every rate.
std::string count_with_interval(int successes, int cases);

}  // namespace beamid::study
