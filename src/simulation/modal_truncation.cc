#include "simulation/modal_truncation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "simulation/modal_simulator.h"

namespace beamid::simulation {

TruncationSplit widest_gap(const Eigen::VectorXd& omega_rad_s, double band_rad_s) {
  const auto n = static_cast<int>(omega_rad_s.size());
  if (n == 0) throw InputError("widest_gap: the spectrum is empty");
  TruncationSplit split{n, 1.0};
  for (int k = 0; k + 1 < n; ++k) {
    if (omega_rad_s(k) < band_rad_s) continue;
    const double ratio = omega_rad_s(k + 1) / omega_rad_s(k);
    if (ratio > split.gap_ratio) split = {k + 1, ratio};
  }
  return split;
}

namespace {

// M, C, K in the undamped modal basis (exact congruences with Phi, so M~ = I and K~ = Omega^2 up to round-off) and
// Phi itself.
struct ModalBasis {
  Eigen::MatrixXd shapes, mass, damping, stiffness;
};

ModalBasis modal_basis(const galerkin::SecondOrderSystem& s) {
  ModalBasis b;
  b.shapes = galerkin::undamped_modes(s).shapes;
  b.mass = b.shapes.transpose() * s.M * b.shapes;
  b.damping = b.shapes.transpose() * s.C * b.shapes;
  b.stiffness = b.shapes.transpose() * s.K * b.shapes;
  return b;
}

void check_retained(int retained, Eigen::Index size) {
  if (retained < 1 || retained > size)
    throw InputError("retained = " + std::to_string(retained) + ": must be in 1.." + std::to_string(size));
}

}  // namespace

Trace truncated_response(const galerkin::SecondOrderSystem& system, const ResponseProblem& problem, int retained,
                         Truncation kind) {
  if (!problem.w0.isZero(0.0)) throw InputError("truncated_response: only a pulse from rest (w0 = 0)");
  check_retained(retained, system.M.rows());
  ModalBasis b;
  try {
    b = modal_basis(system);
  } catch (const NumericalError& error) {
    Trace trace;
    trace.stats.integrator = kFast;
    trace.y.assign(static_cast<std::size_t>(problem.samples), 0.0);
    trace.status = std::string(kind == Truncation::truncated ? "truncated: " : "decoupled: ") + error.what();
    return trace;
  }
  const Eigen::Index n = b.shapes.cols();
  const Eigen::Index m = kind == Truncation::truncated ? retained : n;  // the reduced system's size
  galerkin::SecondOrderSystem reduced{b.mass.topLeftCorner(m, m), b.damping.topLeftCorner(m, m),
                                      b.stiffness.topLeftCorner(m, m)};
  if (kind == Truncation::decoupled) {
    // The retained block as it is and each discarded mode j as its own oscillator (M~_jj, C~_jj, K~_jj): in M~ and K~
    // this drops only round-off, except within a group of nearly equal shear frequencies, whose computed shapes are
    // mixed to about 1e-6 (galerkin/modes.cc, separate_close_modes); in C~ it drops the damping's coupling.
    const Eigen::Index h = n - retained;
    for (Eigen::MatrixXd* x : {&reduced.M, &reduced.C, &reduced.K}) {
      const Eigen::VectorXd own = x->bottomRightCorner(h, h).diagonal();
      x->topRightCorner(retained, h).setZero();
      x->bottomLeftCorner(h, retained).setZero();
      x->bottomRightCorner(h, h) = own.asDiagonal();
    }
  }
  ResponseProblem p = problem;
  p.load = b.shapes.leftCols(m).transpose() * problem.load;
  p.sensor = b.shapes.leftCols(m).transpose() * problem.sensor;
  p.w0 = Eigen::VectorXd::Zero(m);
  return ModalSimulator().run(reduced, p);
}

TruncationDiagnostics truncation_diagnostics(const galerkin::SecondOrderSystem& system, int retained) {
  check_retained(retained, system.M.rows());
  const ModalBasis b = modal_basis(system);
  const Eigen::Index n = b.shapes.cols(), h = n - retained;
  TruncationDiagnostics d;
  const galerkin::SecondOrderSystem kept{b.mass.topLeftCorner(retained, retained),
                                         b.damping.topLeftCorner(retained, retained),
                                         b.stiffness.topLeftCorner(retained, retained)};
  const Eigen::VectorXcd lambda = galerkin::StateSpaceModes(kept).eigenvalues();
  d.fastest_retained_rad_s = lambda.cwiseAbs().maxCoeff();
  d.nearest_retained_relative = std::numeric_limits<double>::infinity();
  if (h == 0) return d;

  // C~_ij / sqrt(C~_ii C~_jj): the coupling against the modes' own damping (C~ is positive semi-definite, so this is
  // at most 1; a mode without damping of its own has no coupling either).
  const Eigen::ArrayXd own = b.damping.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index j = retained; j < n; ++j)
    for (Eigen::Index i = 0; i < retained; ++i)
      if (own(i) > 0 && own(j) > 0)
        d.coupling_relative = std::max(d.coupling_relative, std::abs(b.damping(i, j)) / (own(i) * own(j)));

  double slowest = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = retained; j < n; ++j) {
    // Roots of a lambda^2 + c lambda + k (c >= 0, k > 0): a complex pair (-c +- i sqrt(4ak - c^2)) / 2a; real roots
    // q / a and k / q with q = -(c + sqrt(c^2 - 4ak)) / 2 (cancellation-free), the smaller in magnitude k / q (since
    // |q| >= sqrt(ak)).
    const double a = b.mass(j, j), c = b.damping(j, j), k = b.stiffness(j, j), disc = c * c - 4 * a * k;
    const std::complex<double> root =
        disc < 0 ? std::complex<double>(-c, std::sqrt(-disc)) / (2 * a) : k / (-0.5 * (c + std::sqrt(disc)));
    if (std::abs(root) < slowest) {
      slowest = std::abs(root);
      d.slowest_discarded_rad_s = root;
    }
  }
  d.nearest_retained_relative =
      (lambda.array() - d.slowest_discarded_rad_s).abs().minCoeff() / std::abs(d.slowest_discarded_rad_s);
  return d;
}

}  // namespace beamid::simulation
