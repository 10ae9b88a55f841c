#include "fit/identification.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "core/errors.h"
#include "core/limits.h"
#include "fit/joint_objective.h"
#include "fit/noise_estimation.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "signal/spikes.h"
#include "simulation/free_decay.h"
#include "simulation/modal_simulator.h"
#include "simulation/sensitivities.h"

namespace beamid::fit {

const core::NameSet& record_weight_names() {
  static const core::NameSet names(
      {{kRmsWeights, "each record's residuals relative to its data's RMS (records of equal signal-to-noise ratio)"},
       {kNoiseWeights, "maximum likelihood with each record's own noise level, reweighted until it settles"}});
  return names;
}

const core::NameSet& strategy_names() {
  static const core::NameSet names({{kDirect, "all estimated parameters at once"},
                                    {kStaged, "the paper's three stages: stiffness and inertia, damping, all"},
                                    {kContinuation, "record-length continuation: Nbar/16, /8, /4, /2, then all"},
                                    {kHybrid,
                                     "the fit's cost (spike-smooth, or modal) from the start(s), then --refine "
                                     "(time, freq-band or spike-smooth) from its estimate"}});
  return names;
}

std::string default_optimizer(const std::string& cost) { return cost == costs::kSpikeCost ? "nelder-mead" : "lm"; }

FitResult chained(const FitResult& first, FitResult second, const std::string& first_name,
                  const std::string& second_name) {
  std::vector<StageResult> stages;
  for (StageResult stage : first.stages) {
    stage.name = first_name + stage.name;
    stages.push_back(std::move(stage));
  }
  for (StageResult stage : second.stages) {
    stage.name = second_name + stage.name;
    stages.push_back(std::move(stage));
  }
  second.stages = std::move(stages);
  second.evaluations += first.evaluations;
  second.wall_time_s += first.wall_time_s;
  second.best_start = first.best_start;
  for (std::size_t i = 0; i < second.parameters.size(); ++i) second.parameters[i].start = first.parameters[i].start;
  // The starts ran in the first fit: its other minimum is the chain's (a hybrid or a noise-estimating fit from
  // --starts K lost it, the second fit having one start: the twenty-fourth pass's adv57 P1), named as the first's.
  if (second.other_minimum.empty() && !first.other_minimum.empty())
    second.other_minimum =
        "in the " + first_name.substr(0, first_name.find_last_not_of(": ") + 1) + " stage: " + first.other_minimum;
  if (second.start_ends.empty()) second.start_ends = first.start_ends;
  return second;
}

namespace {

// The optimizer problem over a subset `active` of the estimated coordinates, the others held at `x_fixed`.
Problem subproblem(JointObjective& objective, const ParameterMap& map, const std::vector<int>& active,
                   const Eigen::VectorXd& x_fixed) {
  Problem p;
  const auto n = static_cast<Eigen::Index>(active.size());
  p.lower.resize(n);
  p.upper.resize(n);
  const Eigen::VectorXd lo = map.lower(), hi = map.upper();
  for (Eigen::Index i = 0; i < n; ++i)
    p.lower(i) = lo(active[static_cast<std::size_t>(i)]), p.upper(i) = hi(active[static_cast<std::size_t>(i)]);
  auto all = [active, x_fixed](const Eigen::VectorXd& x) {
    Eigen::VectorXd coordinates = x_fixed;
    for (std::size_t i = 0; i < active.size(); ++i) coordinates(active[i]) = x(static_cast<Eigen::Index>(i));
    return coordinates;
  };
  auto full = [&map, all](const Eigen::VectorXd& x) { return map.beams(all(x)); };
  p.cost = [&objective, full](const Eigen::VectorXd& x) { return objective.evaluate(full(x)).evaluation.value; };
  p.residual_count = objective.residual_count();
  p.rejection = std::make_shared<std::string>();
  p.residuals = [&objective, full, why = p.rejection](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    auto out = objective.evaluate(full(x));
    if (!out.evaluation.ok()) {
      *why = out.evaluation.status;
      return false;
    }
    r = std::move(out.evaluation.residuals);
    return true;
  };
  if (objective.has_exact_jacobian()) {
    // d r / d x_i = d r / d q_i  d q_i / d x_i (the coordinate map is diagonal).
    p.jacobian = [&objective, &map, all, active, why = p.rejection](const Eigen::VectorXd& x, Eigen::VectorXd& r,
                                                                    Eigen::MatrixXd& j) {
      const Eigen::VectorXd coordinates = all(x);
      auto out = objective.evaluate_with_jacobian(map.beams(coordinates), active, j);
      if (!out.evaluation.ok() || j.size() == 0) {
        *why = out.evaluation.ok() ? "no Jacobian" : out.evaluation.status;
        return false;
      }
      r = std::move(out.evaluation.residuals);
      for (std::size_t i = 0; i < active.size(); ++i)
        j.col(static_cast<Eigen::Index>(i)) *= map.derivative(active[i], coordinates(active[i]));
      return true;
    };
  }
  return p;
}

struct StrategyRun {
  Eigen::VectorXd x;
  double cost = std::numeric_limits<double>::infinity();
  long evaluations = 0;
  std::vector<StageResult> stages;
};

StrategyRun run_strategy(JointObjective& objective, const ParameterMap& map, const FitOptions& o, Eigen::VectorXd x,
                         const std::vector<Record>& records) {
  std::vector<std::pair<std::string, std::vector<int>>> plan;
  std::vector<int> all(static_cast<std::size_t>(map.size()));
  for (int i = 0; i < map.size(); ++i) all[static_cast<std::size_t>(i)] = i;
  StrategyRun run;
  run.x = x;
  if (o.strategy == kContinuation) {
    // Record-length continuation: all parameters on the first Nbar/16, Nbar/8, Nbar/4, Nbar/2 samples (at least
    // 64) of every record, each from the previous estimate; the full records follow as the final stage below. A
    // record of length T has a basin about 1/(2 f T) wide in relative frequency for a lightly damped mode at f
    // (model.md section 4), so short records make the start good enough for the next.
    for (int divisor = 16; divisor >= 2; divisor /= 2) {
      std::vector<Record> heads = records;
      bool long_enough = true;
      for (Record& head : heads) {
        head.experiment.samples /= divisor;
        long_enough = long_enough && head.experiment.samples >= 64;
        head.data.resize(static_cast<std::size_t>(head.experiment.samples));
      }
      if (!long_enough) continue;
      StageResult stage;
      stage.name = "first " + std::to_string(heads.front().experiment.samples) + " samples";
      if (heads.size() > 1) stage.name = "first 1/" + std::to_string(divisor) + " of every record";
      for (const auto& e : map.estimated()) stage.keys.push_back(e.key);
      // A head too short for what the cost asks of its data (the modal cost's modes, the spike costs' spikes) is a
      // stage skipped with its reason, not the fit's failure: the whole record showed the 4 modes asked for, and the
      // error blamed the record (the seventh pass's G19, G23).
      std::optional<JointObjective> part;
      try {
        part.emplace(o, heads, map);
      } catch (const InputError& e) {
        stage.result.status = "skipped";
        stage.result.termination = std::string("too short for the cost: ") + e.what();
        run.stages.push_back(std::move(stage));
        continue;
      }
      run.x = run.x.cwiseMax(map.lower()).cwiseMin(map.upper());
      stage.result = minimize(subproblem(*part, map, all, run.x), run.x, o.optimizer);
      run.evaluations += stage.result.evaluations;
      if (stage.result.usable()) run.x = stage.result.x;
      run.stages.push_back(std::move(stage));
    }
  }
  if (o.strategy == kStaged) {
    const auto structural = map.with_roles({"stiffness", "inertia", "geometry"});
    const auto damping = map.with_roles({"damping"});
    if (!structural.empty() && !damping.empty()) {
      plan.emplace_back("stiffness and inertia", structural);
      plan.emplace_back("damping", damping);
    }
    plan.emplace_back("all", all);
  } else {
    plan.emplace_back(o.strategy == kContinuation ? "full record" : kDirect, all);
  }
  for (const auto& [name, active] : plan) {
    const Problem p = subproblem(objective, map, active, run.x);
    Eigen::VectorXd start(static_cast<Eigen::Index>(active.size()));
    // A previous stage may end on a bound, and an optimizer may leave it by a rounding error: the next stage
    // starts on the bound, not outside it.
    for (std::size_t i = 0; i < active.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      start(k) = std::clamp(run.x(active[i]), p.lower(k), p.upper(k));
    }
    StageResult stage;
    stage.name = name;
    for (int i : active) stage.keys.push_back(map.estimated()[static_cast<std::size_t>(i)].key);
    stage.result = minimize(p, start, o.optimizer);
    run.evaluations += stage.result.evaluations;
    if (stage.result.usable() && stage.result.cost <= run.cost) {
      for (std::size_t i = 0; i < active.size(); ++i) run.x(active[i]) = stage.result.x(static_cast<Eigen::Index>(i));
      run.cost = stage.result.cost;
    }
    const bool failed = !stage.result.usable();
    run.stages.push_back(std::move(stage));
    if (failed) break;
  }
  return run;
}

// The records' start beams, each holding record 1's start of every shared estimated parameter (the value the fit
// starts from, and the one its bounds are checked against).
std::vector<model::BeamParameters> record_starts(const std::vector<Record>& records,
                                                 const std::vector<EstimatedParameter>& estimate) {
  std::vector<model::BeamParameters> starts;
  for (const Record& r : records) starts.push_back(r.start);
  for (const auto& e : estimate)
    if (!record_key(e.key) && model::describe_parameter(starts.front(), e.key))
      for (auto& b : starts)
        if (model::describe_parameter(b, e.key))
          model::set_parameter_value(b, e.key, model::parameter_value(starts.front(), e.key));
  return starts;
}

}  // namespace

void validate(const FitOptions& o) {
  if (auto error = strategy_names().violation("strategy", o.strategy)) throw InputError(*error);
  // The refinement is a least-squares cost with a Jacobian (Levenberg-Marquardt from the global estimate): time or
  // freq-band (the efficient ones with a narrow basin), or spike-smooth (a measured record's, under model error),
  // after a global cost (spike-smooth, or modal with starts over the bounds: the route from nominal starts, issue 31).
  if (o.strategy == kHybrid && o.refine != costs::kTimeCost && !costs::is_band_cost(o.refine) &&
      o.refine != costs::kSpikeSmoothCost)
    throw InputError("refine = '" + o.refine + "': must be one of " + costs::kTimeCost + ", " + costs::kBandCost +
                     ", " + costs::kMaxLikelihoodCost + ", " + costs::kSpikeSmoothCost);
  // The estimated noise's shortest records: the local polynomial method's 13 complex bins (28 samples), an AR
  // model's 8.
  const bool estimated = o.cost.noise_model == costs::kEstimatedNoise;
  const std::string& reader = o.strategy == kHybrid ? o.refine : o.cost.name;
  if (estimated && reader == costs::kMaxLikelihoodCost && o.experiment.samples < 28)
    throw InputError(
        "noise_model = 'estimated': freq-ml estimates each bin's noise from 13 neighbouring complex DFT "
        "bins, which needs at least 28 samples; the record has " +
        std::to_string(o.experiment.samples));
  if (o.strategy == kHybrid && o.refine == o.cost.name)
    throw InputError("refine = '" + o.refine + "': must differ from the cost it refines (cost = '" + o.cost.name +
                     "')");
  if (auto error = validation_error(o.optimizer)) throw InputError(*error);
  // The paper's spike cost is piecewise constant in the model's frequencies (its spikes sit on DFT bins): a
  // derivative-based method sees a zero gradient on each step and stops where it started, "converged" (EI 9 % off
  // with 1 % standard errors: the sixth pass's S272). Its derivative-free default, or spike-smooth, is the way.
  if (o.cost.name == costs::kSpikeCost && needs_residuals(o.optimizer.method))
    throw InputError("optimizer = '" + o.optimizer.method + "': cost spike is piecewise constant (its spikes sit on " +
                     "DFT bins), so a derivative-based method stalls on its first step; use a derivative-free one " +
                     "(the default, nelder-mead) or cost spike-smooth");
  if (o.starts < 1) throw InputError("starts = " + std::to_string(o.starts) + ": must be >= 1");
  record_weight_names().require("record_weights", o.record_weights);
  start_design_names().require("start_design", o.start_design);
  const ParameterMap map(o.start, o.estimate, o.scaling);
  // A length below a force, sensor or body position would take it off the beam mid-fit.
  for (const auto& e : o.estimate) {
    if (local_key(e.key) != "l") continue;
    double farthest = 0;
    if (o.experiment.force_x_m) farthest = std::max(farthest, *o.experiment.force_x_m);
    if (o.experiment.sensor_x_m) farthest = std::max(farthest, *o.experiment.sensor_x_m);
    for (const auto& a : o.start.attachments) farthest = std::max(farthest, a.x);
    if (e.lower < farthest)
      throw InputError("bounds of " + e.key + " [" + format_value(e.lower) + ", " + format_value(e.upper) +
                       "]: lower must be >= " + format_value(farthest) +
                       " m, the farthest force, sensor or attachment position from the clamp");
  }
  for (int i = 0; i < map.size(); ++i) {
    const auto& e = map.estimated()[static_cast<std::size_t>(i)];
    const double s = model::parameter_value(o.start, local_key(e.key));
    if (!(s >= e.lower && s <= e.upper))
      throw InputError("start " + e.key + " = " + format_value(s) + ": outside its bounds [" + format_value(e.lower) +
                       ", " + format_value(e.upper) + "]");
  }
  // A hybrid's force noise is its refinement's (freq-ml's errors-in-variables form): each stage's cost is checked as
  // it runs (the global one was refused for it: the twenty-second pass's P2).
  costs::CostOptions global = o.cost;
  if (o.strategy == kHybrid) {
    global.force_noise_sd = 0;
    costs::CostOptions fine = o.cost;
    fine.name = o.refine;
    if (auto error = costs::validation_error(fine)) throw InputError(*error);
  }
  if (auto error = costs::validation_error(global)) throw InputError(*error);
  if (auto error = simulation::validation_error(o.experiment, o.start.l)) throw InputError(*error);
  if (auto error = simulation::validation_error(o.simulator)) throw InputError(*error);
}

namespace {

constexpr double kMaxFirstStepOverStart = 10;

// Every check of validate() for each record's own options (naming the record when there are several); `records`
// hold their starts (record_starts) and `map` is built on them, which checks the estimated keys against them all.
void validate_records(const FitOptions& o, const std::vector<Record>& records, const ParameterMap& map) {
  for (std::size_t r = 0; r < records.size(); ++r) {
    try {
      validate(record_options(o, records[r], map, static_cast<int>(r)));
    } catch (const InputError& error) {
      if (records.size() == 1) throw;
      throw InputError("record " + std::to_string(r + 1) + " (" + records[r].name + "): " + error.what());
    }
  }
  // One measurement fitted twice (a column pasted twice, a record listed under two names, a copy rounded: the
  // eleventh pass's DC_round) counts its information twice: every standard error came out sqrt(2) too small, with
  // nothing said (the tenth pass's RL_02, DC_2).
  // Equal to a millionth of the larger peak: a copy rounded to 7 digits or through float32 is the same measurement.
  const auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    if (x.size() != y.size()) return false;
    double peak = 0, apart = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      peak = std::max({peak, std::abs(x[i]), std::abs(y[i])}), apart = std::max(apart, std::abs(x[i] - y[i]));
    return apart <= 1e-6 * peak;
  };
  for (std::size_t a = 0; a < records.size(); ++a)
    for (std::size_t b = a + 1; b < records.size(); ++b)
      if (same(records[a].data, records[b].data))
        throw InputError("records " + std::to_string(a + 1) + " (" + records[a].name + ") and " +
                         std::to_string(b + 1) + " (" + records[b].name +
                         ") hold the same samples: one measurement fitted twice counts its information twice (every "
                         "standard error sqrt(2) too small); fit it once");
}

// A local derivative-free search (nelder-mead, bobyqa, sbplx) takes a first step of initial_step times each bound
// range. In linear coordinates (x = p / start) a range of many decades makes that step many times the start itself:
// bobyqa from J_o = 1e-5 in [1e-9, 1e6] stepped 2e4 and "converged" 80 standard errors off, and in EI = [1e-300,
// 1e300] it never came back to a finite cost. Refused when the first step exceeds 10 times the start (bounds wider
// than about 500 times the start), with the two ways out; log coordinates step by a factor instead.
void check_first_step(const FitOptions& o, const ParameterMap& map) {
  const std::string& method = o.optimizer.method;
  if (map.scaling() != "linear" || (method != "nelder-mead" && method != "bobyqa" && method != "sbplx")) return;
  const Eigen::VectorXd lower = map.lower(), upper = map.upper();
  for (int i = 0; i < map.size(); ++i) {
    const double step = o.optimizer.initial_step * (upper(i) - lower(i));  // in units of the start value
    if (step > kMaxFirstStepOverStart) {
      const EstimatedParameter& e = map.estimated()[static_cast<std::size_t>(i)];
      throw InputError("bounds of " + e.key + " = [" + format_value(e.lower) + ", " + format_value(e.upper) +
                       "]: " + method + "'s first step in linear coordinates (" +
                       format_value(o.optimizer.initial_step) + " of the range) is " + format_rounded(step) +
                       " times the start " + format_value(map.reference(i)) +
                       ", and the search leaves the start's scale behind: give log coordinates (--scaling log) or "
                       "bounds within about 500 times the start");
    }
  }
}

// The hybrid strategy: the global fit (direct, from every start), then the refinement from its estimate. The result
// is the refinement's, with the stages and evaluations of both.
FitResult fit_hybrid(const FitOptions& o, const std::vector<Record>& records) {
  FitOptions global = o;
  global.strategy = kDirect;
  global.cost.force_noise_sd = 0;  // the refinement's (validate)
  const FitResult first = fit(global, records);
  FitOptions fine = o;
  fine.strategy = kDirect;
  fine.cost.name = o.refine;
  fine.optimizer.method = default_optimizer(o.refine);
  fine.starts = 1;
  std::vector<Record> from_first = records;
  for (std::size_t r = 0; r < records.size(); ++r) from_first[r].start = first.records[r].beam;  // inside the bounds
  return chained(first, fit(fine, from_first), o.cost.name + ": ",
                 o.refine + " from the " + o.cost.name + " estimate: ");
}

}  // namespace

