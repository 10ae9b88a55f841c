// The clamped cubic B-spline space: basis identities and Gram matrices against closed-form stencils (model.md 2).
#include "galerkin/spline_space.h"

#include <gtest/gtest.h>

#include "core/errors.h"

namespace beamid::galerkin {
namespace {

TEST(CardinalBspline, KnotValuesAndPartitionOfUnity) {
  EXPECT_DOUBLE_EQ(cardinal_bspline(0), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(cardinal_bspline(1), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(cardinal_bspline(-1), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(cardinal_bspline(2), 0.0);
  // Integer translates sum to one everywhere, and their slopes to zero (exact in exact arithmetic; 1e-14 = round-off).
  for (double t = 0; t < 1; t += 0.137) {
    double sum = 0, slope = 0;
    for (int j = -3; j <= 3; ++j) sum += cardinal_bspline(t - j), slope += cardinal_bspline_derivative(t - j);
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(slope, 0.0, 1e-14);
  }
}

TEST(CardinalBspline, DerivativeMatchesCentralDifference) {
  // Central difference error is O(d^2 B''') ~ 1e-10 for d = 1e-5; tolerance 1e-8 leaves margin, catches sign errors.
  const double d = 1e-5;
  for (double t : {-1.7, -1.2, -0.6, -0.1, 0.3, 0.9, 1.4, 1.9}) {
    EXPECT_NEAR(cardinal_bspline_derivative(t), (cardinal_bspline(t + d) - cardinal_bspline(t - d)) / (2 * d), 1e-8)
        << "t = " << t;
  }
}

TEST(SplineSpace, ClampedAtRootAndTipTrace) {
  for (int n : {1, 2, 5, 16}) {
    const SplineSpace space(n);
    ASSERT_EQ(space.dimension(), n + 2);
    EXPECT_LT(space.values(0.0).cwiseAbs().maxCoeff(), 1e-15) << "every basis function vanishes at x = 0";
    const Eigen::VectorXd nu = space.tip_trace();
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(n + 2);
    expected(n - 1) += 1.0 / 6.0;  // for N = 1, beta_0 = B_0 - 4 B_{-1} and B_{-1}(1) = 0
    expected(n) += 2.0 / 3.0;
    expected(n + 1) += 1.0 / 6.0;
    EXPECT_LT((nu - expected).cwiseAbs().maxCoeff(), 1e-15) << "N = " << n;
    // Slope at the root is free (Timoshenko): beta_1'(0) = (B'(-1) - B'(1)) N = N != 0.
    EXPECT_NEAR(space.slopes(0.0)(1), n, 1e-12);
  }
}

TEST(SplineSpace, InteriorStencils) {
  // model.md: int B_i B_{i+k} / h = 151/315, 397/1680, 1/42, 1/5040; h int B_i' B_{i+k}' = 2/3, -1/8, -1/5, -1/120.
  // Gauss-Legendre with 4 points is exact for these degree-6 integrands: tolerance is round-off (1e-14).
  const int n = 12;
  const SplineSpace space(n);
  const double h = 1.0 / n;
  const int i = 6;  // beta_6 = B_6, far from both ends
  const double mass[] = {151.0 / 315, 397.0 / 1680, 1.0 / 42, 1.0 / 5040};
  const double stiff[] = {2.0 / 3, -1.0 / 8, -1.0 / 5, -1.0 / 120};
  for (int k = 0; k <= 3; ++k) {
    EXPECT_NEAR(space.G0()(i, i + k) / h, mass[k], 1e-14) << "k = " << k;
    EXPECT_NEAR(space.G11()(i, i + k) * h, stiff[k], 1e-13) << "k = " << k;
  }
  EXPECT_EQ(space.G0()(i, i + 4), 0.0);  // supports of B_i and B_{i+4} only touch
}

TEST(SplineSpace, GramIdentities) {
  const SplineSpace space(7);
  const int m = space.dimension();
  // G10 + G10^T = nu nu^T (integration by parts: int (beta_i beta_j)' = beta_i(1) beta_j(1) - 0).
  const Eigen::MatrixXd parts =
      space.G10() + space.G10().transpose() - space.tip_trace() * space.tip_trace().transpose();
  EXPECT_LT(parts.cwiseAbs().maxCoeff(), 1e-13);
  // sum_ij G0_ij c_i c_j = int (sum c_j beta_j)^2: for c with sum c_j beta_j = x (representable: cubic splines
  // contain linears), int_0^1 x^2 = 1/3 and int_0^1 1 = 1 for its slope.
  Eigen::VectorXd c(m);
  // x = sum_j (j h) B_j on the full B-spline basis (Marsden); in the clamped basis the coefficient of beta_0 is 0,
  // of beta_1 is h (B_{-1} coefficient -h is absorbed by beta_1 = B_1 - B_{-1}), then j h.
  const double h = 1.0 / space.elements();
  for (int j = 0; j < m; ++j) c(j) = j * h;
  for (double xi : {0.0, 0.21, 0.5, 0.93, 1.0}) EXPECT_NEAR(space.values(xi).dot(c), xi, 1e-14);
  EXPECT_NEAR(c.dot(space.G0() * c), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(c.dot(space.G11() * c), 1.0, 1e-13);
}

TEST(SplineSpace, RejectsBadInput) {
  EXPECT_THROW(SplineSpace(0), InputError);
  const SplineSpace space(3);
  EXPECT_THROW(space.values(1.5), InputError);
  EXPECT_THROW(space.values(-0.1), InputError);
}

}  // namespace
}  // namespace beamid::galerkin
