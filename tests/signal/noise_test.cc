// The synthetic-data noise: portable (the engine's sequence is fixed by the C++ standard, the transform is ours),
// standard normal in distribution, and scaled to the requested fraction of the clean RMS.
#include "signal/noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>

#include "core/errors.h"
#include "signal/spectrum.h"

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

// Coloured noise (issue 33 item 6): white is add_noise itself; an AR process has unit stationary variance and its
// autocorrelation; power-law noise has its spectral slope; every model is reproducible per seed; bad names are named.
double autocorrelation(const std::vector<double>& e, std::size_t lag) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < e.size(); ++i) den += e[i] * e[i];
  for (std::size_t i = lag; i < e.size(); ++i) num += e[i] * e[i - lag];
  return num / den;
}

TEST(Noise, WhiteModelIsAddNoiseItself) {
  std::vector<double> clean(1000);
  for (std::size_t i = 0; i < clean.size(); ++i) clean[i] = std::cos(0.03 * static_cast<double>(i));
  EXPECT_EQ(add_noise(clean, 0.01, 5, parse_noise_model("white")), add_noise(clean, 0.01, 5));
}

TEST(Noise, AnArProcessHasUnitVarianceAndItsAutocorrelation) {
  constexpr std::size_t n = 1 << 16;
  // AR(1), a = 0.9: rho_1 = 0.9, sampling sd (1 - a^2) / sqrt(n) = 7e-4; the sample variance's relative sd is
  // sqrt(2 (1 + a^2) / ((1 - a^2) n)) = 1.7e-2. Tolerances about 6 sd.
  const auto e = model_deviates(parse_noise_model("ar:0.9"), 3, n);
  EXPECT_NEAR(rms(e), 1.0, 0.06);
  EXPECT_NEAR(autocorrelation(e, 1), 0.9, 0.005);
  // AR(2), a = (0.5, -0.3): rho_1 = a1 / (1 - a2) = 0.3846, rho_2 = a1 rho_1 + a2 = -0.1077 (Yule-Walker).
  const auto f = model_deviates(parse_noise_model("ar:0.5,-0.3"), 4, n);
  EXPECT_NEAR(rms(f), 1.0, 0.03);
  EXPECT_NEAR(autocorrelation(f, 1), 0.5 / 1.3, 0.02);
  EXPECT_NEAR(autocorrelation(f, 2), 0.5 * 0.5 / 1.3 - 0.3, 0.02);
  // Started stationary: the first samples are as large as the rest (no transient from zero), over 2000 short draws.
  double first = 0;
  for (std::uint64_t seed = 0; seed < 2000; ++seed)
    first += std::pow(model_deviates(parse_noise_model("ar:0.9"), seed, 1)[0], 2);
  EXPECT_NEAR(first / 2000, 1.0, 0.2);  // the mean of 2000 chi-square(1) values: sd 0.03
}

