// Identification of beam parameters from one sampled record: the forward model (Galerkin order N, an integrator)
// and a cost (costs/cost.h) minimised over chosen parameters (fit/parameter_map.h) by an optimizer
// (fit/optimizer.h), with one of two strategies:
//   "direct": all estimated parameters at once;
//   "staged": the paper's procedure, (1) damping fixed at its start, fit stiffness and inertia; (2) those fixed,
//             fit damping; (3) fit all from there (a stage with no parameter is skipped);
//   "continuation": record-length continuation, all parameters on the first Nbar/16, /8, /4, /2 samples and then
//             the whole record, each from the previous estimate (not in the paper; a known remedy for the narrow
//             basins of the time-domain cost);
//   "hybrid": the fit's cost (a global one with a wide basin: spike-smooth, or modal with starts spread over the
//             bounds) directly from the start(s), then the `refine` cost (time or freq-band: efficient, but with a
//             basin of about 1/(2 f T); or spike-smooth, a measured record's) by Levenberg-Marquardt from that
//             estimate. "modal" with --starts, refined by spike-smooth, is the route from nominal starts: the modal
//             cost needs no simulation, so many starts are cheap, and its pairing by frequency has the widest basin;
//             it reached a tip inertia started 10 times off and a length 5 % off where spike-smooth from the nominal
//             start stalled on its bounds (issue 31, tests/fit/identification_test.cc);
// each run from the given start and, with starts > 1, from further space-filling starts in the bounds (the lowest
// final cost wins; ties go to the earlier start, so the outcome does not depend on timing).
// A failed model evaluation (integration, eigen-decomposition, (A4)) is an infinite cost; a failed fit is a status.
//
// A joint fit identifies one parameter set from several records at once: several channels of one test (sensors at
// different points), or several tests of one beam (one strip clamped at four lengths). Each record has its own
// experiment, data and beam (its values of every parameter that is not estimated, and its own estimated ones); an
// estimated key is shared by every record ("EI") or belongs to one ("record2.l": fit/parameter_map.h). The records'
// residual vectors are stacked into one sum of squares. With more than one record, each record's residuals are made
// dimensionless so that a channel in g and one in m/s, or two gains, weigh alike: the time-domain costs' (time,
// freq-band) are divided by the RMS of the record's data (times sqrt(Nbar) for freq-band, whose J_B = J_T / Nbar on
// the full band), which weights records of equal signal-to-noise ratio by their number of samples, as maximum
// likelihood does; the spike and modal costs' residuals are dimensionless already. A gain unknown per channel is
// --unknown-amplitude, solved per record.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/names.h"
#include "costs/cost.h"
#include "fit/identifiability.h"
#include "fit/optimizer.h"
#include "fit/parameter_map.h"
#include "fit/start_minima.h"
#include "model/beam_parameters.h"
#include "signal/sensor_filter.h"
#include "simulation/experiment.h"
#include "simulation/simulator.h"

