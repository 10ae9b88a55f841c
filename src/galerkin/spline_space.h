// Clamped cubic B-spline space of order N on the reference interval [0, 1] (model.md section 2).
//
// Knots xi_k = k h, h = 1/N. Cardinal cubic B-spline
//   B(t) = (4 - 6 t^2 + 3 |t|^3)/6 for |t| <= 1,  (2 - |t|)^3/6 for 1 <= |t| <= 2,  0 otherwise,
// B_j(xi) = B(xi/h - j), j = -1..N+1. The clamped subspace (every function zero at xi = 0) has dimension N + 2:
//   beta_0 = B_0 - 4 B_{-1},  beta_1 = B_1 - B_{-1},  beta_j = B_j (j = 2..N+1).
// Everything here is parameter-free; a beam of length l maps it by x = l xi (see BeamForms), so the space is
// built once per N and reused for every parameter value a fit tries.
#pragma once

#include <Eigen/Dense>

namespace beamid::galerkin {

double cardinal_bspline(double t);
double cardinal_bspline_derivative(double t);

class SplineSpace {
 public:
  // N >= 1 elements; throws InputError otherwise.
  explicit SplineSpace(int elements);

  int elements() const { return elements_; }
  int dimension() const { return elements_ + 2; }

  // beta_j(xi) and d beta_j / d xi for j = 0..N+1, at any xi in [0, 1] (InputError outside).
  Eigen::VectorXd values(double xi) const;
  Eigen::VectorXd slopes(double xi) const;

  // Gram matrices on [0, 1], exact (4-point Gauss-Legendre per knot interval; integrands have degree <= 6):
  //   G0_ij = int beta_i beta_j,  G11_ij = int beta_i' beta_j',  G10_ij = int beta_i' beta_j (row differentiated).
  const Eigen::MatrixXd& G0() const { return G0_; }
  const Eigen::MatrixXd& G11() const { return G11_; }
  const Eigen::MatrixXd& G10() const { return G10_; }
  // Tip trace nu_j = beta_j(1): nu_{N-1} = 1/6, nu_N = 2/3, nu_{N+1} = 1/6, all others 0.
  const Eigen::VectorXd& tip_trace() const { return tip_; }

  // The unclamped space B_{-1..N+1} (dimension N + 3), for a block whose root is free (a compliant clamp): its Gram
  // matrices, and T with beta = T B (the clamped basis above), so that a clamped block's forms are T G T^T.
  const Eigen::MatrixXd& full_G0() const { return full_G0_; }
  const Eigen::MatrixXd& full_G11() const { return full_G11_; }
  const Eigen::MatrixXd& full_G10() const { return full_G10_; }
  const Eigen::MatrixXd& clamping() const { return clamping_; }
  // B_j(xi) and d B_j / d xi, j = -1..N+1 (InputError outside [0, 1]).
  Eigen::VectorXd full_values(double xi) const;
  Eigen::VectorXd full_slopes(double xi) const;

 private:
  // Values (derivative = false) or slopes of B_{-1..N+1} at xi (unclamped).
  Eigen::VectorXd evaluate(double xi, bool derivative) const;

  int elements_;
  Eigen::MatrixXd G0_, G11_, G10_;
  Eigen::VectorXd tip_;
  Eigen::MatrixXd full_G0_, full_G11_, full_G10_, clamping_;
};

}  // namespace beamid::galerkin
