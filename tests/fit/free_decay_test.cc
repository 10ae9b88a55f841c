// Free decay with an unknown initial state: the closed-form amplitudes reproduce a sum of damped modes exactly, and
// a fit over physical parameters alone recovers them from a record cut after the excitation.
#include "simulation/free_decay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "central_difference.h"
#include "core/errors.h"
#include "fit/identification.h"
#include "fit/objective.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "simulation/simulator.h"
#include "study/tables/overlay.h"

namespace beamid {
namespace {

TEST(FreeDecay, ClosedFormAmplitudesReproduceDampedModes) {
  const double dt = 1e-3;
  const std::vector<std::complex<double>> poles{{-0.3, 2 * std::numbers::pi * 5},
                                                {-1.5, 2 * std::numbers::pi * 40},
                                                {-2.0, 2 * std::numbers::pi * 700}};  // the last is above Nyquist
  std::vector<double> z(2000);
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double t = static_cast<double>(i) * dt;
    z[i] = 0.01 + 2 * std::exp(-0.3 * t) * std::cos(2 * std::numbers::pi * 5 * t + 0.4) +
           0.5 * std::exp(-1.5 * t) * std::sin(2 * std::numbers::pi * 40 * t);
  }
  const auto fit = simulation::fit_free_decay(poles, dt, z);
  ASSERT_EQ(fit.status, "ok");
  ASSERT_EQ(fit.poles_rad_s.size(), 2u);  // 700 Hz is above the 500 Hz Nyquist frequency: left out
  double worst = 0;
  for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(fit.y[i] - z[i]));
  // An exact model: the least-squares residual is round-off (columns of order one, 2000 rows).
  EXPECT_LT(worst, 1e-11);
  EXPECT_NEAR(fit.amplitudes[0], 0.01, 1e-12);               // offset
  EXPECT_NEAR(fit.amplitudes[1], 2 * std::cos(0.4), 1e-11);  // a_1 = 2 cos(phase), b_1 = -2 sin(phase)
  EXPECT_NEAR(fit.amplitudes[2], -2 * std::sin(0.4), 1e-11);
  // A pole given twice gives two equal column pairs: the semi-normal equations step aside (their Gram matrix is
  // singular) and the pivoted QR names the deficient rank, as it did alone.
  const std::vector<std::complex<double>> twins{poles[0], poles[0], poles[1]};
  EXPECT_NE(simulation::fit_free_decay(twins, dt, z).status.find("rank-deficient"), std::string::npos);
  EXPECT_THROW(simulation::fit_free_decay(poles, 0, z), InputError);
  EXPECT_NE(simulation::fit_free_decay({{-1, 2 * std::numbers::pi * 900}}, dt, z).status, "ok");
}

TEST(FreeDecay, ALinearTrendIsFittedBesideTheConstantWhenAsked) {
  // A sensor that drifts: 0.5 + 0.3 t under two damped modes (the eighteenth pass's P5). With the trend column the
  // synthesis is exact to round-off and the amplitudes are the modes' own; without it the drift is left in the
  // residual (its largest part, 0.3 t against the modes' 1e-11), and the modes' amplitudes absorb some of it.
  const double dt = 1e-3;
  const std::vector<std::complex<double>> poles{{-0.3, 2 * std::numbers::pi * 5}, {-1.5, 2 * std::numbers::pi * 40}};
  std::vector<double> z(2000);
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double t = static_cast<double>(i) * dt;
    z[i] = 0.5 + 0.3 * t + 2 * std::exp(-0.3 * t) * std::cos(2 * std::numbers::pi * 5 * t + 0.4) +
           0.5 * std::exp(-1.5 * t) * std::sin(2 * std::numbers::pi * 40 * t);
  }
  const auto with = simulation::fit_free_decay(poles, dt, z, true);
  ASSERT_EQ(with.status, "ok");
  double worst = 0;
  for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(with.y[i] - z[i]));
  EXPECT_LT(worst, 1e-11);
  EXPECT_NEAR(with.amplitudes[0], 0.5, 1e-11);
  EXPECT_NEAR(with.amplitudes[1], 0.3 * 1999 * dt, 1e-11);  // c1 multiplies t / T, T = (n - 1) dt
  EXPECT_NEAR(with.amplitudes[2], 2 * std::cos(0.4), 1e-10);
  const auto without = simulation::fit_free_decay(poles, dt, z);
  double left = 0;
  for (std::size_t i = 0; i < z.size(); ++i) left = std::max(left, std::abs(without.y[i] - z[i]));
  EXPECT_GT(left, 0.05);  // a line of 0.6 across the record, fitted by a constant and two decaying modes
}

