// M, K, C of the Galerkin system: structure, definiteness, linearity in the parameters, and convergence of the
// undamped frequencies to the exact Timoshenko ones (model.md sections 2 and 6).
#include "galerkin/second_order_system.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "model/exact_frequencies.h"

namespace beamid::galerkin {
namespace {

using model::BeamParameters;

double asymmetry(const Eigen::MatrixXd& a) {
  return (a - a.transpose()).cwiseAbs().maxCoeff() / a.cwiseAbs().maxCoeff();
}

TEST(SecondOrderSystem, SymmetricAndDefinite) {
  for (const auto& name : model::preset_names()) {
    for (int n : {1, 4, 16}) {
      const SecondOrderSystem s = assemble(SplineSpace(n), model::preset(name));
      // Exactly symmetric by construction (blocks and their transposes): allow only round-off.
      EXPECT_LT(asymmetry(s.M), 1e-15) << name << " N=" << n;
      EXPECT_LT(asymmetry(s.K), 1e-15) << name << " N=" << n;
      EXPECT_LT(asymmetry(s.C), 1e-15) << name << " N=" << n;
      EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(s.M).info(), Eigen::Success) << "M positive definite, " << name;
      EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(s.K).info(), Eigen::Success) << "K positive definite, " << name;
      // C is positive semi-definite (dissipative): smallest eigenvalue >= -round-off.
      const double cmin = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s.C).eigenvalues().minCoeff();
      EXPECT_GT(cmin, -1e-12 * s.C.cwiseAbs().maxCoeff()) << name;
    }
  }
}

TEST(SecondOrderSystem, LinearInParameters) {
  // M(p + q) = M(p) + M(q) for every parameter that enters linearly (all but l, and m c, m c^2 in the tip block).
  const SplineSpace space(6);
  const BeamForms forms(space, 0.5);
  BeamParameters p{0.5, 0.1, 2e-8, 7e5, 0.5, 0.01, 6e-6, 9.0, 0.0, 0.0, 0.0, {}, {}};
  BeamParameters q{0.5, 0.3, 5e-8, 2e5, 1.5, 0.02, 1e-6, 3.0, 0.0, 0.0, 0.0, {}, {}};
  BeamParameters sum = p;
  sum.rho += q.rho, sum.rho_r2 += q.rho_r2, sum.kAG += q.kAG, sum.EI += q.EI, sum.gamma += q.gamma, sum.cDI += q.cDI,
      sum.kAcs += q.kAcs;
  const SecondOrderSystem a = combine(forms, p), b = combine(forms, q), c = combine(forms, sum);
  EXPECT_LT((c.M - a.M - b.M).cwiseAbs().maxCoeff(), 1e-15 * c.M.cwiseAbs().maxCoeff());
  EXPECT_LT((c.K - a.K - b.K).cwiseAbs().maxCoeff(), 1e-15 * c.K.cwiseAbs().maxCoeff());
  EXPECT_LT((c.C - a.C - b.C).cwiseAbs().maxCoeff(), 1e-15 * c.C.cwiseAbs().maxCoeff());
  BeamParameters no_length = p;  // another length scales the forms (BeamLength tests); none is an error
  no_length.l = 0;
  EXPECT_THROW(combine(forms, no_length), InputError);
}

TEST(SecondOrderSystem, RigidTipBlockAndStaticDeflection) {
  // A tip body adds Lambda = [[m, mc], [mc, mc^2 + J_o]] on (u(l), alpha(l)): check it through the tip trace.
  const SplineSpace space(5);
  BeamParameters bare = model::preset("thick-steel");
  BeamParameters tip = bare;
  bare.m = bare.c = bare.J_o = 0;
  const Eigen::MatrixXd dm = assemble(space, tip).M - assemble(space, bare).M;
  const Eigen::VectorXd nu = space.tip_trace();
  const int n = space.dimension();
  const Eigen::VectorXd eu = (Eigen::VectorXd(2 * n) << nu, Eigen::VectorXd::Zero(n)).finished();
  const Eigen::VectorXd ea = (Eigen::VectorXd(2 * n) << Eigen::VectorXd::Zero(n), nu).finished();
  // Any w with u(l) = x, alpha(l) = y sees [x y] Lambda [x y]^T; nu.nu normalises these trace vectors.
  const double s = nu.squaredNorm();
  EXPECT_NEAR(eu.dot(dm * eu) / (s * s), tip.m, 1e-14);
  EXPECT_NEAR(eu.dot(dm * ea) / (s * s), tip.m * tip.c, 1e-14);
  EXPECT_NEAR(ea.dot(dm * ea) / (s * s), tip.m * tip.c * tip.c + tip.J_o, 1e-14);

  // Static tip deflection under a tip load P: Timoshenko cantilever P l^3/(3 EI) + P l/kAG, which cubic splines
  // represent exactly (u is cubic, alpha quadratic): agreement to round-off amplified by cond(K) (~1e-10 here).
  const BeamParameters beam = model::preset("thick-steel");
  const SecondOrderSystem sys = assemble(space, beam);
  const BeamForms forms(space, beam.l);
  const Eigen::VectorXd f = point_load(forms, beam.l);
  const Eigen::VectorXd w = sys.K.llt().solve(f);
  const double exact = std::pow(beam.l, 3) / (3 * beam.EI) + beam.l / beam.kAG;
  EXPECT_NEAR(f.dot(w), exact, 1e-9 * exact);
}

