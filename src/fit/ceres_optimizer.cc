// Ceres adapter: the only file that sees Ceres types. Levenberg-Marquardt with dense QR on the residual vector and
// box bounds, with the problem's exact Jacobian where it has one (the time cost: simulation/sensitivities.h), else
// central numeric differences (relative step 1e-6 on coordinates of order one: truncation O(h^2) ~ 1e-12, and
// round-off ~ eps/h ~ 1e-10 of a smooth residual; the thin beam's model output carries ~1e-9 of round-off, which at
// this step corrupts the weakly sensitive damping columns, so LM then needs tens of iterations near a minimum).
#include <ceres/ceres.h>
#include <ceres/version.h>
#include <glog/logging.h>

#include <memory>
#include <mutex>

#include "fit/optimizer.h"

namespace beamid::fit::detail {
namespace {

// Ceres' residual functor: evaluations go through the guard (counted, exceptions and non-finite values caught).
struct Residuals {
  GuardedProblem* guarded;
  double scale = 1;  // the solver sees scale * r, so that its absolute tolerances mean the same for any units
  bool operator()(double const* const* parameters, double* out) const {
    const int n = guarded->problem.dimension();
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(parameters[0], n);
    Eigen::VectorXd r;
    if (!guarded->residuals(x, r)) return false;  // Ceres rejects the step and shrinks the trust region
    Eigen::Map<Eigen::VectorXd>(out, guarded->problem.residual_count) = scale * r;
    return true;
  }
};

// The same residuals with the problem's exact Jacobian (Ceres wants it row-major: jacobians[0][i n + j] = dr_i/dx_j).
class ExactJacobian final : public ceres::CostFunction {
 public:
  ExactJacobian(GuardedProblem* guarded, double scale) : guarded_(guarded), scale_(scale) {
    set_num_residuals(guarded->problem.residual_count);
    mutable_parameter_block_sizes()->push_back(guarded->problem.dimension());
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = guarded_->problem.dimension(), m = guarded_->problem.residual_count;
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(parameters[0], n);
    Eigen::VectorXd r;
    if (jacobians == nullptr || jacobians[0] == nullptr) {
      if (!guarded_->residuals(x, r)) return false;
    } else {
      Eigen::MatrixXd j;
      if (!guarded_->jacobian(x, r, j)) return false;
      using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
      Eigen::Map<RowMajor>(jacobians[0], m, n) = scale_ * j;
    }
    Eigen::Map<Eigen::VectorXd>(residuals, m) = scale_ * r;
    return true;
  }

 private:
  GuardedProblem* guarded_;
  double scale_;
};

// Remembers the last point's residuals and Jacobian. With bounds Ceres' trust-region loop evaluates one point up to
// three times: its projected line search (bounded problems only) asks for the candidate's cost and gradient, hence
// the Jacobian; then the candidate's cost again; then, once the step is accepted, residuals and Jacobian at it for the
// next iteration. Measured on the staged time fit: every iteration evaluated two Jacobians and one residual vector at
// the same point. Answering the repeats from memory leaves every value Ceres sees as it was (a Jacobian evaluation
// returns the residuals too) and costs one model run with its derivatives (or 2n + 1 runs for central differences) per
// iteration instead of two such plus one run.
class RememberLast final : public ceres::CostFunction {
 public:
  explicit RememberLast(ceres::CostFunction* inner) : inner_(inner) {
    set_num_residuals(inner->num_residuals());
    *mutable_parameter_block_sizes() = inner->parameter_block_sizes();
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = parameter_block_sizes().front(), m = num_residuals();
    const bool wants_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    const Eigen::Map<const Eigen::VectorXd> x(parameters[0], n);
    const bool same = valid_ && x_.size() == n && (x_.array() == x.array()).all();  // bitwise: NaN is never the same
    if (same && (!wants_jacobian || has_jacobian_)) {
      Eigen::Map<Eigen::VectorXd>(residuals, m) = r_;
      if (wants_jacobian) Eigen::Map<Eigen::VectorXd>(jacobians[0], j_.size()) = j_;
      return true;
    }
    valid_ = false;
    if (!inner_->Evaluate(parameters, residuals, jacobians)) return false;
    x_ = x;
    r_ = Eigen::Map<const Eigen::VectorXd>(residuals, m);
    has_jacobian_ = wants_jacobian;
    if (wants_jacobian) j_ = Eigen::Map<const Eigen::VectorXd>(jacobians[0], static_cast<Eigen::Index>(m) * n);
    valid_ = true;
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> inner_;
  mutable Eigen::VectorXd x_, r_, j_;  // j_: row-major m x n, as Ceres lays it out
  mutable bool valid_ = false, has_jacobian_ = false;
};

ceres::CostFunction* cost_function(GuardedProblem& guarded, double scale = 1) {
  if (guarded.problem.jacobian) return new RememberLast(new ExactJacobian(&guarded, scale));
  auto* f = new ceres::DynamicNumericDiffCostFunction<Residuals, ceres::CENTRAL>(new Residuals{&guarded, scale});
  f->AddParameterBlock(guarded.problem.dimension());
  f->SetNumResiduals(guarded.problem.residual_count);
  return new RememberLast(f);
}

// Stops the solver once the evaluation budget is spent.
class Budget final : public ceres::IterationCallback {
 public:
  Budget(const GuardedProblem& guarded, long limit) : guarded_(guarded), limit_(limit) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (guarded_.evaluations < limit_) return ceres::SOLVER_CONTINUE;
    exhausted = true;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }
  bool exhausted = false;

