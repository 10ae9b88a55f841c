// The frequency-band cost (costs/least_squares.h): Parseval against the time cost, the band's bins, its closed-form
// amplitude, its linear residual map, and a fit that recovers the beam with it (exact Jacobian).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "costs/least_squares.h"
#include "fit/identification.h"
#include "fit/objective.h"
#include "thin_beam_fit.h"

namespace beamid::costs {
namespace {

constexpr int kSamples = 256;
constexpr double kDt = 1.0 / 256;  // df = 1 Hz

std::vector<double> decaying_tone(double amplitude, double frequency_hz, double sigma, double phase = 0) {
  std::vector<double> y(kSamples);
  for (int i = 0; i < kSamples; ++i)
    y[static_cast<std::size_t>(i)] =
        amplitude * std::exp(-sigma * i * kDt) * std::cos(2 * std::numbers::pi * frequency_hz * i * kDt + phase);
  return y;
}

double value(Cost& cost, const std::vector<double>& y) {
  const std::vector<std::complex<double>> none;
  return cost.evaluate(ModelResponse{y, none}).value;
}

TEST(BandCost, OnTheFullBandIsTheTimeCostOverNbar) {
  // Parseval with the 1/Nbar DFT scaling: sum_{k<Nbar} |U - Z|^2 = sum_i (y_i - z_i)^2 / Nbar; the stored half
  // spectrum counts the bins above Nbar/2 through w_k = 2. Round-off of two FFTs: 1e-12.
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4, 0.2);
  CostOptions time, band;
  band.name = kBandCost;
  auto t = make_cost(time, z, kDt);
  auto b = make_cost(band, z, kDt);
  EXPECT_EQ(b->residual_count(), 2 * (kSamples / 2 + 1));
  EXPECT_NEAR(value(*b, y) * kSamples / value(*t, y), 1.0, 1e-12);
}

TEST(BandCost, KeepsTheBinsOfItsBandAndSolvesTheAmplitude) {
  const auto z = decaying_tone(2.0, 20.0, 0.3);
  CostOptions o;
  o.name = kBandCost;
  o.spikes.min_frequency_hz = 10;
  o.spikes.max_frequency_hz = 30.5;
  auto b = make_cost(o, z, kDt);
  EXPECT_EQ(b->residual_count(), 2 * 21);  // bins 10..30 at df = 1 Hz
  EXPECT_GT(value(*b, decaying_tone(1.0, 20.0, 0.3)), 0);
  o.unknown_amplitude = true;
  auto scaled = make_cost(o, z, kDt);
  // The model is the data at half the amplitude: the closed-form a = 2 makes the cost vanish.
  const std::vector<std::complex<double>> none;
  const auto half = decaying_tone(1.0, 20.0, 0.3);
  const Evaluation e = scaled->evaluate(ModelResponse{half, none});
  EXPECT_NEAR(e.amplitude_scale, 2.0, 1e-12);
  EXPECT_LT(e.value, 1e-24);
  o.spikes.min_frequency_hz = 200;  // above Nyquist (128 Hz): no bin
  EXPECT_THROW(make_cost(o, z, kDt), InputError);
}

TEST(BandCost, ResidualDerivativeIsTheDftOfTheOutputChange) {
  // The residuals are linear in y: r(y + h dy) - r(y) = h dr exactly, up to round-off (1e-12 of |dr|).
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4);
  CostOptions o;
  o.name = kBandCost;
  o.spikes.max_frequency_hz = 40;
  auto b = make_cost(o, z, kDt);
  const auto dy = decaying_tone(1.0, 12.0, 1.0, 0.7);
  Eigen::MatrixXd dy_matrix = Eigen::Map<const Eigen::VectorXd>(dy.data(), kSamples);
  ASSERT_TRUE(b->has_output_jacobian());
  const std::vector<std::complex<double>> no_poles;
  const Eigen::MatrixXd dr = b->output_jacobian(ModelResponse{y, no_poles}, dy_matrix);
  std::vector<double> moved = y;
  for (int i = 0; i < kSamples; ++i) moved[static_cast<std::size_t>(i)] += dy[static_cast<std::size_t>(i)];
  const std::vector<std::complex<double>> none;
  const Eigen::VectorXd difference =
      b->evaluate(ModelResponse{moved, none}).residuals - b->evaluate(ModelResponse{y, none}).residuals;
  EXPECT_LT((difference - dr.col(0)).cwiseAbs().maxCoeff(), 1e-12 * dr.cwiseAbs().maxCoeff());
  o.unknown_amplitude = true;  // then not linear: no map
  EXPECT_FALSE(make_cost(o, z, kDt)->has_output_jacobian());
}

TEST(BandCost, FitRecoversTheBeamWithItsExactJacobian) {
  // Noise-free data from the same model (N = 8, fast): the band below 120 Hz holds modes 1-3 of the thin beam; from
  // every parameter 5 % off in mixed directions the fit must return the truth to 1e-6.
  const auto truth = model::preset("banks-aluminium");
  fit::FitOptions o = thin_beam_fit(kBandCost);
  const auto data = thin_beam_data(o);
  const std::map<std::string, double> scale = {{"EI", 1.005}, {"rho", 0.995}, {"cDI", 1.05}, {"gamma", 0.95}};
  for (const auto& [key, factor] : scale) {
    double& v = o.start.*(model::find_parameter(key)->member);
    o.estimate.push_back({key, v / 2, v * 2});
    v *= factor;
  }
  fit::Objective objective(o, data);
  EXPECT_TRUE(objective.has_exact_jacobian());
  const fit::FitResult r = fit::fit(o, data);
  EXPECT_EQ(r.status, "converged") << r.termination;
  for (const auto& p : r.parameters)
    EXPECT_NEAR(p.estimate / (truth.*(model::find_parameter(p.key)->member)), 1.0, 1e-6) << p.key;
}

}  // namespace
}  // namespace beamid::costs