std::vector<double> galerkin_frequencies_hz(const BeamParameters& beam, int n, int count) {
  const Eigen::VectorXd omega = undamped_modes(assemble(SplineSpace(n), beam)).omega_rad_s;
  std::vector<double> f;
  for (int k = 0; k < count; ++k) f.push_back(omega(k) / (2 * std::numbers::pi));
  return f;
}

TEST(GalerkinConvergence, ThickSteelAtSixteenElements) {
  // model.md section 6: set B at N = 16 is within 3e-6 of exact for modes 1-3.
  const BeamParameters beam = model::preset("thick-steel");
  const auto exact = model::timoshenko_frequencies_rad_s(beam, 3);
  const auto galerkin = galerkin_frequencies_hz(beam, 16, 3);
  for (int k = 0; k < 3; ++k) {
    const double error = (galerkin[k] - exact[k] / (2 * std::numbers::pi)) / (exact[k] / (2 * std::numbers::pi));
    EXPECT_GE(error, -1e-12) << "Rayleigh-Ritz bounds from above, mode " << k + 1;
    EXPECT_LT(error, 3e-6) << "mode " << k + 1;
  }
}

// Round-off floor of the undamped frequencies: the thin beam's stiffness rows cancel from ~kAG/h down to
// rho h omega_1^2 (ratio ~1e8 at N = 32), so eigenvalues carry ~1e-16 x 1e8 relative noise; 1e-8 bounds it.
constexpr double kFloor = 1e-8;

TEST(GalerkinConvergence, MonotoneFromAboveAsNDoubles) {
  // Nested spaces (N -> 2N) and Rayleigh-Ritz: each undamped frequency is >= exact and does not increase.
  for (const auto& name : model::preset_names()) {
    const BeamParameters beam = model::preset(name);
    const auto exact = model::timoshenko_frequencies_rad_s(beam, 4);
    std::vector<double> previous(4, INFINITY), previous_error(4, INFINITY);
    for (int n : {4, 8, 16, 32}) {
      const auto f = galerkin_frequencies_hz(beam, n, 4);
      for (int k = 0; k < 4; ++k) {
        const double fe = exact[k] / (2 * std::numbers::pi);
        const double error = f[k] / fe - 1;
        EXPECT_GE(error, -kFloor) << name << " N=" << n << " mode " << k + 1;
        EXPECT_LE(f[k], previous[k] * (1 + kFloor)) << name << " N=" << n << " mode " << k + 1;
        // Convergence order in the asymptotic range (16 -> 32): eigenvalue errors fall as O(h^6) here (measured
        // ratios 66-76); require at least 32 (between h^5 and h^6) wherever the error stands clear of the floor.
        if (n == 32 && error > 1e3 * kFloor) {
          EXPECT_GT(previous_error[k] / error, 32.0) << name << " mode " << k + 1;
        }
        previous[k] = f[k];
        previous_error[k] = error;
      }
    }
  }
}

TEST(GalerkinConvergence, BanksThinBeamMatchesModelNotes) {
  // model.md: mode 2 is 0.45 % high at N = 8 (two digits), and mode 3 at N = 4 sits at 140 Hz against 82 Hz exact
  // (the (A4) pairing warning). model.md also says mode 2 is 25 % high at N = 4 and 0.008 % at N = 16; this Galerkin
  // solution gives 13.8 % and 0.0066 %. Galerkin in a given space is unique and these values are verified upper
  // bounds converging at O(h^6), so the two other figures are not asserted (see the closing note of issue 2).
  const BeamParameters beam = model::preset("banks-aluminium");
  const auto exact = model::timoshenko_frequencies_rad_s(beam, 3);
  const double exact2 = exact[1] / (2 * std::numbers::pi);
  EXPECT_NEAR(galerkin_frequencies_hz(beam, 8, 2)[1] / exact2 - 1, 0.0045, 0.00005);
  EXPECT_NEAR(galerkin_frequencies_hz(beam, 4, 3)[2], 140.0, 0.5);
  EXPECT_NEAR(exact[2] / (2 * std::numbers::pi), 81.67, 0.005);
}

