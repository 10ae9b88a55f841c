// A real-data study (studies/real-*.toml): measured free-decay records fitted with each cost, and with each
// candidate model, reported against the records' own spectral peaks. There is no truth: what is compared is the
// model at the estimate with the measurement (identified against measured peak frequencies, damping ratios per mode,
// the identified parameters against their nominal values, their three uncertainties, and what each candidate model
// leaves undetermined).
//
//   [study]        name, question
//   [record]       file (relative to the study file), channel, units, start_s, duration_s, resample,
//                  peaks_hz: the measured peak frequencies of the modes the model has (the spikes are chosen near
//                  them, and data and model are paired by frequency, so torsion modes and mains lines are left out),
//                  name, beam (a beam file of this record's own: its length, attachments; default [beam].file),
//                  sample_rate_hz, variable, time_variable, time_channel, resample_rate_hz (.npy, .mat, UFF:
//                  io/time_series.h).
//                  [[record]] instead: several records fitted jointly (fit/identification.h), e.g. one strip at
//                  several lengths, sharing the parameters in fit.estimate.
//   [beam]         file: a beam TOML ([beam] or [geometry]) giving the nominal values and the starts
//   [fit]          elements, estimate (shared by every record), per_record (estimated for each record: recordK.KEY),
//                  costs, bounds (a table KEY = [lo, hi]; default [v/2, 2v] around each record's nominal v),
//                  max_evaluations, frequency_weight (the spike costs'), mode_weight (the modal cost's; default
//                  measured: each mode over its measured uncertainty, costs/modal_cost.h), windows (K >= 2: also the
//                  spread over K disjoint windows, fit/window_spread.h; 0: not done), starts (the nominal start
//                  and starts - 1 space-filling ones over the bounds, the lowest cost kept; default 1), seed (of
//                  those starts), start_from (the first of costs: the route from nominal starts, fit/identification.h:
//                  that cost fitted from the starts, every later cost from its estimate, so "modal" with starts and
//                  then "spike-smooth" globalises with the cheap modal cost and refines with the spike cost),
//                  fixed (a table "record name" = [keys]: per_record keys that record keeps at its nominal value,
//                  a record left out of one parameter)
//   [[candidate]]  optional alternative models, each fitted with every cost: name, and any of beam (file, replacing
//                  every record's), values (a table KEY = nominal value, e.g. "support.k_theta" = 6000 makes the
//                  clamp compliant), estimate, per_record, bounds (over [fit]'s), records (the names of the records
//                  it fits; default all), fixed (as in [fit]). Without candidates, [fit] is the one model ("as
//                  given"). A position's default bounds end at the beam's length.
//
// Writes to results/<name>/: fits.csv (candidate, cost, parameter, estimate, three standard errors, nominal, ratio),
// modes.csv (candidate, cost, record, mode, measured and identified frequency, damping ratio), candidates.csv (fit
// quality and identifiability per candidate and cost), overlay.csv, spectrum.csv, spikes.csv (the first candidate
// and record), manifest.json, provenance.csv, report.md (the REPORT.md block) and timings.csv.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "fit/identification.h"
#include "io/time_series.h"
#include "model/beam_parameters.h"
#include "study/tables/overlay.h"
#include "study/tables/rendered.h"

