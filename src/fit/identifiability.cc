#include "fit/identifiability.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace beamid::fit {

namespace {

// The pseudo-inverse of a symmetric positive semi-definite matrix: eigenvalues below n eps lambda_max are dropped (a
// nuisance combination the record does not determine is not divided by zero).
Eigen::MatrixXd symmetric_pseudo_inverse(const Eigen::MatrixXd& a) {
  if (a.size() == 0) return a;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(a);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  const double cutoff = static_cast<double>(a.rows()) * std::numeric_limits<double>::epsilon() * lambda.maxCoeff();
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(lambda.size());
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
    if (lambda(k) > cutoff) inverse(k) = 1 / lambda(k);
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

Eigen::MatrixXd block(const Eigen::MatrixXd& m, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j)
      out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = m(rows[i], cols[j]);
  return out;
}

}  // namespace

// The information in ln-parameter coordinates: x_i -> ln q_i has d x_i / d ln q_i = q_i / (d q_i / d x_i).
Identifiability identifiability_of(const Covariance& covariance, const ParameterMap& map, const Eigen::VectorXd& x,
                                   const VerdictScope& scope) {
  Identifiability id;
  if (covariance.information.size() == 0) {
    id.status = covariance.status;
    return id;
  }
  const int total = map.size();
  Eigen::VectorXd d(total);
  for (int i = 0; i < total; ++i) d(i) = map.value(i, x(i)) / map.derivative(i, x(i));
  const Eigen::MatrixXd full = d.asDiagonal() * covariance.information * d.asDiagonal();
  if (!full.allFinite()) {
    id.status = "the information matrix has no eigen-decomposition";
    return id;
  }
  // The parameters of interest (a), the free nuisances (b), and those on a bound (left out).
  std::vector<int> a, b;
  const auto key = [&](int i) { return map.estimated()[static_cast<std::size_t>(i)].key; };
  for (int i = 0; i < total; ++i) {
    const auto u = static_cast<std::size_t>(i);
    if (u < scope.on_bound.size() && scope.on_bound[u])
      id.on_bound.push_back(key(i));
    else
      (u >= scope.of_interest.size() || scope.of_interest[u] ? a : b).push_back(i);
  }
  if (a.empty()) a.swap(b);  // nothing free is of interest: the verdict is about every free parameter
  if (a.empty()) {
    id.status = "every estimated parameter is on a bound";
    return id;
  }
  for (int i : a) id.keys.push_back(key(i));
  for (int i : b) id.nuisance.push_back(key(i));
  const Eigen::MatrixXd information =
      block(full, a, a) - block(full, a, b) * symmetric_pseudo_inverse(block(full, b, b)) * block(full, b, a);
  const int n = static_cast<int>(a.size());
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
  id.weakest = signed_direction(0);
  id.weakest_sd = sd(0);
  for (int k = 0; k < n; ++k) {
    const double ratio = lambda(k) > 0 ? std::sqrt(lambda(n - 1) / lambda(k)) : std::numeric_limits<double>::infinity();
    if (ratio > 1e3) id.weak.push_back({signed_direction(k), ratio, sd(k)});
  }
  id.verdict = id.condition <= 1e3 ? "identifiable" : id.condition <= 1e7 ? "ill-conditioned" : "not identifiable";
  return id;
}

std::string Identifiability::scope() const {
  if (nuisance.empty() && on_bound.empty()) return "";
  const auto listed = [](const std::vector<std::string>& keys) {
    std::string out;
    for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
    return out;
  };
  std::string out = " about " + listed(keys) + " (";
  if (!nuisance.empty()) out += listed(nuisance) + " marginalised";
  if (!on_bound.empty()) out += std::string(nuisance.empty() ? "" : "; ") + listed(on_bound) + " on a bound, left out";
  return out + ")";
}

std::string Identifiability::combination(const std::vector<double>& v) const { return combination_text(keys, v); }

std::string combination_text(const std::vector<std::string>& keys, const std::vector<double>& v) {
  // Signed so that the first printed component is positive: a direction and its opposite read the same.
  double sign = 1;
  for (std::size_t i = 0; i < keys.size() && i < v.size(); ++i)
    if (std::abs(v[i]) >= 0.05) {
      sign = v[i] < 0 ? -1 : 1;
      break;
    }
  std::string out;
  for (std::size_t i = 0; i < keys.size() && i < v.size(); ++i) {
    const double c = sign * v[i];
    if (std::abs(c) < 0.05) continue;
    char number[32];
    std::snprintf(number, sizeof number, "%.2f", std::abs(c));
    out += (out.empty() ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + ")) + std::string(number) + " ln " + keys[i];
  }
  return out;
}

}  // namespace beamid::fit
