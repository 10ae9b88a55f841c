// The CVODE reference integrator: accuracy against an analytic solution, convergence with rtol, statistics as data,
// and failures reported as a status rather than thrown.
#include "simulation/cvode_simulator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "model/beam_parameters.h"
#include "simulation/simulator.h"
#include "test_systems.h"

namespace beamid::simulation {
namespace {

double max_error(const Trace& trace, double m, double c, double k, double x0, int derivative, double dt) {
  double error = 0, scale = 0;
  for (std::size_t i = 0; i < trace.y.size(); ++i) {
    const double exact = testing::free_decay(m, c, k, x0, derivative, i * dt);
    error = std::max(error, std::abs(trace.y[i] - exact));
    scale = std::max(scale, std::abs(exact));
  }
  return error / scale;
}

TEST(CvodeSimulator, FreeDecayConvergesWithTolerance) {
  // BDF's global error on an oscillation is roughly proportional to rtol times the accumulated number of steps
  // (measured 170 rtol at 1e-8 and 280 rtol at 1e-10 over these 16 periods): require 1e-5 and 1e-7, 20x apart.
  const double m = 2.0, c = 0.7, k = 5000.0, x0 = 0.01;
  const auto s = testing::oscillator(m, c, k);
  for (int derivative : {0, 1, 2}) {
    const auto p = testing::release(x0, derivative, 1e-3, 2000);
    CvodeOptions loose, tight;
    loose.rtol = 1e-8;
    tight.rtol = 1e-10;
    const Trace a = CvodeSimulator(loose).run(s, p);
    const Trace b = CvodeSimulator(tight).run(s, p);
    ASSERT_TRUE(a.ok() && b.ok()) << a.status << b.status;
    const double ea = max_error(a, m, c, k, x0, derivative, p.dt_s);
    const double eb = max_error(b, m, c, k, x0, derivative, p.dt_s);
    EXPECT_LT(ea, 1e-5) << "derivative " << derivative;
    EXPECT_LT(eb, 1e-7) << "derivative " << derivative;
    EXPECT_LT(eb, ea / 20) << "derivative " << derivative;
    EXPECT_GT(b.stats.steps, a.stats.steps);
    EXPECT_GT(b.stats.rhs_evaluations, b.stats.steps);
    EXPECT_GE(b.stats.linear_solver_setups, 1);
  }
}

TEST(CvodeSimulator, StructuredAndDenseNewtonSolversAgree) {
  // Both solve the same BDF equations; they differ only in how Newton's linear systems are solved (exact
  // Schur-complement Cholesky vs SUNDIALS dense LU with a Jacobian it may keep for several steps), which moves the
  // result within the tolerance: 1e-6 of max |y| at rtol 1e-8 (the free-decay error above is ~2e-6 at most).
  const double m = 2.0, c = 0.7, k = 5000.0, x0 = 0.01;
  const auto s = testing::oscillator(m, c, k);
  const auto p = testing::release(x0, 2, 1e-3, 500);
  CvodeOptions structured, dense;
  structured.rtol = dense.rtol = 1e-8;
  dense.linear_solver = "dense";
  const Trace a = CvodeSimulator(structured).run(s, p), b = CvodeSimulator(dense).run(s, p);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(b.stats.integrator, "cvode.dense");
  EXPECT_GE(b.stats.jacobian_evaluations, 1);
  EXPECT_LT(testing::relative_difference(a.y, b.y), 1e-6);
}

TEST(CvodeSimulator, FailureIsAStatusNotAnException) {
  // One step allowed per sample interval cannot cover 1 ms of a 11 Hz oscillator at rtol 1e-10.
  const auto s = testing::oscillator(2.0, 0.7, 5000.0);
  CvodeOptions options;
  options.max_steps_per_sample = 1;
  const Trace t = CvodeSimulator(options).run(s, testing::release(0.01, 0, 1e-3, 100));
  EXPECT_FALSE(t.ok());
  EXPECT_NE(t.status.find("CV_TOO_MUCH_WORK"), std::string::npos) << t.status;
}

TEST(CvodeSimulator, AStepBudgetStopsTheRunWithTheSamplesItReached) {
  // An oscillator of 11 Hz over 500 samples of 1 ms takes some hundreds of steps at rtol 1e-10; a budget of 50 stops
  // it early, with a status that says where, and y holds exactly the samples reached, each equal to the unbudgeted
  // run's (the same steps up to there: to round-off, 1e-12 of max |y|).
  const auto s = testing::oscillator(2.0, 0.7, 5000.0);
  const auto p = testing::release(0.01, 0, 1e-3, 500);
  CvodeOptions budgeted;
  budgeted.max_total_steps = 50;
  const Trace whole = CvodeSimulator(CvodeOptions{}).run(s, p), cut = CvodeSimulator(budgeted).run(s, p);
  ASSERT_TRUE(whole.ok()) << whole.status;
  ASSERT_GT(whole.stats.steps, 50);
  EXPECT_FALSE(cut.ok());
  EXPECT_NE(cut.status.find("stopped at its budget of 50 steps after " + std::to_string(cut.y.size()) + " of 500"),
            std::string::npos)
      << cut.status;
  ASSERT_GT(cut.y.size(), 1u);
  ASSERT_LT(cut.y.size(), 500u);
  EXPECT_GE(cut.stats.steps, 50);
  const double peak = 0.01;
  for (std::size_t i = 0; i < cut.y.size(); ++i) EXPECT_NEAR(cut.y[i], whole.y[i], 1e-12 * peak) << i;
  // A budget the run stays within changes nothing.
  budgeted.max_total_steps = whole.stats.steps + 1;
  const Trace within = CvodeSimulator(budgeted).run(s, p);
  EXPECT_TRUE(within.ok()) << within.status;
  EXPECT_EQ(within.y, whole.y);
}

TEST(CvodeSimulator, ANarrowPulseIsIntegratedToItsOwnSize) {
  // A pulse far shorter than the beam's period moves it by its impulse, omega tau / 2 of the static deflection; with
  // tolerances sized to the static deflection CVODE was 1.9e-4 of the peak off at tau = 1e-8 s (acceleration, 125 %
  // at 1e-12 s: the fifteenth pass's P2). Against the exact modal solution (the fast integrator) at the default rtol
  // 1e-10, now within 1e-6 of the peak, the bound AgreesWithCvodeOnPresets allows for ordinary pulses, 10x.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(6);
  const galerkin::BeamForms forms(space, beam.l);
  Experiment e;
  e.dt_s = 1e-3;
  e.samples = 512;
  e.force_x_m = 0.7 * beam.l;
  e.output = "acceleration";
  for (const double tau : {1e-8, 1e-12}) {
    e.pulse_width_s = tau;
    SimulatorOptions cvode;
    cvode.integrator = kCvode;
    const Trace exact = simulate(forms, beam, e, {}), stepped = simulate(forms, beam, e, cvode);
    ASSERT_TRUE(exact.ok() && stepped.ok()) << stepped.status;
    EXPECT_LT(testing::relative_difference(stepped.y, exact.y), 1e-6) << tau;
  }
}

TEST(CvodeSimulator, ZeroInputGivesZeroResponse) {
  const auto s = testing::oscillator(2.0, 0.7, 5000.0);
  const Trace t = CvodeSimulator(CvodeOptions{}).run(s, testing::release(0.0, 0, 1e-3, 10));
  ASSERT_TRUE(t.ok());
  for (double y : t.y) EXPECT_EQ(y, 0.0);
}

}  // namespace
}  // namespace beamid::simulation