TEST(StateSpaceModes, DampedModesOfPresets) {
  // model.md section 5: banks-aluminium damping ratios about 8.1e-4, 1.5e-3, 3.5e-3, 6.9e-3 ("about": 5 %).
  // The natural frequency |lambda| of a damped mode differs from the undamped one at the same N only at O(zeta^2)
  // (damping is not proportional, so not exactly): 10 zeta^2 bounds it.
  const BeamParameters beam = model::preset("banks-aluminium");
  const SecondOrderSystem system = assemble(SplineSpace(16), beam);
  const auto modes = StateSpaceModes(system).underdamped_modes();
  const Eigen::VectorXd omega = undamped_modes(system).omega_rad_s;
  const double zeta[] = {8.1e-4, 1.5e-3, 3.5e-3, 6.9e-3};
  ASSERT_GE(modes.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(modes[k].frequency_hz / (omega(k) / (2 * std::numbers::pi)), 1.0, 10 * zeta[k] * zeta[k])
        << "mode " << k + 1;
    EXPECT_NEAR(modes[k].damping_ratio / zeta[k], 1.0, 0.05) << "mode " << k + 1;
  }
}

TEST(StateSpaceModes, EigenvalueDerivativesEqualCentralDifferences) {
  // d lambda_k / d q = -x_k^T (lambda_k^2 dM + lambda_k dC + dK) x_k / n_k against central differences of the
  // eigenvalues at a relative step h = 1e-4 of each parameter, for the five lowest underdamped modes of both presets
  // (the tip offset c enters M as m c and m c^2: not linear, the formula holds all the same). Compared as
  // q d lambda / d q in units of |lambda|: the difference's truncation error is O(h^2) = 1e-8, and its round-off is
  // the eigenvalues' error over h: the thin beam's first eigenvalue is accurate to about 2e-11 relative (measured: at
  // h = 1e-5 the difference in kAG, whose true derivative is ~1e-10 of |lambda| / kAG, came out 9e-7), so 2e-7 here;
  // 1e-6 is the bound.
  for (const auto& name : model::preset_names()) {
    const BeamParameters beam = model::preset(name);
    const BeamForms forms(SplineSpace(8), beam.l);
    const StateSpaceModes modes(combine(forms, beam));
    for (const char* key : {"EI", "rho", "cDI", "gamma", "kAG", "kAcs", "m", "c"}) {
      const double value = beam.*(model::find_parameter(key)->member);
      if (value == 0) continue;
      const Eigen::VectorXcd analytic = modes.eigenvalue_derivative(parameter_derivative(forms, beam, key));
      const double h = 1e-4 * value;
      BeamParameters up = beam, down = beam;
      up.*(model::find_parameter(key)->member) += h;
      down.*(model::find_parameter(key)->member) -= h;
      const auto plus = StateSpaceModes(combine(forms, up)).underdamped_modes();
      const auto minus = StateSpaceModes(combine(forms, down)).underdamped_modes();
      const auto base = modes.underdamped_modes();
      for (std::size_t j = 0; j < 5; ++j) {
        Eigen::Index k = 0;  // the index of underdamped mode j in eigenvalues()
        while (k < modes.size() && modes.eigenvalues()(k) != base[j].lambda) ++k;
        ASSERT_LT(k, modes.size()) << "underdamped mode " << j + 1 << " is not among the eigenvalues";
        const std::complex<double> numeric = (plus[j].lambda - minus[j].lambda) / (2 * h);
        EXPECT_LT(std::abs(analytic(k) - numeric) * value / std::abs(base[j].lambda), 1e-6)
            << name << " " << key << " mode " << j + 1 << ": " << analytic(k) << " vs " << numeric;
      }
    }
  }
}

TEST(StateSpaceModes, ConjugatePairsStayPairedWhenTwoModesNearlyCoincide) {
  // Two underdamped modes 5e-7 apart in omega^2 (K = diag(1, 1 + 1e-6, 4), M = I, C = diag(0.1, 0.1, 0.2), rotated so
  // that nothing is diagonal): after the refinement every eigenvalue with Im < 0 is the exact conjugate of one with
  // Im > 0, and every eigenpair satisfies T(lambda) x = 0 to round-off (1e-12 of |T| |x|; a partner taken from the
  // other mode would leave a residual of the gap, ~1e-6).
  const double angle = 0.3;
  Eigen::Matrix3d q;
  q = Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  SecondOrderSystem s;
  s.M = Eigen::MatrixXd::Identity(3, 3);
  s.K = q * Eigen::Vector3d(1, 1 + 1e-6, 4).asDiagonal() * q.transpose();
  s.C = q * Eigen::Vector3d(0.1, 0.1, 0.2).asDiagonal() * q.transpose();
  const StateSpaceModes modes(s);
  const Eigen::MatrixXcd x = modes.physical_vectors();
  for (Eigen::Index k = 0; k < modes.size(); ++k) {
    const std::complex<double> l = modes.eigenvalues()(k);
    if (l.imag() < 0) {
      bool paired = false;
      for (Eigen::Index j = 0; j < modes.size(); ++j) paired = paired || modes.eigenvalues()(j) == std::conj(l);
      EXPECT_TRUE(paired) << "eigenvalue " << k << " = " << l;
    }
    const Eigen::MatrixXcd t = l * l * s.M + l * s.C + s.K;
    EXPECT_LT((t * x.col(k)).norm(), 1e-12 * t.norm() * x.col(k).norm()) << "eigenvalue " << k << " = " << l;
  }
}

