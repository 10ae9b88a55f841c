#include "signal/noise.h"

#include <cmath>
#include <numbers>
#include <random>

namespace beamid::signal {

std::vector<double> gaussian_deviates(std::uint64_t seed, std::size_t count) {
  std::mt19937_64 engine(core::mix64(seed));
  // ((x >> 11) + 0.5) 2^-53 lies strictly inside (0, 1), so ln u1 is finite.
  const auto uniform = [&engine] { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; };
  std::vector<double> g;
  g.reserve(count + 1);
  while (g.size() < count) {
    const double u1 = uniform(), u2 = uniform();
    const double r = std::sqrt(-2 * std::log(u1));
    g.push_back(r * std::cos(2 * std::numbers::pi * u2));
    g.push_back(r * std::sin(2 * std::numbers::pi * u2));
  }
  g.resize(count);
  return g;
}

double rms(const std::vector<double>& signal) {
  if (signal.empty()) return 0;
  double sum = 0;
  for (double v : signal) sum += v * v;
  return std::sqrt(sum / static_cast<double>(signal.size()));
}

std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed) {
  if (level == 0) return clean;
  const double sigma = level * rms(clean);
  const std::vector<double> g = gaussian_deviates(seed, clean.size());
  std::vector<double> z(clean.size());
  for (std::size_t i = 0; i < clean.size(); ++i) z[i] = clean[i] + sigma * g[i];
  return z;
}

}  // namespace beamid::signal
