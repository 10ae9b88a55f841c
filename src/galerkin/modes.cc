#include "galerkin/modes.h"

#include <algorithm>
#include <cmath>
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

StateSpaceModes::StateSpaceModes(const SecondOrderSystem& s) {
  const int n = static_cast<int>(s.M.rows());
  shapes_ = undamped_modes(s).shapes;
  phi_t_mass_ = shapes_.transpose() * s.M;
  const Eigen::MatrixXd mt = phi_t_mass_ * shapes_;
  const Eigen::MatrixXd kt = shapes_.transpose() * s.K * shapes_;
  const Eigen::MatrixXd ct = shapes_.transpose() * s.C * shapes_;
  mass_.compute(0.5 * (mt + mt.transpose()));
  system_mass_.compute(s.M);
  if (mass_.info() != Eigen::Success || system_mass_.info() != Eigen::Success)
    throw NumericalError("mass matrix is not positive definite");
  scale_ = kt.diagonal().cwiseMax(0.0).cwiseSqrt();
  if ((scale_.array() <= 0).any()) throw NumericalError("stiffness matrix is not positive definite");

  a_ = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a_.topRightCorner(n, n) = scale_.asDiagonal();
  a_.bottomLeftCorner(n, n) = -mass_.solve(kt) * scale_.cwiseInverse().asDiagonal();
  a_.bottomRightCorner(n, n) = -mass_.solve(ct);

  Eigen::EigenSolver<Eigen::MatrixXd> eig(a_, true);
  if (eig.info() != Eigen::Success) throw NumericalError("state-space eigen-decomposition did not converge");
  lambda_ = eig.eigenvalues();
  vectors_ = eig.eigenvectors();
  refine_eigenvalues(s);
  lu_.compute(vectors_);
  rcond_ = lu_.rcond();
  if (!(rcond_ > 1e3 * std::numeric_limits<double>::epsilon()))
    throw NumericalError("state-space modes are (nearly) defective: eigenvector matrix rcond = " +
                         format_value(rcond_));
}

void StateSpaceModes::refine_eigenvalues(const SecondOrderSystem& s) {
  // The QR algorithm's backward error is eps ||A||, and ||A|| is set by the largest damping rates (kAcs/rho_r2 ~ 5e8
  // 1/s for the thin beam), which can cost a slow mode 1e-7 of relative accuracy. For the complex-symmetric
  // T(lambda) = lambda^2 M + lambda C + K the Rayleigh functional, the root of v^T T(lambda) v = 0 (transpose, not
  // conjugate), is stationary at eigenvectors: with the computed v it corrects lambda to second order in v's error,
  // using the stored M, C, K. The root nearest the QR value is taken, and only if it moves lambda by < 1e-6
  // relative (else v is too inaccurate, e.g. inside a cluster of nearly equal shear relaxation rates).
  using complex = std::complex<double>;
  const Eigen::Index n = scale_.size();
  for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
    if (lambda_(k).imag() < 0) continue;  // set with its partner below
    const Eigen::VectorXcd w = shapes_ * (scale_.cwiseInverse().asDiagonal() * vectors_.col(k).head(n));  // w = Phi q
    const complex a = w.transpose() * (s.M * w), b = w.transpose() * (s.C * w), c = w.transpose() * (s.K * w);
    const complex root = std::sqrt(b * b - 4.0 * a * c);
    // Cancellation-free roots of a x^2 + b x + c: q = -(b + sign root)/2, x1 = q/a, x2 = c/q.
    const complex q = -0.5 * (b + (std::real(std::conj(b) * root) >= 0 ? root : -root));
    if (std::abs(a) == 0 || std::abs(q) == 0) continue;
    const complex x1 = q / a, x2 = c / q;
    const complex best = std::abs(x1 - lambda_(k)) <= std::abs(x2 - lambda_(k)) ? x1 : x2;
    if (!(std::abs(best - lambda_(k)) < 1e-6 * std::abs(lambda_(k)))) continue;
    if (lambda_(k).imag() == 0) {
      lambda_(k) = best.real();
      continue;
    }
    lambda_(k) = best;
    for (Eigen::Index j = 0; j < lambda_.size(); ++j)  // its conjugate partner (Eigen stores it next to it)
      if (j != k && lambda_(j).imag() < 0 && std::abs(lambda_(j) - std::conj(lambda_(k))) < 1e-6 * std::abs(best)) {
        lambda_(j) = std::conj(best);
        break;
      }
  }
}

Eigen::VectorXcd StateSpaceModes::input_coefficients(const Eigen::VectorXd& load) const {
  const int n = static_cast<int>(scale_.size());
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * n);
  b.tail(n) = mass_.solve(shapes_.transpose() * load);
  return lu_.solve(b.cast<std::complex<double>>());
}

Eigen::VectorXcd StateSpaceModes::state_coefficients(const Eigen::VectorXd& w0, const Eigen::VectorXd& v0) const {
  const int n = static_cast<int>(scale_.size());
  Eigen::VectorXd z(2 * n);
  z.head(n) = scale_.asDiagonal() * mass_.solve(phi_t_mass_ * w0);  // D Phi^-1 w0
  z.tail(n) = mass_.solve(phi_t_mass_ * v0);                        // Phi^-1 v0
  return lu_.solve(z.cast<std::complex<double>>());
}

Eigen::VectorXcd StateSpaceModes::output_coefficients(const Eigen::VectorXd& sensor, int derivative) const {
  const int n = static_cast<int>(scale_.size());
  const Eigen::VectorXd pc = shapes_.transpose() * sensor;  // y = c^T Phi q
  Eigen::VectorXd row = Eigen::VectorXd::Zero(2 * n);
  if (derivative == 0) {
    row.head(n) = scale_.cwiseInverse().asDiagonal() * pc;  // q = D^-1 z1
  } else if (derivative == 1) {
    row.tail(n) = pc;  // q' = z2
  } else {
    row = a_.bottomRows(n).transpose() * pc;  // q'' = (A z)_2 + load term
  }
  return vectors_.transpose() * row.cast<std::complex<double>>();
}

Eigen::MatrixXcd StateSpaceModes::physical_vectors() const {
  const Eigen::Index n = scale_.size();
  // z = [D q; q'] and w = Phi q, so the displacement part of column k is Phi D^-1 z1.
  return shapes_.cast<std::complex<double>>() *
         (scale_.cwiseInverse().cast<std::complex<double>>().asDiagonal() * vectors_.topRows(n));
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
