// Products of real and complex matrices as real products: Eigen's mixed real-complex product, and at these sizes
// (n ~ 36, 2n ~ 72) its complex-complex kernel, are several times slower than its real one. Used by the damped modes
// (galerkin/modes.cc) and their parameter derivatives (simulation/sensitivities.cc).
#pragma once

#include <Eigen/Dense>

namespace beamid::galerkin {

// a x for real a and complex x: two real products.
inline Eigen::MatrixXcd real_times(const Eigen::MatrixXd& a, const Eigen::MatrixXcd& x) {
  Eigen::MatrixXcd out(a.rows(), x.cols());
  out.real() = a * x.real();
  out.imag() = a * x.imag();
  return out;
}

// x^T y for complex x = xr + i xi (its parts given, so that a caller with many products splits it once) and complex y:
// four real products. Transpose, not adjoint: the damped pencil is complex symmetric.
inline Eigen::MatrixXcd transpose_times(const Eigen::MatrixXd& xr, const Eigen::MatrixXd& xi,
                                        const Eigen::MatrixXcd& y) {
  const Eigen::MatrixXd yr = y.real(), yi = y.imag();
  Eigen::MatrixXcd out(xr.cols(), y.cols());
  out.real() = xr.transpose() * yr - xi.transpose() * yi;
  out.imag() = xr.transpose() * yi + xi.transpose() * yr;
  return out;
}

// x_k^T y_k for every column k (transpose, not adjoint).
inline Eigen::VectorXcd column_products(const Eigen::MatrixXcd& x, const Eigen::MatrixXcd& y) {
  return x.cwiseProduct(y).colwise().sum().transpose();
}

}  // namespace beamid::galerkin
