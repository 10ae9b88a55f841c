// The requests that compute from a beam model alone (no record): beamid modes, simulate, system and crb. Each holds
// the beam as parameters (resolved from a preset, a file or a dict by the front end), the Galerkin order and, where
// the computation has one, the experiment; each compute function validates it (errors in the command line's
// one-line form) and returns values.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "api/experiment_request.h"
#include "api/request.h"
#include "fit/cramer_rao.h"
#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "simulation/experiment.h"
#include "simulation/simulator.h"

namespace beamid::api {

// A model run as a request describes it: the beam, N and the experiment (beamid system's whole request).
struct ModelRunRequest {
  Caller caller{"beamid system"};
  std::string beam_name;         // what the program says it ran
  model::BeamParameters beam;    // --beam
  int elements = 0;              // --elements N (required)
  ExperimentRequest experiment;  // --dt, --samples, ...
  // A run request whose errors start with `label` (the default of the requests that hold one).
  static ModelRunRequest labelled(std::string label) {
    ModelRunRequest r;
    r.caller.label = std::move(label);
    return r;
  }
};
struct ModelRun {
  std::string beam_name;
  model::BeamParameters beam;
  int elements = 0;
  simulation::Experiment experiment;
};
// The run, validated, with its size guarded (guard_run_size with `bytes_per_sample`; 0 for a run that simulates no
// samples).
ModelRun model_run(const ModelRunRequest& request, double bytes_per_sample, std::ostream& warnings);

// beamid modes: the first `count` modes (all underdamped Galerkin modes, or 4 exact ones, by default).
struct ModesRequest {
  Caller caller{"beamid modes"};
  model::BeamParameters beam;   // --beam
  std::optional<int> elements;  // --elements N: the Galerkin model's modes
  bool exact = false;           // --exact: the exact (determinant) frequencies instead; one of the two
  bool undamped = false;        // --undamped: the Galerkin model's undamped modes
  std::optional<int> count;     // --count
};
struct ModesResult {
  std::string kind;                   // "exact" | "undamped" | "damped"
  std::vector<double> frequency_hz;   // ascending
  std::vector<double> damping_ratio;  // empty for exact
  std::optional<int> requested;       // count
  int available = 0;                  // modes the model has (Galerkin), before count
  std::string note;                   // "" or what the command says on stderr: fewer modes than count asked
};
ModesResult compute_modes(const ModesRequest& request, std::ostream& warnings);

// beamid simulate: the trace (clean) and the samples with noise_level's noise, if any.
struct SimulateRequest {
  ModelRunRequest run = ModelRunRequest::labelled("beamid simulate");
  std::string integrator = "fast";         // --integrator
  std::optional<double> rtol;              // --rtol (cvode)
  std::optional<double> atol;              // --atol (cvode)
  std::optional<int> max_order;            // --max-order (cvode)
  std::optional<double> noise_level;       // --noise-level: white noise of this times the clean signal's RMS (none: 0)
  std::optional<std::string> noise_model;  // --noise-model (signal/noise.h; needs noise_level; default white)
  std::optional<long long> seed;           // --seed of the noise (needs noise_level; default 1)
  // --force-column: also the force at each sample (a pulse's F0 sin^2, as a hammer's force channel records it), with
  // --force-noise-level white noise of this times the force's RMS on it (an independent stream of the same seed).
  bool force_column = false;
  std::optional<double> force_noise_level;
};
struct SimulateResult {
  ModelRun run;
  simulation::Trace trace;
  std::vector<double> y;
  std::vector<double> force_N;  // with force_column
};
SimulateResult compute_simulate(const SimulateRequest& request, std::ostream& warnings);

// beamid system: the Galerkin matrices and the response problem of the experiment.
struct SystemResult {
  ModelRun run;
  galerkin::SecondOrderSystem system;
  simulation::ResponseProblem problem;
};
SystemResult compute_system(const ModelRunRequest& request, std::ostream& warnings);

// beamid crb: the Cramér-Rao bound on `estimate` at the beam's values, with white noise of noise_sd (absolute) or
// noise_level (times the clean signal's RMS): one of the two.
struct CrbRequest {
  ModelRunRequest run = ModelRunRequest::labelled("beamid crb");
  std::vector<std::string> estimate;       // --estimate (required)
  std::optional<double> noise_sd;          // --noise-sd
  std::optional<double> noise_level;       // --noise-level
  std::optional<double> log_step;          // --log-step of the sensitivities' Ridders extrapolation
  std::optional<std::string> noise_model;  // --noise-model: the noise's colour (signal/noise.h; default white)
};
struct CrbResult {
  ModelRun run;
  std::vector<std::string> keys;
  std::vector<double> values;
  double noise_sd = 0;
  fit::SensitivityOptions options;
  fit::CramerRaoBound bound;
};
CrbResult compute_crb(const CrbRequest& request, std::ostream& warnings);

}  // namespace beamid::api