// The eigenvalue nearest `lambda` of T(l) = l^2 M + l C + K by Newton's method on (x, l) in long double (64-bit
// mantissa), started from `lambda` and `x`: a reference 2^11 times more precise than the double-precision solvers.
std::complex<long double> newton_eigenvalue(const SecondOrderSystem& s, std::complex<double> lambda,
                                            const Eigen::VectorXcd& x0) {
  using C = std::complex<long double>;
  const Eigen::Index n = s.M.rows();
  const Eigen::Matrix<C, -1, -1> m = s.M.cast<long double>().cast<C>(), c = s.C.cast<long double>().cast<C>(),
                                 k = s.K.cast<long double>().cast<C>();
  Eigen::Matrix<C, -1, 1> x(n);
  for (Eigen::Index i = 0; i < n; ++i) x(i) = C(x0(i).real(), x0(i).imag());
  Eigen::Index pivot = 0;
  x.cwiseAbs().maxCoeff(&pivot);
  x /= x(pivot);
  C l(lambda.real(), lambda.imag());
  for (int iteration = 0; iteration < 6; ++iteration) {
    const Eigen::Matrix<C, -1, -1> t = l * l * m + l * c + k;
    Eigen::Matrix<C, -1, -1> jacobian = Eigen::Matrix<C, -1, -1>::Zero(n + 1, n + 1);
    jacobian.topLeftCorner(n, n) = t;
    jacobian.topRightCorner(n, 1) = (C(2) * l * m + c) * x;
    jacobian(n, pivot) = 1;
    Eigen::Matrix<C, -1, 1> rhs(n + 1);
    rhs.head(n) = -t * x;
    rhs(n) = 0;
    const Eigen::Matrix<C, -1, 1> step = jacobian.partialPivLu().solve(rhs);
    x += step.head(n);
    l += step(n);
  }
  return l;
}

TEST(StateSpaceModes, IterationInTheUndampedBasisAgreesWithTheDenseDecomposition) {
  // The thin beam's damping couples its undamped modes weakly (air damping only: its two relaxation times are equal),
  // so its damped modes come from the Jacobi iteration at every N; they must equal the dense decomposition's. Measured:
  // eigenvalues agree to 3e-15 relative (N = 4 .. 48), so 1e-12. The pulse response through either set of modes
  // agrees to 1e-10 of max |y| (the slow shear relaxation block, 21 rates within 1e-6 of each other, is resolved only
  // to its Gram matrix's accuracy).
  const BeamParameters beam = model::preset("banks-aluminium");
  for (const int n : {4, 8, 16, 32}) {
    const SecondOrderSystem system = assemble(SplineSpace(n), beam);
    const StateSpaceModes iterated(system), dense(system, DampedModesMethod::dense);
    ASSERT_TRUE(iterated.iterated()) << "N = " << n;
    ASSERT_FALSE(dense.iterated());
    ASSERT_EQ(iterated.size(), dense.size());
    for (Eigen::Index k = 0; k < iterated.size(); ++k) {
      double nearest = std::numeric_limits<double>::infinity();
      for (Eigen::Index j = 0; j < dense.size(); ++j)
        nearest = std::min(nearest, std::abs(iterated.eigenvalues()(k) - dense.eigenvalues()(j)));
      EXPECT_LT(nearest, 1e-12 * std::abs(iterated.eigenvalues()(k))) << "N = " << n << ", eigenvalue " << k;
    }
  }
}

TEST(StateSpaceModes, AwayFromEqualRelaxationTimesEitherMethodGivesTheDenseEigenvalues) {
  // A fit moves cDI, kAcs and EI apart, so the thin beam's bending and shear relaxation times (cDI/EI, kAcs/kAG) stop
  // being equal: its slow shear roots spread and the damping couples them as strongly as they are apart. Then the
  // iteration must either converge to the dense decomposition's eigenvalues or give up (measured at N = 16: with the
  // wide blocks it is used out to 10 % from equal times, where its eigenvalues agree to 3.3e-15 relative; at 30 % the
  // dense one runs), so 1e-12 whichever ran. And it must be used within 10 % of the truth, where a fit spends its
  // evaluations.
  for (const double factor : {0.9, 0.99, 0.999, 0.9999, 1.0001, 1.001, 1.01, 1.1}) {
    for (const std::string parameter : {"cDI", "kAcs", "EI"}) {
      BeamParameters beam = model::preset("banks-aluminium");
      double& value = parameter == "cDI" ? beam.cDI : parameter == "kAcs" ? beam.kAcs : beam.EI;
      value *= factor;
      const SecondOrderSystem system = assemble(SplineSpace(16), beam);
      const StateSpaceModes automatic(system), dense(system, DampedModesMethod::dense);
      ASSERT_EQ(automatic.size(), dense.size());
      for (Eigen::Index k = 0; k < automatic.size(); ++k) {
        double nearest = std::numeric_limits<double>::infinity();
        for (Eigen::Index j = 0; j < dense.size(); ++j)
          nearest = std::min(nearest, std::abs(automatic.eigenvalues()(k) - dense.eigenvalues()(j)));
        EXPECT_LT(nearest, 1e-12 * std::abs(automatic.eigenvalues()(k)))
            << parameter << " x " << factor << ", eigenvalue " << k;
      }
      if (std::abs(factor - 1) <= 0.1) {
        EXPECT_TRUE(automatic.iterated()) << parameter << " x " << factor;
      }
    }
  }
}

