// The least-squares costs (costs/least_squares.h). The frequency-band cost: Parseval against the time cost, the band's
// bins, its closed-form amplitude, its linear residual map, and a fit that recovers the beam with it (exact Jacobian).
// The costs that assume a noise model: time prewhitened (generalised least squares) is the Gaussian likelihood's
// quadratic form r^T R^-1 r; freq-ml with white noise is Nbar times freq-band; with circulant (power-law) noise
// freq-ml and prewhitened time are the same likelihood; both residual maps are linear in y; and a fit with each
// recovers the beam.
#include "costs/least_squares.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../fit/central_difference.h"
#include "core/errors.h"
#include "fit/identification.h"
#include "fit/objective.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "signal/noise.h"
#include "signal/spectrum.h"
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

// EI, rho, cDI and gamma estimated within [v/2, 2 v], started 0.5-5 % off in mixed directions.
void estimate_from_mixed_offsets(fit::FitOptions& o) {
  const std::map<std::string, double> scale = {{"EI", 1.005}, {"rho", 0.995}, {"cDI", 1.05}, {"gamma", 0.95}};
  for (const auto& [key, factor] : scale) {
    double& v = o.start.*(model::find_parameter(key)->member);
    o.estimate.push_back({key, v / 2, v * 2});
    v *= factor;
  }
}

TEST(BandCost, FitRecoversTheBeamWithItsExactJacobian) {
  // Noise-free data from the same model (N = 8, fast): the band below 120 Hz holds modes 1-3 of the thin beam; from
  // every parameter 5 % off in mixed directions the fit must return the truth to 1e-6.
  const auto truth = model::preset("banks-aluminium");
  fit::FitOptions o = thin_beam_fit(kBandCost);
  const auto data = thin_beam_data(o);
  estimate_from_mixed_offsets(o);
  fit::Objective objective(o, data);
  EXPECT_TRUE(objective.has_exact_jacobian());
  const fit::FitResult r = fit::fit(o, data);
  EXPECT_EQ(r.status, "converged") << r.termination;
  for (const auto& p : r.parameters)
    EXPECT_NEAR(p.estimate / (truth.*(model::find_parameter(p.key)->member)), 1.0, 1e-6) << p.key;
}

Evaluation evaluate(Cost& cost, const std::vector<double>& y) {
  const std::vector<std::complex<double>> none;
  return cost.evaluate(ModelResponse{y, none});
}

CostOptions options(const std::string& cost, const std::string& noise) {
  CostOptions o;
  o.name = cost;
  o.noise_model = noise;
  return o;
}

TEST(NoiseWeightedCost, PrewhitenedTimeIsTheLikelihoodsQuadraticForm) {
  // r = y - z; the AR(2) process's correlation R_ij = rho(|i - j|) (unit variance) from the Yule-Walker equations
  // rho(1) = a1 / (1 - a2), rho(l) = a1 rho(l - 1) + a2 rho(l - 2); the cost must be r^T R^-1 r to round-off (1e-9
  // relative: R's condition number is about 1e3).
  const double a1 = 0.6, a2 = -0.3;
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4, 0.2);
  auto cost = make_cost(options(kTimeCost, "ar:0.6,-0.3"), z, kDt);
  std::vector<double> rho(kSamples);
  rho[0] = 1;
  rho[1] = a1 / (1 - a2);
  for (int l = 2; l < kSamples; ++l) rho[static_cast<std::size_t>(l)] = a1 * rho[l - 1] + a2 * rho[l - 2];
  Eigen::MatrixXd r_matrix(kSamples, kSamples);
  for (int i = 0; i < kSamples; ++i)
    for (int j = 0; j < kSamples; ++j) r_matrix(i, j) = rho[static_cast<std::size_t>(std::abs(i - j))];
  Eigen::VectorXd r(kSamples);
  for (int i = 0; i < kSamples; ++i) r(i) = y[static_cast<std::size_t>(i)] - z[static_cast<std::size_t>(i)];
  const double quadratic = r.dot(r_matrix.ldlt().solve(r));
  EXPECT_NEAR(evaluate(*cost, y).value / quadratic, 1.0, 1e-9);
  // White noise: the plain time cost.
  auto white = make_cost(options(kTimeCost, "white"), z, kDt);
  EXPECT_NEAR(evaluate(*white, y).value / r.squaredNorm(), 1.0, 1e-14);
}

