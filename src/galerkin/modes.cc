#include "galerkin/modes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "core/errors.h"
#include "galerkin/complex_products.h"

namespace beamid::galerkin {

namespace {

// M phi = mu (K + sigma M) phi, mu = 1/(omega^2 + sigma), through the Cholesky factor K + sigma M = L L^T; nothing
// when the factorisation or the eigensolver fails, or a mu is not positive.
std::optional<UndampedModes> shifted_undamped_modes(const SecondOrderSystem& s, double sigma) {
  const Eigen::LLT<Eigen::MatrixXd> stiffness(sigma == 0 ? s.K : Eigen::MatrixXd(s.K + sigma * s.M));
  if (stiffness.info() != Eigen::Success) return std::nullopt;
  const Eigen::MatrixXd l_inv_m = stiffness.matrixL().solve(s.M);
  const Eigen::MatrixXd reduced = stiffness.matrixL().solve(l_inv_m.transpose());  // L^-1 M L^-T
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(0.5 * (reduced + reduced.transpose()));
  if (solver.info() != Eigen::Success || solver.eigenvalues().minCoeff() <= 0) return std::nullopt;
  const Eigen::Index n = s.M.rows();
  UndampedModes modes;
  modes.omega_rad_s.resize(n);
  modes.shapes.resize(n, n);
  // Eigenvalues come in increasing mu, i.e. decreasing omega: reverse. phi = L^-T y / sqrt(mu) has phi^T M phi = 1.
  const Eigen::MatrixXd phi = stiffness.matrixU().solve(solver.eigenvectors());
  for (Eigen::Index k = 0; k < n; ++k) {
    const double mu = solver.eigenvalues()(n - 1 - k);
    const double omega2 = 1 / mu - sigma;
    if (!(omega2 > 0)) return std::nullopt;
    modes.omega_rad_s(k) = std::sqrt(omega2);
    modes.shapes.col(k) = phi.col(n - 1 - k) / std::sqrt(mu);
  }
  return modes;
}

}  // namespace

UndampedModes undamped_modes(const SecondOrderSystem& s) {
  // Solved as M phi = mu K phi, mu = 1/omega^2, through the Cholesky factor K = L L^T: the symmetric eigensolver's
  // absolute error eps max(mu) is then relative to the low modes, which are the ones observed. The direct form
  // (Cholesky of M) has absolute error eps omega_max^2 instead, and the shear modes near the cut-off (~1e7 rad/s for
  // the thin beam) then cost the first mode ~1e-4 of relative accuracy and break Rayleigh-Ritz bounds.
  if (auto modes = shifted_undamped_modes(s, 0)) return *modes;
  // A near-rigid mode (a soft clamp spring: omega_min^2 below eps omega_max^2) makes max(mu) so large that the
  // smallest mu drowns in its error. Shifted by sigma, mu = 1/(omega^2 + sigma) is at most 1/sigma: with sigma =
  // 1e-10 max_i K_ii/M_ii (at most 1e-10 omega_max^2, a Rayleigh quotient), the smallest mu stays ~1e-10 of the
  // largest, far above eps, while the near-rigid mode keeps a relative accuracy of eps sigma/omega_min^2 (3e-10 for the
  // thin beam on a clamp spring of k_theta l/EI = 1e-4) and the elastic modes eps (1 + sigma/omega^2)^2.
  const double ratio = (s.K.diagonal().array() / s.M.diagonal().array()).maxCoeff();
  if (std::isfinite(ratio) && ratio > 0)
    if (auto modes = shifted_undamped_modes(s, 1e-10 * ratio)) return *modes;
  throw NumericalError(
      "undamped eigenproblem M phi = mu (K + sigma M) phi failed: the mass or stiffness matrix is "
      "not positive definite to double precision");
}

SecondOrderSystem with_modal_damping(SecondOrderSystem system, double damping_ratio) {
  if (!(damping_ratio >= 0 && damping_ratio < 1))
    throw InputError("modal damping ratio = " + format_value(damping_ratio) + ": must be in [0, 1)");
  if (damping_ratio == 0) return system;
  const UndampedModes modes = undamped_modes(system);
  const Eigen::MatrixXd m_phi = system.M * modes.shapes;  // M Phi
  system.C += m_phi * (2 * damping_ratio * modes.omega_rad_s).asDiagonal() * m_phi.transpose();
  return system;
}

UndampedModes lowest_undamped_modes(const BeamForms& forms, const model::BeamParameters& beam, int modes) {
  UndampedModes m = undamped_modes(combine(forms, beam));
  if (m.omega_rad_s.size() < modes)
    throw InputError("the Galerkin model has " + std::to_string(m.omega_rad_s.size()) + " modes, " +
                     std::to_string(modes) + " are fitted");
  m.omega_rad_s.conservativeResize(modes);
  m.shapes.conservativeResize(Eigen::NoChange, modes);
  return m;
}

Eigen::MatrixXd frequency_sensitivities(const BeamForms& forms, const model::BeamParameters& beam,
                                        const std::vector<std::string>& keys, int modes) {
  const UndampedModes m = lowest_undamped_modes(forms, beam, modes);
  Eigen::MatrixXd g(modes, static_cast<Eigen::Index>(keys.size()));
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const SecondOrderSystem d = parameter_derivative(forms, beam, keys[i]);
    const double q = model::parameter_value(beam, keys[i]);
    for (int k = 0; k < modes; ++k) {
      const Eigen::VectorXd phi = m.shapes.col(k);
      const double w2 = m.omega_rad_s(k) * m.omega_rad_s(k);
      g(k, static_cast<Eigen::Index>(i)) = q * phi.dot(d.K * phi - w2 * (d.M * phi)) / (2 * w2);
    }
  }
  return g;
}