TEST(StateSpaceModes, LowDampingRatiosAreAccurateToTheirOwnSize) {
  // A slow mode's damping ratio is a fitted quantity and must be accurate to its own size, not to the fastest damping
  // rate's (the dense QR's backward error eps ||A||, ||A|| ~ 5e8 1/s for the thin beam: before the modal refinement in
  // the undamped basis, the first mode's zeta came out 5.2e-8 of its value off). Against Newton's method in long
  // double from the computed pair, the three lowest modes of the thin beam at N = 16 (measured: 3.5e-11, 1.6e-12 and
  // 2e-12 relative in zeta, 4e-11 in frequency, the latter set by the cancellation in x^T K x of a bending mode against
  // the shear stiffness). Bound 1e-9.
  const BeamParameters beam = model::preset("banks-aluminium");
  const SecondOrderSystem system = assemble(SplineSpace(16), beam);
  const StateSpaceModes modes(system);
  const Eigen::MatrixXcd x = modes.physical_vectors();
  const auto damped = modes.underdamped_modes();
  for (std::size_t j = 0; j < 3; ++j) {
    Eigen::Index k = 0;
    while (modes.eigenvalues()(k) != damped[j].lambda) ++k;
    const std::complex<long double> reference = newton_eigenvalue(system, damped[j].lambda, x.col(k));
    const double zeta = static_cast<double>(-reference.real() / std::abs(reference));
    const double hz = static_cast<double>(std::abs(reference) / (2 * std::numbers::pi_v<long double>));
    EXPECT_LT(std::abs(damped[j].damping_ratio / zeta - 1), 1e-9) << "mode " << j + 1;
    EXPECT_LT(std::abs(damped[j].frequency_hz / hz - 1), 1e-9) << "mode " << j + 1;
  }
}

TEST(StateSpaceModes, StronglyCoupledDampingFallsBackToTheDenseDecomposition) {
  // thick-steel's shear and bending relaxation times differ 10x: its damping couples the undamped modes with ratios up
  // to 26, where the iteration cannot converge; the dense decomposition must take over, with the same eigenvalues as
  // asking for it directly.
  const SecondOrderSystem system = assemble(SplineSpace(16), model::preset("thick-steel"));
  const StateSpaceModes automatic(system), dense(system, DampedModesMethod::dense);
  EXPECT_FALSE(automatic.iterated());
  EXPECT_EQ(automatic.eigenvalues(), dense.eigenvalues());
}

// ---- Attachments on the span (issue 11)

TEST(AttachedBodies, AttachmentAtTheTipIsTheTipBody) {
  // The same inertia on the same trace: beta(l/l) = nu (the tip trace), so M agrees to rounding.
  for (const auto& name : model::preset_names()) {
    const BeamParameters tip = model::preset(name);
    BeamParameters moved = tip;
    moved.attachments.push_back({tip.l, tip.m, tip.J_o, tip.c});
    moved.m = moved.c = moved.J_o = 0;
    const SecondOrderSystem a = assemble(SplineSpace(12), tip), b = assemble(SplineSpace(12), moved);
    EXPECT_LT((a.M - b.M).cwiseAbs().maxCoeff(), 1e-15 * a.M.cwiseAbs().maxCoeff()) << name;
    EXPECT_EQ(a.K, b.K) << name;
    EXPECT_EQ(a.C, b.C) << name;
  }
}