TEST(FreeDecay, FitRecoversStiffnessAndDampingFromARecordCutAfterTheImpulse) {
  // banks-aluminium at N = 8: a 4 ms pulse, velocity at the tip; the record kept from t = 0.1 s on is a free decay
  // whose initial state the fit does not know. Data and model share N and the exact propagator (this checks the
  // closed-form amplitudes and the search, not discretisation), so the recovery is limited by the optimizer's
  // tolerance: 1e-6 relative is asked, far above it.
  const model::BeamParameters truth = model::preset("banks-aluminium");
  simulation::Experiment pulse;
  pulse.dt_s = 1e-3;
  pulse.samples = 4096;
  pulse.pulse_width_s = 0.004;
  pulse.force_x_m = 0.32;
  pulse.output = "velocity";
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, truth.l);
  const auto trace = simulation::simulate(forms, truth, pulse, {});
  ASSERT_TRUE(trace.ok());
  const std::vector<double> data(trace.y.begin() + 100, trace.y.end());

  for (const std::string cost : {"time", "spike-smooth"}) {
    fit::FitOptions o;
    o.elements = 8;
    o.experiment.excitation = "free-decay";
    o.experiment.dt_s = 1e-3;
    o.experiment.samples = static_cast<int>(data.size());
    o.cost.name = cost;
    o.cost.spikes.frequencies_hz = {2.46, 26.6, 81.8};
    o.cost.spikes.count = 3;
    o.optimizer.method = "lm";
    o.start = truth;
    o.start.EI *= 1.03;
    o.start.cDI *= 0.9;
    o.start.gamma *= 1.1;
    for (const char* key : {"EI", "cDI", "gamma"}) {
      const double v = truth.*(model::find_parameter(key)->member);
      o.estimate.push_back({key, v / 2, v * 2});
    }
    const fit::FitResult r = fit::fit(o, data);
    ASSERT_NE(r.status, "failed") << cost << ": " << r.termination;
    for (const auto& p : r.parameters) {
      const double v = truth.*(model::find_parameter(p.key)->member);
      EXPECT_NEAR(p.estimate / v, 1, 1e-6) << cost << " " << p.key;
    }
  }
}

TEST(FreeDecay, TheModalCostTakesTheExactPoleJacobianAndNoSynthesis) {
  // A free decay's poles are the model's whatever its unknown amplitudes, so the modal cost's residuals and their
  // exact Jacobian (eigenvalue derivatives) hold as for a simulated record, and the least-squares synthesis of y,
  // which the cost never reads, is skipped during the search (left empty) and computed on request for the report.
  // The Jacobian matches central differences of the residuals to 1e-5 relative: steps of 1e-5 relative, whose
  // truncation error is ~1e-10 relative and whose rounding, residuals of ~1e-3 computed to ~1e-13, is ~1e-8.
  const model::BeamParameters truth = model::preset("banks-aluminium");
  simulation::Experiment pulse;
  pulse.dt_s = 1e-3;
  pulse.samples = 4096;
  pulse.pulse_width_s = 0.004;
  pulse.force_x_m = 0.32;
  pulse.output = "velocity";
  const galerkin::SplineSpace space(8);
  const auto trace = simulation::simulate(galerkin::BeamForms(space, truth.l), truth, pulse, {});
  ASSERT_TRUE(trace.ok());
  const std::vector<double> data(trace.y.begin() + 100, trace.y.end());
  fit::FitOptions o;
  o.elements = 8;
  o.experiment.excitation = "free-decay";
  o.experiment.dt_s = 1e-3;
  o.experiment.samples = static_cast<int>(data.size());
  o.cost.name = "modal";
  o.cost.spikes.count = 3;
  o.start = truth;
  o.start.EI *= 1.02;
  o.estimate = {{"EI", truth.EI / 2, truth.EI * 2}, {"cDI", truth.cDI / 2, truth.cDI * 2}};
  fit::Objective objective(o, data);
  ASSERT_TRUE(objective.has_exact_jacobian());
  EXPECT_TRUE(objective.evaluate(o.start).y.empty());
  EXPECT_EQ(objective.evaluate(o.start, fit::Objective::Response::always).y.size(), data.size());
  // A study's overlay shows the model's output, and no spikes for a cost that has none (its pairs, the identified
  // modes, have no bin: spikes.csv listed them all at 0 Hz, the fifteenth pass's P3).
  const study::Overlay overlay = study::compute_overlay(o, data, o.start);
  EXPECT_TRUE(overlay.spike_bins.empty());
  EXPECT_TRUE(std::isfinite(overlay.model.back()));
  Eigen::MatrixXd jacobian;
  const auto at = objective.evaluate_with_jacobian(o.start, {"EI", "cDI"}, jacobian);
  ASSERT_TRUE(at.evaluation.ok()) << at.evaluation.status;
  ASSERT_EQ(jacobian.cols(), 2);
  for (int q = 0; q < 2; ++q) {
    const Eigen::VectorXd difference =
        fit::testing::residual_central_difference(objective, o.start, q == 0 ? "EI" : "cDI");
    EXPECT_LT((jacobian.col(q) - difference).norm(), 1e-5 * difference.norm()) << q;
  }
}

TEST(FreeDecay, CannotBeSimulated) {
  simulation::Experiment e;
  e.excitation = "free-decay";
  const model::BeamParameters b = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(4);
  const galerkin::BeamForms forms(space, b.l);
  EXPECT_THROW(simulation::simulate(forms, b, e, {}), InputError);
}

}  // namespace
}  // namespace beamid