namespace beamid::study {

struct RealRecordSpec {
  std::string name;  // given, or "record1", "record2", ...
  std::string file, channel, units = "auto";
  std::optional<double> start_s, duration_s;
  bool resample = false;
  std::vector<double> peaks_hz;
  std::string beam_file;  // empty: the study's [beam] file
  // The formats without a time base, and a rate (io/time_series.h): .npy and .mat arrays need sample_rate_hz (or a
  // .mat time_variable, or an array's time_channel); variable names a .mat file's record; resample_rate_hz resamples
  // any record.
  std::optional<double> sample_rate_hz, resample_rate_hz;
  std::string variable, time_variable, time_channel;
  // "file:line" of each key given, and "" -> of the [[record]] table: errors found when the record is read name them.
  std::map<std::string, std::string> where;
};

struct CandidateSpec {
  std::string name = "as given";
  std::string beam_file;                               // empty: each record's
  std::vector<std::pair<std::string, double>> values;  // nominal values set on every record's beam
  std::vector<std::string> estimate, per_record;       // shared keys; keys estimated for each record
  std::vector<int> records;                            // indices of the records it fits (all by default)
  std::map<std::string, std::pair<double, double>> bounds;
  // The study's record index -> per_record keys it keeps at its nominal value instead of estimating (`fixed`).
  std::map<int, std::vector<std::string>> fixed;
};

struct RealStudySpec {
  std::string path, name, question, file_hash;
  std::vector<RealRecordSpec> records;  // at least one
  std::string beam_file;
  int elements = 16;
  std::vector<CandidateSpec> candidates;  // at least one
  std::vector<std::string> costs;
  int max_evaluations = 3000;
  std::string frequency_weight = "relative";  // spike costs (costs/cost.h): a measured record's default
  // The modal cost's (costs/cost.h): by default each mode over its measured uncertainty, the maximum-likelihood
  // weighting that the study's verdict (a model frequency within 2 u) also judges by.
  std::string mode_weight = "measured";
  int windows = 0;         // 0: no window spread
  int starts = 1;          // per fit (of start_from's cost alone when given)
  std::uint64_t seed = 1;  // of the space-filling starts
  std::string start_from;  // "": every cost from the nominal start; else the first cost, the others from its estimate
};

// Strict reading, as for synthetic studies (InputError naming file:line, key, value and constraint).
RealStudySpec load_real_study(const std::string& path);

// One candidate's fit of the records with one cost (a failed fit has its status and nothing else).
struct RealFit {
  std::string candidate, cost, status;
  double cost_value = std::numeric_limits<double>::infinity();
  long evaluations = 0;
  double wall_time_s = 0;
  std::vector<fit::ParameterEstimate> parameters;
  std::vector<double> window_sd;  // per parameter (empty without windows; NaN where too few windows converged)
  int windows_used = 0;
  fit::Identifiability identifiability;
  std::vector<int> records;                              // the study's records it fitted (indices)
  std::vector<std::vector<double>> identified_hz, zeta;  // [its record][mode]: the model's modes nearest each peak
  // [its record][mode]: the identified frequency's discretisation error, estimated as its change when the elements
  // are doubled (|f_2N - f_N|: the Galerkin error falls as N^-4 for cubic splines, so this is f_N's error to 6 %).
  // A model that is right but discretised is wrong by this much, which the verdict allows for beside u.
  std::vector<std::vector<double>> discretisation_hz;
  std::optional<Overlay> overlay;  // of the first record
  // RMS and largest |f_identified / f_measured - 1| over every record's modes (NaN for a failed fit), and the largest
  // |f_identified - f_measured| / sqrt(u^2 + d^2) in units of each measured frequency's uncertainty u and the
  // identified one's discretisation error d: a fit fits a record when that is at most 2 on each of its modes.
  // (A4) in words when two measured modes of a record pair with one model mode ("" when each has its own): a fit
  // that leaves a measured mode without a partner does not fit the record, whatever its misfits (the ninth pass's
  // RU: 14.32 and 24.79 Hz both paired with 16.73 Hz, said nowhere).
  std::string shared_mode;
  int shared_record = -1;  // the study's record it happened in
  double rms_misfit = std::numeric_limits<double>::quiet_NaN(), worst_misfit = rms_misfit,
         worst_in_uncertainty = rms_misfit;
};

struct RealRecordData {
  io::TimeSeries series;
  model::BeamParameters nominal;  // the record's beam file
  // The record's modes near peaks_hz by the measured-frequency estimator (signal/measured_modes.h), which modal-id,
  // spikes and fit share: frequency, damping ratio, uncertainty u, and what widens u when notable.
  std::vector<double> measured_hz, measured_zeta, measured_uncertainty_hz;
  std::vector<std::string> measured_notes;
};

struct RealResults {
  std::vector<RealRecordData> records;
  std::vector<RealFit> fits;  // candidate-major, in the order of the candidates and of fit.costs
};

// Imports the records and fits them with each candidate and cost (real_execute.cc); progress on `log`.
RealResults compute_real_study(const RealStudySpec& spec, std::ostream& log);
// Every table of the study (real_tables.cc), from its results alone.
RenderedFiles render_real_study(const RealStudySpec& spec, const RealResults& results);
// Computes, renders and writes the tables to `output_dir`. Returns the number of failed fits.
int run_real_study(const RealStudySpec& spec, const std::string& output_dir, std::ostream& log);

}  // namespace beamid::study