int robust_lags(const std::string& cost, int residuals) {
  return cost == costs::kTimeCost ? static_cast<int>(std::floor(4 * std::pow(residuals / 100.0, 2.0 / 9.0))) : 0;
}

FitResult fit(const FitOptions& o, const std::vector<double>& data) {
  Record record;
  record.name = "record1";
  record.start = o.start;
  record.experiment = o.experiment;
  record.data = data;
  return fit(o, std::vector<Record>{record});
}

namespace {

// Every start through the strategy; the lowest final cost wins (ties: the earlier start). Adds their evaluations.
StrategyRun best_of_starts(JointObjective& objective, const ParameterMap& map, const FitOptions& o,
                           const std::vector<Eigen::VectorXd>& x_starts, const std::vector<Record>& records,
                           FitResult& result) {
  StrategyRun best;
  for (std::size_t s = 0; s < x_starts.size(); ++s) {
    FitOptions seeded = o;
    seeded.optimizer.seed = o.seed + s;  // a distinct, reproducible stream per start
    StrategyRun run = run_strategy(objective, map, seeded, x_starts[s], records);
    result.evaluations += run.evaluations;
    StartEnd end{run.cost, {}, !run.stages.empty() && run.stages.back().result.usable()};
    for (int i = 0; i < map.size(); ++i) end.values.push_back(map.value(i, run.x(i)));
    result.start_ends.push_back(std::move(end));
    if (s == 0 || run.cost < best.cost) {
      best = std::move(run);
      result.best_start = static_cast<int>(s);
    }
  }
  return best;
}

// Maximum likelihood with each record's own noise level (FitOptions::record_weights): reweight by the records'
// residual sd at the estimate and fit again from it, until the weights settle.
void reweight_by_noise(JointObjective& objective, const ParameterMap& map, const FitOptions& o,
                       const std::vector<Record>& records, StrategyRun& best, FitResult& result) {
  FitOptions again = o;
  again.strategy = kDirect;
  for (int pass = 0; pass < 5 && !best.stages.empty() && best.stages.back().result.usable(); ++pass) {
    const JointObjective::Output at = objective.evaluate(map.beams(best.x));
    if (!at.evaluation.ok()) break;
    std::vector<double> weights;
    double change = 0;
    for (std::size_t r = 0; r < records.size(); ++r) {
      const Eigen::VectorXd& e = at.records[r].evaluation.residuals;
      const double sd = std::sqrt(e.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(e.size(), 1)));
      weights.push_back(1 / sd);
      // Only the weights' ratios change the estimate: the change of each relative to record 1's.
      change = std::max(
          change,
          std::abs(weights.back() / weights.front() * objective.weight(0) / objective.weight(static_cast<int>(r)) - 1));
    }
    if (std::any_of(weights.begin(), weights.end(), [](double w) { return !(std::isfinite(w) && w > 0); })) break;
    if (pass > 0 && change < 1e-3) break;
    objective.set_weights(weights);
    StrategyRun run = run_strategy(objective, map, again, best.x, records);
    result.evaluations += run.evaluations;
    if (run.stages.empty() || !run.stages.back().result.usable()) break;
    best = std::move(run);
  }
}