namespace {

using complex = std::complex<double>;

// A cluster's Gram matrix G = q^T C~ q + diag(l) q^T M~ q + q^T M~ q diag(l) (real or complex columns q, their
// products mq = M~ q, cq = C~ q, eigenvalues l), scaled to a unit diagonal, G = D S D with D = diag(sqrt |G_aa|), and
// S factored into lu: sets inverse_scale = D^-1 and returns S's reciprocal condition estimate (0 when S is not finite,
// and then lu is left unfactored).
template <typename Matrix, typename Vector, typename Lu>
double factor_scaled_gram(const Matrix& q, const Matrix& mq, const Matrix& cq, const Vector& l,
                          Eigen::VectorXd& inverse_scale, Lu& lu) {
  const Matrix mass_part = q.transpose() * mq;
  const Matrix gram = q.transpose() * cq + l.asDiagonal() * mass_part + mass_part * l.asDiagonal();
  inverse_scale = gram.diagonal().cwiseAbs().cwiseSqrt().cwiseInverse();
  const Matrix scaled = inverse_scale.asDiagonal() * gram * inverse_scale.asDiagonal();
  if (!scaled.allFinite()) return 0;
  lu.compute(scaled);
  return lu.rcond();
}

}  // namespace

StateSpaceModes::StateSpaceModes(const SecondOrderSystem& s, DampedModesMethod method) {
  const UndampedModes undamped = undamped_modes(s);
  shapes_ = undamped.shapes;
  mass_shapes_ = s.M * shapes_;
  damping_shapes_ = s.C * shapes_;
  Eigen::MatrixXd mt = shapes_.transpose() * mass_shapes_;
  Eigen::MatrixXd kt = shapes_.transpose() * (s.K * shapes_);
  Eigen::MatrixXd ct = shapes_.transpose() * damping_shapes_;
  separate_close_modes(undamped.omega_rad_s, mt, kt, ct);
  system_mass_.compute(s.M);
  if (system_mass_.info() != Eigen::Success || (mt.diagonal().array() <= 0).any())
    throw NumericalError("mass matrix is not positive definite");
  const Eigen::VectorXd scale = kt.diagonal().cwiseMax(0.0).cwiseSqrt();
  if ((scale.array() <= 0).any()) throw NumericalError("stiffness matrix is not positive definite");

  Eigen::VectorXcd stiffness_forms;
  iterated_ = method == DampedModesMethod::automatic && iterate_damped_modes(mt, ct, kt, stiffness_forms);
  if (iterated_) {
    // A wrong convergence (two starts reaching one eigenpair, or a vector spoilt by a near-defective mode) shows as a
    // singular cluster Gram matrix or a vanishing n_k: the dense decomposition decides then.
    const double rcond = finish(stiffness_forms, scale);
    if (rcond > 1e3 * std::numeric_limits<double>::epsilon()) {
      rcond_ = rcond;
      require_resolved_decay_rates(s.C);
      return;
    }
    iterated_ = false;
    clusters_.clear();
    cluster_gram_.clear();
  }
  const Eigenpairs dense = decompose_state_matrix(mt, ct, kt, scale);
  Eigen::MatrixXcd stiffness_q;  // K~ q_k, for the forms and the residuals
  adopt(dense, mt, ct, kt, stiffness_q, stiffness_forms);
  rcond_ = finish(stiffness_forms, scale);
  std::string doubt = doubtful_eigenpair(stiffness_q);
  if (!doubt.empty()) {
    // A graded spectrum (heavy Kelvin-Voigt damping: the thin beam with cDI = 1e3, kAcs = 1e9 has damping rates up
    // to 5e16 1/s and eigenvalues down to 5e-4 1/s): A's absolute error eps ||A|| swamps the small eigenvalues, which
    // then come out with the wrong sign or as spurious underdamped pairs. The reversed pencil's error is
    // eps ||B|| |lambda|^2 in lambda, so the two are combined at |lambda| = sqrt(||A|| / ||B||), where their errors are
    // equal: the larger eigenvalues from A, the smaller from B (tropical scaling's idea, Gaubert & Sharify 2009).
    clusters_.clear();
    cluster_gram_.clear();
    Eigenpairs graded = combine_graded(dense, decompose_reversed_state_matrix(mt, ct, kt), mt, ct, kt, scale);
    refine_eigenpairs(graded, mt, ct, kt);
    adopt(std::move(graded), mt, ct, kt, stiffness_q, stiffness_forms);
    rcond_ = finish(stiffness_forms, scale);
    doubt = doubtful_eigenpair(stiffness_q);
    if (!doubt.empty())
      throw NumericalError("the damped modes cannot be computed accurately in double precision: " + doubt +
                           " (the damping rates span too many orders of magnitude)");
  }
  if (!(rcond_ > 1e3 * std::numeric_limits<double>::epsilon()))
    throw NumericalError(
        "state-space modes are (nearly) defective: eigenvalue condition rcond = " + format_rounded(rcond_, 2) +
        " (two damped modes coincide: a mode damped almost exactly critically, which shear damping "
        "kAcs or cDI far beyond a real beam's makes likely; another N, or smaller damping, avoids "
        "it)");
  require_resolved_decay_rates(s.C);
}

