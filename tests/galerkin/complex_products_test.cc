// ConjugatePairs (galerkin/complex_products.h): the congruences X^T D X of the damped eigenvectors from one real
// product, checked against the complex product written out, on both presets (the thin beam has real overdamped roots
// and complex pairs, the thick beam's modes come from the dense decomposition).
#include "galerkin/complex_products.h"

#include <gtest/gtest.h>

#include <complex>
#include <string>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"

namespace beamid::galerkin {
namespace {

TEST(ConjugatePairs, CongruencesEqualTheComplexProducts) {
  for (const char* name : {"banks-aluminium", "thick-steel"}) {
    const SplineSpace space(8);
    const SecondOrderSystem s = assemble(space, model::preset(name));
    const StateSpaceModes modes(s);
    const Eigen::VectorXcd& lambda = modes.eigenvalues();
    const ConjugatePairs pairs(modes.physical_vectors(), lambda);
    const Eigen::MatrixXcd& x = pairs.vectors();
    int real_roots = 0;
    for (Eigen::Index k = 0; k < lambda.size(); ++k) {
      // Every column is still an eigenvector (the Im < 0 ones are now their partners' conjugates): its residual
      // against the size of its terms is that of the decomposition, ~1e-8 at most (modes.h's acceptance residuals).
      const Eigen::VectorXcd r = (lambda(k) * lambda(k)) * (s.M.cast<std::complex<double>>() * x.col(k)) +
                                 lambda(k) * (s.C.cast<std::complex<double>>() * x.col(k)) +
                                 s.K.cast<std::complex<double>>() * x.col(k);
      const double size =
          (std::norm(lambda(k)) * s.M.norm() + std::abs(lambda(k)) * s.C.norm() + s.K.norm()) * x.col(k).norm();
      EXPECT_LT(r.norm(), 1e-8 * size) << name << " mode " << k;
      if (lambda(k).imag() == 0) {
        ++real_roots;
        EXPECT_EQ(x.col(k).imag().norm(), 0.0) << name << " mode " << k;
      }
      if (lambda(k).imag() < 0) {
        for (Eigen::Index j = 0; j < lambda.size(); ++j) {
          if (lambda(j) == std::conj(lambda(k))) {
            EXPECT_EQ((x.col(j).conjugate() - x.col(k)).norm(), 0.0) << name;
          }
        }
      }
    }
    if (std::string(name) == "banks-aluminium") {
      EXPECT_GT(real_roots, 0) << "the thin beam's shear modes are overdamped";
    }
    for (const Eigen::MatrixXd* d : {&s.M, &s.C, &s.K}) {
      // Both sides are sums of n products of entries of size |x|^2 |D|: they agree to round-off, 1e-13 of that.
      const Eigen::MatrixXcd direct = x.transpose() * (d->cast<std::complex<double>>() * x);
      const Eigen::MatrixXcd fast = pairs.congruence(*d);
      Eigen::VectorXd scale = x.colwise().norm().transpose();
      for (Eigen::Index j = 0; j < x.cols(); ++j)
        for (Eigen::Index k = 0; k < x.cols(); ++k)
          EXPECT_LE(std::abs(fast(j, k) - direct(j, k)), 1e-13 * scale(j) * scale(k) * d->norm()) << name;
    }
  }
}

TEST(ConjugatePairs, AnUnpairedComplexEigenvalueIsANumericalError) {
  Eigen::MatrixXcd x = Eigen::MatrixXcd::Identity(2, 2);
  Eigen::VectorXcd lambda(2);
  lambda << std::complex<double>(-1, 2), std::complex<double>(-1, -3);  // not conjugates
  EXPECT_THROW(ConjugatePairs(x, lambda), NumericalError);
}

}  // namespace
}  // namespace beamid::galerkin