// Each record's own evaluation and output at the estimate (the joint evaluation's parts).
void record_results(JointObjective& objective, const std::vector<Record>& records,
                    const std::vector<model::BeamParameters>& estimates, FitResult& result) {
  JointObjective::Output final_output = objective.evaluate(estimates, Objective::Response::always);
  result.final_evaluation = final_output.evaluation;
  for (std::size_t r = 0; r < records.size(); ++r) {
    RecordResult part{records[r].name, estimates[r], {}, {}, objective.weight(static_cast<int>(r))};
    if (r < final_output.records.size()) {
      part.evaluation = final_output.records[r].evaluation;
      part.model_output = std::move(final_output.records[r].y);
      part.zero_model_value = objective.part(static_cast<int>(r))
                                  .cost()
                                  .zero_model_value()
                                  .value_or(std::numeric_limits<double>::quiet_NaN());
    } else {
      part.evaluation.status = "not evaluated: an earlier record failed";
    }
    result.records.push_back(std::move(part));
  }
  result.model_output = result.records.front().model_output;
  if (result.final_evaluation.ok()) result.cost = result.final_evaluation.value;
}

// What the identifiability verdict is about (FitOptions::of_interest): the parameters of interest among the estimated
// ones, and those a bound set.
VerdictScope verdict_scope(const ParameterMap& map, const FitOptions& o, const std::vector<ParameterEstimate>& p) {
  VerdictScope scope;
  for (int i = 0; i < map.size(); ++i) {
    const std::string& key = map.estimated()[static_cast<std::size_t>(i)].key;
    const std::string local = local_key(key);
    scope.of_interest.push_back(o.of_interest.empty()
                                    ? model::parameter_role(local) != "damping"
                                    : std::any_of(o.of_interest.begin(), o.of_interest.end(),
                                                  [&](const std::string& k) { return k == key || k == local; }));
    scope.on_bound.push_back(static_cast<std::size_t>(i) < p.size() &&
                             (p[static_cast<std::size_t>(i)].status == kAtLowerBound ||
                              p[static_cast<std::size_t>(i)].status == kAtUpperBound));
  }
  return scope;
}