void StateSpaceModes::separate_close_modes(const Eigen::VectorXd& omega, Eigen::MatrixXd& mt, Eigen::MatrixXd& kt,
                                           Eigen::MatrixXd& ct) {
  // undamped_modes solves M phi = mu K phi so that the low modes are accurate; its error eps max(mu) is absolute, so
  // within a group of nearly equal high frequencies (the thin beam's 17 shear modes at 6.09e6 .. 6.13e6 rad/s at
  // N = 16) the shapes are mixed and M~ has off-diagonal entries up to ~1e-6 there. That is harmless to an exact
  // similarity (the dense path), but it is a coupling the Jacobi iteration would have to remove, larger than the
  // damping's own. So each group of consecutive frequencies less than 1 % apart is rotated by the solution of its own
  // small pencil (K~_BB, M~_BB) in the direct form (Cholesky of M~_BB ~ I, no grading within a group): afterwards
  // M~_BB = I and K~_BB is diagonal to round-off, and the basis is still exact (Phi_B Z for an invertible Z).
  // A group whose every member is overdamped on its own (C~_jj^2 > 4 M~_jj K~_jj), such as the thin beam's shear
  // modes, is left as it is: its real roots fall into the iteration's Rayleigh-Ritz blocks (damped_iteration.cc),
  // whose projected pencils take the coupling within the group exactly, mixing included. Skipping its rotation saves
  // a tenth of StateSpaceModes at N = 16 (BM_StateSpaceModes/16 0.388 -> 0.350 ms, side by side), and the iteration
  // still converges as often: 371 against 373 of 400 thin beams with six parameters drawn within 10 % of the preset,
  // where the rest fall back to the dense decomposition either way.
  const Eigen::Index n = omega.size();
  for (Eigen::Index first = 0; first < n;) {
    Eigen::Index last = first;
    while (last + 1 < n && omega(last + 1) < 1.01 * omega(last)) ++last;
    const Eigen::Index size = last - first + 1;
    const auto overdamped = [&] {
      for (Eigen::Index j = first; j <= last; ++j)
        if (!(ct(j, j) * ct(j, j) > 4 * mt(j, j) * kt(j, j))) return false;
      return true;
    };
    if (size > 1 && !overdamped()) {
      const Eigen::LLT<Eigen::MatrixXd> mass(mt.block(first, first, size, size));
      if (mass.info() != Eigen::Success) throw NumericalError("mass matrix is not positive definite");
      Eigen::MatrixXd reduced = mass.matrixL().solve(kt.block(first, first, size, size));
      reduced = mass.matrixL().solve(reduced.transpose()).eval();
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(0.5 * (reduced + reduced.transpose()));
      if (solver.info() != Eigen::Success) throw NumericalError("undamped eigenproblem of a mode group failed");
      const Eigen::MatrixXd z = mass.matrixU().solve(solver.eigenvectors());
      for (Eigen::MatrixXd* x : {&mt, &kt, &ct}) {
        x->middleCols(first, size) = (x->middleCols(first, size) * z).eval();
        x->middleRows(first, size) = (z.transpose() * x->middleRows(first, size)).eval();
      }
      for (Eigen::MatrixXd* x : {&shapes_, &mass_shapes_, &damping_shapes_})
        x->middleCols(first, size) = (x->middleCols(first, size) * z).eval();
    }
    first = last + 1;
  }
}

