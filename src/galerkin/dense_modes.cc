// The dense decompositions of the damped modes (StateSpaceModes, modes.h): the state matrix A when the Jacobi
// iteration (damped_iteration.cc) gives way, the checks of every eigenpair it gives (residual, passivity), and for a
// graded spectrum the reversed pencil, the combination of the two and their Newton refinement.
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "galerkin/complex_products.h"
#include "galerkin/modes.h"

namespace beamid::galerkin {

using complex = std::complex<double>;

StateSpaceModes::Eigenpairs StateSpaceModes::decompose_state_matrix(const Eigen::MatrixXd& mt,
                                                                    const Eigen::MatrixXd& ct,
                                                                    const Eigen::MatrixXd& kt,
                                                                    const Eigen::VectorXd& scale) {
  const Eigen::Index n = mt.rows();
  const Eigen::LLT<Eigen::MatrixXd> mass(0.5 * (mt + mt.transpose()));
  if (mass.info() != Eigen::Success) throw NumericalError("mass matrix is not positive definite");
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n) = scale.asDiagonal();
  a.bottomLeftCorner(n, n) = -mass.solve(kt) * scale.cwiseInverse().asDiagonal();
  a.bottomRightCorner(n, n) = -mass.solve(ct);

  Eigen::EigenSolver<Eigen::MatrixXd> eig(a, true);
  if (eig.info() != Eigen::Success) throw NumericalError("state-space eigen-decomposition did not converge");
  Eigenpairs pairs{eig.eigenvalues(), Eigen::MatrixXcd(n, 2 * n)};
  // q_k = D^-1 (v_k)_top = (v_k)_bottom / lambda_k, taken component by component from the half with the larger
  // divisor: the eigensolver's error is eps |v_k| in every component, so the top half loses accuracy in the components
  // where D_j < |lambda_k| (overdamped modes) and the bottom half where D_j > |lambda_k|.
  const Eigen::MatrixXcd& v = eig.eigenvectors();
  for (Eigen::Index k = 0; k < 2 * n; ++k)
    for (Eigen::Index j = 0; j < n; ++j)
      pairs.q(j, k) = scale(j) >= std::abs(pairs.lambda(k)) ? v(j, k) / scale(j) : v(n + j, k) / pairs.lambda(k);
  return pairs;
}

StateSpaceModes::Eigenpairs StateSpaceModes::decompose_reversed_state_matrix(const Eigen::MatrixXd& mt,
                                                                             const Eigen::MatrixXd& ct,
                                                                             const Eigen::MatrixXd& kt) {
  // mu^2 K~ q + mu C~ q + M~ q = 0 in z = [E q; mu q] with E = sqrt(diag M~) (M~ ~ I after the undamped rotation):
  //   B = [ 0                 E          ]
  //       [ -K~^-1 M~ E^-1    -K~^-1 C~  ],
  // whose entries are of the size of the relaxation times c/k and 1/omega^2 (2e3 s for cDI/EI = 2e3 s).
  const Eigen::Index n = mt.rows();
  const Eigen::LLT<Eigen::MatrixXd> stiffness(0.5 * (kt + kt.transpose()));
  if (stiffness.info() != Eigen::Success) throw NumericalError("stiffness matrix is not positive definite");
  const Eigen::VectorXd e = mt.diagonal().cwiseMax(0.0).cwiseSqrt();
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  b.topRightCorner(n, n) = e.asDiagonal();
  b.bottomLeftCorner(n, n) = -stiffness.solve(mt) * e.cwiseInverse().asDiagonal();
  b.bottomRightCorner(n, n) = -stiffness.solve(ct);
  Eigen::EigenSolver<Eigen::MatrixXd> eig(b, true);
  if (eig.info() != Eigen::Success) throw NumericalError("reversed state-space eigen-decomposition did not converge");
  const Eigen::VectorXcd mu = eig.eigenvalues();
  const Eigen::MatrixXcd& v = eig.eigenvectors();
  Eigenpairs pairs{Eigen::VectorXcd(2 * n), Eigen::MatrixXcd(n, 2 * n)};
  for (Eigen::Index k = 0; k < 2 * n; ++k) {
    // lambda = conj(mu) / |mu|^2, so that a conjugate pair of mu gives an exact conjugate pair of lambda; mu = 0
    // (an infinite lambda) cannot come from a positive definite M~ and is left infinite for the checks to refuse.
    pairs.lambda(k) = std::conj(mu(k)) / std::norm(mu(k));
    for (Eigen::Index j = 0; j < n; ++j)  // as in decompose_state_matrix, from the half with the larger divisor
      pairs.q(j, k) = e(j) >= std::abs(mu(k)) ? v(j, k) / e(j) : v(n + j, k) / mu(k);
  }
  return pairs;
}