// The estimates with their formal and sandwich standard errors (physical units), correlations, identifiability and
// bound statuses.
void parameter_results(JointObjective& objective, const ParameterMap& map, const FitOptions& o, const StrategyRun& best,
                       const std::vector<model::BeamParameters>& starts,
                       const std::vector<model::BeamParameters>& estimates, FitResult& result) {
  // Standard errors from the formal covariance on all estimated coordinates, mapped to physical units.
  std::vector<int> all(static_cast<std::size_t>(map.size()));
  for (int i = 0; i < map.size(); ++i) all[static_cast<std::size_t>(i)] = i;
  const Covariance covariance = covariance_at(subproblem(objective, map, all, best.x), best.x,
                                              robust_lags(o.cost.name, objective.residual_count()));
  result.covariance_status = covariance.status;
  result.sandwich_status = covariance.ok() ? covariance.robust_status : covariance.status;
  if (covariance.rough_coordinate >= 0)
    result.roughness = "its derivative in " +
                       map.estimated()[static_cast<std::size_t>(covariance.rough_coordinate)].key + " changes by " +
                       format_rounded(100 * covariance.rough_change, 2) + " % between steps of 1e-6 and 1e-5";
  if (covariance.nonquadratic_coordinate >= 0)
    result.nonquadratic =
        "one standard error of " + map.estimated()[static_cast<std::size_t>(covariance.nonquadratic_coordinate)].key +
        " away, its sum of squares changes by " + format_rounded(covariance.nonquadratic_rise, 3) +
        " where its derivatives at the estimate predict " + format_rounded(covariance.quadratic_rise, 3);
  Eigen::VectorXd standard_error = Eigen::VectorXd::Constant(map.size(), std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd robust_error = standard_error;
  if (covariance.ok()) {
    Eigen::VectorXd d(map.size());
    for (int i = 0; i < map.size(); ++i) d(i) = map.derivative(i, best.x(i));
    const Eigen::MatrixXd physical = d.asDiagonal() * covariance.matrix * d.asDiagonal();
    standard_error = physical.diagonal().cwiseMax(0.0).cwiseSqrt();
    if (covariance.robust.size() > 0)
      robust_error = (d.asDiagonal() * covariance.robust * d.asDiagonal()).diagonal().cwiseMax(0.0).cwiseSqrt();
    else
      robust_error.setConstant(std::numeric_limits<double>::quiet_NaN());
    result.correlation = physical;
    for (int i = 0; i < map.size(); ++i)
      for (int j = 0; j < map.size(); ++j) {
        const double s = standard_error(i) * standard_error(j);
        result.correlation(i, j) = s > 0 ? physical(i, j) / s : std::numeric_limits<double>::quiet_NaN();
      }
  }
  const Eigen::VectorXd lower = map.lower(), upper = map.upper();
  bool at_bound = false;
  for (int i = 0; i < map.size(); ++i) {
    const auto& e = map.estimated()[static_cast<std::size_t>(i)];
    const auto split = record_key(e.key);
    const std::size_t r = split ? static_cast<std::size_t>(split->first) : 0;
    const std::string local = local_key(e.key);
    ParameterEstimate p{e.key,
                        model::parameter_value(estimates[r], local),
                        standard_error(i),
                        model::parameter_value(starts[r], local),
                        e.lower,
                        e.upper,
                        kFree,
                        robust_error(i)};
    // Within 1e-6 of the range in the optimizer's coordinates, and within 1e-3 of the bound's own value: with very
    // wide linear bounds (--bound-factor 1e6: [v/1e6, 1e6 v]) 1e-6 of the range is v itself, and an interior estimate
    // near the truth was reported at-lower-bound without a standard error. At the usual widths (factor 10, or log
    // coordinates) the first test is the tighter one, so the second changes nothing there.
    const double margin = 1e-6 * (upper(i) - lower(i));
    if (best.x(i) - lower(i) <= margin && p.estimate - e.lower <= 1e-3 * std::abs(e.lower)) p.status = kAtLowerBound;
    if (upper(i) - best.x(i) <= margin && e.upper - p.estimate <= 1e-3 * std::abs(e.upper)) p.status = kAtUpperBound;
    if (p.status != kFree) p.standard_error = p.robust_standard_error = std::numeric_limits<double>::quiet_NaN();
    at_bound = at_bound || p.status != kFree;
    if (result.status == "failed") {
      p.status = "failed";
      p.estimate = p.standard_error = p.robust_standard_error = std::numeric_limits<double>::quiet_NaN();
    }
    result.parameters.push_back(p);
  }
  if (at_bound && result.status != "failed") result.status += "-at-bound";
  // Other minima: only where the starts' costs are the estimate's sum of squares (a noise reweighting changes it).
  if (covariance.ok() && !(o.record_weights == kNoiseWeights && result.records.size() > 1)) {
    std::vector<std::string> keys;
    std::vector<double> values, errors;
    for (const ParameterEstimate& p : result.parameters)
      keys.push_back(p.key), values.push_back(p.estimate), errors.push_back(p.standard_error);
    result.other_minimum =
        other_minimum(result.start_ends, result.best_start, keys, values, errors, covariance.residual_variance);
  }
  result.identifiability = identifiability_of(covariance, map, best.x, verdict_scope(map, o, result.parameters));
}

}  // namespace

