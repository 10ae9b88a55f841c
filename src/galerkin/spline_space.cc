#include "galerkin/spline_space.h"

#include <array>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace beamid::galerkin {

double cardinal_bspline(double t) {
  const double a = std::abs(t);
  if (a <= 1) return (4 - 6 * a * a + 3 * a * a * a) / 6;
  if (a <= 2) return (2 - a) * (2 - a) * (2 - a) / 6;
  return 0;
}

double cardinal_bspline_derivative(double t) {
  const double a = std::abs(t);
  if (a <= 1) return -2 * t + 1.5 * t * a;  // d/dt (4 - 6t^2 + 3|t|^3)/6
  if (a <= 2) return -std::copysign((2 - a) * (2 - a) / 2, t);
  return 0;
}

namespace {

// Coefficients of the clamped basis in terms of B_{-1..N+1}: beta = T B, T of size (N+2) x (N+3).
// Column c holds B_{c-1}.
Eigen::MatrixXd clamping_matrix(int n) {
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(n + 2, n + 3);
  t(0, 1) = 1;  // beta_0 = B_0 - 4 B_{-1}: value 2/3 - 4/6 = 0 at xi = 0
  t(0, 0) = -4;
  t(1, 2) = 1;  // beta_1 = B_1 - B_{-1}: value 1/6 - 1/6 = 0 at xi = 0, slope free (Timoshenko)
  t(1, 0) = -1;
  for (int j = 2; j <= n + 1; ++j) t(j, j + 1) = 1;
  return t;
}

}  // namespace

SplineSpace::SplineSpace(int elements) : elements_(elements) {
  if (elements < 1) throw InputError("elements N = " + std::to_string(elements) + ": must be >= 1");
  const int n = elements;
  const double h = 1.0 / n;

  // 4-point Gauss-Legendre on [-1, 1]: nodes +-sqrt(3/7 -+ (2/7) sqrt(6/5)), weights (18 +- sqrt 30)/36.
  const double r = 2.0 / 7.0 * std::sqrt(6.0 / 5.0);
  const std::array<double, 4> nodes = {-std::sqrt(3.0 / 7.0 + r), -std::sqrt(3.0 / 7.0 - r), std::sqrt(3.0 / 7.0 - r),
                                       std::sqrt(3.0 / 7.0 + r)};
  const std::array<double, 4> weights = {(18 - std::sqrt(30.0)) / 36, (18 + std::sqrt(30.0)) / 36,
                                         (18 + std::sqrt(30.0)) / 36, (18 - std::sqrt(30.0)) / 36};

  // Gram matrices of the unclamped B_{-1..N+1}; on knot interval e the active splines are B_{e-1..e+2},
  // i.e. columns e..e+3.
  Eigen::MatrixXd g0 = Eigen::MatrixXd::Zero(n + 3, n + 3);
  Eigen::MatrixXd g11 = g0, g10 = g0;
  for (int e = 0; e < n; ++e) {
    for (int q = 0; q < 4; ++q) {
      const double s = (e + 0.5 * (nodes[q] + 1));  // position in knot units, xi / h
      const double w = weights[q] * 0.5 * h;        // d xi = (h/2) d node
      std::array<double, 4> value{}, slope{};
      for (int a = 0; a < 4; ++a) {
        const int j = e - 1 + a;
        value[a] = cardinal_bspline(s - j);
        slope[a] = cardinal_bspline_derivative(s - j) / h;  // d/d xi = (1/h) d/dt
      }
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          g0(e + a, e + b) += w * value[a] * value[b];
          g11(e + a, e + b) += w * slope[a] * slope[b];
          g10(e + a, e + b) += w * slope[a] * value[b];
        }
    }
  }
  full_G0_ = g0;
  full_G11_ = g11;
  full_G10_ = g10;
  clamping_ = clamping_matrix(n);
  const Eigen::MatrixXd& t = clamping_;
  G0_ = t * g0 * t.transpose();
  G11_ = t * g11 * t.transpose();
  G10_ = t * g10 * t.transpose();
  // Symmetrise what is symmetric in exact arithmetic, so downstream Cholesky and symmetric solvers see it so.
  G0_ = 0.5 * (G0_ + G0_.transpose()).eval();
  G11_ = 0.5 * (G11_ + G11_.transpose()).eval();
  tip_ = values(1.0);
}

Eigen::VectorXd SplineSpace::evaluate(double xi, bool derivative) const {
  if (!(xi >= 0 && xi <= 1))
    throw InputError("spline evaluation at xi = " + format_value(xi) + ": must lie in [0, 1] (0 <= x <= l)");
  const int n = elements_;
  const double s = xi * n;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 3);
  // Only B_j with |s - j| < 2 are nonzero: j from floor(s) - 1 to floor(s) + 2, clipped to -1..N+1.
  const int k = static_cast<int>(std::floor(s));
  for (int j = std::max(-1, k - 1); j <= std::min(n + 1, k + 2); ++j)
    b(j + 1) = derivative ? cardinal_bspline_derivative(s - j) * n : cardinal_bspline(s - j);
  return b;
}

Eigen::VectorXd SplineSpace::values(double xi) const { return clamping_ * evaluate(xi, false); }
Eigen::VectorXd SplineSpace::slopes(double xi) const { return clamping_ * evaluate(xi, true); }
Eigen::VectorXd SplineSpace::full_values(double xi) const { return evaluate(xi, false); }
Eigen::VectorXd SplineSpace::full_slopes(double xi) const { return evaluate(xi, true); }

}  // namespace beamid::galerkin