TEST(NoiseWeightedCost, FreqMlWithWhiteNoiseIsNbarTimesFreqBand) {
  // E|N(k)|^2 = 1/Nbar for white noise of unit variance, so every bin's weight is Nbar times freq-band's; in a band
  // too. Round-off: 1e-12.
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4, 0.2);
  for (const double top : {128.0, 30.0}) {
    CostOptions band = options(kBandCost, "white"), ml = options(kMaxLikelihoodCost, "white");
    band.spikes.max_frequency_hz = ml.spikes.max_frequency_hz = top;
    auto b = make_cost(band, z, kDt);
    auto m = make_cost(ml, z, kDt);
    EXPECT_EQ(m->residual_count(), b->residual_count());
    EXPECT_NEAR(evaluate(*m, y).value / (kSamples * evaluate(*b, y).value), 1.0, 1e-12);
  }
}

TEST(NoiseWeightedCost, WithCirculantNoiseFreqMlAndPrewhitenedTimeAreOneLikelihood) {
  // Power-law noise is circulant: its DFT bins are independent, so the frequency-domain likelihood is exact, and the
  // time-domain whitening (each bin over its sd, the offset left out) gives the same quadratic form: the two costs
  // agree to round-off (1e-10) for alpha = 1 and 2, on the full band with the offset bin that neither counts.
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4, 0.2);
  for (const std::string noise : {"power:1", "power:2"}) {
    auto t = make_cost(options(kTimeCost, noise), z, kDt);
    auto m = make_cost(options(kMaxLikelihoodCost, noise), z, kDt);
    EXPECT_EQ(m->residual_count(), 2 * (kSamples / 2));  // bins 1..128: the offset has no noise
    EXPECT_NEAR(evaluate(*m, y).value / evaluate(*t, y).value, 1.0, 1e-10) << noise;
  }
}

TEST(NoiseWeightedCost, ResidualsAreLinearInTheOutputWithTheJacobianGiven) {
  // r(y + dy) - r(y) = dr exactly (round-off 1e-11 of |dr|) for both costs with an AR(1) model.
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4);
  const auto dy = decaying_tone(1e-3, 12.0, 1.0, 0.7);
  const Eigen::MatrixXd dy_matrix = Eigen::Map<const Eigen::VectorXd>(dy.data(), kSamples);
  std::vector<double> moved = y;
  for (int i = 0; i < kSamples; ++i) moved[static_cast<std::size_t>(i)] += dy[static_cast<std::size_t>(i)];
  for (const std::string& name : {kTimeCost, kMaxLikelihoodCost}) {
    auto c = make_cost(options(name, "ar:0.9"), z, kDt);
    ASSERT_TRUE(c->has_output_jacobian());
    const std::vector<std::complex<double>> none;
    const Eigen::MatrixXd dr = c->output_jacobian(ModelResponse{y, none}, dy_matrix);
    const Eigen::VectorXd difference = evaluate(*c, moved).residuals - evaluate(*c, y).residuals;
    EXPECT_LT((difference - dr.col(0)).cwiseAbs().maxCoeff(), 1e-11 * dr.cwiseAbs().maxCoeff()) << name;
  }
}

TEST(NoiseWeightedCost, FitsRecoverTheBeamAndABadNoiseModelIsRefused) {
  // Noise-free data from the same model: whatever the weighting, the truth is the minimum; from 0.5-5 % off both
  // generalised fits must return it to 1e-6.
  const auto truth = model::preset("banks-aluminium");
  for (const std::string& name : {kTimeCost, kMaxLikelihoodCost}) {
    fit::FitOptions o = thin_beam_fit(name);
    o.cost.noise_model = "ar:0.9";
    const auto data = thin_beam_data(o);
    estimate_from_mixed_offsets(o);
    const fit::FitResult r = fit::fit(o, data);
    EXPECT_EQ(r.status, "converged") << r.termination;
    for (const auto& p : r.parameters)
      EXPECT_NEAR(p.estimate / (truth.*(model::find_parameter(p.key)->member)), 1.0, 1e-6) << name << " " << p.key;
  }
  EXPECT_THROW(make_cost(options(kMaxLikelihoodCost, "ar:1.5"), decaying_tone(1, 10, 1), kDt), InputError);
  // "estimated" is a fit's to resolve: a cost alone cannot.
  EXPECT_THROW(make_cost(options(kTimeCost, kEstimatedNoise), decaying_tone(1, 10, 1), kDt), InputError);
  EXPECT_FALSE(validation_error(options(kTimeCost, kEstimatedNoise)).has_value());
  EXPECT_TRUE(validation_error(options(kTimeCost, "pink")).has_value());
  EXPECT_TRUE(cost_uses(kMaxLikelihoodCost).noise_model && cost_uses(kTimeCost).noise_model);
  EXPECT_FALSE(cost_uses(kBandCost).noise_model || cost_uses(kSpikeSmoothCost).noise_model);
  EXPECT_FALSE(cost_uses(kMaxLikelihoodCost).window);  // its weights are the rectangular window's
  // ... and a window reaching it through shared options (a hybrid's, a study's [fit]) is not applied.
  CostOptions hann = options(kMaxLikelihoodCost, "ar:0.9");
  hann.window.name = "hann";
  const auto z = decaying_tone(1, 10, 1), y = decaying_tone(0.9, 10.5, 1.2);
  const std::vector<std::complex<double>> none;
  EXPECT_EQ(make_cost(hann, z, kDt)->evaluate(ModelResponse{y, none}).value,
            make_cost(options(kMaxLikelihoodCost, "ar:0.9"), z, kDt)->evaluate(ModelResponse{y, none}).value);
}

