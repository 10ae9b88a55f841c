#include "simulation/modal_truncation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "galerkin/modes.h"
#include "model/errors.h"
#include "simulation/modal_simulator.h"

namespace beamid::simulation {

TruncationSplit widest_gap(const Eigen::VectorXd& omega_rad_s, double band_rad_s) {
  const auto n = static_cast<int>(omega_rad_s.size());
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
    trace.stats.integrator = "fast";
    trace.y.assign(static_cast<std::size_t>(problem.samples), 0.0);
    trace.status = std::string("truncated: ") + error.what();
    return trace;
  }
  const Eigen::Index n = b.shapes.cols();
  const Eigen::Index m = kind == Truncation::truncated ? retained : n;  // the reduced system's size
  galerkin::SecondOrderSystem reduced{b.mass.topLeftCorner(m, m), b.damping.topLeftCorner(m, m),
                                      b.stiffness.topLeftCorner(m, m)};
  if (kind == Truncation::decoupled) {
    // Block-diagonal damping: the retained block as it is, each discarded mode with its own C~_jj only.
    const Eigen::Index h = n - retained;
    const Eigen::VectorXd own = b.damping.bottomRightCorner(h, h).diagonal();
    reduced.C.topRightCorner(retained, h).setZero();
    reduced.C.bottomLeftCorner(h, retained).setZero();
    reduced.C.bottomRightCorner(h, h) = own.asDiagonal();
  }
  ResponseProblem p = problem;
  p.load = b.shapes.leftCols(m).transpose() * problem.load;
  p.sensor = b.shapes.leftCols(m).transpose() * problem.sensor;
  p.w0 = Eigen::VectorXd::Zero(m);
  return ModalSimulator().run(reduced, p);
}

SpectrumOverlap spectrum_overlap(const galerkin::SecondOrderSystem& system, int retained) {
  check_retained(retained, system.M.rows());
  const ModalBasis b = modal_basis(system);
  const Eigen::Index n = b.shapes.cols();
  SpectrumOverlap overlap;
  overlap.nearest_retained_relative = std::numeric_limits<double>::infinity();
  if (n == retained) return overlap;
  double slowest = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = retained; j < n; ++j) {
    // Roots of a lambda^2 + c lambda + k: a complex pair (-c +- i sqrt(4ak - c^2)) / 2a; real roots q / a and k / q with
    // q = -(c + sqrt(c^2 - 4ak)) / 2 (cancellation-free), the smaller in magnitude k / q.
    const double a = b.mass(j, j), c = b.damping(j, j), k = b.stiffness(j, j), disc = c * c - 4 * a * k;
    const std::complex<double> root =
        disc < 0 ? std::complex<double>(-c, std::sqrt(-disc)) / (2 * a) : k / (-0.5 * (c + std::sqrt(disc)));
    if (std::abs(root) < slowest) {
      slowest = std::abs(root);
      overlap.slowest_discarded_rad_s = root;
    }
  }
  const galerkin::SecondOrderSystem kept{b.mass.topLeftCorner(retained, retained),
                                         b.damping.topLeftCorner(retained, retained),
                                         b.stiffness.topLeftCorner(retained, retained)};
  const Eigen::VectorXcd lambda = galerkin::StateSpaceModes(kept).eigenvalues();
  overlap.fastest_retained_rad_s = lambda.cwiseAbs().maxCoeff();
  overlap.nearest_retained_relative =
      (lambda.array() - overlap.slowest_discarded_rad_s).abs().minCoeff() / std::abs(overlap.slowest_discarded_rad_s);
  return overlap;
}

}  // namespace beamid::simulation
