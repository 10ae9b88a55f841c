// Modal truncation (simulation/modal_truncation.h): the split at the widest gap, the identities that make both
// reductions exact (nothing discarded; damping that the undamped modes decouple), and the thin beam's damped spectrum,
// whose slow shear roots fall among the retained roots although its undamped spectrum has a gap.
#include "simulation/modal_truncation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "model/beam_parameters.h"
#include "simulation/modal_simulator.h"
#include "test_systems.h"

namespace beamid::simulation {
namespace {

TEST(ModalTruncation, SplitsAtTheWidestGapAboveTheBand) {
  Eigen::VectorXd omega_rad_s(6);
  omega_rad_s << 1, 2, 3, 30, 31, 100;
  // Above 2.5 the ratios are 10 (3 -> 30), 1.03 and 3.2: keep 1, 2, 3.
  const TruncationSplit split = widest_gap(omega_rad_s, 2.5);
  EXPECT_EQ(split.retained, 3);
  EXPECT_DOUBLE_EQ(split.gap_ratio, 10.0);
  // The gap 3 -> 30 lies inside a band reaching 10: the next widest above it, 31 -> 100.
  EXPECT_EQ(widest_gap(omega_rad_s, 10).retained, 5);
  // Nothing above the band: nothing is discarded.
  const TruncationSplit none = widest_gap(omega_rad_s, 200);
  EXPECT_EQ(none.retained, 6);
  EXPECT_DOUBLE_EQ(none.gap_ratio, 1.0);
  EXPECT_THROW(widest_gap(Eigen::VectorXd(), 1.0), InputError);
}

struct Case {
  galerkin::BeamForms forms;
  galerkin::SecondOrderSystem system;
  Experiment experiment;
};

Case thin_beam(const model::BeamParameters& beam, int elements) {
  const galerkin::SplineSpace space(elements);
  galerkin::BeamForms forms(space, beam.l);
  Experiment e;
  e.dt_s = 1e-4;
  e.samples = 2048;
  e.pulse_width_s = 4e-3;
  e.force_x_m = 0.7 * beam.l;
  return {forms, galerkin::combine(forms, beam), e};
}

using testing::relative_difference;

// Two exact modal solutions of congruent systems (Phi^T (M, C, K) Phi against M, C, K, or a mode's oscillator against
// the same mode inside the decoupled system) differ by their round-off, measured <= 3e-11 of max |y| here
// (acceleration); 1e-9 leaves a margin of 30 and is still 100x below the 1e-7 the forward run is held to.
constexpr double kRoundOff = 1e-9;
// C~ = Phi^T C Phi of Rayleigh damping is diagonal but for round-off, measured 4e-14 against sqrt(C~_ii C~_jj) here;
// the thin beam's own damping couples its blocks by 3e-6 at the preset (N = 8) and 4e-3 with cDI 30 % low.
constexpr double kCouplingRoundOff = 1e-10;

TEST(ModalTruncation, NothingDiscardedIsTheExactResponse) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  Case c = thin_beam(beam, 8);
  const auto n = static_cast<int>(c.system.M.rows());
  for (const std::string& output : output_names().names()) {
    c.experiment.output = output;
    const ResponseProblem p = make_problem(c.forms, c.system, c.experiment);
    const Trace exact = ModalSimulator().run(c.system, p);
    for (Truncation kind : {Truncation::truncated, Truncation::decoupled}) {
      const Trace reduced = truncated_response(c.system, p, n, kind);
      ASSERT_TRUE(reduced.ok()) << reduced.status;
      EXPECT_LT(relative_difference(reduced.y, exact.y), kRoundOff) << output;
    }
  }
}

TEST(ModalTruncation, DecouplingIsExactForDampingTheUndampedModesDiagonalise) {
  // C = a M + b K (Rayleigh damping) is diagonal in the undamped basis: the decoupled reduction drops nothing, at any
  // split, for every output. a and b are the thin beam's own rates gamma / rho and kAcs / kAG.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  Case c = thin_beam(beam, 8);
  c.system.C = (beam.gamma / beam.rho) * c.system.M + (beam.kAcs / beam.kAG) * c.system.K;
  const Eigen::VectorXd omega_rad_s = galerkin::undamped_modes(c.system).omega_rad_s;
  const TruncationSplit split = widest_gap(omega_rad_s, std::acos(-1.0) / c.experiment.dt_s);
  ASSERT_LT(split.retained, omega_rad_s.size());  // the shear modes lie above a gap
  // No coupling but the congruence's round-off.
  EXPECT_LT(truncation_diagnostics(c.system, split.retained).coupling_relative, kCouplingRoundOff);
  for (const std::string& output : output_names().names()) {
    c.experiment.output = output;
    const ResponseProblem p = make_problem(c.forms, c.system, c.experiment);
    const Trace exact = ModalSimulator().run(c.system, p);
    const Trace decoupled = truncated_response(c.system, p, split.retained, Truncation::decoupled);
    ASSERT_TRUE(decoupled.ok()) << decoupled.status;
    EXPECT_LT(relative_difference(decoupled.y, exact.y), kRoundOff) << output;
  }
}

TEST(ModalTruncation, DecoupledKeepsEachDiscardedModeAsItsOwnOscillator) {
  // Load and sensor M phi_j act on mode j alone (phi_k^T M phi_j = delta_kj, up to round-off): under `decoupled` a
  // discarded mode j then answers as the oscillator m q'' + c q' + k q = m P(t), y = m q, with m, c, k = phi_j^T (M, C,
  // K) phi_j, whatever the damping couples elsewhere, and under `truncated` not at all. The thin beam with cDI 30 %
  // low, whose blocks the damping couples.
  model::BeamParameters beam = model::preset("banks-aluminium");
  beam.cDI *= 0.7;
  Case c = thin_beam(beam, 8);
  const galerkin::UndampedModes modes = galerkin::undamped_modes(c.system);
  const TruncationSplit split = widest_gap(modes.omega_rad_s, std::acos(-1.0) / c.experiment.dt_s);
  const auto n = static_cast<int>(modes.omega_rad_s.size());
  ASSERT_LT(split.retained, n);
  EXPECT_GT(truncation_diagnostics(c.system, split.retained).coupling_relative, 1e-3);
  for (int j : {split.retained, n - 1}) {
    const Eigen::VectorXd phi = modes.shapes.col(j), modal = c.system.M * phi;
    const double m = phi.dot(modal);
    const galerkin::SecondOrderSystem oscillator{Eigen::MatrixXd::Constant(1, 1, m),
                                                 Eigen::MatrixXd::Constant(1, 1, phi.dot(c.system.C * phi)),
                                                 Eigen::MatrixXd::Constant(1, 1, phi.dot(c.system.K * phi))};
    for (const std::string& output : output_names().names()) {
      c.experiment.output = output;
      ResponseProblem p = make_problem(c.forms, c.system, c.experiment);
      p.load = modal;
      p.sensor = modal;
      ResponseProblem one = p;
      one.load = one.sensor = Eigen::VectorXd::Constant(1, m);
      one.w0 = Eigen::VectorXd::Zero(1);
      const Trace expected = ModalSimulator().run(oscillator, one);
      const Trace decoupled = truncated_response(c.system, p, split.retained, Truncation::decoupled);
      const Trace truncated = truncated_response(c.system, p, split.retained, Truncation::truncated);
      ASSERT_TRUE(expected.ok() && decoupled.ok() && truncated.ok())
          << expected.status << decoupled.status << truncated.status << output << j;
      // A stiff mode's acceleration is the small difference of its direct term m P(t) and its modal sum (about
      // P'' / omega^2), so its round-off is relative to m max P, not to max |y| (measured 1.7e-8 of max |y| for mode
      // 11 here, 6e-16 of m max P).
      double largest = 0;
      for (double v : expected.y) largest = std::max(largest, std::abs(v));
      if (output == kAcceleration) largest = std::max(largest, m * std::abs(p.amplitude_N));
      double worst = 0;
      for (std::size_t i = 0; i < expected.y.size(); ++i)
        worst = std::max(worst, std::abs(decoupled.y[i] - expected.y[i]));
      EXPECT_LT(worst, kRoundOff * largest) << "mode " << j << " " << output;
      // Nothing of mode j is retained: only round-off of the other modes' components of M phi_j is left.
      for (double v : truncated.y) EXPECT_LT(std::abs(v), kRoundOff * largest) << "mode " << j << " " << output;
    }
  }
}

TEST(ModalTruncation, ThinBeamSlowShearRootsFallAmongTheRetainedRoots) {
  // The thin beam at N = 16: its undamped spectrum has a gap of more than 10x below the shear modes, but each shear
  // mode's slow root sits near -kAG / kAcs (7.6e4 1/s), inside the range of the retained block's roots.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const Case c = thin_beam(beam, 16);
  const Eigen::VectorXd omega_rad_s = galerkin::undamped_modes(c.system).omega_rad_s;
  const TruncationSplit split = widest_gap(omega_rad_s, std::acos(-1.0) / c.experiment.dt_s);
  EXPECT_GT(split.gap_ratio, 10.0);
  const TruncationDiagnostics d = truncation_diagnostics(c.system, split.retained);
  // The slow root of lambda^2 + tau omega^2 lambda + omega^2 = 0 is -1/tau (1 + O(1/(tau omega)^2)), tau = kAcs/kAG,
  // and (tau omega)^2 >= 2e3 for the shear modes: within 1 % of kAG / kAcs.
  const double rate_per_s = beam.kAG / beam.kAcs;
  EXPECT_NEAR(d.slowest_discarded_rad_s.real(), -rate_per_s, 0.01 * rate_per_s);
  EXPECT_EQ(d.slowest_discarded_rad_s.imag(), 0.0);
  EXPECT_LT(std::abs(d.slowest_discarded_rad_s), d.fastest_retained_rad_s);
  // The retained block's own overdamped modes (its bending modes with tau omega > 2, omega > 2 EI/cDI = 1.5e5 rad/s)
  // relax at 7.9e4 to 9.8e4 1/s, and its fast roots reach 1.6e6 1/s: the discarded slow roots lie inside the retained
  // spectrum, 5 % from a retained root, so there is no gap in the damped spectrum across which the coupling acts.
  EXPECT_LT(d.nearest_retained_relative, 0.1);
}

TEST(ModalTruncation, RejectsAnInitialDisplacementAndABadSplit) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  Case c = thin_beam(beam, 4);
  ResponseProblem p = make_problem(c.forms, c.system, c.experiment);
  EXPECT_THROW(truncated_response(c.system, p, 0, Truncation::truncated), InputError);
  EXPECT_THROW(truncated_response(c.system, p, static_cast<int>(c.system.M.rows()) + 1, Truncation::decoupled),
               InputError);
  p.w0 = Eigen::VectorXd::Ones(p.load.size());
  EXPECT_THROW(truncated_response(c.system, p, 2, Truncation::truncated), InputError);
}

}  // namespace
}  // namespace beamid::simulation