TEST(NoiseWeightedCost, TheExactJacobianThroughTheSensitivitiesIsTheResidualsCentralDifference) {
  // d r / d q of prewhitened time and freq-ml (ar:0.9) on the thin beam's pulse record, from the exact sensitivities
  // through each cost's linear map, against central differences of the residuals with h = 1e-5 q: they agree to the
  // differences' own error, O(h^2) of the second derivative (bound 1e-5 of |d r|), for EI, rho, cDI and gamma.
  for (const std::string& name : {kTimeCost, kMaxLikelihoodCost}) {
    fit::FitOptions o = thin_beam_fit(name);
    o.cost.noise_model = "ar:0.9";
    const auto data = thin_beam_data(o);
    estimate_from_mixed_offsets(o);
    fit::Objective objective(o, data);
    ASSERT_TRUE(objective.has_exact_jacobian()) << name;
    const std::vector<std::string> keys = {"EI", "rho", "cDI", "gamma"};
    Eigen::MatrixXd jacobian;
    ASSERT_TRUE(objective.evaluate_with_jacobian(o.start, keys, jacobian).evaluation.ok());
    for (std::size_t q = 0; q < keys.size(); ++q) {
      const Eigen::VectorXd difference = fit::testing::residual_central_difference(objective, o.start, keys[q]);
      EXPECT_LT((jacobian.col(static_cast<Eigen::Index>(q)) - difference).norm(), 1e-5 * difference.norm())
          << name << " " << keys[q];
    }
  }
}

