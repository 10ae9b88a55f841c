// Start-distance curves (study_spec.h, StartDistanceSpec): the starts at a prescribed frequency offset, and the
// metrics of the curves (share of starts that reach the minimum, against the offset, and the offset at which that
// share falls through one half), as pure functions. Theory (comparison.md section 1): least squares on a record of
// length T has a basin of about 1/(2 f T) in relative frequency for its highest fitted mode f, the offset at which
// that mode's phase is off by half a cycle at the end of the record.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "study/analysis/results.h"
#include "study/analysis/statistics.h"

namespace beamid::study {

// A unit vector of `dimension` components, uniform on the sphere (normalised standard normal deviates of `seed`).
Eigen::VectorXd random_direction(std::uint64_t seed, int dimension);

struct OffsetStart {
  model::BeamParameters start;
  double step = 0;              // s: log q = log q_true + s u
  bool shrunk = false;          // s was reduced to keep every parameter within 0.9 of the log bound range
  double frequency_offset = 0;  // max_k |f_k(start) / f_k(truth) - 1| over the fitted modes, exact
};
// The start at frequency offset r in direction u (study_spec.h): s = log(1 + r) / max_k |g_k . u|, g = the
// sensitivities above, then shrunk to max_i |s u_i| <= 0.9 log(bound_factor) when it would leave the bounds.
OffsetStart offset_start(const galerkin::BeamForms& forms, const model::BeamParameters& truth,
                         const std::vector<std::string>& keys, int modes, const Eigen::VectorXd& direction,
                         double offset, double bound_factor);

// The offset at which a success curve falls through 1/2: rates[j] at offsets[j] (increasing, > 0). Interpolated
// linearly in log offset between the last offset of the leading run of rates >= 1/2 and the next one. `below` when
// the first rate is already < 1/2, `above` when no rate falls below 1/2 (value is then that end of the range).
struct HalfRadius {
  double value = 0;
  bool below = false, above = false;
};
HalfRadius half_radius(const std::vector<double>& offsets, const std::vector<double>& rates);
// "0.31 %", "< 0.05 %" or "> 20 %".
std::string radius_text(const HalfRadius& r);

// One start's outcome in a run over several records: which record, direction and offset, and whether it reached
// its record's reference minimum.
struct ReachOutcome {
  int record = 0, direction = 0;
  double offset = 0;
  bool reached = false;
};
// The 50 % radius of a fitted reach curve (issue 35): the logistic P(reach) = 1 / (1 + exp(-(a + b ln r))) fitted to
// the outcomes by Firth's penalised likelihood (statistics.h), r50 = exp(-a / b). `below` or `above` (value: that end
// of offsets, the range tried) when r50 lies outside the offsets or the curve does not fall (b >= 0: then by the
// share reached). Where the fit fails, the pooled rates' half_radius.
HalfRadius reach_radius(const std::vector<double>& offsets, const std::vector<ReachOutcome>& outcomes);
// Its 95 % interval across records: `resamples` bootstrap resamples of the records (with replacement, each
// record's outcomes kept together), r50 refitted on each, the 2.5 % and 97.5 % quantiles of ln r50 (a censored
// resample at its end of the range). {low, high}.
std::pair<HalfRadius, HalfRadius> reach_radius_interval(const std::vector<double>& offsets,
                                                        const std::vector<ReachOutcome>& outcomes, int records,
                                                        std::uint64_t seed, int resamples);

// A run's fits from the truth over its records, for one parameter (issue 35: over every fit of the cell, none
// selected by where it ended): relative errors (estimate - truth) / truth, the mean's Monte-Carlo standard error
// sd / sqrt(fits), and the Cramér-Rao bound of the fitted model for the records' noise (NaN without a bound unit
// for the experiment at start_distance.elements and .noise).
struct ReferenceErrors {
  std::string parameter;
  Stats errors;
  double mcse = std::nan(""), bound = std::nan("");
  double efficiency() const { return errors.rmse / bound; }  // RMSE / bound
};

// A run's fits from the truth, for one mode of the data (issue 35: damping judged per mode, since under a damping law
// the model lacks cDI and gamma have no true value): the fitted model's k-th damped mode against the truth's k-th
// (natural frequency and damping ratio, the truth's as its beam has them, before any sensor), as relative errors
// over the records with their Monte-Carlo standard errors.
struct ModeErrors {
  int mode = 0;  // 1-based
  double truth_frequency_hz = std::nan(""), truth_damping_ratio = std::nan("");
  Stats frequency, damping;  // relative errors f_fit / f_truth - 1 and zeta_fit / zeta_truth - 1
  double frequency_mcse = std::nan(""), damping_mcse = std::nan("");
};

// The curves of a finished study.
struct StartCurvePoint {
  double offset = 0;
  int reached = 0, fits = 0, shrunk = 0;  // fits: directions whose outcome is known (the reference fit ok)
  double median_evaluations = 0;
  double rate() const { return fits > 0 ? static_cast<double>(reached) / fits : std::nan(""); }
};
struct StartRun {
  std::string cost, method;
  // The experiment (study_spec.h: start_distance.experiments): its truth, record length and modes, and its own
  // predicted basins (as StartDistanceMetrics's below, which are the first experiment's).
  int experiment = 0;  // 0-based, in plan order (pulse widths, then record lengths)
  int truth = 0, samples = 0;
  double pulse_width_s = 0, record_s = 0;
  int modes_in_data = 0, fitted_modes = 0;
  double predicted_basin = std::nan(""), predicted_basin_decay = std::nan("");
  double predicted_basin_highest_decay = std::nan("");
  int limiting_mode = 0;
  const LandscapeRow* reference = nullptr;  // the fit from the truth on record 0 (nullptr when missing)
  bool reference_ok = false;                // some record's fit from the truth did not fail
  // start_distance.records: each record's fit from the truth is its own reference; a record whose reference failed
  // or is missing is left out of the curve (counted here).
  int records = 1, references_failed = 0;
  std::vector<const LandscapeRow*> references;    // by record
  std::vector<ReachOutcome> outcomes;             // every start of the counted records
  std::vector<StartCurvePoint> points;            // by offset, pooled over records
  std::vector<ReferenceErrors> reference_errors;  // per estimated parameter, over the counted records
  std::vector<ModeErrors> mode_errors;            // per mode of the data (fitted_modes), over the counted records
  // Every fit of the run (from the truth and the offsets) and those whose evaluation budget ran out (status
  // "max-evaluations": where a derivative-free search's budget binds, the tables count it).
  int fits_run = 0, budget_exhausted = 0;
  // One record: from the rates, their Wilson lower and upper bounds. Several: the fitted reach curve and its
  // bootstrap interval across records (reach_radius).
  HalfRadius radius, radius_low, radius_high;
};
// Two runs of one experiment compared on the same starts (issue 35: paired, as they share records, directions and
// offsets): the starts both runs counted, split by outcome, and the exact McNemar p-value of the discordant ones.
struct StartPair {
  int experiment = 0;
  std::size_t first = 0, second = 0;  // indices into StartDistanceMetrics::runs
  int matched = 0, both = 0, first_only = 0, second_only = 0, neither = 0;
  double p_value = 1;
};
// The reference errors of a run whose references, truth and samples are set (start_distance_metrics fills them).
std::vector<ReferenceErrors> reference_errors(const StudyResults& results, const StartRun& run);

// The same run's mode errors for its first `modes` modes (empty when the truth's modes or the fits' are not recorded).
std::vector<ModeErrors> mode_errors(const StudyResults& results, const StartRun& run, int modes);

// Every pair of runs within each experiment, in run order.
std::vector<StartPair> paired_comparisons(const std::vector<StartRun>& runs);

struct StartDistanceMetrics {  // predictions NaN when unknown (the tables print "-" for them)
  int fitted_modes = 0;
  double highest_mode_hz = std::nan("");  // the truth's mode `fitted_modes`
  double record_s = 0;
  double predicted_basin = std::nan("");  // 1 / (2 f T)
  // The same with each mode's own duration: a mode of decay rate sigma is visible for about 1/sigma, so its phase
  // error accumulates only over T_eff = min(T, 1/sigma), and the basin is that of the most restrictive fitted mode,
  // min_k 1 / (2 f_k T_eff,k) (the highest mode when the modes decay slowly, as on the thin beam; a lower, longer-lived
  // one when the highest decays fast, as on the thick beam).
  // Neither is the measured radius: the cost sums the modes' terms weighted by their energy, so the radius lies
  // between the most restrictive term's basin and the dominant mode's; the highest mode's 1/(2 f T_eff) is kept
  // beside it (radius.csv).
  int limiting_mode = 0;                   // 1-based: the k of the minimum
  double limiting_mode_hz = std::nan("");  // its f_k
  double decay_rate_1_s = std::nan("");    // its sigma_k
  double predicted_basin_decay = std::nan("");
  double predicted_basin_highest_decay = std::nan("");  // 1 / (2 f T_eff) of mode `fitted_modes`
  int experiments = 1;
  std::vector<StartRun> runs;  // experiment-major, then in the order of start_distance.runs
  std::vector<StartPair> pairs;
  std::vector<bool> reached;  // per results.starts row
};
// Fills the predictions above (highest_mode_hz, record_s, predicted_basin, limiting_mode ...
// predicted_basin_highest_decay) for the first m.fitted_modes modes of natural frequencies f (Hz) and damping ratios
// zeta, on a record of record_s.
void predict_basins(const std::vector<double>& f, const std::vector<double>& zeta, double record_s,
                    StartDistanceMetrics& m);
// The same for truth record `truth` of a finished study (its modes' frequencies and damping ratios) on a record of
// `samples` samples, for m.fitted_modes modes; false, and m's predictions left unknown, when the truth's modes are not
// recorded.
bool predict_basins(const StudyResults& results, int truth, int samples, StartDistanceMetrics& m);
// Whether `fit` reached the minimum of `reference`: not failed, and every estimate within start_distance.agreement
// (damping parameters: damping_agreement) of the reference's, relatively.
bool reaches(const StudySpec& spec, const Record& reference, const Record& fit);
StartDistanceMetrics start_distance_metrics(const StudyResults& results);

}  // namespace beamid::study
