// DFT scaling, windows, Parseval, spike detection, 20 % supports and the 3-bin pole estimator, on signals whose
// spectra are known in closed form.
#include "signal/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/errors.h"
#include "signal/noise.h"
#include "signal/spikes.h"

namespace beamid::signal {
namespace {

constexpr double kPi = std::numbers::pi;

// sum of a_m e^{-sigma_m t} cos(2 pi f_m t + phi_m), sampled at t_i = i dt.
struct Mode {
  double amplitude, frequency_hz, decay_1_s, phase;
};
std::vector<double> damped_sinusoids(const std::vector<Mode>& modes, int samples, double dt) {
  std::vector<double> z(static_cast<std::size_t>(samples), 0.0);
  for (int i = 0; i < samples; ++i)
    for (const Mode& m : modes)
      z[static_cast<std::size_t>(i)] +=
          m.amplitude * std::exp(-m.decay_1_s * i * dt) * std::cos(2 * kPi * m.frequency_hz * i * dt + m.phase);
  return z;
}

TEST(Dft, ScalingIsOneOverNbarAndBinFrequenciesAreKdf) {
  // A cosine exactly on bin 10 of a 256-point record: Z(10) = 1/2 (the 1/Nbar scaling), every other bin 0.
  const int n = 256;
  const double dt = 1e-3;
  Dft dft(n, dt);
  const auto s = dft.transform(damped_sinusoids({{1.0, 10 / (n * dt), 0.0, 0.0}}, n, dt));
  EXPECT_NEAR(std::abs(s.at(10)), 0.5, 1e-14);
  EXPECT_NEAR(std::abs(s.at(n - 10)), 0.5, 1e-14);  // full-DFT index, read by conjugate symmetry
  EXPECT_NEAR(std::abs(s.at(-10)), 0.5, 1e-14);     // index modulo Nbar
  EXPECT_NEAR(std::abs(s.at(11)), 0.0, 1e-14);
  EXPECT_DOUBLE_EQ(s.df_hz(), 1 / (n * dt));
  EXPECT_DOUBLE_EQ(s.frequency_hz(10), 10 / (n * dt));
  // The same plan reused on another record gives the transform of that record (no state carried over).
  const auto constant = dft.transform(std::vector<double>(n, 2.0));
  EXPECT_NEAR(constant.at(0).real(), 2.0, 1e-14);
  EXPECT_NEAR(std::abs(constant.at(10)), 0.0, 1e-14);
}

TEST(Dft, ParsevalFourierLeastSquaresIsTimeCostOverNbar) {
  // model.md section 4: sum_k |U(k) - Z(k)|^2 = sum_i (y_i - z_i)^2 / Nbar exactly, for odd and even Nbar.
  for (int n : {1000, 1001, 4096}) {
    std::mt19937_64 engine(7);
    std::normal_distribution<double> normal;  // values only need to be generic; exactness does not depend on them
    std::vector<double> y(static_cast<std::size_t>(n)), z(static_cast<std::size_t>(n));
    double time_cost = 0;
    for (int i = 0; i < n; ++i) {
      y[static_cast<std::size_t>(i)] = normal(engine);
      z[static_cast<std::size_t>(i)] = normal(engine);
      time_cost += std::pow(y[static_cast<std::size_t>(i)] - z[static_cast<std::size_t>(i)], 2);
    }
    Dft dft(n, 1e-3);
    const double fourier = fourier_least_squares(dft.transform(y), dft.transform(z));
    // Round-off of an FFT is O(eps log2 Nbar) relative: 1e-13 leaves a factor > 10 of margin.
    EXPECT_NEAR(fourier, time_cost / n, 1e-13 * time_cost / n) << "Nbar = " << n;
  }
}

TEST(Dft, WindowsAreTheDocumentedWeights) {
  const auto hann = window_weights({"hann", 0.01}, 8);
  EXPECT_DOUBLE_EQ(hann[0], 0.0);
  EXPECT_NEAR(hann[4], 1.0, 1e-15);
  EXPECT_NEAR(hann[2], 0.5, 1e-15);
  const auto expo = window_weights({"exponential", 0.01}, 100);
  EXPECT_DOUBLE_EQ(expo[0], 1.0);
  EXPECT_NEAR(expo[50], 0.1, 1e-14);  // exp(-ln(100) / 2)
  EXPECT_TRUE(validation_error(WindowOptions{"blackman", 0.01}).has_value());
  EXPECT_TRUE(validation_error(WindowOptions{"exponential", 1.5}).has_value());
  // An end value that leaves nothing of the record (1e-300: the modes were gone from the spectrum; second pass N358).
  EXPECT_TRUE(validation_error(WindowOptions{"exponential", 1e-300}).has_value());
  EXPECT_FALSE(validation_error(WindowOptions{"exponential", 1e-6}).has_value());
  EXPECT_THROW(Dft(1, 1e-3), InputError);
  EXPECT_THROW(Dft(16, 0.0), InputError);
  Dft dft(16, 1e-3);
  EXPECT_THROW(dft.transform(std::vector<double>(15, 0.0)), InputError);
}

TEST(Dft, WindowSnrRetentionIsOneForRectangularAndTheClosedFormsForHann) {
  const int n = 65536;
  const double dt = 1e-4, record_s = n * dt;
  const auto rectangular = window_weights({"rectangular", 0.01}, n);
  const auto hann = window_weights({"hann", 0.01}, n);
  // Rectangular: the definition's ratio is 1 for every decay rate (identity, to round-off).
  for (double sigma : {0.0, 1.0, 100.0}) EXPECT_NEAR(window_snr_retention(rectangular, sigma, dt), 1, 1e-12);
  // A mode that does not decay under the periodic Hann window: (sum w)^2 / (Nbar sum w^2) = (Nbar/2)^2 / (Nbar 3
  // Nbar/8) = 2/3 exactly (sum sin^2 = Nbar/2, sum sin^4 = 3 Nbar/8 over a full period).
  EXPECT_NEAR(window_snr_retention(hann, 0.0, dt), 2.0 / 3.0, 1e-12);
  // A mode gone long before the window opens, sigma T = 200: w ~ (pi t/T)^2 where it lives, so the ratio tends to
  // (32/3) pi^4 / (sigma T)^4 (from sum w e^{-sigma t} ~ 2 (pi/T)^2 / (sigma^3 dt)); the neglected terms are
  // O((pi/(sigma T))^2 x 30) = 0.7 % from sin^2's next term and O(sigma dt) = 0.3 % from the sum's discreteness.
  const double sigma_t = 200;
  const double limit = 32.0 / 3.0 * std::pow(kPi, 4) / std::pow(sigma_t, 4);
  EXPECT_NEAR(window_snr_retention(hann, sigma_t / record_s, dt) / limit, 1, 0.02);
  // The exponential window follows a decay: matched to it (alpha / T = sigma) it gains over the rectangular window.
  const auto exponential = window_weights({"exponential", 0.01}, n);
  EXPECT_GT(window_snr_retention(exponential, std::log(100.0) / record_s, dt), 1.5);
}

TEST(Spikes, LocalMaximaRuleOnAHandMadeSpectrum) {
  // |Z| = 0 1 3 3 2 5 1 4 4 (k = 0..8, Nbar = 16): maxima where |Z(k)| > |Z(k-1)| and |Z(k)| >= |Z(k+1)|:
  // k = 2 (3 > 1, 3 >= 3), not k = 3 (3 > 3 fails), k = 5, k = 7 (4 > 1, 4 >= 4), not 8 (4 > 4 fails).
  Spectrum s;
  s.samples = 16;
  s.dt_s = 1.0 / 16;
  for (double m : {0, 1, 3, 3, 2, 5, 1, 4, 4}) s.half.emplace_back(m, 0.0);
  EXPECT_EQ(local_maxima(s), (std::vector<int>{2, 5, 7}));
  // The two largest, in order of frequency: k = 5 (5) and k = 7 (4); supports at 20 %: left of 5, |Z| >= 1 runs
  // over 4, 3, 2, 1 (stops at 0 < 1), right: 6 (1 >= 1), 7, 8 then the Nyquist edge.
  SpikeOptions o;
  o.count = 2;
  const auto spikes = detect_spikes(s, o);
  ASSERT_EQ(spikes.size(), 2u);
  EXPECT_EQ(spikes[0].bin, 5);
  EXPECT_EQ(spikes[1].bin, 7);
  EXPECT_EQ(spikes[0].n_left, 4);
  EXPECT_EQ(spikes[0].n_right, 3);
  EXPECT_DOUBLE_EQ(spikes[0].frequency_hz, 5.0);
  // A band that excludes bin 5 leaves 2 and 7.
  o.max_frequency_hz = 4.5;
  o.min_frequency_hz = 1.5;
  const auto band = detect_spikes(s, o);
  ASSERT_EQ(band.size(), 1u);
  EXPECT_EQ(band[0].bin, 2);
  o.count = 0;
  EXPECT_THROW(detect_spikes(s, o), InputError);
  // The Nyquist bin is a band edge, never a maximum: with |Z(8)| = 6 above |Z(7)| = 4 (and its mirror), bin 8 is not
  // listed and a band holding only bin 8 has no spike (it was listed with N_l = 0: the second pass's N359).
  s.half.back() = 6.0;
  EXPECT_EQ(local_maxima(s), (std::vector<int>{2, 5}));
  o.count = 1;
  o.min_frequency_hz = 7.9;
  o.max_frequency_hz = 8.0;
  EXPECT_TRUE(detect_spikes(s, o).empty());
}

TEST(Spikes, DetectsDampedSinusoidsWithTheirTwentyPercentWidths) {
  // Three well separated damped modes with known frequencies; each spike lies within half a bin of its frequency,
  // and the 20 % support is about 2 sigma sqrt(1/0.2^2 - 1) / (2 pi df) bins wide (model.md section 4, property 4),
  // up to +-1 bin of quantisation on each side and the leakage of the other modes.
  const int n = 4096;
  const double dt = 1e-3, df = 1 / (n * dt);
  const std::vector<Mode> modes{{1.0, 12.3, 0.6, 0.2}, {0.5, 47.9, 1.2, 1.0}, {0.3, 151.1, 2.5, 2.0}};
  Dft dft(n, dt);
  const auto s = dft.transform(damped_sinusoids(modes, n, dt));
  SpikeOptions o;
  o.count = 3;
  const auto spikes = detect_spikes(s, o);
  ASSERT_EQ(spikes.size(), 3u);
  for (int l = 0; l < 3; ++l) {
    const Mode& m = modes[static_cast<std::size_t>(l)];
    EXPECT_LE(std::abs(spikes[static_cast<std::size_t>(l)].frequency_hz - m.frequency_hz), 0.5 * df + 1e-12);
    const double width_bins = 2 * m.decay_1_s * std::sqrt(1 / 0.04 - 1) / (2 * kPi * df);
    const int measured = spikes[static_cast<std::size_t>(l)].n_left + spikes[static_cast<std::size_t>(l)].n_right;
    EXPECT_NEAR(measured, width_bins, 2.0) << "mode " << l;
  }
}

TEST(Spikes, ProminenceRuleSkipsNoiseOnAStrongPeaksSkirt) {
  // A strong undamped cosine's skirt falls off as 0.13 / d at d bins (offset 0.3 bin); noise of DFT level
  // 0.01/sqrt(1024) = 3e-4 makes local maxima on it where the skirt's slope 0.13/d^2 drops below that (d > 20), and
  // those (~0.005) are higher than a weak second mode (0.002), so "largest" picks a skirt bump, while "prominence"
  // (the bump rises ~3e-4 above its surroundings, the weak mode ~2e-3) picks the mode.
  const int n = 1024;
  const double dt = 1e-3;
  const double df = 1 / (n * dt);
  auto z = damped_sinusoids({{1.0, 100.3 * df, 0.0, 0.0}, {0.004, 300.0 * df, 0.0, 0.0}}, n, dt);
  std::mt19937_64 engine(3);
  std::normal_distribution<double> normal(0.0, 0.01);  // any noise of this size will do: the margins are 5x or more
  for (double& v : z) v += normal(engine);
  Dft dft(n, dt);
  const auto s = dft.transform(z);
  SpikeOptions o;
  o.count = 2;
  const auto largest = detect_spikes(s, o);
  ASSERT_EQ(largest.size(), 2u);
  EXPECT_LT(std::abs(largest[1].bin - 100), 60);  // a bump on the main peak's skirt
  EXPECT_NE(largest[1].bin, 300);
  o.rule = "prominence";
  const auto prominent = detect_spikes(s, o);
  ASSERT_EQ(prominent.size(), 2u);
  EXPECT_EQ(prominent[0].bin, 100);
  EXPECT_EQ(prominent[1].bin, 300);
}

TEST(ThreeBin, RecoversFrequencyAndDecayOfADampedExponential) {
  // A single damped complex pole (its conjugate far away in a complex record is absent) gives R exactly up to the
  // small-angle step, which Candan's factor corrects to O((pi/Nbar)^2): errors well below 1e-3 bins.
  const int n = 4096;
  const double dt = 1e-3, df = 1 / (n * dt), T = n * dt;
  for (double offset : {-0.4, -0.1, 0.0, 0.25, 0.49}) {
    for (double sigma : {0.2, 1.0, 5.0}) {
      const double f = (200 + offset) * df;
      // Real damped cosine far from 0 and Nyquist: the mirror pole adds a leakage of order 1/(2 f / df) bins.
      std::vector<double> z(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i)
        z[static_cast<std::size_t>(i)] = std::exp(-sigma * i * dt) * std::cos(2 * kPi * f * i * dt);
      Dft dft(n, dt);
      const auto s = dft.transform(z);
      SpikeOptions one;
      one.count = 1;
      const auto peaks = detect_spikes(s, one);
      ASSERT_EQ(peaks.size(), 1u);
      const auto e = three_bin_estimate(s, peaks[0].bin);
      ASSERT_TRUE(e.ok);
      // Tolerance: the mirror pole at -f contributes ~ (width in bins)/(400 bins) relative leakage, so 5e-3 bins
      // in frequency and 5e-3 bins (2 pi df per bin) in sigma T/(2 pi).
      EXPECT_NEAR(e.frequency_hz, f, 5e-3 * df) << "offset " << offset << " sigma " << sigma;
      EXPECT_NEAR(e.decay_rate_1_s * T / (2 * kPi), sigma * T / (2 * kPi), 5e-3)
          << "offset " << offset << " sigma " << sigma;
    }
  }
}

}  // namespace
}  // namespace beamid::signal