TEST(NoiseWeightedCost, TheErrorsInVariablesFormWeighsEachBinAndProjectsOutTheTransient) {
  // freq-ml with a force's noise: each bin's residual over sqrt(sd_Y^2 s(k) + sd_F^2 |G(z_k)|^2 / Nbar) (s the noise
  // model's bin variance, white: 1/Nbar; G the given transfer function), then the weighted least-squares fit by the
  // transient terms taken out: with no pole given, the two fixed terms, a constant and z^-1 (real coefficients), so
  // that the value is the weighted sum of squares less its least-squares fit by w_b and w_b z_b^-1; computed here in
  // full (round-off 1e-12). Without the
  // transfer function it is refused in words; with G = 0 and no pole, the output-error form over sd_Y^2 less its
  // weighted mean real part.
  const auto z = decaying_tone(1.0, 10.3, 0.5), y = decaying_tone(0.9, 10.6, 0.4, 0.2);
  CostOptions o = options(kMaxLikelihoodCost, "white");
  o.noise_sd = 0.01;
  o.force_noise_sd = 0.5;
  auto c = make_cost(o, z, kDt);
  ASSERT_TRUE(c->uses_transfer_function());
  EXPECT_FALSE(c->has_output_jacobian());  // its weights move with the parameters
  std::vector<std::complex<double>> frf(kSamples / 2 + 1);
  for (std::size_t k = 0; k < frf.size(); ++k) frf[k] = std::complex<double>(0.03, 0.01 * k) / (1.0 + 0.1 * k);
  const std::vector<std::complex<double>> none;
  const Evaluation e = c->evaluate(ModelResponse{y, none, &frf});
  ASSERT_TRUE(e.ok()) << e.status;
  signal::Dft dft(kSamples, kDt);
  const signal::Spectrum zs = dft.transform(z), ys = dft.transform(y);
  const auto rows = static_cast<Eigen::Index>(2 * frf.size());
  Eigen::VectorXd r(rows);
  Eigen::MatrixXd terms(rows, 2);
  for (std::size_t k = 0; k < frf.size(); ++k) {
    const double w = (k == 0 || k == frf.size() - 1) ? 1.0 : 2.0;
    const double v = (o.noise_sd * o.noise_sd + std::norm(frf[k]) * o.force_noise_sd * o.force_noise_sd) / kSamples;
    const std::complex<double> rk = std::sqrt(w / v) * (ys.half[k] - zs.half[k]);
    const std::complex<double> z_inverse = std::polar(1.0, -2 * std::numbers::pi * static_cast<double>(k) / kSamples);
    const auto row = static_cast<Eigen::Index>(2 * k);
    r(row) = rk.real(), r(row + 1) = rk.imag();
    terms(row, 0) = std::sqrt(w / v), terms(row + 1, 0) = 0;
    terms(row, 1) = std::sqrt(w / v) * z_inverse.real(), terms(row + 1, 1) = std::sqrt(w / v) * z_inverse.imag();
  }
  const Eigen::VectorXd left = r - terms * terms.colPivHouseholderQr().solve(r);
  EXPECT_NEAR(e.value / left.squaredNorm(), 1.0, 1e-12);
  EXPECT_FALSE(c->evaluate(ModelResponse{y, none}).ok());
  // A band of 6 bins (12 residuals) against the transients of 8 modes (18 terms) would be fitted by the transient
  // alone: refused in words, never a cost of 0.
  CostOptions narrow = o;
  narrow.spikes.max_frequency_hz = 5;
  auto n = make_cost(narrow, z, kDt);
  std::vector<std::complex<double>> poles;
  for (int m = 1; m <= 8; ++m) poles.emplace_back(-0.5 * m, 2 * std::numbers::pi * 7.0 * m);
  const Evaluation refused = n->evaluate(ModelResponse{y, poles, &frf});
  EXPECT_FALSE(refused.ok());
  EXPECT_NE(refused.status.find("more than half of the band's 12 residuals"), std::string::npos) << refused.status;
}

TEST(NoiseWeightedCost, TheErrorsInVariablesCostAtTheTruthIsASumOfIndependentBins) {
  // With the response's noise and the force channel's, each weighted bin left after the transient is taken out is
  // independent with mean 1 per real residual: over draws, the cost at the truth has mean (residuals - transient
  // terms) and the spread of that many independent chi-square terms. Thin beam, N = 4, 512 samples at 1 ms, the 4 ms
  // pulse as its force channel records it, velocity at the tip; the response's noise 0.1 % of its RMS, the force
  // channel's 20 %. Over 400 draws the mean is within 3 % (its sd about 1.2 %) and the sd within 30 % of
  // sqrt(2 x (residuals - terms)) (the sd's relative sd 3.5 %). Weighing each bin by its exact variance over the record
  // instead, with no transient, also had the right mean but an sd of 336, 10 times this one (measured, 400 draws):
  // the transient of the noise's response is common to every bin.
  fit::FitOptions o = thin_beam_fit(kMaxLikelihoodCost);
  o.elements = 4;
  o.experiment.samples = 512;
  o.experiment.force_x_m = o.start.l;
  o.experiment.excitation = simulation::kSampledForce;
  o.experiment.force_samples_N = simulation::sampled_pulse(o.experiment);
  o.cost.spikes.max_frequency_hz = 500;  // Nyquist: every bin
  const std::vector<double> clean = thin_beam_data(o), force = o.experiment.force_samples_N;
  o.cost.noise_sd = 1e-3 * signal::rms(clean);
  o.cost.force_noise_sd = 0.2 * signal::rms(force);
  o.estimate.push_back({"EI", o.start.EI / 2, o.start.EI * 2});
  const galerkin::SplineSpace space(o.elements);
  const galerkin::StateSpaceModes modes(galerkin::combine(galerkin::BeamForms(space, o.start.l), o.start));
  // The transient's terms: the two fixed ones, and a pair per mode not fast enough for them (|e^{lambda dt}| >= 1e-3).
  int terms = 2;
  for (const auto& mode : modes.underdamped_modes())
    if (std::abs(std::exp(mode.lambda * o.experiment.dt_s)) >= 1e-3) terms += 2;
  constexpr int kDraws = 400;
  double mean = 0, square = 0;
  for (int d = 0; d < kDraws; ++d) {
    fit::FitOptions draw = o;
    draw.experiment.force_samples_N = signal::add_noise(force, 0.2, 7000 + static_cast<std::uint64_t>(d));
    fit::Objective objective(draw, signal::add_noise(clean, 1e-3, 9000 + static_cast<std::uint64_t>(d)));
    const fit::Objective::Output out = objective.evaluate(o.start);
    ASSERT_TRUE(out.evaluation.ok()) << out.evaluation.status;
    mean += out.evaluation.value / kDraws;
    square += out.evaluation.value * out.evaluation.value / kDraws;
  }
  const double dof = 512.0 - terms, sd = std::sqrt(square - mean * mean);
  EXPECT_NEAR(mean / dof, 1.0, 0.03);
  EXPECT_NEAR(sd / std::sqrt(2 * dof), 1.0, 0.3);
}

