#include "fit/optimizer.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>

#include "core/errors.h"

namespace beamid::fit {

const core::NameSet& optimizer_names() {
  static const core::NameSet names({{"lm", "Ceres Levenberg-Marquardt on the residual vector"},
                                    {"bobyqa", "NLopt BOBYQA (quadratic models, derivative-free)"},
                                    {"nelder-mead", "NLopt Nelder-Mead simplex"},
                                    {"sbplx", "NLopt Subplex"},
                                    {"direct-l", "NLopt DIRECT-L (global)"},
                                    {"crs2-lm", "NLopt controlled random search (global)"}});
  return names;
}

bool needs_residuals(const std::string& method) { return method == "lm"; }

std::optional<std::string> validation_error(const OptimizerOptions& o) {
  if (auto error = optimizer_names().violation("optimizer", o.method)) return error;
  if (o.max_evaluations < 1) return "max_evaluations = " + std::to_string(o.max_evaluations) + ": must be >= 1";
  if (!(std::isfinite(o.xtol_rel) && o.xtol_rel >= 0))
    return "xtol_rel = " + format_value(o.xtol_rel) + ": must be >= 0";
  if (!(std::isfinite(o.ftol_rel) && o.ftol_rel >= 0))
    return "ftol_rel = " + format_value(o.ftol_rel) + ": must be >= 0";
  if (!(o.initial_step > 0 && o.initial_step <= 1))
    return "initial_step = " + format_value(o.initial_step) + ": must be in (0, 1]";
  return std::nullopt;
}

namespace detail {

GuardedProblem::GuardedProblem(const Problem& p) : problem(p) {}

double GuardedProblem::cost(const Eigen::VectorXd& x) {
  ++evaluations;
  double value = std::numeric_limits<double>::infinity();
  try {
    value = problem.cost(x);
  } catch (const std::exception& error) {
    if (first_exception.empty()) first_exception = error.what();
  } catch (...) {
    if (first_exception.empty()) first_exception = "unknown exception";
  }
  if (!std::isfinite(value)) value = std::numeric_limits<double>::infinity();
  if (value < best_cost) best_cost = value, best_x = x;
  return value;
}

namespace {

// One counted call of the objective: an exception or an undefined result is a rejected point, never a throw; the
// best residual norm seen is kept.
template <class Call>
bool guarded_call(GuardedProblem& g, const Eigen::VectorXd& x, Eigen::VectorXd& r, Call call) {
  ++g.evaluations;
  bool ok = false;
  try {
    ok = call() && r.size() == g.problem.residual_count && r.allFinite();
  } catch (const std::exception& error) {
    if (g.first_exception.empty()) g.first_exception = error.what();
  } catch (...) {
    if (g.first_exception.empty()) g.first_exception = "unknown exception";
  }
  if (!ok && g.first_rejection.empty() && g.problem.rejection) g.first_rejection = *g.problem.rejection;
  if (ok) {
    const double value = r.squaredNorm();
    if (value < g.best_cost) g.best_cost = value, g.best_x = x;
  }
  return ok;
}

}  // namespace

bool GuardedProblem::residuals(const Eigen::VectorXd& x, Eigen::VectorXd& r) {
  return guarded_call(*this, x, r, [&] { return problem.residuals(x, r); });
}

bool GuardedProblem::jacobian(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& j) {
  return guarded_call(*this, x, r, [&] {
    return problem.jacobian(x, r, j) && j.rows() == problem.residual_count && j.cols() == problem.dimension() &&
           j.allFinite();
  });
}

void GuardedProblem::finish(OptimizerResult& result, const std::string& what, const std::string& detail) const {
  if (!first_exception.empty()) {
    result.status = "failed";
    result.termination = "the objective threw: " + first_exception;
  } else if (!std::isfinite(result.cost)) {
    result.status = "failed";
    result.termination = "no evaluation gave a finite " + what +
                         (first_rejection.empty() ? "" : " (the first: " + first_rejection + ")") + " (" + detail + ")";
  }
}

}  // namespace detail

OptimizerResult minimize(const Problem& problem, const Eigen::VectorXd& start, const OptimizerOptions& options) {
  if (auto error = validation_error(options)) throw InputError(*error);
  OptimizerResult failed;
  failed.x = start;
  const int n = problem.dimension();
  if (n < 1 || problem.upper.size() != n || start.size() != n) {
    failed.termination = "the problem has no parameters, or bounds and start differ in size";
    return failed;
  }
  for (int i = 0; i < n; ++i) {
    if (!(std::isfinite(problem.lower(i)) && std::isfinite(problem.upper(i)) && problem.lower(i) < problem.upper(i))) {
      failed.termination = "bounds of coordinate " + std::to_string(i) + " are not finite with lower < upper";
      return failed;
    }
    if (!(start(i) >= problem.lower(i) && start(i) <= problem.upper(i))) {
      failed.termination = "the start lies outside the bounds at coordinate " + std::to_string(i) + " (" +
                           format_value(start(i)) + " not in [" + format_value(problem.lower(i)) + ", " +
                           format_value(problem.upper(i)) + "])";
      return failed;
    }
  }
  if (needs_residuals(options.method) && (problem.residual_count < 1 || !problem.residuals)) {
    failed.termination = "optimizer '" + options.method + "' needs a residual vector, which this cost does not give";
    return failed;
  }
  const auto begin = std::chrono::steady_clock::now();
  OptimizerResult result = options.method == "lm" ? detail::minimize_ceres(problem, start, options)
                                                  : detail::minimize_nlopt(problem, start, options);
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
}

const core::NameSet& start_design_names() {
  static const core::NameSet names({{"lhs", "Latin hypercube: one start in each of count strata of every axis"},
                                    {"random", "independent uniform starts in the bounds"}});
  return names;
}

std::vector<Eigen::VectorXd> space_filling_starts(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int count,
                                                  const std::string& design, std::uint64_t seed) {
  start_design_names().require("start_design", design);
  std::mt19937_64 engine(seed);
  auto uniform = [&engine] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };  // [0, 1)
  const auto n = lower.size();
  std::vector<Eigen::VectorXd> points(static_cast<std::size_t>(std::max(count, 0)), Eigen::VectorXd(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    std::vector<int> strata(points.size());
    for (std::size_t s = 0; s < strata.size(); ++s) strata[s] = static_cast<int>(s);
    for (std::size_t s = strata.size(); s > 1; --s)  // Fisher-Yates
      std::swap(strata[s - 1], strata[static_cast<std::size_t>(uniform() * static_cast<double>(s))]);
    for (std::size_t p = 0; p < points.size(); ++p) {
      const double u = design == "lhs" ? (strata[p] + uniform()) / static_cast<double>(points.size()) : uniform();
      points[p](i) = lower(i) + u * (upper(i) - lower(i));
    }
  }
  return points;
}

namespace {

// The sandwich of covariance_at (optimizer.h), into c.robust, or why not into c.robust_status.
void form_sandwich(const Eigen::MatrixXd& jacobian, const Eigen::MatrixXd& inverse, const Eigen::VectorXd& r, int lags,
                   Covariance& c) {
  const int m = static_cast<int>(jacobian.rows()), n = static_cast<int>(jacobian.cols());
  // The sandwich (optimizer.h): the scores g_i = r_i J_i / sqrt(1 - h_i) as the rows of G, S = G^T G plus the
  // weighted lag products. h_i = J_i B^-1 J_i^T is row i's leverage (the hat matrix's diagonal, summing to n). A fit
  // leaves of row i's own noise e_i the part (1 - h_i) e_i in r_i, and mixes in the others' with weights summing to
  // h_i (1 - h_i) in variance, so with equal variances E r_i^2 = (1 - h_i) sigma^2: HC2 divides it out (at the time
  // cost's thousands of rows every h is about n/m, and HC2 is HC1's m/(m - n)). Above kMaxSandwichLeverage most of a
  // residual's variance is other rows' noise and no r_i-based estimate of row i's variance is sound, in either
  // direction: the modal cost's first-mode frequency, which alone separates EI from rho on the thin beam, has
  // h = 0.992; its HC1 sandwich of EI came out 15x below the scatter over 30 noise seeds, HC2's 2.3x below and HC3's
  // 5x above; spike-smooth's (h = 0.97) 12x above with HC2.
  const Eigen::MatrixXd influence = jacobian * inverse;  // row i: J_i B^-1
  const Eigen::VectorXd leverage = influence.cwiseProduct(jacobian).rowwise().sum();
  Eigen::Index worst = 0;
  if (!(leverage.maxCoeff(&worst) <= kMaxSandwichLeverage)) {
    std::ostringstream why;
    why << "residual " << worst + 1 << " of " << m << " has leverage "
        << std::setprecision(leverage(worst) < kMaxSandwichLeverage + 0.01 ? 6 : 3) << leverage(worst) << " (above "
        << kMaxSandwichLeverage
        << "): it nearly alone fixes a combination of the parameters, so its residual is mostly the other rows' "
           "noise and the residuals cannot estimate its variance";
    c.robust_status = why.str();
    return;
  }
  // Kish's effective count of the terms of each estimate's sandwich variance, (sum_i w_i)^2 / sum_i w_i^2 with
  // w_i = (B^-1 J_i^T)_j^2, the weight row i's variance has in estimate j's: below kMinSandwichTerms the sandwich is
  // one or two squared residuals, a chi-square of as many degrees of freedom. Two channels of one beam measure each
  // mode twice, so that each of the pair had leverage 0.4999, under the bound above, and a joint modal fit's sandwich
  // of EI came out 2.9x below its scatter over 30 seeds (the twelfth pass's P3): its count was about 2.
  const Eigen::MatrixXd weights = influence.cwiseAbs2();  // w_ij, m x n
  for (int j = 0; j < n; ++j) {
    const double count = std::pow(weights.col(j).sum(), 2) / weights.col(j).squaredNorm();
    if (!(count >= kMinSandwichTerms)) {
      std::ostringstream why;
      why << "the sandwich of estimated parameter " << j + 1 << " rests on about " << std::setprecision(2) << count
          << " residuals (the effective count of its terms, below " << kMinSandwichTerms
          << "): too few squared residuals to estimate a variance";
      c.robust_status = why.str();
      return;
    }
  }
  const Eigen::MatrixXd scores = r.cwiseQuotient((1.0 - leverage.array()).sqrt().matrix()).asDiagonal() * jacobian;
  Eigen::MatrixXd meat = scores.transpose() * scores;
  const int bandwidth = std::clamp(lags, 0, m - 1);
  for (int l = 1; l <= bandwidth; ++l) {
    const Eigen::MatrixXd lagged = scores.topRows(m - l).transpose() * scores.bottomRows(m - l);
    meat += (1.0 - static_cast<double>(l) / (bandwidth + 1)) * (lagged + lagged.transpose());
  }
  c.robust = inverse * meat * inverse;
}

// Covariance::nonquadratic_coordinate: the sum of squares one formal standard error either side of `at` against its
// Gauss-Newton prediction (sides outside the bounds are skipped).
void check_quadratic(detail::GuardedProblem& guarded, const Problem& problem, const Eigen::VectorXd& at,
                     const Eigen::VectorXd& r, const Eigen::MatrixXd& jacobian, Covariance& c) {
  const double cost = r.squaredNorm();
  // A record the model fits to round-off (a noise-free record of the model itself) has standard errors of round-off,
  // and one of them away the sum of squares is round-off too: every cost was called "not quadratic" there (the
  // twenty-fifth pass's adv59 P3). Skipped where the residuals' rms is under 1e-9 of the output's change for a
  // relative change of a parameter (|J_i| |x_i| / sqrt(m), the largest).
  double sensitivity = 0;
  for (Eigen::Index i = 0; i < at.size(); ++i)
    sensitivity = std::max(sensitivity, jacobian.col(i).norm() * std::abs(at(i)));
  if (!(std::sqrt(cost) > 1e-9 * sensitivity)) return;
  double worst = 0;
  for (Eigen::Index i = 0; i < at.size(); ++i) {
    const double sd = std::sqrt(c.matrix(i, i));
    if (!(sd > 0) || !std::isfinite(sd)) continue;
    const double q = sd * sd * jacobian.col(i).squaredNorm();
    for (const double step : {sd, -sd}) {
      Eigen::VectorXd x = at, moved;
      x(i) += step;
      if (x(i) < problem.lower(i) || x(i) > problem.upper(i) || !guarded.residuals(x, moved) ||
          moved.size() != r.size() || !moved.allFinite())
        continue;
      const double rise = moved.squaredNorm() - cost;
      const double predicted = (r + step * jacobian.col(i)).squaredNorm() - cost;
      const double mismatch = std::abs(rise - predicted) / q;
      if (mismatch > kNonQuadraticRise && mismatch > worst) {
        worst = mismatch;
        c.nonquadratic_coordinate = static_cast<int>(i);
        c.nonquadratic_rise = rise;
        c.quadratic_rise = predicted;
      }
    }
  }
}

}  // namespace

Covariance covariance_at(const Problem& problem, const Eigen::VectorXd& at, int lags) {
  // cov = s^2 (J^T J)^-1 with s^2 = |r|^2 / (m - n), J by central differences with steps 1e-6 max(|x_i|, 1) (the
  // optimizer's coordinates are of order one). Computed here rather than by ceres::Covariance: its dense SVD
  // crashed (SIGSEGV inside Eigen's BDCSVD) on a Jacobian from a study case, and a non-finite Jacobian must be a
  // status, not a crash. J^T J is n x n (n <= a dozen), so its symmetric eigen-decomposition is cheap and exact
  // enough; a reciprocal condition number below 1e-14 (Ceres' DENSE_SVD default) means not identifiable.
  Covariance c;
  const int n = problem.dimension();
  const int m = problem.residual_count;
  if (m < 1 || !problem.residuals) {
    c.status = "the cost has no residual vector";
    return c;
  }
  if (m <= n) {
    c.status = "no degrees of freedom (" + std::to_string(m) + " residuals, " + std::to_string(n) + " parameters)";
    return c;
  }
  detail::GuardedProblem guarded(problem);
  Eigen::VectorXd r;
  if (!guarded.residuals(at, r) || r.size() != m || !r.allFinite()) {
    c.status = "the residual vector is undefined at the estimate";
    return c;
  }
  Eigen::MatrixXd jacobian(m, n);
  for (int i = 0; i < n; ++i) {
    // The step 1e-6 max(|x|, 1), and where the residuals are undefined at x +- h, 1e-6 of |x| (or of the bounds'
    // width where x = 0): coordinates are scaled by the start, and an estimate far below its start (cDI 6.6e-6 from a
    // start of 1e3, x = 6.6e-9) stepped to a negative damping and gave NaN errors with nothing said (the twelfth
    // pass's P4). The first step is kept where it works, so that no standard error an earlier version gave moves.
    Eigen::VectorXd r_plus, r_minus;
    const auto difference = [&](double h) {
      Eigen::VectorXd plus = at, minus = at;
      plus(i) += h;
      minus(i) -= h;
      return guarded.residuals(plus, r_plus) && guarded.residuals(minus, r_minus) && r_plus.size() == m &&
             r_minus.size() == m;
    };
    double h = 1e-6 * std::max(std::abs(at(i)), 1.0);
    if (!difference(h)) {
      h = 1e-6 * (at(i) != 0 ? std::abs(at(i)) : 1e-6 * (problem.upper(i) - problem.lower(i)));
      if (!(h > 0) || !difference(h)) {
        c.status = "the residual vector is undefined next to the estimate (coordinate " + std::to_string(i) + ")";
        return c;
      }
    }
    jacobian.col(i) = (r_plus - r_minus) / (2 * h);
    // The same difference 10 times wider: on a smooth cost the two agree to their truncation error (kRoughJacobian).
    const Eigen::VectorXd column = jacobian.col(i);
    if (difference(10 * h) && r_plus.allFinite() && r_minus.allFinite()) {
      const Eigen::VectorXd wide = (r_plus - r_minus) / (20 * h);
      const double change = wide.norm() > 0 ? (column - wide).norm() / wide.norm() : 0;
      if (change > kRoughJacobian && change > c.rough_change) c.rough_coordinate = i, c.rough_change = change;
    }
  }
  if (!jacobian.allFinite()) {
    c.status = "the Jacobian at the estimate is not finite";
    return c;
  }
  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  c.information = information;
  c.residual_variance = r.squaredNorm() / (m - n);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(information);
  const Eigen::VectorXd lambda = eigen.eigenvalues();  // ascending
  if (eigen.info() != Eigen::Success || !(lambda(n - 1) > 0) || !(lambda(0) > 1e-14 * lambda(n - 1))) {
    c.status = "the information matrix J^T J is singular or too ill-conditioned (parameters not identifiable)";
    return c;
  }
  const Eigen::MatrixXd& v = eigen.eigenvectors();
  const Eigen::MatrixXd inverse = v * lambda.cwiseInverse().asDiagonal() * v.transpose();
  c.matrix = inverse * c.residual_variance;
  form_sandwich(jacobian, inverse, r, lags, c);
  check_quadratic(guarded, problem, at, r, jacobian, c);
  return c;
}

}  // namespace beamid::fit