StateSpaceModes::Eigenpairs StateSpaceModes::combine_graded(const Eigenpairs& dense, const Eigenpairs& reversed,
                                                            const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                                                            const Eigen::MatrixXd& kt, const Eigen::VectorXd& scale) {
  // ||A|| and ||B|| by their largest blocks' max norms (only their ratio matters, within a factor of order one).
  const double norm_a =
      std::max({scale.maxCoeff(), (ct.cwiseAbs().rowwise().sum().array() / mt.diagonal().array()).maxCoeff()});
  const double norm_b = std::max({mt.diagonal().cwiseSqrt().maxCoeff(),
                                  (ct.cwiseAbs().rowwise().sum().array() / kt.diagonal().array()).maxCoeff()});
  const double threshold = std::sqrt(norm_a / norm_b);
  const Eigen::Index m = dense.lambda.size();
  std::vector<std::pair<const Eigenpairs*, Eigen::Index>> chosen;
  for (const auto& [from, large] : {std::pair{&dense, true}, std::pair{&reversed, false}})
    for (Eigen::Index j = 0; j < from->lambda.size(); ++j) {
      const double size = std::abs(from->lambda(j));
      if (std::isfinite(size) && (size > threshold) == large) chosen.emplace_back(from, j);  // (mu = 0: no lambda)
    }
  if (static_cast<Eigen::Index>(chosen.size()) != m)
    throw NumericalError(
        "the damped modes cannot be computed accurately in double precision: the two decompositions of the graded "
        "spectrum disagree about its eigenvalues near " +
        format_value(threshold) + " 1/s");
  Eigenpairs out{Eigen::VectorXcd(m), Eigen::MatrixXcd(dense.q.rows(), m)};
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto& [from, j] = chosen[static_cast<std::size_t>(k)];
    out.lambda(k) = from->lambda(j);
    out.q.col(k) = from->q.col(j);
  }
  return out;
}

namespace {

// max_j |(T~(lambda) q)_j| / max_j (|lambda|^2 |M~ q|_j + |lambda| |C~ q|_j + |K~ q|_j).
double relative_residual(complex l, const Eigen::VectorXcd& mq, const Eigen::VectorXcd& cq,
                         const Eigen::VectorXcd& kq) {
  double residual = 0, size = 0;
  for (Eigen::Index j = 0; j < mq.size(); ++j) {
    residual = std::max(residual, std::abs(l * l * mq(j) + l * cq(j) + kq(j)));
    size = std::max(size, std::norm(l) * std::abs(mq(j)) + std::abs(l) * std::abs(cq(j)) + std::abs(kq(j)));
  }
  return residual / size;
}

}  // namespace

void StateSpaceModes::refine_eigenpairs(Eigenpairs& pairs, const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                                        const Eigen::MatrixXd& kt) {
  // For T(lambda) x = 0 Newton's method is inverse iteration with a moving shift: x <- T(lambda)^-1 T'(lambda) x with
  // T' = 2 lambda M~ + C~, then lambda <- the root of the Rayleigh functional x^T T(lambda) x = 0 nearest lambda
  // (transpose: T is complex symmetric). It converges quadratically from the combined decompositions' pairs, whose
  // eigenvalues are already accurate to their decomposition's error; T(lambda) is factored with partial pivoting,
  // which is backward stable for its graded rows. A complex pair's partner is its conjugate; a real pair stays real.
  constexpr int kSteps = 6;
  const Eigen::MatrixXcd m = mt.cast<complex>(), c = ct.cast<complex>(), k = kt.cast<complex>();
  for (Eigen::Index p = 0; p < pairs.lambda.size(); ++p) {
    complex l = pairs.lambda(p);
    if (l.imag() < 0 || !std::isfinite(std::abs(l))) continue;  // set with its partner, or left to the checks
    const bool real = l.imag() == 0;
    Eigen::VectorXcd x = pairs.q.col(p);
    double best = relative_residual(l, m * x, c * x, k * x);
    for (int step = 0; step < kSteps && best > 1e-14; ++step) {
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(l * l * m + l * c + k);
      Eigen::VectorXcd y = lu.solve((2.0 * l * m + c) * x);
      Eigen::Index at = 0;
      y.cwiseAbs().maxCoeff(&at);
      if (!(std::abs(y(at)) > 0) || !y.allFinite()) break;
      y /= y(at);
      if (real) y = y.real().cast<complex>();
      const Eigen::VectorXcd my = m * y, cy = c * y, ky = k * y;
      const std::optional<complex> root =
          nearest_root((y.transpose() * my)(0), (y.transpose() * cy)(0), (y.transpose() * ky)(0), l);
      if (!root) break;
      const complex next = real ? complex(root->real()) : *root;
      const double residual = relative_residual(next, my, cy, ky);
      if (!(residual < best)) break;
      best = residual;
      l = next;
      x = y;
    }
    const complex partner = std::conj(pairs.lambda(p));
    pairs.lambda(p) = l;
    pairs.q.col(p) = x;
    if (real) continue;
    for (Eigen::Index j = 0; j < pairs.lambda.size(); ++j)  // (the reversed pairs may come partner first)
      if (j != p && pairs.lambda(j) == partner) {
        pairs.lambda(j) = std::conj(l);
        pairs.q.col(j) = x.conjugate();
        break;
      }
  }
}