TEST(AttachedBodies, GalerkinConvergesToTheSegmentedExactFrequencies) {
  // A body on the span makes the shear force jump, so the exact U has a kink (U' - Psi jumps by Delta S / kAG) and,
  // with an offset or inertia, Psi has one too. C^2 cubic splines cannot follow a kink: the best H^1 error is
  // O(h^1/2), so the eigenvalue error falls only as O(h) once the kink dominates (measured ratios per doubling of
  // N: 2.0-2.1 on the thick beam from N = 16; on the thin beam, whose stiff shear makes the kink tiny, 7-44 up to
  // N = 128, still approaching the O(h^6) of the smooth part). Checked: Rayleigh-Ritz bounds from above (up to the
  // round-off floor kFloor), monotone decrease, at least first order (ratio >= 1.8 from N = 64 to 128), and the
  // measured accuracy at N = 128 with a 50 % margin (thick: 2.1e-5 at mode 4; thin: 1.2e-6).
  struct Case {
    std::string beam;
    model::Attachment body;
    double tolerance_at_128;
  };
  const Case cases[] = {{"thick-steel", {0.2, 0.1, 2e-6, 0.01}, 3.2e-5},
                        {"banks-aluminium", {0.397, 0.012, 1e-6, 0.0}, 1.8e-6}};  // a sensor board 6 cm from the tip
  for (const Case& c : cases) {
    BeamParameters beam = model::preset(c.beam);
    beam.attachments.push_back(c.body);
    const auto exact = model::timoshenko_frequencies_rad_s(beam, 4);
    std::vector<double> previous(4, INFINITY), previous_error(4, INFINITY);
    for (int n : {16, 32, 64, 128}) {
      const auto f = galerkin_frequencies_hz(beam, n, 4);
      for (int k = 0; k < 4; ++k) {
        const double error = f[k] / (exact[k] / (2 * std::numbers::pi)) - 1;
        EXPECT_GE(error, -kFloor) << c.beam << " N=" << n << " mode " << k + 1;
        EXPECT_LE(f[k], previous[k] * (1 + kFloor)) << c.beam << " N=" << n << " mode " << k + 1;
        if (n == 128) {
          EXPECT_LT(error, c.tolerance_at_128) << c.beam << " mode " << k + 1;
          if (error > 1e2 * kFloor) {
            EXPECT_GT(previous_error[k] / error, 1.8) << c.beam << " mode " << k + 1;
          }
        }
        previous[k] = f[k];
        previous_error[k] = error;
      }
    }
  }
}

// ---- A compliant clamp (issue 11)

TEST(CompliantClamp, GalerkinConvergesToTheExactFrequenciesAtFullOrder) {
  // Root springs leave the exact modes smooth (no kink), so the unclamped spline blocks converge as for the rigid
  // clamp: modes 1-3 within the 3e-6 of GalerkinConvergence.ThickSteelAtSixteenElements at N = 16 (measured 1.2e-6),
  // from above, and O(h^6) from 16 to 32 (measured ratios 66-470; >= 32 asserted as there). Both springs, and each
  // alone (the blocks then have N + 3 and N + 2 functions). The exact reference's root rows are derived from the
  // boundary terms, the Galerkin springs from the energy (1/2) k alpha(0)^2: agreement checks one against the other.
  constexpr double kRigid = std::numeric_limits<double>::infinity();
  for (const auto& [k_theta, k_w] : {std::pair{1e4, 1e7}, std::pair{1e4, kRigid}, std::pair{kRigid, 1e6}}) {
    BeamParameters beam = model::preset("thick-steel");
    beam.support.k_theta = k_theta;
    beam.support.k_w = k_w;
    const auto exact = model::timoshenko_frequencies_rad_s(beam, 3);
    std::vector<double> previous_error(3, INFINITY);
    for (int n : {16, 32}) {
      const auto f = galerkin_frequencies_hz(beam, n, 3);
      for (int k = 0; k < 3; ++k) {
        const double error = f[k] / (exact[k] / (2 * std::numbers::pi)) - 1;
        const std::string what = "k_theta " + std::to_string(k_theta) + ", k_w " + std::to_string(k_w) +
                                 ", N=" + std::to_string(n) + " mode " + std::to_string(k + 1);
        EXPECT_GE(error, -kFloor) << what;
        EXPECT_LT(error, 3e-6) << what;
        if (n == 32 && error > 1e2 * kFloor) {
          EXPECT_GT(previous_error[k] / error, 32.0) << what;
        }
        previous_error[k] = error;
      }
    }
  }
}

TEST(CompliantClamp, ANearlyRigidModeOfAVerySoftSpringIsResolved) {
  // On the thin beam with a clamp spring as soft as a fit may reach (k_theta l/EI = 1.1e-4; a beam file admits 1e-2),
  // the root's near-rigid rotation is at 0.014 Hz against the shear modes' ~1e6 Hz: mu = 1/omega^2 spans 1e17, beyond
  // double, and the unshifted eigenproblem failed ("is M positive definite?"). The shifted solve resolves it: the
  // near-rigid mode within 1e-5 of the exact determinant's (measured 3e-6: the spring's energy, 1e-4 of the beam's,
  // carries the rounding of K's entries), and the elastic modes 2-3 from above, within 5e-2 at this coarse N = 8
  // (measured 1.9e-3 and 3.0e-2; Rayleigh-Ritz: never below).
  BeamParameters beam = model::preset("banks-aluminium");
  beam.support.k_theta = 1.1e-4 * beam.EI / beam.l;
  const auto exact = model::timoshenko_frequencies_rad_s(beam, 3);
  const Eigen::VectorXd omega = undamped_modes(assemble(SplineSpace(8), beam)).omega_rad_s;
  EXPECT_NEAR(omega(0) / exact[0], 1.0, 1e-5);
  for (int k = 1; k < 3; ++k) {
    EXPECT_GE(omega(k) / exact[static_cast<std::size_t>(k)] - 1, -kFloor) << "mode " << k + 1;
    EXPECT_LT(omega(k) / exact[static_cast<std::size_t>(k)] - 1, 5e-2) << "mode " << k + 1;
  }
}

