// A study file (studies/*.toml), read strictly: one table per concern, every key known, every value admissible.
// An error names file:line, the key, the value and the violated constraint, e.g.
//   studies/paper.toml:14: fit.success_tolerance = -0.01: must be > 0
// and the whole study (every case) is validated before anything runs.
//
//   [study]      name, question, seed
//   [truth]      the beam and experiment the data come from, and how they are simulated (cvode, N_truth >= 48)
//   [fit]        what is estimated and how a fit is judged
//   [starts.X]   named starting points, as factors on the true values of the estimated parameters
//   [methods.X]  named fitting methods: strategy, optimizer, number of starts
//   [sweep]      the axes of the case grid (N, cost, noise, replicates, method, start, pulse width, record length)
//   [landscape]  optional: cost slices and grids through the truth, and multi-start basin statistics
//   [outputs]    which case is shown in the fit-overlay and spectrum plots
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/beam_parameters.h"
#include "signal/sensor_filter.h"
#include "simulation/experiment.h"

namespace beamid::study {

struct TruthSpec {
  std::string beam = "banks-aluminium";  // preset, or a beam TOML file (relative paths: to the study file)
  std::string beam_path;                 // resolved path of a beam file ("" for a preset)
  model::BeamParameters parameters;      // the beam itself, read once with the study file
  int elements = 48;                     // N_truth: finer than any fitted N (no inverse crime)
  bool control = false;                  // fitted N may equal N_truth (a control: the estimators alone)
  double rtol = 1e-10;                   // CVODE relative tolerance of the cross-check of the first truth record
  simulation::Experiment experiment;
  // The colour of every record's noise (signal/noise.h: white, ar:a1,..., power:alpha) at the sweep's levels (its
  // process sd over the clean RMS); the efficiency tables' bound is the bound in that noise (fit::coloured_bound).
  std::string noise_model = "white";
  // excitation "force": the sin^2 pulse as a force channel records it (simulation::sampled_pulse), which drives the
  // truth and every fit (linear between samples). force_noise: white noise on that channel, sd over the force's RMS
  // over the record, on every noisy record (seeded from its noise seed); the fits are driven by the noisy force, as
  // a measured one drives them.
  double force_noise = 0;
  // A damping law no fitted model has (issue 35): constant modal damping of this ratio added to every mode of the
  // truth (galerkin::with_modal_damping: a hysteresis-like loss, where Kelvin-Voigt damping grows with frequency and
  // air damping falls). 0: none.
  double modal_damping_ratio = 0;
  // A sensor with a finite bandwidth (issue 35): the truth's output through an order-n Butterworth anti-alias filter
  // of this cut-off before sampling (signal/sensor_filter.h: the truth simulated 16 times finer, filtered, every 16th
  // sample kept). Cut-off 0: an ideal sensor.
  signal::SensorFilter sensor;
};

struct FitSpec {
  std::vector<std::string> estimate;   // beam keys
  int spikes = 3;                      // NM for the spike costs; 0: "auto", every mode the data show (see cases.h)
  int max_spikes = 6;                  // cap for "auto"
  std::string spike_rule = "largest";  // "largest" (the paper's) | "prominence"
  double min_frequency_hz = 0;         // spikes are sought in [min, max] Hz
  double max_frequency_hz = 0;         // 0: up to the Nyquist frequency
  std::string window = "rectangular";
  // Spike costs' weighting of frequency errors across spikes (costs/cost.h): the paper's absolute Hz by default, as
  // the synthetic studies reproduce its (3.5) as written.
  std::string frequency_weight = "absolute";
  double bound_factor = 2;          // bounds [v/F, v F] around the true value v
  std::string scaling = "linear";   // "linear" | "log"
  int max_evaluations = 3000;       // per stage and start
  double xtol_rel = 1e-10;          // stop when a step changes every parameter by less than this, relatively
  double success_tolerance = 0.01;  // a fit succeeds when every estimate is within this relative error,
  double damping_tolerance = 0.01;  // or this one for damping parameters (default: success_tolerance)
};

struct StartSpec {
  std::string name;
  std::map<std::string, double> factor;  // start = factor * truth, for every estimated key
};

struct MethodSpec {
  std::string name;
  std::string strategy = "direct";    // "direct" | "staged" | "continuation"
  std::string optimizer = "default";  // "default" (lm, or nelder-mead for spike) or an optimizer name
  int starts = 1;                     // > 1: the start plus Latin-hypercube starts in the bounds
  std::string refine = "time";        // "hybrid": the least-squares cost that refines the global fit (time | freq-band)
  // Overrides of [fit] for this method's fits (issue 15 item 6: windows and weights compared on the same records):
  // the DFT window, the spike costs' weighting of frequency errors across spikes, and factors on the (3.5) weights
  // eps1 (frequencies) and eps2 (magnitudes), given or default (costs/cost.h).
  std::string window;            // "": fit.window
  std::string frequency_weight;  // "": fit.frequency_weight
  double eps1_factor = 1;
  double eps2_factor = 1;
  // The noise the time and freq-ml costs assume (costs/cost.h): "" white; "truth" the records' own ([truth]
  // noise_model, known to the estimator: the maximum-likelihood and generalised least-squares fits); "estimated" from
  // each fit's own white-noise residuals (fit/identification.cc); or a model.
  std::string noise_model;
  // freq-ml's errors-in-variables form with the records' true noise levels (the response's sd, the force channel's
  // sd): each bin over its response noise plus the force's through the model (costs/least_squares.h).
  bool errors_in_variables = false;
  // The truth's sensor filter ([truth] sensor_bandwidth_hz) in the fitted model (fit/sensed_output.h): a method that
  // knows the measurement chain, as least squares on a record from a known anti-alias filter is run.
  bool sensor_in_model = false;
};

struct SweepSpec {
  std::vector<int> elements;
  std::vector<std::string> cost;
  std::vector<double> noise;  // noise standard deviation / clean RMS
  int replicates = 1;         // per noise level > 0 (a noise-free case is run once)
  std::vector<std::string> method;
  std::vector<std::string> start;
  std::vector<double> pulse_width_s;  // default: [truth.pulse_width_s]
  std::vector<int> samples;           // record lengths Nbar; default: [truth.samples]
};

struct LandscapeSpec {
  bool enabled = false;
  // Fitted orders and noise levels of the slices (a noisy record is the sweep's replicate-0 draw at that level, the
  // one its cases see); the first of each is the tables' (wide grids, multi-starts, the slice plots).
  std::vector<int> elements = {16};
  std::vector<double> noise = {0.0};
  std::vector<std::string> cost;
  double range_factor = 2;                                 // slices and grids span [v/F, v F] (log-spaced)
  int points = 121;                                        // per slice
  std::vector<std::pair<std::string, std::string>> pairs;  // 2-D grids
  int grid_points = 41;                                    // per grid axis
  // Fine grids over [v/Z, v Z] of every pair, for every N and noise level (Z <= 1: none): where the wide grids are too
  // coarse to resolve the least-squares basin, these resolve it (the tables state each grid's step).
  double zoom_range_factor = 0;
  int zoom_points = 61;
  int multistarts = 12;  // local fits from random starts in the bounds, per cost
};

// Start-distance curves (comparison.md section 1): how far from the truth each cost and strategy may be started and
// still reach the minimum it reaches from the truth. For every run (a cost with a method), every offset r and every
// direction d: a fit from  log q = log q_true + s u_d,  u_d a random unit vector in the log space of the estimated
// parameters (the same directions for every run and offset), s such that the fitted modes' frequencies move by r at
// most (to first order: s = log(1 + r) / max_k |d log f_k / d log q . u_d|, k over the fitted modes), and s shrunk to
// stay inside the bounds when the direction barely moves a frequency. A fit "reaches" the minimum when every estimate
// is within `agreement` (damping parameters: `damping_agreement`) of the run's own fit from the truth on the same
// record: this measures the basin alone, apart from the bias that the model error and the noise put into the minimum.
struct StartDistanceSpec {
  bool enabled = false;
  int elements = 16;
  std::vector<double> offsets;                            // r, relative frequency offsets (0.0015 = 0.15 %)
  int directions = 30;                                    // per offset
  std::vector<std::pair<std::string, std::string>> runs;  // (cost, method name)
  double noise = 0;                                       // the records' noise level
  // Independent noise records per experiment (issue 35: records are the replication unit). Record r is the sweep's
  // replicate-r draw at `noise`; each has its own fit from the truth (its reference minimum) and its own directions
  // (`directions` per offset), so that a radius's interval is a bootstrap across records, not across directions of
  // one record. 1: one record for every fit (the directions' seeds then name the direction alone).
  int records = 1;
  double agreement = 1e-3;
  double damping_agreement = 1e-2;
  // false: the first experiment only (truth pulse width and record length); true: every experiment of the sweep
  // (pulse widths x record lengths), so that the radius can be set against the number of modes in the data.
  bool every_experiment = false;
};

struct OutputsSpec {
  int overlay_elements = 0;  // 0: the largest N of the sweep
  double overlay_noise = 0;  // noise level of the overlay case (must be in the sweep)
  // Efficiency tables: the Cramér-Rao bound (fit/cramer_rao.h) of the model at each fitted N, at the truth, for the
  // noise of each noisy level of the sweep (level x RMS of the clean record), beside the fits' RMSE.
  bool efficiency = false;
  // Bias decomposition tables: per group of noisy replicates, the noise-free fit's error (the bias of the minimum:
  // discretisation, or with [truth] control the estimator's own) beside the replicates' mean and their difference,
  // the noise-induced bias, each with its Monte-Carlo standard error. Needs noise 0 in the sweep.
  bool bias_decomposition = false;
};

struct StudySpec {
  std::string path;  // as given
  std::string name;
  std::string question;
  std::uint64_t seed = 1;
  TruthSpec truth;
  FitSpec fit;
  std::vector<StartSpec> starts;  // in file order
  std::vector<MethodSpec> methods;
  SweepSpec sweep;
  LandscapeSpec landscape;
  StartDistanceSpec start_distance;
  OutputsSpec outputs;
  std::string file_hash;  // FNV-1a 64 of the file's bytes, hex

  const StartSpec& start(const std::string& name) const;
  const MethodSpec& method(const std::string& name) const;
};

// Reads and validates a study file (InputError naming file:line, key, value and constraint).
StudySpec load_study(const std::string& path);
// Same, from text; `source_name` stands for the file in messages and `directory` resolves relative beam files.
StudySpec parse_study(const std::string& text, const std::string& source_name, const std::string& directory);

}  // namespace beamid::study
