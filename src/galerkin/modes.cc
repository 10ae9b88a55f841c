#include "galerkin/modes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "model/errors.h"

namespace beamid::galerkin {

UndampedModes undamped_modes(const SecondOrderSystem& s) {
  // Solved as M phi = mu K phi, mu = 1/omega^2, through the Cholesky factor K = L L^T: the symmetric eigensolver's
  // absolute error eps max(mu) is then relative to the low modes, which are the ones observed. The direct form
  // (Cholesky of M) has absolute error eps omega_max^2 instead, and the shear modes near the cut-off (~1e7 rad/s for
  // the thin beam) then cost the first mode ~1e-4 of relative accuracy and break Rayleigh-Ritz bounds.
  const Eigen::LLT<Eigen::MatrixXd> stiffness(s.K);
  if (stiffness.info() != Eigen::Success) throw NumericalError("stiffness matrix K is not positive definite");
  const Eigen::MatrixXd l_inv_m = stiffness.matrixL().solve(s.M);
  const Eigen::MatrixXd reduced = stiffness.matrixL().solve(l_inv_m.transpose());  // L^-1 M L^-T
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(0.5 * (reduced + reduced.transpose()));
  if (solver.info() != Eigen::Success || solver.eigenvalues().minCoeff() <= 0)
    throw NumericalError("undamped eigenproblem M phi = mu K phi failed (is M positive definite?)");
  const Eigen::Index n = s.M.rows();
  UndampedModes modes;
  modes.omega_rad_s.resize(n);
  modes.shapes.resize(n, n);
  // Eigenvalues come in increasing mu, i.e. decreasing omega: reverse. phi = L^-T y / sqrt(mu) has phi^T M phi = 1.
  const Eigen::MatrixXd phi = stiffness.matrixU().solve(solver.eigenvectors());
  for (Eigen::Index k = 0; k < n; ++k) {
    const double mu = solver.eigenvalues()(n - 1 - k);
    modes.omega_rad_s(k) = 1 / std::sqrt(mu);
    modes.shapes.col(k) = phi.col(n - 1 - k) / std::sqrt(mu);
  }
  return modes;
}

namespace {

using complex = std::complex<double>;

// a x for real a and complex x, as two real products (Eigen's mixed real-complex product is several times slower).
Eigen::MatrixXcd real_times(const Eigen::MatrixXd& a, const Eigen::MatrixXcd& x) {
  Eigen::MatrixXcd out(a.rows(), x.cols());
  out.real() = a * x.real();
  out.imag() = a * x.imag();
  return out;
}

// x_k^T y_k for every column k (transpose, not adjoint: the pencil is complex symmetric).
Eigen::VectorXcd column_products(const Eigen::MatrixXcd& x, const Eigen::MatrixXcd& y) {
  return x.cwiseProduct(y).colwise().sum().transpose();
}

}  // namespace

StateSpaceModes::StateSpaceModes(const SecondOrderSystem& s) {
  const int n = static_cast<int>(s.M.rows());
  const Eigen::MatrixXd shapes = undamped_modes(s).shapes;
  const Eigen::MatrixXd mt = shapes.transpose() * s.M * shapes;
  const Eigen::MatrixXd kt = shapes.transpose() * s.K * shapes;
  const Eigen::MatrixXd ct = shapes.transpose() * s.C * shapes;
  const Eigen::LLT<Eigen::MatrixXd> mass(0.5 * (mt + mt.transpose()));
  system_mass_.compute(s.M);
  if (mass.info() != Eigen::Success || system_mass_.info() != Eigen::Success)
    throw NumericalError("mass matrix is not positive definite");
  const Eigen::VectorXd scale = kt.diagonal().cwiseMax(0.0).cwiseSqrt();
  if ((scale.array() <= 0).any()) throw NumericalError("stiffness matrix is not positive definite");

  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n) = scale.asDiagonal();
  a.bottomLeftCorner(n, n) = -mass.solve(kt) * scale.cwiseInverse().asDiagonal();
  a.bottomRightCorner(n, n) = -mass.solve(ct);

  Eigen::EigenSolver<Eigen::MatrixXd> eig(a, true);
  if (eig.info() != Eigen::Success) throw NumericalError("state-space eigen-decomposition did not converge");
  lambda_ = eig.eigenvalues();
  // x_k = Phi q_k with q_k = D^-1 (v_k)_top = (v_k)_bottom / lambda_k, taken component by component from the
  // half with the larger divisor: the eigensolver's error is eps |v_k| in every component, so the top half loses
  // accuracy in the components where D_j < |lambda_k| (overdamped modes) and the bottom half where D_j > |lambda_k|.
  // Then the products with M, C, K that the refinement, the normalisation and the modal coefficients share.
  const Eigen::MatrixXcd& v = eig.eigenvectors();
  Eigen::MatrixXcd q(n, 2 * n);
  for (Eigen::Index k = 0; k < 2 * n; ++k)
    for (Eigen::Index j = 0; j < n; ++j)
      q(j, k) = scale(j) >= std::abs(lambda_(k)) ? v(j, k) / scale(j) : v(n + j, k) / lambda_(k);
  vectors_ = real_times(shapes, q);
  mass_vectors_ = real_times(s.M, vectors_);
  damping_vectors_ = real_times(s.C, vectors_);
  const Eigen::MatrixXcd stiffness_vectors = real_times(s.K, vectors_);
  const Eigen::VectorXcd mass_forms = column_products(vectors_, mass_vectors_);
  const Eigen::VectorXcd damping_forms = column_products(vectors_, damping_vectors_);
  refine_eigenvalues(mass_forms, damping_forms, column_products(vectors_, stiffness_vectors));
  normalisation_ = 2.0 * lambda_.cwiseProduct(mass_forms) + damping_forms;
  const double cluster_rcond = group_clusters();