TEST(Noise, PowerLawNoiseHasItsSlope) {
  // alpha = 1 (pink): the mean periodogram over 32 draws of 4096 samples falls as 1/f; a least-squares slope of
  // log P against log k over bins 4..1024, each point the mean of 32 exponential variates (relative sd 18 %), has sd
  // about 0.01.
  constexpr int n = 4096;
  std::vector<double> mean_power(n / 2 + 1, 0.0);
  double variance = 0;
  Dft dft(n, 1.0);
  for (std::uint64_t seed = 1; seed <= 32; ++seed) {
    const auto e = model_deviates(parse_noise_model("power:1"), seed, n);
    variance += rms(e) * rms(e) / 32;
    const Spectrum s = dft.transform(e);
    for (int k = 4; k <= 1024; ++k)
      mean_power[static_cast<std::size_t>(k)] += std::norm(s.half[static_cast<std::size_t>(k)]) / 32;
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
  for (int k = 4; k <= 1024; ++k) {
    const double x = std::log(k), y = std::log(mean_power[static_cast<std::size_t>(k)]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
  }
  EXPECT_NEAR((m * sxy - sx * sy) / (m * sxx - sx * sx), -1.0, 0.05);
  // Unit variance as a process: the mean over 32 draws (pink noise's variance sits in its lowest bins, so one draw's
  // scatters by about 25 %).
  EXPECT_NEAR(variance, 1.0, 0.2);
}

TEST(Noise, ModelsAreReproducibleAndBadOnesNamed) {
  for (const std::string name : {"ar:0.9", "power:1.5"}) {
    const NoiseModel model = parse_noise_model(name);
    EXPECT_EQ(model.text(), name);
    EXPECT_EQ(model_deviates(model, 9, 777), model_deviates(model, 9, 777)) << name;
    EXPECT_NE(model_deviates(model, 9, 777), model_deviates(model, 10, 777)) << name;
  }
  const auto message = [](const std::string& text) {
    try {
      parse_noise_model(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("ar:1.2").find("noise model 'ar:1.2': not stationary"), std::string::npos) << message("ar:1.2");
  EXPECT_NE(message("ar:0.5,0.5").find("not stationary"), std::string::npos);  // a unit root: a random walk
  EXPECT_NE(message("ar:").find("at least one coefficient"), std::string::npos);
  EXPECT_NE(message("ar:0.5,").find("no empty one"), std::string::npos);
  EXPECT_NE(message("ar:x").find("'x' is not a finite number"), std::string::npos);
  EXPECT_NE(message("power:5").find("alpha must be in [0, 4]"), std::string::npos);
  EXPECT_NE(message("pink").find("must be white, ar:"), std::string::npos);
}

}  // namespace
}  // namespace beamid::signal

namespace beamid::signal {
namespace {

// whiten() against the dense definition X^T R^-1 X, R the unit-variance noise's correlation matrix: for AR(p) the
// Toeplitz matrix of its autocorrelations (from its impulse response), for power-law noise the circulant matrix of its
// bin variances (the offset bin, noise-free, left out: the pseudo-inverse). Round-off tolerances.
Eigen::MatrixXd sensitivities_like(Eigen::Index n) {
  Eigen::MatrixXd x(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n);
    x(i, 0) = std::exp(-2 * t) * std::sin(40 * t);
    x(i, 1) = t * std::cos(25 * t);
    x(i, 2) = 1 + 0.3 * std::sin(7 * t);  // with an offset, which power-law noise leaves out
  }
  return x;
}

TEST(Noise, WhiteningMatchesTheNoisesCorrelationMatrix) {
  constexpr Eigen::Index n = 96;
  const Eigen::MatrixXd x = sensitivities_like(n);
  EXPECT_EQ(whiten(parse_noise_model("white"), x), x);
  for (const std::string name : {"ar:0.9", "ar:0.5,-0.3", "ar:1.2,-0.5,0.1"}) {
    const NoiseModel m = parse_noise_model(name);
    // rho(l) from a long simulated impulse response: h_0 = 1, h_i = sum_j a_j h_{i-j}.
    std::vector<double> h{1.0};
    for (int i = 1; i < 4000; ++i) {
      double v = 0;
      for (std::size_t j = 0; j < m.ar.size() && j < h.size(); ++j) v += m.ar[j] * h[h.size() - 1 - j];
      h.push_back(v);
    }
    double energy = 0;
    for (double v : h) energy += v * v;
    Eigen::MatrixXd r(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) {
        double s = 0;
        for (std::size_t k = 0; k + static_cast<std::size_t>(std::abs(i - j)) < h.size(); ++k)
          s += h[k] * h[k + static_cast<std::size_t>(std::abs(i - j))];
        r(i, j) = s / energy;
      }
    const Eigen::MatrixXd exact = x.transpose() * r.llt().solve(x);
    const Eigen::MatrixXd w = whiten(m, x);
    EXPECT_LT((w.transpose() * w - exact).norm(), 1e-9 * exact.norm()) << name;
  }
  // Power law, alpha = 1.5: R = F^H diag(lambda) F / n (circulant), lambda_k = n k^-alpha / P, lambda_0 = 0.
  const NoiseModel m = parse_noise_model("power:1.5");
  double power = 0;
  for (Eigen::Index k = 1; k <= n / 2; ++k) power += (k == n / 2 ? 1 : 2) * std::pow(static_cast<double>(k), -1.5);
  Eigen::MatrixXd pseudo_inverse = Eigen::MatrixXd::Zero(n, n);  // sum over bins of (1 / lambda_k) u_k u_k^H
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index k = 1; k < n; ++k) {
        const Eigen::Index folded = std::min(k, n - k);
        const double lambda = static_cast<double>(n) * std::pow(static_cast<double>(folded), -1.5) / power;
        pseudo_inverse(i, j) += std::cos(2 * std::numbers::pi * static_cast<double>(k * (i - j)) / n) / lambda / n;
      }
  const Eigen::MatrixXd exact = x.transpose() * pseudo_inverse * x;
  const Eigen::MatrixXd w = whiten(m, x);
  EXPECT_LT((w.transpose() * w - exact).norm(), 1e-9 * exact.norm());
}

}  // namespace
}  // namespace beamid::signal