FitResult fit(const FitOptions& o, const std::vector<Record>& given) {
  if (given.empty()) throw InputError("records: none to fit");
  std::vector<Record> records = given;
  const std::vector<model::BeamParameters> starts = record_starts(given, o.estimate);
  for (std::size_t r = 0; r < records.size(); ++r) records[r].start = starts[r];
  const ParameterMap map(starts, o.estimate, o.scaling);
  validate_records(o, records, map);
  check_first_step(o, map);
  if (o.strategy == kHybrid) return fit_hybrid(o, records);
  if (costs::is_estimated_noise(o.cost.noise_model) && costs::cost_uses(o.cost.name).noise_model &&
      records.front().noise_model.empty())
    return o.cost.noise_model == costs::kRepeatedNoise ? fit_with_repeated_noise(o, records)
                                                       : fit_with_estimated_noise(o, records);
  JointObjective objective(o, records, map);

  const auto begin = std::chrono::steady_clock::now();
  std::vector<Eigen::VectorXd> x_starts{map.coordinates(starts)};
  if (o.starts > 1)
    for (auto& x : space_filling_starts(map.lower(), map.upper(), o.starts - 1, o.start_design, o.seed))
      x_starts.push_back(x);
  FitResult result;
  StrategyRun best = best_of_starts(objective, map, o, x_starts, records, result);
  if (o.record_weights == kNoiseWeights && records.size() > 1)
    reweight_by_noise(objective, map, o, records, best, result);
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  result.stages = best.stages;
  result.status = best.stages.empty() ? "failed" : best.stages.back().result.status;
  result.termination = best.stages.empty() ? "no stage ran" : best.stages.back().result.termination;
  const std::vector<model::BeamParameters> estimates = map.estimates(best.x);  // inside the bounds, always
  result.beam = estimates.front();
  result.cost = best.cost;
  result.final_cost = o.cost.name;
  record_results(objective, records, estimates, result);
  parameter_results(objective, map, o, best, starts, estimates, result);
  return result;
}

}  // namespace beamid::fit
