// NLopt adapter (the C++ interface, nlopt.hpp): the only file that sees NLopt types.
#include <map>
#include <nlopt.hpp>
#include <stdexcept>

#include "fit/optimizer.h"

namespace beamid::fit::detail {
namespace {

// The NLopt algorithm of an optimizer name (fit/optimizer.h's registry): an unknown name is an InputError listing
// the valid ones, never a default algorithm; a registered name without an entry here is a programming error.
nlopt::algorithm algorithm_of(const std::string& method) {
  static const std::map<std::string, nlopt::algorithm> algorithms = {{"nelder-mead", nlopt::LN_NELDERMEAD},
                                                                     {"bobyqa", nlopt::LN_BOBYQA},
                                                                     {"sbplx", nlopt::LN_SBPLX},
                                                                     {"direct-l", nlopt::GN_DIRECT_L},
                                                                     {"crs2-lm", nlopt::GN_CRS2_LM}};
  const auto it = algorithms.find(optimizer_names().require("optimizer", method));
  if (it == algorithms.end()) throw std::logic_error("optimizer '" + method + "' is not an NLopt algorithm");
  return it->second;
}

std::string words(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS:
      return "success";
    case nlopt::STOPVAL_REACHED:
      return "cost reached the stop value";
    case nlopt::FTOL_REACHED:
      return "relative cost change below ftol_rel";
    case nlopt::XTOL_REACHED:
      return "relative parameter change below xtol_rel";
    case nlopt::MAXEVAL_REACHED:
      return "evaluation budget exhausted";
    case nlopt::MAXTIME_REACHED:
      return "time budget exhausted";
    case nlopt::ROUNDOFF_LIMITED:
      return "progress limited by round-off";
    case nlopt::FORCED_STOP:
      return "stopped";
    default:
      return "failure";
  }
}

struct Callback {
  GuardedProblem* guarded;
  Eigen::VectorXd x;
};

double objective(unsigned n, const double* x, double* gradient, void* data) {
  auto* c = static_cast<Callback*>(data);
  (void)gradient;  // derivative-free methods only
  for (unsigned i = 0; i < n; ++i) c->x(static_cast<Eigen::Index>(i)) = x[i];
  return c->guarded->cost(c->x);  // never throws
}

}  // namespace

OptimizerResult minimize_nlopt(const Problem& problem, const Eigen::VectorXd& start, const OptimizerOptions& options) {
  const int n = problem.dimension();
  GuardedProblem guarded(problem);
  Callback callback{&guarded, Eigen::VectorXd(n)};
  OptimizerResult result;
  result.x = start;
  std::vector<double> x(start.data(), start.data() + n);
  try {
    nlopt::srand(options.seed);  // CRS2's random population; harmless for the deterministic methods
    nlopt::opt opt(algorithm_of(options.method), static_cast<unsigned>(n));
    opt.set_lower_bounds(std::vector<double>(problem.lower.data(), problem.lower.data() + n));
    opt.set_upper_bounds(std::vector<double>(problem.upper.data(), problem.upper.data() + n));
    opt.set_min_objective(objective, &callback);
    opt.set_maxeval(options.max_evaluations);
    if (options.xtol_rel > 0) opt.set_xtol_rel(options.xtol_rel);
    if (options.ftol_rel > 0) opt.set_ftol_rel(options.ftol_rel);
    std::vector<double> step(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
      step[static_cast<std::size_t>(i)] = options.initial_step * (problem.upper(i) - problem.lower(i));
    if (options.method == "nelder-mead" || options.method == "bobyqa" || options.method == "sbplx")
      opt.set_initial_step(step);
    double f = 0;
    const nlopt::result r = opt.optimize(x, f);
    result.termination = words(r);
    result.status = r == nlopt::MAXEVAL_REACHED || r == nlopt::MAXTIME_REACHED ? "max-evaluations" : "converged";
  } catch (const nlopt::roundoff_limited&) {
    result.termination = words(nlopt::ROUNDOFF_LIMITED);
    result.status = "converged";  // NLopt's best point is still returned and usually final
  } catch (const std::exception& error) {
    result.termination = std::string("NLopt: ") + error.what();
    result.status = "failed";
  }
  result.evaluations = guarded.evaluations;
  // The best point seen: NLopt's x is that point for these methods, but a stop by exception leaves x unchanged.
  if (guarded.best_x.size() == n) {
    result.x = guarded.best_x;
    result.cost = guarded.best_cost;
  }
  guarded.finish(result, "cost", result.termination);
  return result;
}

}  // namespace beamid::fit::detail

namespace beamid::fit {

std::string nlopt_library_version() {
  int major = 0, minor = 0, bugfix = 0;
  nlopt_version(&major, &minor, &bugfix);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(bugfix);
}

}  // namespace beamid::fit
