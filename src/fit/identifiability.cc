#include "fit/identifiability.h"

#include <cmath>
#include <cstdio>

namespace beamid::fit {

// The information in ln-parameter coordinates: x_i -> ln q_i has d x_i / d ln q_i = q_i / (d q_i / d x_i).
Identifiability identifiability_of(const Covariance& covariance, const ParameterMap& map, const Eigen::VectorXd& x) {
  Identifiability id;
  if (covariance.information.size() == 0) {
    id.status = covariance.status;
    return id;
  }
  const int n = map.size();
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d(i) = map.value(i, x(i)) / map.derivative(i, x(i));
  const Eigen::MatrixXd information = d.asDiagonal() * covariance.information * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(information);
  if (eigen.info() != Eigen::Success || !information.allFinite()) {
    id.status = "the information matrix has no eigen-decomposition";
    return id;
  }
  const Eigen::VectorXd lambda = eigen.eigenvalues();  // ascending
  id.status = "ok";
  id.condition = lambda(0) > 0 ? std::sqrt(lambda(n - 1) / lambda(0)) : std::numeric_limits<double>::infinity();
  // Sign: the first component that combination() prints (|v_i| >= 0.05) is positive, so the text reads the same
  // whichever sign the eigensolver returned.
  const auto signed_direction = [&](int k) {
    Eigen::VectorXd v = eigen.eigenvectors().col(k);
    for (int i = 0; i < n; ++i)
      if (std::abs(v(i)) >= 0.05) {
        if (v(i) < 0) v = -v;
        break;
      }
    return std::vector<double>(v.data(), v.data() + n);
  };
  const auto sd = [&](int k) {
    return lambda(k) > 0 ? std::sqrt(covariance.residual_variance / lambda(k))
                         : std::numeric_limits<double>::infinity();
  };
  for (int i = 0; i < n; ++i) id.keys.push_back(map.estimated()[static_cast<std::size_t>(i)].key);
  id.weakest = signed_direction(0);
  id.weakest_sd = sd(0);
  for (int k = 0; k < n; ++k) {
    const double ratio = lambda(k) > 0 ? std::sqrt(lambda(n - 1) / lambda(k)) : std::numeric_limits<double>::infinity();
    if (ratio > 1e3) id.weak.push_back({signed_direction(k), ratio, sd(k)});
  }
  id.verdict = id.condition <= 1e3 ? "identifiable" : id.condition <= 1e7 ? "ill-conditioned" : "not identifiable";
  return id;
}

std::string Identifiability::combination(const std::vector<double>& v) const {
  std::string out;
  for (std::size_t i = 0; i < keys.size() && i < v.size(); ++i) {
    if (std::abs(v[i]) < 0.05) continue;
    char number[32];
    std::snprintf(number, sizeof number, "%.2f", std::abs(v[i]));
    out += (out.empty() ? (v[i] < 0 ? "-" : "") : (v[i] < 0 ? " - " : " + ")) + std::string(number) + " ln " + keys[i];
  }
  return out;
}

}  // namespace beamid::fit