double StateSpaceModes::finish(const Eigen::VectorXcd& stiffness_forms, const Eigen::VectorXd& scale) {
  const Eigen::VectorXcd mass_forms = column_products(q_, mass_q_);
  const Eigen::VectorXcd damping_forms = column_products(q_, damping_q_);
  refine_eigenvalues(mass_forms, damping_forms, stiffness_forms);
  normalisation_ = 2.0 * lambda_.cwiseProduct(mass_forms) + damping_forms;
  const double cluster_rcond = group_clusters();

  // The condition of eigenvalue k of A, |u_k| |v_k| / |u_k^T v_k|, with its right eigenvector v_k = [D q_k;
  // lambda_k q_k] in z = [D q; q'] coordinates and its left one from the symmetric pencil (eta_k = phi_k^T [C M; M 0]
  // u / n_k with u = [w; w'] = [Phi D^-1 z1; Phi z2]): u_k = [D^-1 (lambda_k M~ + C~) q_k; M~ q_k] / n_k.
  double worst = 0;
  for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
    const double left = std::sqrt(
        (scale.cwiseInverse().asDiagonal() * (lambda_(k) * mass_q_.col(k) + damping_q_.col(k))).squaredNorm() +
        mass_q_.col(k).squaredNorm());
    const double right =
        std::sqrt((scale.asDiagonal() * q_.col(k)).squaredNorm() + std::norm(lambda_(k)) * q_.col(k).squaredNorm());
    const double condition = left * right / std::abs(normalisation_(k));
    worst = std::isfinite(condition) ? std::max(worst, condition) : std::numeric_limits<double>::infinity();
  }
  // A cluster whose vectors are nearly parallel has a near-singular Gram matrix even when each n_k is not small.
  return std::min(worst > 0 ? 1 / worst : 0.0, cluster_rcond);
}

