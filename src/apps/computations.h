// What the commands compute, without their output: each compute_* validates the command's flags (with the command's
// own one-line messages), computes, and returns values. The command line (commands.h) writes them as CSV or JSON and
// says on stderr what ran; the Python package (python/) hands them over as NumPy arrays and dicts. One body for both,
// so a computation from Python and the same flags on the command line give the same numbers, bit for bit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "apps/command_flags.h"
#include "apps/flags.h"
#include "costs/cost.h"
#include "fit/cramer_rao.h"
#include "fit/identification.h"
#include "galerkin/second_order_system.h"
#include "io/time_series.h"
#include "signal/matrix_pencil.h"
#include "signal/spikes.h"
#include "simulation/simulator.h"

namespace beamid::apps {

// beamid modes: the first `count` modes (all underdamped Galerkin modes, or 4 exact ones, by default).
struct ModesResult {
  std::string kind;                   // "exact" | "undamped" | "damped"
  std::vector<double> frequency_hz;   // ascending
  std::vector<double> damping_ratio;  // empty for exact
  std::optional<int> requested;       // --count
  int available = 0;                  // modes the model has (Galerkin), before --count
  std::string note;                   // "" or what the command says on stderr: fewer modes than --count asked
};
ModesResult compute_modes(const Flags& a);

// beamid simulate: the trace (clean) and the samples as printed (with --noise-level's noise, if any).
struct SimulateResult {
  ModelRun run;
  simulation::Trace trace;
  std::vector<double> y;
};
SimulateResult compute_simulate(const Flags& a);

// beamid system: the Galerkin matrices and the response problem of the experiment.
struct SystemResult {
  ModelRun run;
  galerkin::SecondOrderSystem system;
  simulation::ResponseProblem problem;
};
SystemResult compute_system(const Flags& a);

// beamid spikes: every peak of the (detrended) record's spectrum with its label, and the picks (no label) by bin.
struct SpikesResult {
  signal::Spectrum spectrum;
  std::vector<signal::LabelledPeak> peaks;
  std::vector<signal::Spike> picks;
  int requested = 0;  // --spikes
};
SpikesResult compute_spikes(const Flags& a, const io::TimeSeries& data);

// beamid cost: the cost of a prediction (same length and step as the data) against the data.
costs::Evaluation compute_cost(const Flags& a, const io::TimeSeries& data, const io::TimeSeries& prediction);

// beamid fit: api/fit_request.h (api::FitRequest, api::compute_fit; the flags map to it by fit_request_of,
// apps/command_flags.h).

// beamid crb: the bound on the --estimate keys at the --beam values, with the noise sd it assumed.
struct CrbResult {
  ModelRun run;
  std::vector<std::string> keys;
  std::vector<double> values;
  double noise_sd = 0;
  fit::SensitivityOptions options;
  fit::CramerRaoBound bound;
};
CrbResult compute_crb(const Flags& a);

// beamid modal-id: the options the flags give and the modes found.
struct ModalIdResult {
  signal::PencilOptions options;
  std::vector<signal::IdentifiedMode> modes;
};
ModalIdResult compute_modal_id(const Flags& a, const io::TimeSeries& data);

}  // namespace beamid::apps
