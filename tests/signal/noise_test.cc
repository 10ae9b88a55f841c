// The synthetic-data noise: portable (the engine's sequence is fixed by the C++ standard, the transform is ours),
// standard normal in distribution, and scaled to the requested fraction of the clean RMS.
#include "signal/noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace beamid::signal {
namespace {

TEST(Noise, EngineIsTheStandardsMersenneTwister) {
  // [rand.predef]: the 10000th output of a default-constructed std::mt19937_64 is 9981545732273789042. Our
  // deviates depend only on this sequence and on std::log/cos/sin, so they are the same with any standard library.
  std::mt19937_64 engine;
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ULL);
}

TEST(Noise, DeviatesAreStandardNormalAndReproducible) {
  const std::size_t n = 200000;
  const auto g = gaussian_deviates(7, n);
  ASSERT_EQ(g.size(), n);
  EXPECT_EQ(g, gaussian_deviates(7, n));
  EXPECT_NE(g[0], gaussian_deviates(8, 1)[0]);
  double mean = 0, var = 0, fourth = 0;
  for (double x : g) mean += x;
  mean /= n;
  for (double x : g) var += (x - mean) * (x - mean), fourth += std::pow(x - mean, 4);
  var /= n - 1;
  fourth /= n;
  // Sampling errors: sd(mean) = 1/sqrt(n) = 2.2e-3, sd(var) = sqrt(2/n) = 3.2e-3, sd(4th moment) = sqrt(96/n) = 0.022;
  // bounds at about 5 standard deviations, so a correct generator fails with probability < 1e-6.
  EXPECT_NEAR(mean, 0, 0.011);
  EXPECT_NEAR(var, 1, 0.016);
  EXPECT_NEAR(fourth, 3, 0.11);
  // Tail share beyond 2: 4.55 % for a normal (sd of the share 4.7e-4).
  const double tail =
      static_cast<double>(std::count_if(g.begin(), g.end(), [](double x) { return std::abs(x) > 2; })) / n;
  EXPECT_NEAR(tail, 0.0455, 0.0025);
  // Prefixes agree: the first k deviates do not depend on how many are drawn.
  const auto head = gaussian_deviates(7, 11);
  for (std::size_t i = 0; i < head.size(); ++i) EXPECT_EQ(head[i], g[i]);
}

TEST(Noise, LevelIsAFractionOfTheCleanRms) {
  std::vector<double> clean(50000);
  for (std::size_t i = 0; i < clean.size(); ++i) clean[i] = 3 * std::sin(0.01 * static_cast<double>(i));
  EXPECT_EQ(add_noise(clean, 0, 1), clean);  // level 0: the clean record itself
  const auto z = add_noise(clean, 0.05, 3);
  std::vector<double> e(clean.size());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = z[i] - clean[i];
  // rms(clean) = 3/sqrt(2); the noise RMS estimates 0.05 of it with relative sd 1/sqrt(2n) = 3e-3.
  EXPECT_NEAR(rms(e) / rms(clean), 0.05, 0.05 * 0.015);
}

}  // namespace
}  // namespace beamid::signal
