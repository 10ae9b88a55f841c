// Bound-constrained minimisation behind one small interface, with two adapters:
//   NLopt (fit/nlopt_optimizer.cc):  "nelder-mead" (LN_NELDERMEAD), "bobyqa" (LN_BOBYQA), "sbplx" (LN_SBPLX),
//                                    "direct-l" (GN_DIRECT_L), "crs2-lm" (GN_CRS2_LM, stochastic: seeded by
//                                    nlopt_srand(seed) before every run);
//   Ceres (fit/ceres_optimizer.cc):  "lm", Levenberg-Marquardt on the residual vector with the bounds, with the
//                                    problem's exact Jacobian where it has one, else central numeric differences.
// Optimizers see dimensionless coordinates of order one (fit/parameter_map.h maps them to physical values).
// Nothing here throws for what happens during a run: an exception inside the objective, a non-finite cost or an
// undefined residual vector becomes an infinite cost (or a rejected step), and a run that cannot go on becomes a
// result with status "failed" and the reason in words.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/names.h"

namespace beamid::fit {

struct Problem {
  Eigen::VectorXd lower, upper;  // finite, lower < upper
  // The scalar cost; may throw (caught) and may return a non-finite value (treated as +infinity).
  std::function<double(const Eigen::VectorXd&)> cost;
  // Optional residual vector with cost = |r|^2; returns false where it is undefined. Needed by "lm".
  int residual_count = 0;
  std::function<bool(const Eigen::VectorXd&, Eigen::VectorXd&)> residuals;
  // Optional: the residuals and their exact Jacobian (residual_count x dimension) at once; "lm" then uses it instead
  // of central differences. Returns false where undefined.
  std::function<bool(const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::MatrixXd&)> jacobian;
  // Optional: where the residual functions write why they returned false (the model's own status), so that a fit no
  // point of which was defined says why, not only that (the twelfth pass's P9).
  std::shared_ptr<std::string> rejection;
  int dimension() const { return static_cast<int>(lower.size()); }
};

struct OptimizerOptions {
  std::string method = "bobyqa";
  int max_evaluations = 3000;  // cost or residual evaluations (a central-difference Jacobian costs 2n)
  double xtol_rel = 1e-10;     // stop when a step changes every coordinate by less than this, relatively
  double ftol_rel = 0;         // stop when the cost changes by less than this, relatively (0: off)
  double initial_step = 0.02;  // NLopt local methods: first step, as a fraction of each bound range
  std::uint64_t seed = 1;      // stochastic methods
};
const core::NameSet& optimizer_names();
// First violated constraint ("optimizer = 'x': must be one of ..."), or nothing.
std::optional<std::string> validation_error(const OptimizerOptions& options);
// Whether the method needs Problem::residuals.
bool needs_residuals(const std::string& method);

struct OptimizerResult {
  Eigen::VectorXd x;  // the best point seen
  double cost = std::numeric_limits<double>::infinity();
  long evaluations = 0;  // calls of cost or residuals
  double wall_time_s = 0;
  std::string status = "failed";  // "converged" | "max-evaluations" | "failed"
  std::string termination;        // the reason in words
  bool usable() const { return status != "failed"; }
};

// Runs `options.method` from `start` (which must lie within the bounds, else status "failed").
OptimizerResult minimize(const Problem& problem, const Eigen::VectorXd& start, const OptimizerOptions& options);

// Formal covariance of the least-squares estimate x: (J^T J)^-1 |r|^2 / (m - n), J by central differences
// (computed here; optimizer.cc says why not by ceres::Covariance). Valid for independent Gaussian residuals of
// equal variance; status says why when unavailable.
//
// Beside it the sandwich (robust) covariance, which holds whatever the residuals' variances and, within `lags`
// rows, their correlation (White 1980; Newey & West 1987):
//   robust = B^-1 S B^-1,  B = J^T J,  S = sum_{|l| <= L} (1 - |l|/(L + 1)) sum_i g_i g_{i+l}^T,
// g_i = r_i J_i^T / sqrt(1 - h_i) (row i's score, corrected for its leverage h_i = J_i B^-1 J_i^T), L = lags (0:
// the HC2 form of MacKinnon & White 1985, unbiased for independent residuals of equal variance whatever the leverage,
// for residuals that are independent but of unequal variance). Where a row's leverage exceeds kMaxSandwichLeverage
// (a modal fit's first-mode frequency: 0.99), under half of its residual's variance is its own noise and no
// residual-based estimate holds (Chesher & Jewitt 1987: the bias grows without bound with the largest leverage):
// robust is then left empty and robust_status says why; quote the spread over windows instead. The same where an
// estimate's sandwich rests on fewer than kMinSandwichTerms residuals' worth (two channels measuring one mode each
// carry leverage 0.4999, and the sandwich was 2.9x low).
// With independent residuals of equal variance it tends to the formal one; with model error, whose residuals are
// systematic, it does not, and the ratio says how far the formal one can be trusted. Residuals
// correlated over more than L rows (a model error in a lightly damped mode lasts 1/sigma) are still understated.
struct Covariance {
  Eigen::MatrixXd matrix;  // in the optimizer's coordinates
  Eigen::MatrixXd robust;  // the sandwich, in the same coordinates (empty when matrix is, or when robust_status says)
  std::string status = "ok";         // "ok" or why not (no residuals, m <= n, singular information matrix)
  std::string robust_status = "ok";  // "ok" or why the sandwich is not formed where the formal one is
  bool ok() const { return status == "ok"; }
  // J^T J at the estimate and s^2 = |r|^2 / (m - n), kept also when J^T J is singular (empty when J was not formed),
  // so that a caller can say which combination of parameters the data do not determine.
  Eigen::MatrixXd information;
  double residual_variance = 0;
  // Whether the residuals are smooth at the estimate: the coordinate whose Jacobian column, differenced with steps h
  // and 10 h, differs most, and by how much (|J_h - J_10h| / |J_10h|); rough_coordinate = -1 when none differs by
  // more than kRoughJacobian. A cost that jumps between parameters 1e-10 apart gave columns of garbage, standard
  // errors 20-160 times below the Cramer-Rao bound and "converged" 12 % off, with nothing said (the twenty-first
  // pass's P1): the standard errors are kept, and the fit says they cannot be trusted.
  int rough_coordinate = -1;
  double rough_change = 0;
  // Whether the cost is quadratic over the standard errors it reports: for each coordinate, the sum of squares one
  // formal standard error away on either side against its Gauss-Newton prediction |r + s J_i|^2 (rise q_i = s^2
  // |J_i|^2). The coordinate with the largest mismatch beyond kNonQuadraticRise q_i, with the actual and predicted
  // rises; -1 when none. A cliff of the spike cost (3.5) 1e-3 from the estimate, where a model spike changes its bin,
  // lies far beyond the steps of the Jacobian check above: Nelder-Mead stopped "converged" on it and the standard
  // errors were printed with nothing said (the twenty-second pass's P5).
  int nonquadratic_coordinate = -1;
  double nonquadratic_rise = 0, quadratic_rise = 0;
};
// At one standard error a smooth cost's sum of squares rises by q_i (at least one residual variance) to within its
// third-order term, small wherever the standard error means anything; a rise off by more than 2 q_i (below -q_i or
// above 3 q_i) is a cliff, or a cost so far from quadratic that the standard error is no interval.
inline constexpr double kNonQuadraticRise = 2.0;
// On a smooth cost the central differences at h = 1e-6 and 10 h of the coordinate differ by their truncation error,
// O((10 h)^2) of the column (a resonance 1e-3 wide moves by 1 % of its width at 10 h: 1e-4 of it); 10 % is a jump.
inline constexpr double kRoughJacobian = 0.1;
// The largest leverage at which the sandwich is formed: at h <= 1/2 at least half of every residual's variance (with
// equal variances) is its own noise.
inline constexpr double kMaxSandwichLeverage = 0.5;
// The least effective count of squared residuals (Kish's, optimizer.cc) an estimate's sandwich variance may rest on:
// with fewer its relative sd exceeds sqrt(2/10) = 45 %, and a few modes' residuals decide it.
inline constexpr double kMinSandwichTerms = 10;
Covariance covariance_at(const Problem& problem, const Eigen::VectorXd& x, int lags = 0);

// Space-filling starts in the box: a Latin hypercube (one point per stratum and coordinate, strata shuffled) or
// independent uniform points ("random"). Uniforms are drawn as (engine() >> 11) 2^-53 over std::mt19937_64 and the
// shuffle is a Fisher-Yates on the same draws, so a seed gives the same points with any standard library.
// The designs of the extra starts, by name: "lhs" (Latin hypercube) | "random" (uniform).
const core::NameSet& start_design_names();
std::vector<Eigen::VectorXd> space_filling_starts(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int count,
                                                  const std::string& design, std::uint64_t seed);

namespace detail {
// Adapter entry points (one per library), called by minimize() after the common checks.
OptimizerResult minimize_nlopt(const Problem& problem, const Eigen::VectorXd& start, const OptimizerOptions& options);
OptimizerResult minimize_ceres(const Problem& problem, const Eigen::VectorXd& start, const OptimizerOptions& options);
// Wraps the problem so that every call is counted and guarded: exceptions and non-finite values become +inf
// (cost) or false (residuals), and the first exception's message is kept for the status.
struct GuardedProblem {
  explicit GuardedProblem(const Problem& problem);
  double cost(const Eigen::VectorXd& x);
  bool residuals(const Eigen::VectorXd& x, Eigen::VectorXd& r);
  bool jacobian(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& j);  // counted as one evaluation
  const Problem& problem;
  long evaluations = 0;
  std::string first_exception;
  std::string first_rejection;  // Problem::rejection after the first call that returned false
  Eigen::VectorXd best_x;
  double best_cost = std::numeric_limits<double>::infinity();
  // Overrides the adapter's verdict when the objective threw or never gave a finite value; `what` names the
  // quantity ("cost", "residual vector") and `detail` is the adapter's own termination text.
  void finish(OptimizerResult& result, const std::string& what, const std::string& detail) const;
};
}  // namespace detail

// The optimisation libraries' versions, for provenance (from their adapters).
std::string ceres_library_version();
std::string nlopt_library_version();

}  // namespace beamid::fit