// The thin beam at N = 6, 2048 samples of the tip's displacement after the 4 ms pulse at the tip as its force channel
// records it (clean), every bin to Nyquist, freq-ml's errors-in-variables form for 1 % noise on the response and 2 %
// on the force; rho estimated. With the clean record.
std::pair<fit::FitOptions, std::vector<double>> hit_thin_beam() {
  fit::FitOptions o = thin_beam_fit(kMaxLikelihoodCost);
  o.elements = 6;
  o.experiment.samples = 2048;
  o.experiment.force_x_m = o.start.l;
  o.experiment.output = "displacement";
  o.experiment.excitation = simulation::kSampledForce;
  o.experiment.force_samples_N = simulation::sampled_pulse(o.experiment);
  o.cost.spikes.max_frequency_hz = 500;
  const std::vector<double> clean = thin_beam_data(o);
  o.cost.noise_sd = 0.01 * signal::rms(clean);
  o.cost.force_noise_sd = 0.02 * signal::rms(o.experiment.force_samples_N);
  o.estimate.push_back({"rho", o.start.rho / 2, o.start.rho * 2});
  return {o, clean};
}

TEST(NoiseWeightedCost, TheErrorsInVariablesCostIsSmoothInTheParameters) {
  // The twenty-first pass's P1: the thin beam at N = 6, 2048 samples of the tip's displacement, the 4 ms pulse at the
  // tip as its force channel records it, 1 % noise on the response and 2 % on the force, every bin to Nyquist. The
  // transient of the fast modes (|e^{lambda dt}| down to 1e-40) lay within round-off of the constant, and the rank the
  // pivoted QR found flipped: the cost at rho (1 + i 1e-10), i = 0..15, jumped by 0.2-0.6 on about 2,030 (a second
  // difference of 3e-4 of it), and the standard errors fell 20-160 times below the bound. Smooth, its second
  // differences over such steps are round-off, about 1e-13 of it: bound 1e-9.
  auto [o, clean] = hit_thin_beam();
  o.experiment.force_samples_N = signal::add_noise(o.experiment.force_samples_N, 0.02, 2);
  // Also within a band (the twenty-second pass's P1: below 60 Hz the terms of the modes above it lay within 1e-9
  // of dependent, and the cost scattered by 1e-6 of itself).
  for (const double band_hz : {500.0, 60.0}) {
    o.cost.spikes.max_frequency_hz = band_hz;
    fit::Objective objective(o, signal::add_noise(clean, 0.01, 1));
    std::vector<double> values;
    for (int i = 0; i < 16; ++i) {
      model::BeamParameters at = o.start;
      at.rho *= 1 + 1e-10 * i;
      const fit::Objective::Output out = objective.evaluate(at);
      ASSERT_TRUE(out.evaluation.ok()) << out.evaluation.status;
      values.push_back(out.evaluation.value);
    }
    for (std::size_t i = 1; i + 1 < values.size(); ++i)
      EXPECT_LT(std::abs(values[i + 1] - 2 * values[i] + values[i - 1]), 1e-9 * values[i]) << band_hz << " " << i;
  }
}