void StateSpaceModes::refine_eigenvalues(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b,
                                         const Eigen::VectorXcd& c) {
  // The QR algorithm's backward error is eps ||A||, and ||A|| is set by the largest damping rates (kAcs/rho_r2 ~ 5e8
  // 1/s for the thin beam), which can cost a slow mode 1e-7 of relative accuracy. For the complex-symmetric
  // T(lambda) = lambda^2 M + lambda C + K the Rayleigh functional, the root of x^T T(lambda) x = 0 (transpose, not
  // conjugate), is stationary at eigenvectors: with the computed x it corrects lambda to second order in x's error,
  // using the stored M, C, K. The root nearest the QR value is taken, and only if it moves lambda by < 1e-6
  // relative (else x is too inaccurate, e.g. inside a cluster of nearly equal shear relaxation rates).
  for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
    if (lambda_(k).imag() < 0) continue;  // set with its partner below
    const std::optional<complex> root = nearest_root(a(k), b(k), c(k), lambda_(k));
    if (!root) continue;
    const complex best = *root;
    if (!(std::abs(best - lambda_(k)) < 1e-6 * std::abs(lambda_(k)))) continue;
    if (lambda_(k).imag() == 0) {
      lambda_(k) = best.real();
      continue;
    }
    // Its conjugate partner: Eigen's solver stores a complex pair as exact conjugates at k and k + 1. Matching by
    // that exact value, not by nearness, keeps two underdamped modes less than 1e-6 apart from trading partners.
    const complex partner = std::conj(lambda_(k));
    lambda_(k) = best;
    for (Eigen::Index j = k + 1; j < lambda_.size(); ++j)
      if (lambda_(j) == partner) {
        lambda_(j) = std::conj(best);
        break;
      }
  }
}

double StateSpaceModes::group_clusters() {
  // Union of every pair within 1e-3 (relative) of each other, by a scan over the pairs (2n is small).
  constexpr double kClusterGap = 1e-3;
  const Eigen::Index m = lambda_.size();
  std::vector<Eigen::Index> root(static_cast<std::size_t>(m));
  for (Eigen::Index k = 0; k < m; ++k) root[k] = k;
  const auto find = [&root](Eigen::Index k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index k = j + 1; k < m; ++k)
      if (std::norm(lambda_(j) - lambda_(k)) <=
          kClusterGap * kClusterGap * std::max(std::norm(lambda_(j)), std::norm(lambda_(k))))
        root[find(k)] = find(j);
  std::vector<std::vector<Eigen::Index>> members(static_cast<std::size_t>(m));
  double smallest = 1;
  for (Eigen::Index k = 0; k < m; ++k) members[find(k)].push_back(k);
  for (auto& cluster : members) {
    if (cluster.size() < 2) continue;
    // G_ab = q_a^T C~ q_b + (lambda_a + lambda_b) q_a^T M~ q_b, as products of the cluster's columns: real ones when
    // the cluster is (the thin beam's slow and fast shear roots, two clusters of 17 real roots at N = 16), where
    // Eigen's complex product kernel would take four times the work and more.
    // It is factored once, scaled to a unit diagonal, G = D S D with D = diag(sqrt |G_aa|): S's LU gives the
    // reciprocal condition (its estimate) and the solve, G^-1 r = D^-1 S^-1 D^-1 r.
    const Eigen::VectorXcd l = lambda_(cluster);
    ClusterGram solver;
    solver.real = l.imag().isZero(0.0) && q_(Eigen::all, cluster).imag().isZero(0.0);
    const double rcond = solver.real
                             ? factor_scaled_gram(Eigen::MatrixXd(q_(Eigen::all, cluster).real()),
                                                  Eigen::MatrixXd(mass_q_(Eigen::all, cluster).real()),
                                                  Eigen::MatrixXd(damping_q_(Eigen::all, cluster).real()),
                                                  Eigen::VectorXd(l.real()), solver.inverse_scale, solver.real_lu)
                             : factor_scaled_gram(Eigen::MatrixXcd(q_(Eigen::all, cluster)),
                                                  Eigen::MatrixXcd(mass_q_(Eigen::all, cluster)),
                                                  Eigen::MatrixXcd(damping_q_(Eigen::all, cluster)), l,
                                                  solver.inverse_scale, solver.complex_lu);
    smallest = std::isfinite(rcond) ? std::min(smallest, rcond) : 0.0;
    cluster_gram_.push_back(std::move(solver));
    clusters_.push_back(std::move(cluster));
  }
  return smallest;
}

Eigen::VectorXcd StateSpaceModes::ClusterGram::solve(const Eigen::VectorXcd& rhs) const {
  const auto d_inv = inverse_scale.asDiagonal();
  if (!real) return d_inv * complex_lu.solve(d_inv * rhs);
  Eigen::VectorXcd out(rhs.size());
  out.real() = d_inv * real_lu.solve(d_inv * rhs.real());
  out.imag() = d_inv * real_lu.solve(d_inv * rhs.imag());
  return out;
}

