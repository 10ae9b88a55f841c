// The sensor's anti-alias filter (signal/sensor_filter.h): its digital response against the analog Butterworth's
// magnitude and phase, a sinusoid through it, its steady start, and what it refuses.
#include "signal/sensor_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace beamid::signal {
namespace {

constexpr double kDt = 1e-3;  // the delivered record: 1 kHz

TEST(SensorFilter, FollowsTheAnalogButterworth) {
  // Order 4, f_c = 200 Hz, run at 16 kHz: |H| = 1/sqrt(2) at f_c (the bilinear transform is prewarped there: to
  // round-off); from 0.05 f_c to f_c within 1e-3 of the analog 1/sqrt(1 + (f/f_c)^8), and within 5e-3 up to 1.5 f_c:
  // the bilinear transform maps f to a frequency higher by (pi f / 16 kHz)^2 / 3 relative, less that at f_c where it
  // is prewarped (6e-4 at 300 Hz), which the f^-4 slope beyond f_c turns into 4 times that in magnitude (measured
  // 2.5e-3 at 1.5 f_c). The phase at low frequency is the analog filter's delay, -2.613 f/f_c rad (sum over the poles
  // of 1/sin, the Butterworth group delay at DC), within 1 %.
  const SensorFilter f{200, 4, 16};
  EXPECT_NEAR(std::abs(sensor_response(f, kDt, 200)), 1 / std::sqrt(2.0), 1e-12);
  for (const double ratio : {0.05, 0.2, 0.5, 0.8, 1.0, 1.2, 1.5}) {
    const double analog = 1 / std::sqrt(1 + std::pow(ratio, 8));
    EXPECT_NEAR(std::abs(sensor_response(f, kDt, ratio * 200)) / analog, 1.0, ratio <= 1 ? 1e-3 : 5e-3) << ratio;
  }
  EXPECT_NEAR(std::arg(sensor_response(f, kDt, 10)) / (-2.6131 * 10 / 200.0), 1.0, 0.01);
  EXPECT_NEAR(std::abs(sensor_response(f, kDt, 0)), 1.0, 1e-12);
  // A cut-off of 0 is no filter.
  EXPECT_EQ(sensor_response(SensorFilter{0, 4, 16}, kDt, 100), std::complex<double>(1.0));
}

TEST(SensorFilter, DeliversASinusoidScaledAndDelayedByItsResponseAndStartsSteady) {
  // 50 Hz through the filter above: once the start has decayed (the last half of 1 s), every delivered sample is
  // |H| sin(omega t + arg H) to 1e-9 (the filter is linear and time-invariant; what is left is the start's decay,
  // e^{-0.38 x 2 pi 200 x 0.5} ~ 1e-100, and round-off). A constant record comes out unchanged (the filter starts in
  // its steady state: to round-off), and every 16th sample is kept.
  const SensorFilter f{200, 4, 16};
  const int fine = 16000;
  std::vector<double> x(fine), constant(fine, 0.7);
  const double w = 2 * std::numbers::pi * 50;
  for (int i = 0; i < fine; ++i) x[static_cast<std::size_t>(i)] = std::sin(w * i * kDt / 16);
  const std::vector<double> y = sense(f, x, kDt);
  ASSERT_EQ(y.size(), 1000u);
  const std::complex<double> h = sensor_response(f, kDt, 50);
  for (std::size_t i = 500; i < y.size(); ++i)
    EXPECT_NEAR(y[i], std::abs(h) * std::sin(w * static_cast<double>(i) * kDt + std::arg(h)), 1e-9) << i;
  for (const double v : sense(f, constant, kDt)) EXPECT_NEAR(v, 0.7, 1e-12);
}

TEST(SensorFilter, StartsFromTheLevelBeforeTheRecord) {
  // A record that is 0.7 from its first sample on, after 0 before it (an acceleration at a release): the filter sees
  // a step, so the delivered record starts near 0 and rises to 0.7 (a low-pass's step response: its slowest pole
  // pair decays at 2 pi 200 sin(pi / 8) = 481 /s, so after 40 ms it has settled to e^-19 = 5e-9 of the step, well
  // inside the 1e-6 asked), unlike the steady start of a level held before.
  const SensorFilter f{200, 4, 16};
  const std::vector<double> constant(16000, 0.7);
  const std::vector<double> step = sense(f, constant, kDt, 0.0);
  EXPECT_LT(std::abs(step.front()), 0.07);  // the first delivered sample is 1/16 ms into the step: under a tenth of it
  for (std::size_t i = 40; i < step.size(); ++i) EXPECT_NEAR(step[i], 0.7, 1e-6) << i;
  EXPECT_EQ(sense(f, constant, kDt, 0.7), sense(f, constant, kDt));  // the level held before: the default
}

TEST(SensorFilter, ItsStateSpaceFormIsTheSameRecursion) {
  // The cascade as one system (state_space) run over a record from its steady start gives sense()'s samples: the same
  // products in another order, so to round-off (1e-13 of a unit input); its DC gain is 1, and its response at a
  // frequency, C (zI - A)^-1 B + D at z = e^{j omega dt_fine}, is sensor_response's. Orders 1 to 5 take in a
  // first-order section (odd orders) and several pairs.
  for (const int order : {1, 2, 4, 5}) {
    const SensorFilter f{200, order, 16};
    const FilterStateSpace ss = state_space(f, kDt);
    ASSERT_EQ(ss.a.rows(), order);
    const Eigen::Index n = ss.a.rows();
    EXPECT_NEAR(ss.c.dot((Eigen::MatrixXd::Identity(n, n) - ss.a).lu().solve(ss.b)) + ss.d, 1.0, 1e-12) << order;
    const std::complex<double> z = std::polar(1.0, 2 * std::numbers::pi * 150 * kDt / 16);
    const Eigen::VectorXcd v = (z * Eigen::MatrixXcd::Identity(n, n) - ss.a.cast<std::complex<double>>())
                                   .lu()
                                   .solve(ss.b.cast<std::complex<double>>());
    EXPECT_LT(std::abs(ss.c.cast<std::complex<double>>().dot(v) + ss.d - sensor_response(f, kDt, 150)), 1e-12);
    std::vector<double> x(1600);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.01 * static_cast<double>(i * i)) + 0.3;
    Eigen::VectorXd state = (Eigen::MatrixXd::Identity(n, n) - ss.a).lu().solve(ss.b) * x.front();
    const std::vector<double> expected = sense(f, x, kDt);
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (i % 16 == 0) {
        EXPECT_NEAR(ss.c.dot(state) + ss.d * x[i], expected[i / 16], 1e-13) << order << " " << i;
      }
      state = ss.a * state + ss.b * x[i];
    }
  }
  EXPECT_EQ(state_space(SensorFilter{0, 4, 16}, kDt).a.rows(), 0);  // no filter: the identity
}

TEST(SensorFilter, RefusesWhatItCannotRealise) {
  EXPECT_TRUE(validation_error(SensorFilter{200, 0, 16}, kDt).has_value());
  EXPECT_TRUE(validation_error(SensorFilter{200, 9, 16}, kDt).has_value());
  EXPECT_TRUE(validation_error(SensorFilter{200, 4, 1}, kDt).has_value());
  EXPECT_TRUE(validation_error(SensorFilter{-1, 4, 16}, kDt).has_value());
  // A quarter of the fine Nyquist frequency: 16 kHz / 8 = 2 kHz.
  EXPECT_FALSE(validation_error(SensorFilter{1999, 4, 16}, kDt).has_value());
  EXPECT_TRUE(validation_error(SensorFilter{2000, 4, 16}, kDt).has_value());
  EXPECT_THROW(sense(SensorFilter{200, 4, 16}, std::vector<double>(100, 1.0), kDt), InputError);
}

}  // namespace
}  // namespace beamid::signal