 private:
  const GuardedProblem& guarded_;
  long limit_;
};

// Ceres reports through glog ("Terminating: Residual and Jacobian evaluation failed.", after a "Logging before
// InitGoogleLogging" warning). Those lines would break beamid's one-line stderr contract, and everything they say
// reaches the caller as a status and termination text, so glog is initialised once with only fatal messages shown.
void quiet_glog() {
  static std::once_flag once;
  std::call_once(once, [] {
    FLAGS_minloglevel = google::GLOG_FATAL;
    FLAGS_stderrthreshold = google::GLOG_FATAL;
    FLAGS_logtostderr = false;
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("beamid");
  });
}

}  // namespace

OptimizerResult minimize_ceres(const Problem& problem, const Eigen::VectorXd& start, const OptimizerOptions& options) {
  quiet_glog();
  const int n = problem.dimension();
  GuardedProblem guarded(problem);
  Eigen::VectorXd x = start;
  // Residuals are divided by their norm at the start, so that the solver's absolute gradient tolerance is relative
  // to the initial misfit whatever the signal's units (a thick beam's displacements are ~1e-7 m).
  Eigen::VectorXd r0;
  double scale = 1;
  if (guarded.residuals(start, r0) && r0.norm() > 0) scale = 1 / r0.norm();
  ceres::Problem ceres_problem;
  ceres_problem.AddResidualBlock(cost_function(guarded, scale), nullptr, x.data());
  for (int i = 0; i < n; ++i) {
    ceres_problem.SetParameterLowerBound(x.data(), i, problem.lower(i));
    ceres_problem.SetParameterUpperBound(x.data(), i, problem.upper(i));
  }
  Budget budget(guarded, options.max_evaluations);
  ceres::Solver::Options solver;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_evaluations;  // the budget callback stops it first
  solver.parameter_tolerance = options.xtol_rel;
  solver.function_tolerance = options.ftol_rel > 0 ? options.ftol_rel : 1e-15;
  solver.gradient_tolerance = 1e-14;  // on the scaled residuals: gradient 1e-14 of the initial misfit's
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.num_threads = 1;  // results must not depend on threads
  solver.callbacks.push_back(&budget);

  OptimizerResult result;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &ceres_problem, &summary);
  result.evaluations = guarded.evaluations;
  result.x = guarded.best_x.size() == n ? guarded.best_x : x;
  result.cost = guarded.best_cost;
  result.termination = summary.message;
  if (budget.exhausted) {
    result.status = "max-evaluations";
    result.termination = "evaluation budget exhausted";
  } else if (summary.termination_type == ceres::CONVERGENCE || summary.termination_type == ceres::USER_SUCCESS) {
    result.status = "converged";
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    result.status = "max-evaluations";
  } else {
    result.status = "failed";
  }
  guarded.finish(result, "residual vector", summary.message);
  return result;
}

}  // namespace beamid::fit::detail

namespace beamid::fit {
std::string ceres_library_version() { return CERES_VERSION_STRING; }

}  // namespace beamid::fit
