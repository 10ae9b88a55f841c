#include "study/analysis/statistics.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

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

double Stats::mcse() const { return count > 1 ? std / std::sqrt(static_cast<double>(count)) : kNaN; }

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

double mcnemar_exact_p(int b, int c) {
  const int n = b + c, k = std::min(b, c);
  if (n <= 0) return 1;
  // P(X <= k) for X ~ Binomial(n, 1/2), each term exp(ln C(n, i) - n ln 2) (lgamma: no overflow for large n).
  double tail = 0;
  for (int i = 0; i <= k; ++i)
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) - n * std::log(2.0));
  return std::min(1.0, 2 * tail);
}

LogisticFit firth_logistic(const std::vector<double>& x, const std::vector<int>& y) {
  LogisticFit fit;
  const std::size_t n = x.size();
  if (n == 0 || y.size() != n) return fit;
  Eigen::Vector2d beta = Eigen::Vector2d::Zero();
  for (int iteration = 0; iteration < 200; ++iteration) {
    Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
    std::vector<double> p(n), w(n);
    for (std::size_t i = 0; i < n; ++i) {
      p[i] = 1 / (1 + std::exp(-(beta(0) + beta(1) * x[i])));
      w[i] = p[i] * (1 - p[i]);
      const Eigen::Vector2d xi(1, x[i]);
      information += w[i] * xi * xi.transpose();
    }
    const Eigen::LDLT<Eigen::Matrix2d> solver(information);
    if (solver.info() != Eigen::Success || !(information.determinant() > 0)) return fit;
    const Eigen::Matrix2d inverse = solver.solve(Eigen::Matrix2d::Identity());
    Eigen::Vector2d score = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d xi(1, x[i]);
      const double h = w[i] * xi.dot(inverse * xi);  // the hat value of outcome i
      score += (y[i] - p[i] + h * (0.5 - p[i])) * xi;
    }
    Eigen::Vector2d step = inverse * score;
    // Steps of at most 5 in either coefficient (a half-converged fit far from the data's offsets otherwise
    // overshoots into p = 0 or 1, where the information vanishes).
    const double largest = step.cwiseAbs().maxCoeff();
    if (largest > 5) step *= 5 / largest;
    beta += step;
    if (!std::isfinite(beta(0)) || !std::isfinite(beta(1))) return fit;
    if (largest < 1e-10) {
      fit.converged = true;
      break;
    }
  }
  fit.intercept = beta(0);
  fit.slope = beta(1);
  return fit;
}

std::vector<std::vector<int>> bootstrap_resamples(std::uint64_t seed, int n, int resamples) {
  std::mt19937_64 engine(seed);
  std::vector<std::vector<int>> out(static_cast<std::size_t>(std::max(0, resamples)));
  for (auto& sample : out) {
    sample.resize(static_cast<std::size_t>(std::max(0, n)));
    for (int& index : sample)
      index = std::min(n - 1, static_cast<int>(static_cast<double>(engine() >> 11) * 0x1.0p-53 * n));
  }
  return out;
}

double quantile(std::vector<double> values, double q) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }), values.end());
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double h = (static_cast<double>(values.size()) - 1) * std::clamp(q, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(values.size() - 1, lo + 1);
  if (lo == hi || values[lo] == values[hi]) return values[lo];
  if (!std::isfinite(values[lo]) || !std::isfinite(values[hi])) return h - lo < 0.5 ? values[lo] : values[hi];
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

}  // namespace beamid::study