TEST(CompliantClamp, SpringsEnterKAtTheRootAndFormsMustMatchTheClamp) {
  // The spring adds k_theta e e^T to K, e the alpha block's values at x = 0 (B_{-1}, B_0, B_1 = 1/6, 2/3, 1/6 of the
  // unclamped space): K(k) - K(0+) is k_theta e e^T to rounding, and M, C do not depend on it.
  BeamParameters soft = model::preset("thick-steel"), stiff = soft;
  soft.support.k_theta = 1.0;
  stiff.support.k_theta = 1001.0;
  const SplineSpace space(6);
  const BeamForms forms(space, soft.l, soft.support);
  EXPECT_EQ(forms.u_dimension(), 8);
  EXPECT_EQ(forms.alpha_dimension(), 9);
  const SecondOrderSystem a = combine(forms, soft), b = combine(forms, stiff);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(forms.dimension());
  e(8) = 1.0 / 6, e(9) = 2.0 / 3, e(10) = 1.0 / 6;
  EXPECT_LT((b.K - a.K - 1000.0 * e * e.transpose()).cwiseAbs().maxCoeff(), 1e-12 * b.K.cwiseAbs().maxCoeff());
  EXPECT_EQ(a.M, b.M);
  EXPECT_EQ(a.C, b.C);
  // Forms made for a rigid clamp cannot carry a spring, and the reverse.
  EXPECT_THROW(combine(BeamForms(space, soft.l), soft), InputError);
  EXPECT_THROW(combine(forms, model::preset("thick-steel")), InputError);
}

// ---- Estimable clamp springs and attachment parameters (issue 11 item 3)

TEST(AttachedBodies, DerivativesOfSpringsAndAttachmentsEqualCentralDifferences) {
  // dM/dq, dK/dq against central differences of combine() at a relative step h = 1e-5: M and K are linear in
  // k_theta, k_w, m and J (the difference is exact to rounding, ~1e-16 / h = 1e-11 of the entries) and C^1 in the
  // position x (cubic splines are C^2; truncation O(h^2) = 1e-10 of the entries). 1e-8 of the largest entry of the
  // derivative bounds both; a wrong block or factor is O(1) wrong.
  BeamParameters beam = model::preset("thick-steel");
  beam.support.k_theta = 2e4;
  beam.support.k_w = 3e7;
  beam.attachments = {{0.173, 0.1, 2e-6, 0.01}, {0.25, 0.05, 1e-6, -0.005}};
  const BeamForms forms(SplineSpace(8), beam.l, beam.support);
  for (const char* key : {"support.k_theta", "support.k_w", "attachment1.m", "attachment1.J", "attachment1.x",
                          "attachment2.m", "attachment2.x"}) {
    const SecondOrderSystem analytic = parameter_derivative(forms, beam, key);
    const double value = model::parameter_value(beam, key), h = 1e-5 * value;
    BeamParameters up = beam, down = beam;
    model::set_parameter_value(up, key, value + h);
    model::set_parameter_value(down, key, value - h);
    const SecondOrderSystem plus = combine(forms, up), minus = combine(forms, down);
    const Eigen::MatrixXd dm = (plus.M - minus.M) / (2 * h), dk = (plus.K - minus.K) / (2 * h);
    const double scale = std::max(analytic.M.cwiseAbs().maxCoeff(), analytic.K.cwiseAbs().maxCoeff());
    ASSERT_GT(scale, 0) << key;
    EXPECT_LT((analytic.M - dm).cwiseAbs().maxCoeff(), 1e-8 * scale) << key;
    EXPECT_LT((analytic.K - dk).cwiseAbs().maxCoeff(), 1e-8 * scale) << key;
    EXPECT_EQ(analytic.C.cwiseAbs().maxCoeff(), 0.0) << key;
  }
  // A key the beam does not have is refused, naming what it has.
  EXPECT_THROW(parameter_derivative(forms, beam, "attachment3.m"), InputError);
  EXPECT_THROW(parameter_derivative(BeamForms(SplineSpace(8), beam.l), model::preset("thick-steel"), "support.k_theta"),
               InputError);
}

// ---- The length as a parameter (issue 11 item 3)