Eigen::VectorXcd StateSpaceModes::modal_solve(const Eigen::VectorXcd& rhs) const {
  Eigen::VectorXcd eta = rhs.cwiseQuotient(normalisation_);
  for (std::size_t c = 0; c < clusters_.size(); ++c) {
    const auto& cluster = clusters_[c];
    Eigen::VectorXcd block(static_cast<Eigen::Index>(cluster.size()));
    for (std::size_t a = 0; a < cluster.size(); ++a) block(a) = rhs(cluster[a]);
    block = cluster_gram_[c].solve(block);
    for (std::size_t a = 0; a < cluster.size(); ++a) eta(cluster[a]) = block(a);
  }
  return eta;
}

// x_k^T v = q_k^T (Phi^T v) for every k.
Eigen::VectorXcd StateSpaceModes::project(const Eigen::MatrixXd& basis, const Eigen::VectorXd& v) const {
  const Eigen::VectorXd reduced = basis.transpose() * v;
  Eigen::VectorXcd out(q_.cols());
  out.real() = q_.real().transpose() * reduced;
  out.imag() = q_.imag().transpose() * reduced;
  return out;
}

Eigen::VectorXcd StateSpaceModes::input_coefficients(const Eigen::VectorXd& load) const {
  return modal_solve(project(shapes_, load));
}

Eigen::VectorXcd StateSpaceModes::state_coefficients(const Eigen::VectorXd& w0, const Eigen::VectorXd& v0) const {
  // x_k^T M w0 = q_k^T (M Phi)^T w0, and so on.
  const Eigen::VectorXcd mw = project(mass_shapes_, w0);
  const Eigen::VectorXcd cw = project(damping_shapes_, w0);
  const Eigen::VectorXcd mv = project(mass_shapes_, v0);
  return modal_solve(lambda_.cwiseProduct(mw) + cw + mv);
}

Eigen::VectorXcd StateSpaceModes::output_coefficients(const Eigen::VectorXd& sensor, int derivative) const {
  Eigen::VectorXcd h = project(shapes_, sensor);
  for (int d = 0; d < derivative; ++d) h = h.cwiseProduct(lambda_);
  return h;
}

Eigen::MatrixXcd StateSpaceModes::physical_vectors() const { return real_times(shapes_, q_); }

Eigen::VectorXcd StateSpaceModes::eigenvalue_derivative(const SecondOrderSystem& d) const {
  const Eigen::MatrixXcd x = physical_vectors();
  // x_k^T D x_k for each of dM, dC, dK; a parameter moves one or two of them, and the others are zero.
  const auto forms = [&x](const Eigen::MatrixXd& m) -> Eigen::VectorXcd {
    return m.isZero(0.0) ? Eigen::VectorXcd::Zero(x.cols()) : column_products(x, real_times(m, x));
  };
  const Eigen::VectorXcd dm = forms(d.M), dc = forms(d.C), dk = forms(d.K);
  return -(lambda_.cwiseProduct(lambda_).cwiseProduct(dm) + lambda_.cwiseProduct(dc) + dk)
              .cwiseQuotient(normalisation_);
}

double StateSpaceModes::feedthrough(const Eigen::VectorXd& sensor, const Eigen::VectorXd& load) const {
  return sensor.dot(system_mass_.solve(load));
}

std::vector<DampedMode> StateSpaceModes::underdamped_modes() const {
  std::vector<DampedMode> modes;
  for (const auto& lambda : lambda_) {
    if (lambda.imag() <= 0) continue;
    const double magnitude = std::abs(lambda);
    if (-lambda.real() / magnitude > 1 - kCriticalMargin) continue;
    // An undamped beam's poles lie on the axis to round-off, either side: its ratios of -1e-24 are 0 (a passive beam
    // has no negative damping ratio: the thirty-second pass's adv73 P2). Only round-off's: 1e-12 and beyond is kept.
    const double ratio = -lambda.real() / magnitude;
    modes.push_back({magnitude / (2 * std::numbers::pi), ratio < 0 && ratio > -1e-12 ? 0.0 : ratio, lambda});
  }
  std::sort(modes.begin(), modes.end(),
            [](const DampedMode& a, const DampedMode& b) { return a.frequency_hz < b.frequency_hz; });
  return modes;
}

}  // namespace beamid::galerkin
