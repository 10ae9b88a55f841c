// Products of real and complex matrices as real products: Eigen's mixed real-complex product, and at these sizes
// (n ~ 36, 2n ~ 72) its complex-complex kernel, are several times slower than its real one. Used by the damped modes
// (galerkin/modes.cc) and their parameter derivatives (simulation/sensitivities.cc).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <vector>

namespace beamid::galerkin {

// a x for real a and complex x: two real products.
inline Eigen::MatrixXcd real_times(const Eigen::MatrixXd& a, const Eigen::MatrixXcd& x) {
  Eigen::MatrixXcd out(a.rows(), x.cols());
  out.real() = a * x.real();
  out.imag() = a * x.imag();
  return out;
}

// x_k^T y_k for every column k (transpose, not adjoint).
inline Eigen::VectorXcd column_products(const Eigen::MatrixXcd& x, const Eigen::MatrixXcd& y) {
  return x.cwiseProduct(y).colwise().sum().transpose();
}

// The root of a x^2 + b x + c = 0 nearest `near`: the Rayleigh functional's root for T(lambda) = lambda^2 M + lambda C
// + K at a vector x (a = x^T M x, b = x^T C x, c = x^T K x; transpose, not adjoint), which the damped modes use to
// refine an eigenvalue (modes.cc, damped_iteration.cc). From the cancellation-free pair x1 = q / a, x2 = c / q with
// q = -(b + sign root) / 2; none when a or q vanishes.
inline std::optional<std::complex<double>> nearest_root(std::complex<double> a, std::complex<double> b,
                                                        std::complex<double> c, std::complex<double> near) {
  const std::complex<double> root = std::sqrt(b * b - 4.0 * a * c);
  const std::complex<double> q = -0.5 * (b + (std::real(std::conj(b) * root) >= 0 ? root : -root));
  if (std::abs(a) == 0 || std::abs(q) == 0) return std::nullopt;
  const std::complex<double> x1 = q / a, x2 = c / q;
  return std::abs(x1 - near) <= std::abs(x2 - near) ? x1 : x2;
}

// The eigenvectors x_k of a real pencil, whose eigenvalues are real or come in conjugate pairs, held once as real
// vectors: x_k = V(:, re_k) + i sign_k V(:, im_k), with the two columns of a pair shared by both partners (sign -1 for
// the one with Im lambda < 0) and one column for a real eigenvalue. V has 2n columns for 2n eigenvectors, half the real
// data of X = Xr + i Xi, so that a congruence X^T D X with a real symmetric D is one real product V^T (D V) (instead of
// four) and a recombination of its entries. The partner of a pair is taken as the exact conjugate of the one with
// Im lambda > 0 (vectors() returns X in that form, which every product with it must use).
class ConjugatePairs {
 public:
  // Throws NumericalError when an eigenvalue with Im < 0 has no exact conjugate among those with Im > 0.
  ConjugatePairs(const Eigen::MatrixXcd& x, const Eigen::VectorXcd& lambda);
  const Eigen::MatrixXcd& vectors() const { return x_; }
  // X^T D X (transpose, not adjoint) for a real symmetric n x n matrix D.
  Eigen::MatrixXcd congruence(const Eigen::MatrixXd& d) const;

 private:
  Eigen::MatrixXd v_;
  Eigen::MatrixXcd x_;
  std::vector<Eigen::Index> re_, im_;  // im_ = -1 for a real eigenvalue
  std::vector<double> sign_;
};

}  // namespace beamid::galerkin
