#include "galerkin/complex_products.h"

#include <cmath>
#include <complex>

#include "core/errors.h"

namespace beamid::galerkin {

ConjugatePairs::ConjugatePairs(const Eigen::MatrixXcd& x, const Eigen::VectorXcd& lambda) {
  const Eigen::Index n = x.rows(), m = x.cols();
  v_.resize(n, m);
  x_.resize(n, m);
  re_.assign(static_cast<std::size_t>(m), -1);
  im_.assign(static_cast<std::size_t>(m), -1);
  sign_.assign(static_cast<std::size_t>(m), 1.0);
  Eigen::Index columns = 0;
  for (Eigen::Index k = 0; k < m; ++k) {  // real eigenvalues and the Im > 0 member of each pair
    const auto kk = static_cast<std::size_t>(k);
    if (lambda(k).imag() < 0) continue;
    re_[kk] = columns;
    if (lambda(k).imag() == 0) {
      // A real eigenvalue's vector is real up to a complex scale factor: keep the larger part.
      v_.col(columns++) = x.col(k).real().squaredNorm() >= x.col(k).imag().squaredNorm()
                              ? Eigen::VectorXd(x.col(k).real())
                              : Eigen::VectorXd(x.col(k).imag());
    } else {
      v_.col(columns++) = x.col(k).real();
      im_[kk] = columns;
      v_.col(columns++) = x.col(k).imag();
    }
  }
  for (Eigen::Index k = 0; k < m; ++k) {  // the Im < 0 members: their partner's columns, conjugated
    if (lambda(k).imag() >= 0) continue;
    Eigen::Index partner = -1;
    for (Eigen::Index j = 0; j < m && partner < 0; ++j)
      if (lambda(j) == std::conj(lambda(k))) partner = j;
    if (partner < 0)
      throw NumericalError("eigenvalue " + format_value(lambda(k).real()) + " - " + format_value(-lambda(k).imag()) +
                           " i has no exact conjugate partner");
    re_[static_cast<std::size_t>(k)] = re_[static_cast<std::size_t>(partner)];
    im_[static_cast<std::size_t>(k)] = im_[static_cast<std::size_t>(partner)];
    sign_[static_cast<std::size_t>(k)] = -1;
  }
  if (columns != m) throw NumericalError("eigenvalues are not in conjugate pairs");
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    x_.col(k).real() = v_.col(re_[kk]);
    if (im_[kk] >= 0)
      x_.col(k).imag() = sign_[kk] * v_.col(im_[kk]);
    else
      x_.col(k).imag().setZero();
  }
}

Eigen::MatrixXcd ConjugatePairs::congruence(const Eigen::MatrixXd& d) const {
  // x_j^T D x_k = (a_j + i s_j b_j)^T D (a_k + i s_k b_k)
  //             = G(a_j, a_k) - s_j s_k G(b_j, b_k) + i [s_k G(a_j, b_k) + s_j G(b_j, a_k)],  G = V^T D V.
  const Eigen::MatrixXd g = v_.transpose() * (d * v_);
  const Eigen::Index m = x_.cols();
  Eigen::MatrixXcd p(m, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const Eigen::Index ak = re_[kk], bk = im_[kk];
    const double sk = sign_[kk];
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      const Eigen::Index aj = re_[jj], bj = im_[jj];
      double re = g(aj, ak), im = 0;
      if (bk >= 0) im += sk * g(aj, bk);
      if (bj >= 0) {
        im += sign_[jj] * g(bj, ak);
        if (bk >= 0) re -= sign_[jj] * sk * g(bj, bk);
      }
      p(j, k) = {re, im};
    }
  }
  return p;
}

}  // namespace beamid::galerkin