TEST(NoiseWeightedCost, TheErrorsInVariablesTransientsShareSaysWhetherTheForceExplainsTheResponse) {
  // The free transient terms span every mode's free decay, and so the response to a hit: with the force negated the
  // cost at the truth stays near its chi-square value, and only the share the terms take out tells (the twenty-second
  // pass's P9). Forced right, they take out a few terms' worth of 2 x 1025 unit-variance residuals (measured 1 %);
  // negated, nearly all (measured 99 %): bounds 0.1 and 0.5.
  const auto [o, clean] = hit_thin_beam();
  for (const double sign : {1.0, -1.0}) {
    fit::FitOptions signed_force = o;
    for (double& f : signed_force.experiment.force_samples_N) f *= sign;
    fit::Objective objective(signed_force, signal::add_noise(clean, 0.01, 1));
    const fit::Objective::Output out = objective.evaluate(o.start);
    ASSERT_TRUE(out.evaluation.ok()) << out.evaluation.status;
    if (sign > 0) {
      EXPECT_LT(out.evaluation.transient_share, 0.1);
    } else {
      EXPECT_GT(out.evaluation.transient_share, 0.5);
    }
  }
}

TEST(NoiseWeightedCost, AFitEstimatesTheNoiseFromItsResidualsAndWeighsByIt) {
  // AR(1) noise (a = 0.9) of 2 % of the clean RMS on the thin beam's record: the fit with noise_model "estimated"
  // runs the white fit, estimates the noise from its residuals and fits again. The time cost's AR estimate is within
  // its sampling error of 0.9 (sd about 0.005 over 4096 samples; bound 0.03), and both refits land within 3 of their
  // own standard errors of the fit given the true model (the estimate's error in the weights moves the estimate by a
  // fraction of its sd), and closer to it than the white fit is (measured on this draw: 5-25x closer on EI).
  fit::FitOptions o = thin_beam_fit(kTimeCost);
  const auto clean = thin_beam_data(o);
  const std::vector<double> data = signal::add_noise(clean, 0.02, 7, signal::parse_noise_model("ar:0.9"));
  estimate_from_mixed_offsets(o);
  for (const std::string& name : {kTimeCost, kMaxLikelihoodCost}) {
    o.cost.name = name;
    o.cost.noise_model = "ar:0.9";
    const fit::FitResult known = fit::fit(o, data);
    o.cost.noise_model = "white";
    const fit::FitResult white = fit::fit(o, data);
    o.cost.noise_model = kEstimatedNoise;
    const fit::FitResult estimated = fit::fit(o, data);
    ASSERT_EQ(estimated.status, "converged") << name << " " << estimated.termination;
    ASSERT_GE(estimated.stages.size(), 2u);
    EXPECT_EQ(estimated.stages.front().name.rfind("white noise: ", 0), 0u) << estimated.stages.front().name;
    const std::string& last = estimated.stages.back().name;
    EXPECT_NE(last.find("the noise estimated from its residuals"), std::string::npos) << last;
    if (name == kTimeCost) {
      const auto at = last.find("(ar:");
      ASSERT_NE(at, std::string::npos) << last;
      EXPECT_NEAR(std::stod(last.substr(at + 4)), 0.9, 0.03) << last;
    }
    for (std::size_t i = 0; i < known.parameters.size(); ++i) {
      const auto& k = known.parameters[i];
      const double off = std::abs(estimated.parameters[i].estimate - k.estimate);
      EXPECT_LT(off, 3 * k.standard_error) << name << " " << k.key;
      if (k.key == "EI") {
        EXPECT_LT(off, std::abs(white.parameters[i].estimate - k.estimate)) << name;
      }
    }
    // With the amplitude unknown the residual is the fitted output's, z - a y: a record 1000 times larger gives the
    // same estimate, as the white fit does, to where the optimizer stops (measured 1.2e-6 on gamma, the least
    // determined; bound 1e-5). With z - y, the response itself, the time fit took an AR(20) of the response and
    // moved EI by 1e-3 relative, 6 of its standard errors.
    fit::FitOptions scaled = o;
    scaled.cost.unknown_amplitude = true;
    std::vector<double> larger = data;
    for (double& v : larger) v *= 1000;
    const fit::FitResult as_is = fit::fit(scaled, data), enlarged = fit::fit(scaled, larger);
    for (std::size_t i = 0; i < as_is.parameters.size(); ++i)
      EXPECT_NEAR(enlarged.parameters[i].estimate / as_is.parameters[i].estimate, 1.0, 1e-5)
          << name << " " << as_is.parameters[i].key;
  }
}

}  // namespace
}  // namespace beamid::costs
