#include "study/analysis/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace beamid::study {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::pair<double, double> wilson_interval(int successes, int cases) {
  if (cases <= 0) return {kNaN, kNaN};
  const double z = 1.96, n = cases, p = successes / n, z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

std::string count_with_interval(int successes, int cases) {
  const auto [low, high] = wilson_interval(successes, cases);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%d/%d (95 %% interval %.3g-%.3g %%)", successes, cases, 100 * low, 100 * high);
  return buf;
}

Stats stats(const std::vector<double>& values) {
  Stats s;
  s.mean = s.std = s.rmse = s.median = kNaN;
  std::vector<double> v;
  for (double x : values)
    if (std::isfinite(x)) v.push_back(x);
  s.count = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0, sq = 0;
  for (double x : v) sum += x, sq += x * x;
  s.mean = sum / s.count;
  s.rmse = std::sqrt(sq / s.count);
  if (s.count > 1) {
    double d = 0;
    for (double x : v) d += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(d / (s.count - 1));
  }
  s.median = median(v);
  return s;
}

}  // namespace beamid::study