  // Left eigenvector of A in z = [D q; q'] coordinates: eta_k = phi_k^T [C M; M 0] u / n_k with u = [w; w'] =
  // [Phi D^-1 z1; Phi z2], so u_k = [D^-1 Phi^T (lambda_k M + C) x_k; Phi^T M x_k] / n_k.
  const Eigen::MatrixXcd left_top =
      scale.cwiseInverse().asDiagonal() *
      real_times(shapes.transpose(), mass_vectors_ * lambda_.asDiagonal() + damping_vectors_);
  const Eigen::MatrixXcd left_bottom = real_times(shapes.transpose(), mass_vectors_);
  double worst = 0;
  for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
    const double left = std::sqrt(left_top.col(k).squaredNorm() + left_bottom.col(k).squaredNorm());
    const double condition = left * v.col(k).norm() / std::abs(normalisation_(k));
    worst = std::isfinite(condition) ? std::max(worst, condition) : std::numeric_limits<double>::infinity();
  }
  // A cluster whose vectors are nearly parallel has a near-singular Gram matrix even when each n_k is not small.
  rcond_ = std::min(worst > 0 ? 1 / worst : 0.0, cluster_rcond);
  if (!(rcond_ > 1e3 * std::numeric_limits<double>::epsilon()))
    throw NumericalError("state-space modes are (nearly) defective: eigenvalue condition rcond = " +
                         format_value(rcond_));
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
    const complex root = std::sqrt(b(k) * b(k) - 4.0 * a(k) * c(k));
    // Cancellation-free roots of a x^2 + b x + c: q = -(b + sign root)/2, x1 = q/a, x2 = c/q.
    const complex q = -0.5 * (b(k) + (std::real(std::conj(b(k)) * root) >= 0 ? root : -root));
    if (std::abs(a(k)) == 0 || std::abs(q) == 0) continue;
    const complex x1 = q / a(k), x2 = c(k) / q;
    const complex best = std::abs(x1 - lambda_(k)) <= std::abs(x2 - lambda_(k)) ? x1 : x2;
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
    const auto size = static_cast<Eigen::Index>(cluster.size());
    Eigen::MatrixXcd gram(size, size);
    for (Eigen::Index a = 0; a < size; ++a)
      for (Eigen::Index b = 0; b < size; ++b) {
        const Eigen::Index j = cluster[a], k = cluster[b];
        gram(a, b) =
            vectors_.col(j).transpose() * (damping_vectors_.col(k) + (lambda_(j) + lambda_(k)) * mass_vectors_.col(k));
      }
    // The reciprocal condition of the Gram matrix scaled to a unit diagonal (its LU's estimate).
    Eigen::MatrixXcd scaled(size, size);
    for (Eigen::Index a = 0; a < size; ++a)
      for (Eigen::Index b = 0; b < size; ++b)
        scaled(a, b) = gram(a, b) / std::sqrt(std::abs(gram(a, a)) * std::abs(gram(b, b)));
    const double rcond = scaled.allFinite() ? Eigen::PartialPivLU<Eigen::MatrixXcd>(scaled).rcond() : 0.0;
    smallest = std::isfinite(rcond) ? std::min(smallest, rcond) : 0.0;
    cluster_gram_.emplace_back(gram);
    clusters_.push_back(std::move(cluster));
  }
  return smallest;
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

Eigen::VectorXcd StateSpaceModes::input_coefficients(const Eigen::VectorXd& load) const {
  return modal_solve(vectors_.transpose() * load.cast<complex>());
}

Eigen::VectorXcd StateSpaceModes::state_coefficients(const Eigen::VectorXd& w0, const Eigen::VectorXd& v0) const {
  const Eigen::VectorXcd mw = mass_vectors_.transpose() * w0.cast<complex>();
  const Eigen::VectorXcd cw = damping_vectors_.transpose() * w0.cast<complex>();
  const Eigen::VectorXcd mv = mass_vectors_.transpose() * v0.cast<complex>();
  return modal_solve(lambda_.cwiseProduct(mw) + cw + mv);
}

Eigen::VectorXcd StateSpaceModes::output_coefficients(const Eigen::VectorXd& sensor, int derivative) const {
  Eigen::VectorXcd h = vectors_.transpose() * sensor.cast<complex>();
  for (int d = 0; d < derivative; ++d) h = h.cwiseProduct(lambda_);
  return h;
}

Eigen::MatrixXcd StateSpaceModes::physical_vectors() const { return vectors_; }

Eigen::VectorXcd StateSpaceModes::eigenvalue_derivative(const SecondOrderSystem& d) const {
  const Eigen::VectorXcd dm = column_products(vectors_, real_times(d.M, vectors_));
  const Eigen::VectorXcd dc = column_products(vectors_, real_times(d.C, vectors_));
  const Eigen::VectorXcd dk = column_products(vectors_, real_times(d.K, vectors_));
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
    modes.push_back({magnitude / (2 * std::numbers::pi), -lambda.real() / magnitude, lambda});
  }
  std::sort(modes.begin(), modes.end(),
            [](const DampedMode& a, const DampedMode& b) { return a.frequency_hz < b.frequency_hz; });
  return modes;
}

}  // namespace beamid::galerkin