void StateSpaceModes::adopt(Eigenpairs pairs, const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                            const Eigen::MatrixXd& kt, Eigen::MatrixXcd& stiffness_q,
                            Eigen::VectorXcd& stiffness_forms) {
  lambda_ = std::move(pairs.lambda);
  q_ = std::move(pairs.q);
  mass_q_ = real_times(mt, q_);
  damping_q_ = real_times(ct, q_);
  stiffness_q = real_times(kt, q_);
  stiffness_forms = column_products(q_, stiffness_q);
}

std::string StateSpaceModes::doubtful_eigenpair(const Eigen::MatrixXcd& stiffness_q) const {
  const auto text = [](complex l) {
    return format_value(l.real()) + (l.imag() < 0 ? " - " : " + ") + format_value(std::abs(l.imag())) + "i 1/s";
  };
  for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
    const complex l = lambda_(k);
    if (!std::isfinite(std::abs(l))) return "an eigenvalue is not finite";
    // Passivity, to the round-off of the eigenvalue itself.
    if (l.real() > 1e-10 * std::abs(l))
      return "eigenvalue " + text(l) + " lies in the right half-plane, which a passive beam cannot have";
    const double residual = relative_residual(l, mass_q_.col(k), damping_q_.col(k), stiffness_q.col(k));
    if (!(residual <= kDenseResidual))
      return "eigenvalue " + text(l) + " has a relative residual of " + format_value(residual);
  }
  return "";
}

void StateSpaceModes::require_resolved_decay_rates(const Eigen::MatrixXd& c) const {
  const double eps = std::numeric_limits<double>::epsilon();
  const double cheap = eps * c.cwiseAbs().rowwise().sum().maxCoeff() * shapes_.squaredNorm();
  Eigen::MatrixXd abs_c;  // formed only for a mode the cheap bound does not pass
  for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
    const complex l = lambda_(k);
    if (!(l.imag() > 0)) continue;  // (a conjugate partner has the same decay rate; an overdamped pole has no ratio)
    const double mass_form = 2 * std::abs(q_.col(k).dot(mass_q_.col(k)));  // 2 x^H M x = 2 q^H M~ q
    const double allowed = kDecayResolution * std::abs(l.real()) * mass_form;
    if (cheap * q_.col(k).squaredNorm() <= allowed) continue;
    if (abs_c.size() == 0) abs_c = c.cwiseAbs();
    const Eigen::VectorXd x = (shapes_ * q_.col(k)).cwiseAbs();
    const double bound = eps * x.dot(abs_c * x);
    if (bound > allowed)
      throw NumericalError("the damped modes cannot be computed accurately in double precision: the mode at " +
                           format_rounded(l.imag() / (2 * std::numbers::pi)) + " Hz has a decay rate (damping ratio " +
                           format_rounded(-l.real() / std::abs(l), 3) +
                           ") that the damping matrix's round-off leaves uncertain by up to " +
                           format_rounded(100 * bound / mass_form / std::abs(l.real()), 3) +
                           " % of itself (its entries, up to " + format_rounded(abs_c.maxCoeff(), 2) +
                           ", cancel in it: damping kAcs or cDI far beyond a real beam's)");
  }
}

}  // namespace beamid::galerkin
