// Modal truncation (simulation/modal_truncation.h): the split at the widest gap, the identities that make both
// reductions exact (nothing discarded; damping that the undamped modes decouple), and the thin beam's damped spectrum,
// whose slow shear roots fall among the retained roots although its undamped spectrum has a gap.
#include "simulation/modal_truncation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "galerkin/modes.h"
#include "model/beam_parameters.h"
#include "model/errors.h"
#include "simulation/modal_simulator.h"

namespace beamid::simulation {
namespace {

TEST(ModalTruncation, SplitsAtTheWidestGapAboveTheBand) {
  Eigen::VectorXd omega(6);
  omega << 1, 2, 3, 30, 31, 100;
  // Above 2.5 the ratios are 10 (3 -> 30), 1.03 and 3.2: keep 1, 2, 3.
  const TruncationSplit split = widest_gap(omega, 2.5);
  EXPECT_EQ(split.retained, 3);
  EXPECT_DOUBLE_EQ(split.gap_ratio, 10.0);
  // The gap 3 -> 30 lies inside a band reaching 10: the next widest above it, 31 -> 100.
  EXPECT_EQ(widest_gap(omega, 10).retained, 5);
  // Nothing above the band: nothing is discarded.
  const TruncationSplit none = widest_gap(omega, 200);
  EXPECT_EQ(none.retained, 6);
  EXPECT_DOUBLE_EQ(none.gap_ratio, 1.0);
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

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0, size = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    size = std::max(size, std::abs(b[i]));
  }
  return diff / size;
}

// Two exact modal solutions of congruent systems (Phi^T (M, C, K) Phi against M, C, K) differ by their round-off:
// the damped eigenvectors' relative error is about eps times their condition (rcond >= 1e-6 here), so 1e-9 of max |y|
// leaves a margin of 30 over what is measured (<= 3e-11, acceleration), and a discarded or mis-coupled mode would show as
// 1e-4 (acceleration) to 1e-10 (displacement), as model_reduction.md records.
constexpr double kRoundOff = 1e-9;

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
  const Eigen::VectorXd omega = galerkin::undamped_modes(c.system).omega_rad_s;
  const TruncationSplit split = widest_gap(omega, std::acos(-1.0) / c.experiment.dt_s);
  ASSERT_LT(split.retained, omega.size());  // the shear modes lie above a gap
  for (const std::string& output : output_names().names()) {
    c.experiment.output = output;
    const ResponseProblem p = make_problem(c.forms, c.system, c.experiment);
    const Trace exact = ModalSimulator().run(c.system, p);
    const Trace decoupled = truncated_response(c.system, p, split.retained, Truncation::decoupled);
    ASSERT_TRUE(decoupled.ok()) << decoupled.status;
    EXPECT_LT(relative_difference(decoupled.y, exact.y), kRoundOff) << output;
  }
}

TEST(ModalTruncation, ThinBeamSlowShearRootsFallAmongTheRetainedRoots) {
  // The thin beam at N = 16: its undamped spectrum has a gap of more than 10x below the shear modes, but each shear
  // mode's slow root sits near -kAG / kAcs (7.6e4 1/s), inside the range of the retained block's roots.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const Case c = thin_beam(beam, 16);
  const Eigen::VectorXd omega = galerkin::undamped_modes(c.system).omega_rad_s;
  const TruncationSplit split = widest_gap(omega, std::acos(-1.0) / c.experiment.dt_s);
  EXPECT_GT(split.gap_ratio, 10.0);
  const SpectrumOverlap overlap = spectrum_overlap(c.system, split.retained);
  // The slow root of lambda^2 + tau omega^2 lambda + omega^2 = 0 is -1/tau (1 + O(1/(tau omega)^2)), tau = kAcs/kAG,
  // and (tau omega)^2 >= 2e3 for the shear modes: within 1 % of kAG / kAcs.
  const double rate = beam.kAG / beam.kAcs;
  EXPECT_NEAR(overlap.slowest_discarded_rad_s.real(), -rate, 0.01 * rate);
  EXPECT_EQ(overlap.slowest_discarded_rad_s.imag(), 0.0);
  EXPECT_LT(std::abs(overlap.slowest_discarded_rad_s), overlap.fastest_retained_rad_s);
  // The retained block's own overdamped modes (its bending modes above 2 kAG / (kAcs omega), 1.5e5 rad/s) relax at
  // 7.9e4 to 9.8e4 1/s, and its fast roots reach 1.6e6 1/s: the discarded slow roots lie inside the retained spectrum,
  // 5 % from a retained root, so the damping couples the two blocks across no gap at all.
  EXPECT_LT(overlap.nearest_retained_relative, 0.1);
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