namespace beamid::signal {
namespace {

TEST(UpperBandEnergy, IsWhatASampledPulseHoldsAboveAQuarterOfTheRate) {
  // A sin^2 pulse 4 samples wide is 0.5, 1, 0.5: |X(w)|^2 = (1 + cos w)^2, whose integral over (pi/2, pi),
  // 3 pi / 4 - 2, is 1/2 - 4 / (3 pi) = 0.0756 of that over (0, pi), 3 pi / 2; 1024 bins sum it to within 1e-3 (the
  // bin at exactly a quarter of the rate is left out whole: measured 6.5e-4 below).
  // 20 samples wide: below 1e-4. White noise: half its energy, within 0.03 over 4096 samples. Zeros: 0.
  const auto pulse = [](int width) {
    std::vector<double> x(1024, 0.0);
    for (int i = 0; i <= width; ++i)
      x[static_cast<std::size_t>(i)] = std::pow(std::sin(std::numbers::pi * i / width), 2);
    return x;
  };
  Dft dft(1024, 1e-3);
  EXPECT_NEAR(upper_band_energy_fraction(dft.transform(pulse(4))), 0.5 - 4 / (3 * std::numbers::pi), 1e-3);
  EXPECT_LT(upper_band_energy_fraction(dft.transform(pulse(20))), 1e-4);
  EXPECT_NEAR(upper_band_energy_fraction(Dft(4096, 1e-3).transform(gaussian_deviates(5, 4096))), 0.5, 0.03);
  EXPECT_EQ(upper_band_energy_fraction(dft.transform(std::vector<double>(1024, 0.0))), 0.0);
}

}  // namespace
}  // namespace beamid::signal
