// The modal cost (costs/modal_cost.h): modal updating recovers the beam from its own identified modes, and a record
// without enough modes is refused.
#include "costs/modal_cost.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "fit/identification.h"
#include "fit/objective.h"
#include "signal/measured_modes.h"
#include "signal/noise.h"
#include "thin_beam_fit.h"

namespace beamid::costs {
namespace {

fit::FitOptions modal_fit() {
  fit::FitOptions o = thin_beam_fit(kModalCost);
  o.cost.spikes.count = 3;
  return o;
}

TEST(ModalCost, UpdatingRecoversTheBeamFromItsIdentifiedModes) {
  // Noise-free data from the same model (N = 8, fast): the matrix pencil gives modes 1-3 to round-off (its own
  // tests), so fitting EI, cDI and gamma to their frequencies and decay rates returns the truth to 1e-6 from 5 % off
  // (frequencies 2.5 % off: pairing by frequency still finds every partner).
  const auto truth = model::preset("banks-aluminium");
  fit::FitOptions o = modal_fit();
  const auto data = thin_beam_data(o);  // from the truth, before the start moves
  for (const char* key : {"EI", "cDI", "gamma"}) {
    double& v = o.start.*(model::find_parameter(key)->member);
    o.estimate.push_back({key, v / 2, v * 2});
    v *= 1.05;
  }
  const fit::FitResult r = fit::fit(o, data);
  EXPECT_EQ(r.status, "converged") << r.termination;
  for (const auto& p : r.parameters)
    EXPECT_NEAR(p.estimate / (truth.*(model::find_parameter(p.key)->member)), 1.0, 1e-6) << p.key;
  ASSERT_EQ(r.final_evaluation.pairs.size(), 3u);
  EXPECT_NEAR(r.final_evaluation.pairs[0].model_frequency_hz / r.final_evaluation.pairs[0].data_frequency_hz, 1.0,
              1e-9);
}

TEST(ModalCost, ContinuationSkipsTheHeadsTooShortForTheModes) {
  // The seventh pass's G19: record-length continuation builds the cost on the first Nbar/16 ... Nbar/2 samples, and
  // the modal cost refused the first head (too short to show 3 modes), failing a fit whose whole record shows them.
  // Such a head is a skipped stage with its reason. With 1 % noise the first head (64 ms) shows too few modes.
  const auto truth = model::preset("banks-aluminium");
  fit::FitOptions o = modal_fit();
  o.experiment.samples = 1024;  // the first head, 64 samples (64 ms), holds a sixth of mode 1's period
  const auto data = signal::add_noise(thin_beam_data(o), 0.01, 3);
  o.strategy = fit::kContinuation;
  o.estimate.push_back({"EI", truth.EI / 2, truth.EI * 2});
  o.start.EI *= 1.03;
  const fit::FitResult r = fit::fit(o, data);
  EXPECT_EQ(r.status, "converged") << r.termination;
  // Its last stage is the whole record's from a start near the direct fit's minimum: the same minimum (1e-6: two
  // starts stop 2e-8 apart, each where Levenberg-Marquardt's step falls below tolerance; the noise moves EI by 5e-5).
  fit::FitOptions direct = o;
  direct.strategy = fit::kDirect;
  EXPECT_NEAR(r.parameters[0].estimate / fit::fit(direct, data).parameters[0].estimate, 1.0, 1e-6);
  EXPECT_NEAR(r.parameters[0].estimate / truth.EI, 1.0, 1e-3);
  ASSERT_FALSE(r.stages.empty());
  EXPECT_EQ(r.stages.front().result.status, "skipped");
  EXPECT_NE(r.stages.front().result.termination.find("too short for the cost"), std::string::npos);
}

TEST(ModalCost, RefusesARecordWithTooFewModes) {
  fit::FitOptions o = modal_fit();
  const auto data = thin_beam_data(o);
  CostOptions c = o.cost;
  c.spikes.max_frequency_hz = 10;  // only mode 1 (2.46 Hz) lies below 10 Hz
  EXPECT_THROW(make_cost(c, data, 1e-3), InputError);
  c.spikes.max_frequency_hz = 120;
  c.spikes.count = 2;
  c.spikes.frequencies_hz = {2.46, 26.6};  // chosen modes: found within 5 %
  EXPECT_EQ(make_cost(c, data, 1e-3)->residual_count(), 4);
  c.spikes.frequencies_hz = {2.46, 50.0};  // no mode near 50 Hz
  EXPECT_THROW(make_cost(c, data, 1e-3), InputError);
}

TEST(ModalCost, AHeavilyDampedPoleIsNoModeToPairWith) {
  // The sixth pass's S212: a strong pole of zeta 0.83 (the excitation's) was among the three strongest, paired with
  // the beam's third mode, and EI came out 2.4 % off. Added here to the thin beam's noise-free record at 447 Hz with
  // 50 times the record's largest value (its energy, 2500 max|y|^2, exceeds any mode's, at most 512 max|y|^2 over 1024
  // samples): the cost's three data modes are still the beam's (2.46, 26.6, 85.6 Hz within 0.1 %, the record's own
  // pencil accuracy being 1e-9), and with only one lightly damped mode below 10 Hz the refusal counts the pole it left
  // out.
  fit::FitOptions o = modal_fit();
  std::vector<double> data = thin_beam_data(o);
  double largest = 0;
  for (const double v : data) largest = std::max(largest, std::abs(v));
  const double w = 2 * std::numbers::pi * 447, zeta = 0.83;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double t = 1e-3 * static_cast<double>(i);
    data[i] += 50 * largest * std::exp(-zeta * w * t) * std::cos(w * std::sqrt(1 - zeta * zeta) * t);
  }
  CostOptions c = o.cost;
  c.spikes.max_frequency_hz = 500;
  const auto cost = make_cost(c, data, 1e-3);
  ASSERT_EQ(cost->data_spikes().size(), 3u);
  const double expected[] = {2.4637, 26.618, 85.631};  // beamid modes, N = 8
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(cost->data_spikes()[static_cast<std::size_t>(k)].data_frequency_hz / expected[k], 1, 1e-3) << k;
}

TEST(ModalCost, ExactJacobianEqualsCentralDifferencesOfItsResiduals) {
  // The fit's Jacobian of the modal residuals (eigenvalue derivatives through the cost's map) against central
  // differences of the residuals at a relative step h = 1e-4, away from the truth (EI 3 % up, gamma 10 % down), where
  // the residuals are of order 1e-2. Per unit relative change of the parameter the entries are of order 1 for the
  // frequencies and 1e-3 for the decay rates; the difference's truncation is O(h^2) = 1e-8 and its round-off the
  // eigenvalues' error (~2e-11 relative, StateSpaceModes.EigenvalueDerivativesEqualCentralDifferences) over h, 2e-7:
  // 1e-6 is the bound.
  fit::FitOptions o = modal_fit();
  const auto data = thin_beam_data(o);
  fit::Objective objective(o, data);
  ASSERT_TRUE(objective.has_exact_jacobian());
  model::BeamParameters at = o.start;
  at.EI *= 1.03, at.gamma *= 0.9;
  const std::vector<std::string> keys = {"EI", "rho", "cDI", "gamma"};
  Eigen::MatrixXd jacobian;
  const auto out = objective.evaluate_with_jacobian(at, keys, jacobian);
  ASSERT_TRUE(out.evaluation.ok()) << out.evaluation.status;
  ASSERT_EQ(jacobian.rows(), objective.cost().residual_count());
  EXPECT_EQ(out.evaluation.residuals, objective.evaluate(at).evaluation.residuals);  // the same evaluation
  for (std::size_t q = 0; q < keys.size(); ++q) {
    double& v = at.*(model::find_parameter(keys[q])->member);
    const double value = v, h = 1e-4 * value;
    v = value + h;
    const Eigen::VectorXd plus = objective.evaluate(at).evaluation.residuals;
    v = value - h;
    const Eigen::VectorXd minus = objective.evaluate(at).evaluation.residuals;
    v = value;
    const Eigen::VectorXd numeric = (plus - minus) / (2 * h);
    EXPECT_LT((jacobian.col(static_cast<Eigen::Index>(q)) - numeric).cwiseAbs().maxCoeff() * value, 1e-6) << keys[q];
  }
}

TEST(ModalCost, MeasuredWeightDividesEachModeByItsMeasuredUncertainty) {
  // mode_weight "measured" (costs/modal_cost.h): a model whose pole l lies exactly u_l above the data's natural
  // frequency (u_l the measured frequency's uncertainty, signal/measure_modes on the same record and options) and has
  // its decay rate gives residual 1 for that frequency and 0 for the decay rate; "relative" gives 2 pi u_l / |lambda|.
  // The record: the thin beam's with 1 % noise, so that u is the noise's Cramér-Rao bound and its drift, not
  // round-off. Tolerance 1e-9: the residual is one subtraction of numbers of |lambda| over 2 pi u (~1e-5 |lambda|).
  fit::FitOptions o = modal_fit();
  const auto data = signal::add_noise(thin_beam_data(o), 0.01, 5);
  CostOptions c = o.cost;
  c.mode_weight = kMeasuredModeWeight;
  const auto measured = make_cost(c, data, 1e-3);
  const auto relative = make_cost(o.cost, data, 1e-3);
  signal::MeasureOptions m;
  m.pencil.modes = 3;
  m.pencil.min_frequency_hz = c.spikes.min_frequency_hz;
  m.pencil.max_frequency_hz = c.spikes.max_frequency_hz;
  const signal::MeasuredModes modes = signal::measure_modes(data, 1e-3, m);
  ASSERT_EQ(modes.modes.size(), 3u);
  std::vector<std::complex<double>> poles;
  for (const auto& mode : modes.modes) {
    const double magnitude = std::abs(mode.mode.lambda) + 2 * std::numbers::pi * mode.uncertainty_hz;
    const double re = mode.mode.lambda.real();
    poles.emplace_back(re, std::sqrt(magnitude * magnitude - re * re));
  }
  const Evaluation e = measured->evaluate(ModelResponse{data, poles});
  const Evaluation r = relative->evaluate(ModelResponse{data, poles});
  ASSERT_TRUE(e.ok()) << e.status;
  for (Eigen::Index l = 0; l < 3; ++l) {
    const auto& mode = modes.modes[static_cast<std::size_t>(l)];
    EXPECT_GT(mode.uncertainty_hz, 0);
    EXPECT_NEAR(e.residuals(2 * l), 1, 1e-9) << l;
    EXPECT_NEAR(e.residuals(2 * l + 1), 0, 1e-9) << l;
    EXPECT_NEAR(r.residuals(2 * l) / (2 * std::numbers::pi * mode.uncertainty_hz / std::abs(mode.mode.lambda)), 1, 1e-9)
        << l;
  }
  EXPECT_NE(measured->weights().find("measured uncertainty"), std::string::npos);
}

}  // namespace
}  // namespace beamid::costs