TEST(BeamLength, ScaledFormsEqualFormsBuiltAtThatLength) {
  // combine() at l != l_0 scales the forms in closed form; BeamForms built at l integrate at l directly. Same
  // matrices up to the rounding of the scale factors and of the Gram matrices (~1e-15 relative; 1e-13 allows the
  // thin beam's kAG/rho ratio of 1e7 between entries), with bodies on the span and a compliant clamp.
  for (const auto& name : model::preset_names()) {
    BeamParameters beam = model::preset(name);
    beam.support.k_theta = 1e3;
    beam.attachments = {{0.6 * beam.l, 0.02, 1e-6, 0.003}};
    const BeamForms reference(SplineSpace(10), beam.l, beam.support);
    beam.l *= 1.07;
    const SecondOrderSystem scaled = combine(reference, beam);
    const SecondOrderSystem direct = combine(BeamForms(SplineSpace(10), beam.l, beam.support), beam);
    for (const auto& [a, b, what] : {std::tuple{&scaled.M, &direct.M, "M"}, std::tuple{&scaled.K, &direct.K, "K"},
                                     std::tuple{&scaled.C, &direct.C, "C"}})
      EXPECT_LT((*a - *b).cwiseAbs().maxCoeff(), 1e-13 * b->cwiseAbs().maxCoeff()) << name << " " << what;
  }
}

TEST(BeamLength, DerivativeEqualsCentralDifferences) {
  // d(M, C, K)/dl at l = 1.03 l_0 (forms at l_0) against central differences at h = 1e-5 l: every term is a smooth
  // function of l (powers of l, and beta(x/l) for the body, C^2), truncation O(h^2) ~ 1e-10 of the entries; 1e-8 of
  // the derivative's largest entry bounds it.
  BeamParameters beam = model::preset("thick-steel");
  beam.attachments = {{0.2, 0.1, 2e-6, 0.01}};
  const BeamForms forms(SplineSpace(8), beam.l, beam.support);
  beam.l *= 1.03;
  const SecondOrderSystem analytic = parameter_derivative(forms, beam, "l");
  const double h = 1e-5 * beam.l;
  BeamParameters up = beam, down = beam;
  up.l += h;
  down.l -= h;
  const SecondOrderSystem plus = combine(forms, up), minus = combine(forms, down);
  for (const auto& [a, p, m, what] :
       {std::tuple{&analytic.M, &plus.M, &minus.M, "M"}, std::tuple{&analytic.K, &plus.K, &minus.K, "K"},
        std::tuple{&analytic.C, &plus.C, &minus.C, "C"}}) {
    const Eigen::MatrixXd numeric = (*p - *m) / (2 * h);
    EXPECT_LT((*a - numeric).cwiseAbs().maxCoeff(), 1e-8 * a->cwiseAbs().maxCoeff()) << what;
  }
}

}  // namespace
}  // namespace beamid::galerkin

namespace beamid::galerkin {
namespace {

TEST(ModalDamping, GivesAnUndampedBeamTheRatioInEveryModeAndAddsItToADampedOne) {
  // C + M Phi diag(2 zeta omega) Phi^T M: on the thin beam with its damping removed every damped mode has the ratio
  // zeta (the modal equations decouple exactly; the eigen-solvers' round-off is ~1e-10 of the ratio for the first
  // eight modes), and |lambda| stays the undamped omega (measured within 1.2e-10; bound 1e-9). On the
  // beam with its own damping the first mode's ratio is its own plus zeta to first order (the air term's coupling of
  // the modes is weak: within 2 % of zeta). zeta outside [0, 1) is refused; 0 leaves the system as it was.
  model::BeamParameters beam = model::preset("banks-aluminium");
  const SplineSpace space(16);
  const BeamForms forms(space, beam.l);
  const double zeta = 0.004;
  model::BeamParameters bare = beam;
  bare.cDI = bare.gamma = bare.kAcs = 0;
  const SecondOrderSystem undamped = combine(forms, bare);
  const UndampedModes reference = undamped_modes(undamped);
  const auto modes = StateSpaceModes(with_modal_damping(undamped, zeta)).underdamped_modes();
  ASSERT_GE(modes.size(), 8u);
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_NEAR(modes[k].damping_ratio / zeta, 1.0, 1e-8) << "mode " << k + 1;
    EXPECT_NEAR(std::abs(modes[k].lambda) / reference.omega_rad_s(static_cast<Eigen::Index>(k)), 1.0, 1e-9)
        << "mode " << k + 1;
  }
  const auto own = StateSpaceModes(combine(forms, beam)).underdamped_modes();
  const auto added = StateSpaceModes(with_modal_damping(combine(forms, beam), zeta)).underdamped_modes();
  EXPECT_NEAR((added[0].damping_ratio - own[0].damping_ratio) / zeta, 1.0, 0.02);
  EXPECT_THROW(with_modal_damping(undamped, 1.0), InputError);
  EXPECT_THROW(with_modal_damping(undamped, -0.1), InputError);
  EXPECT_EQ(with_modal_damping(undamped, 0).C, undamped.C);
}

}  // namespace
}  // namespace beamid::galerkin