namespace beamid::fit {

// The fitting strategies by name (see above).
inline const std::string kDirect = "direct";
inline const std::string kStaged = "staged";
inline const std::string kContinuation = "continuation";
inline const std::string kHybrid = "hybrid";
const core::NameSet& strategy_names();

struct FitOptions {
  model::BeamParameters start;             // the fixed parameters, and the start of the estimated ones
  int elements = 16;                       // Galerkin order N
  simulation::Experiment experiment;       // dt_s and samples must match the data
  simulation::SimulatorOptions simulator;  // "fast" by default
  // The measurement chain's anti-alias filter, in the model (fit/sensed_output.h): a record filtered before sampling
  // is fitted by the model filtered alike. A cut-off of 0: none (the model's output is the beam's, sampled).
  signal::SensorFilter sensor;
  costs::CostOptions cost;
  std::vector<EstimatedParameter> estimate;
  std::string scaling = "linear";   // "linear" | "log"
  std::string strategy = "direct";  // "direct" | "staged" | "continuation" | "hybrid"
  std::string refine = "time";      // hybrid only: the second fit's cost, "time" | "freq-band" | "spike-smooth"
  OptimizerOptions optimizer;
  int starts = 1;                    // 1: the given start only; more: plus space-filling starts
  std::string start_design = "lhs";  // "lhs" | "random"
  std::uint64_t seed = 1;            // for the extra starts and stochastic optimizers
  // A joint fit's record weights (above): "rms", each record's residuals relative to its data's RMS (records of equal
  // signal-to-noise ratio); or "noise", maximum likelihood with each record's own unknown noise level: after the fit,
  // w_k = 1 / s_k with s_k^2 = |r_k|^2 / m_k the record's residual variance, and the direct fit repeated from the
  // estimate until the weights settle (at most 5 passes, 1e-3 relative), as minimising sum_k m_k ln |r_k| does.
  std::string record_weights = "rms";
  // The parameters the identifiability verdict is about (fit/identifiability.h), by key as in `estimate` or by base
  // key for every record's ("cDI" for "record2.cDI"); empty: every estimated parameter that is not damping (gamma,
  // cDI, kAcs), or all of them when every one is. The others are marginalised, and those on a bound left out.
  std::vector<std::string> of_interest;
};

inline const std::string kRmsWeights = "rms";
inline const std::string kNoiseWeights = "noise";
const core::NameSet& record_weight_names();

// One record of a joint fit (above).
struct Record {
  std::string name;                   // "record1", or a channel's or file's name, for reports
  model::BeamParameters start;        // this record's beam: its fixed values and the start of its estimates
  simulation::Experiment experiment;  // dt_s and samples must match the data
  std::vector<double> data;
  std::vector<double> spike_frequencies_hz;  // this record's --spike-frequencies (empty: the fit's cost options')
  // This record's noise as the fit estimated it (FitOptions::cost.noise_model "estimated"): an AR model for time, the
  // bins' variances for freq-ml (empty: the fit's cost options').
  std::string noise_model;
  std::vector<double> bin_variance;
};

// The default optimizer for a cost: "lm" for the sums of squares with a usable Jacobian (time, spike-smooth),
// "nelder-mead" for the paper's spike cost, whose frequency term has zero gradient almost everywhere.
std::string default_optimizer(const std::string& cost);

// A parameter's status: "free" (inside its bounds), "at-lower-bound" or "at-upper-bound" (within 1e-6 of the bound
// range of it, in the optimizer's coordinates, and within 1e-3 of the bound's value: the bound, not the data, decided
// the value), or "failed" (the fit
// failed: the estimate is NaN, never the start shown as a result).
inline const std::string kFree = "free";
inline const std::string kAtLowerBound = "at-lower-bound";
inline const std::string kAtUpperBound = "at-upper-bound";

struct ParameterEstimate {
  std::string key;
  double estimate = 0, standard_error = 0, start = 0, lower = 0, upper = 0;  // standard_error NaN when unknown
  std::string status = kFree;  // standard_error is NaN at a bound: the formal covariance assumes an interior minimum
  // The sandwich (robust) standard error (fit/optimizer.h), NaN where standard_error is: it admits residuals of
  // unequal variance and, for the time cost, correlated over robust_lags() samples. A ratio robust / formal well
  // above 1 says that the residuals are not the white noise the formal one assumes (model error).
  double robust_standard_error = 0;
};

// The sandwich's bandwidth for `residuals` residuals of `cost`: Newey and West's (1994) rule floor(4 (m/100)^(2/9))
// for the time cost, whose residuals are ordered in time; 0 (White) for the costs whose residuals are per spike,
// mode or DFT bin.
int robust_lags(const std::string& cost, int residuals);

struct StageResult {
  std::string name;  // "direct", "stiffness and inertia", "damping", "all"
  std::vector<std::string> keys;
  OptimizerResult result;
};

// A record's part of a joint fit's result.
struct RecordResult {
  std::string name;
  model::BeamParameters beam;        // the estimate with the record's fixed parameters
  costs::Evaluation evaluation;      // of the record's own cost, unweighted, at the estimate
  std::vector<double> model_output;  // y at the estimate
  double weight = 1;                 // the factor on the record's residuals in the joint cost (above)
  // The record's own cost at a zero model (costs::Cost::zero_model_value: least-squares costs only, else NaN), so
  // that 1 - evaluation.value / zero_model_value is the fraction of the record the fit explains.
  double zero_model_value = std::numeric_limits<double>::quiet_NaN();
};

struct FitResult {
  std::vector<ParameterEstimate> parameters;
  model::BeamParameters beam;   // the estimate with the fixed parameters (record 1's in a joint fit)
  Eigen::MatrixXd correlation;  // of the estimates (empty when the covariance is unavailable)
  std::string covariance_status = "not computed";
  // "ok", or why the sandwich standard errors are NaN where the formal ones are not (optimizer.h: a residual of
  // leverage 1); the formal one's status when that is not "ok".
  std::string sandwich_status = "not computed";
  // "" when the cost is smooth at the estimate, else what says it is not (Covariance::rough_coordinate): the estimate's
  // key and how much its derivative changes between steps of 1e-6 and 1e-5 of it.
  std::string roughness;
  // "" when the cost is quadratic over one standard error of each parameter, else what says it is not
  // (Covariance::nonquadratic_coordinate): the key, the sum of squares' change there and its prediction.
  std::string nonquadratic;
  // Where each start ended (fit/start_minima.h), and "" or the nearest other minimum nearly as low as the estimate
  // yet far from it (other_minimum()): the cost has minima the data hardly tell apart.
  std::vector<StartEnd> start_ends;
  std::string other_minimum;
  // The errors-in-variables form: its cost's rise with the measured force negated and the fit redone from the
  // estimate (set by api::compute_fit, NaN otherwise): large when the force decides the fit, small when the free
  // transient terms do, negative when the channel's sign is wrong.
  double negated_force_rise = std::numeric_limits<double>::quiet_NaN();
  // The cost of the final stage, whose standard errors these are (a hybrid's refinement's).
  std::string final_cost;
  Identifiability identifiability;
  double cost = 0;
  long evaluations = 0;  // over all starts and stages
  double wall_time_s = 0;
  // Of the final stage of the best start: converged | max-evaluations | failed, with "-at-bound" appended to the first
  // two when any parameter ends on a bound (converged-at-bound is a constrained optimum, not an identification).
  std::string status = "failed";
  std::string termination;
  int best_start = 0;                  // 0: the given start
  std::vector<StageResult> stages;     // of the best start
  costs::Evaluation final_evaluation;  // at the estimate (spike table, (A4), amplitude scale); joint: stacked residuals
  std::vector<double> model_output;    // y at the estimate (record 1's in a joint fit)
  std::vector<RecordResult> records;   // one per record (a single-record fit has one)
};

// Everything about the options that can be checked without data (strategy, optimizer, starts, estimated keys and
// bounds, the start inside them, cost, experiment and simulator options): InputError naming option, value, constraint.
void validate(const FitOptions& options);

// Validates everything first (InputError naming the option, value and constraint), then fits.
FitResult fit(const FitOptions& options, const std::vector<double>& data);
// A joint fit of several records (at least one; above): options.start and options.experiment are replaced by each
// record's, and a shared parameter starts from record 1's value. One record gives exactly fit(options, data).
FitResult fit(const FitOptions& options, const std::vector<Record>& records);

// Two fits in a row, the second from the first's estimate (a hybrid's refinement, a refit with the noise estimated):
// the second's result with the stages of both, named with the prefixes, their evaluations and time, and the first's
// starts.
FitResult chained(const FitResult& first, FitResult second, const std::string& first_name,
                  const std::string& second_name);

}  // namespace beamid::fit
