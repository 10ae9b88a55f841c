// beamid fit as a typed request: the beam, the model, the estimated parameters and their bounds, the cost, the
// optimizer and strategy, and the record-side choices (detrend, Welch picking, windows), each field with the command
// line's default. compute_fit validates it against the records and fits them; it reads no flag and no file (the
// records come read, the beam comes resolved), so the command line, the Python package and a C++ program run one
// body of code with one validation.
//
// Followed from the command line: apps/identification_commands.cc fills a FitRequest from the flags
// (fit_request_of); compute_fit (here) builds fit::FitOptions (fit_options) and calls fit::fit
// (fit/identification.cc), which runs the optimizer (fit/optimizer.cc, fit/ceres_optimizer.cc, fit/nlopt_optimizer.cc).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "api/cost_request.h"
#include "api/experiment_request.h"
#include "api/request.h"
#include "fit/identification.h"
#include "fit/posterior.h"
#include "fit/profile.h"
#include "fit/window_spread.h"
#include "io/time_series.h"
#include "model/beam_parameters.h"

namespace beamid::api {

inline constexpr double kDefaultBoundFactor = 2.0;

struct FitRequest {
  Caller caller{"beamid fit"};
  std::string beam_name;              // what the program says it fitted ("banks-aluminium", "my_beam.toml")
  model::BeamParameters beam;         // --beam: the known parameters and the start of the estimated ones
  int elements = 0;                   // --elements: Galerkin order N (required)
  ExperimentRequest experiment;       // dt and samples, if given, must match the data's
  std::vector<std::string> estimate;  // --estimate: the keys to estimate (required)
  // --of-interest: the estimated keys the identifiability verdict is about (empty: the non-damping ones)
  std::vector<std::string> of_interest;
  std::map<std::string, std::pair<double, double>> bounds;  // --bounds KEY=LO:HI: explicit bounds of some keys
  // --bound-factor F: the others' bounds [v/F, v F] around the --beam value v (kDefaultBoundFactor when not given)
  std::optional<double> bound_factor;
  double start_scale = 1.0;               // --start-scale S: every estimated parameter starts at S x its --beam value
  CostRequest cost;                       // --cost (required) and the spectrum choices
  std::optional<std::string> optimizer;   // --optimizer (default: the cost's, fit::default_optimizer)
  std::optional<int> max_evaluations;     // --max-evaluations per optimizer run
  std::string strategy = fit::kDirect;    // --strategy
  std::optional<std::string> refine;      // --refine: hybrid's second cost (default time)
  std::string scaling = "linear";         // --scaling
  int starts = 1;                         // --starts
  std::optional<long long> seed;          // --seed (>= 0; default 1): the multistart's and crs2-lm's draws
  std::optional<std::string> integrator;  // --integrator (default fast)
  std::optional<std::string> record_weights;  // --record-weights (several channels; unset: fit::kRmsWeights)
  std::optional<std::string> detrend;         // --detrend (default linear for a free decay, none otherwise)
  std::optional<int> welch;                   // --welch K: the spikes picked on Welch's average of K segments
  std::optional<int> windows;                 // --windows K: also the spread of the estimates over K windows
  std::vector<std::string> profile;           // --profile: estimated keys whose profile-likelihood intervals to give
  // --posterior: sample the estimated parameters' posterior (fit/posterior.h), --posterior-steps per walker
  bool posterior = false;
  std::optional<int> posterior_steps;
  // --sensor-bandwidth, --sensor-filter-order, --sensor-oversampling: the record's anti-alias filter in the model
  // (fit/sensed_output.h; unset: none)
  std::optional<double> sensor_bandwidth_hz;
  std::optional<int> sensor_filter_order;
  std::optional<int> sensor_oversampling;
};

// What compute_fit returns: the options the request gave, the records (several for several channels, else none: one
// record, the channel itself), the result, and the window spread with `windows`.
struct FitComputation {
  fit::FitOptions options;
  std::vector<fit::Record> records;
  std::vector<double> sensors_m;  // each record's sensor position (several channels)
  fit::FitResult result;
  std::optional<fit::WindowSpread> spread;
  std::vector<fit::Profile> profiles;       // --profile's, in its order (fit/profile.h)
  std::optional<fit::Posterior> posterior;  // --posterior's
  bool welch_picked = false;  // the spikes were picked on Welch's average (options.cost.spikes.frequencies_hz)
};

// The fit options the request gives for these channels (their time step and length fix dt and Nbar), validated:
// InputError naming the field, value and constraint. Warnings (a long model evaluation) go to `warnings`.
fit::FitOptions fit_options(const FitRequest& request, const std::vector<io::TimeSeries>& channels,
                            std::ostream& warnings, bool* welch_picked = nullptr);
// Validates, then fits the channels (one record each, at its own sensor position, fitted jointly when several).
FitComputation compute_fit(const FitRequest& request, const std::vector<io::TimeSeries>& channels,
                           std::ostream& warnings);

// The estimated parameters with their bounds: `bounds` where given, else [v/F, v F] around the beam's value v
// (fit::bounds_around). InputError for a key the beam lacks, a zero or negative v without explicit bounds, or a
// bound for a key not estimated.
std::vector<fit::EstimatedParameter> estimated_parameters(const FitRequest& request);

// What beamid fit says about a result on stderr beside its summary line, each "" when there is nothing to say: the
// estimates on a bound, a failure, weak identifiability.
// The errors-in-variables form's transient note is not given when the force, negated and refitted, raises the
// likelihood-scaled cost by more than this (a likelihood ratio of exp(-12.5) = 4e-6): the force decides the fit.
inline constexpr double kForceDecides = 25;

struct FitNotes {
  std::string on_bound, failed, identifiability;
  std::string explains_nothing;  // a least-squares fit that explains under half of a record (fit_notes)
  std::string no_errors;         // no degrees of freedom: the standard errors are not defined
  std::string no_sandwich;      // the formal errors are defined but the sandwich ones are not (a residual's leverage 1)
  std::string pairing;          // (A4) fails at the estimate: data and model spikes or modes do not pair one to one
  std::string correlated_bins;  // a window correlates the DFT bins the standard errors take as independent
  std::string correlated_residuals;  // the time cost's residuals are not white: the standard errors understate
  std::string budget;                // the evaluation budget ran out: the estimate is where the optimizer stopped
  std::string rough;                 // the cost is not smooth at the estimate (FitResult::roughness)
  std::string other_minimum;         // another start ended nearly as low, far away (FitResult::other_minimum)
  std::string few_degrees;           // the residual variance rests on fewer than 10 degrees of freedom
  std::string
      weighting;  // a weighting whose formal standard errors do not hold (modal relative, spike not inverse-variance)
  std::string transient;  // errors in variables: the free transient, not the force, accounts for the response
  // The notes that are not empty, in the order the command prints them (identifiability last, after its summary).
  std::vector<std::string> lines() const;
};
// A least-squares fit (time or freq-band, of one record or several, or a hybrid's refinement) that explains less than
// half of a record's sum of squares in what its cost compares (or none of it) is said to: a fit of white noise, of
// another beam's record, or of a record in counts reported precise "free" estimates with exit 0.
// `cost` is the fit's cost (its name and window).
FitNotes fit_notes(const fit::FitResult& result, const costs::CostOptions& cost);
// "3 of 4 windows converged (window 2: max-evaluations); sd over them: EI 0.1 (formal ..., sandwich ...; the windows'
// own formal ...: within the windows' noise)", or why there is no spread: what --windows K says beside the table, on
// the command's stderr and in Python's messages (it was missing there: the twenty-fifth pass's adv59 P2).
std::string window_spread_line(const fit::WindowSpread& spread, const fit::FitResult& result);
// --profile's line (fit::Profile::line), with a caution where the notes doubt the standard errors' weighting of the
// residuals (weighting, colour, a window's correlated bins): the profile weighs them alike (its 95 % intervals covered
// the truth on 4-8 of 12 seeds there: the thirty-first pass's adv71 P5).
std::string profile_line(const fit::Profile& profile, const FitNotes& notes);
// --posterior's lines: one per parameter (fit::Posterior::line), then the chains' verdict and the evidences.
std::vector<std::string> posterior_lines(const fit::Posterior& posterior);

}  // namespace beamid::api
