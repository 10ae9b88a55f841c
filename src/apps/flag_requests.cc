#include "apps/flag_requests.h"

#include <cstdlib>
#include <map>
#include <sstream>

#include "apps/command_flags.h"
#include "core/errors.h"

namespace beamid::apps {

api::Caller caller_of(const Flags& a) { return {"beamid " + a.command()}; }

api::ExperimentRequest experiment_request_of(const Flags& a) {
  api::ExperimentRequest e;
  e.dt_s = a.optional_number("dt");
  e.samples = a.optional_integer("samples");
  e.sensor_x_m = a.numbers("sensor-x");  // fit: one position per --channel; the other commands: one
  if (a.has("output")) e.output = a.text("output");
  if (a.has("excitation")) e.excitation = a.text("excitation");
  e.force_x_m = a.optional_number("force-x");
  e.force_amplitude_N = a.optional_number("force-amplitude");
  e.pulse_width_s = a.optional_number("pulse-width");
  return e;
}

api::ModelRunRequest model_run_request_of(const Flags& a) {
  return {caller_of(a), a.text("beam"), read_beam(a), a.integer("elements"), experiment_request_of(a)};
}

api::SpikeRequest spike_request_of(const Flags& a) {
  api::SpikeRequest r;
  r.count = a.optional_integer("spikes");
  if (a.has("spike-rule")) r.rule = a.text("spike-rule");
  r.min_frequency_hz = a.optional_number("min-frequency");
  r.max_frequency_hz = a.optional_number("max-frequency");
  r.frequencies_hz = a.numbers("spike-frequencies");
  if (a.has("artefacts")) r.artefacts = a.text("artefacts");
  return r;
}

api::WindowRequest window_request_of(const Flags& a) {
  api::WindowRequest w;
  if (a.has("window")) w.name = a.text("window");
  w.exponential_end = a.optional_number("exponential-end");
  return w;
}

api::CostRequest cost_request_of(const Flags& a) {
  api::CostRequest r;
  r.name = a.text("cost");
  r.spikes = spike_request_of(a);
  r.window = window_request_of(a);
  r.eps1 = a.optional_number("eps1");
  r.eps2 = a.optional_number("eps2");
  r.eps3 = a.optional_number("eps3");
  r.unknown_amplitude = a.has("unknown-amplitude");
  if (a.has("model-poles")) r.model_poles = a.text("model-poles");
  if (a.has("mode-weight")) r.mode_weight = a.text("mode-weight");
  if (a.has("frequency-weight")) r.frequency_weight = a.text("frequency-weight");
  if (a.has("noise-model")) r.noise_model = a.text("noise-model");
  r.noise_sd = a.optional_number("noise-sd");
  r.force_noise_sd = a.optional_number("force-noise-sd");
  return r;
}

api::ModesRequest modes_request_of(const Flags& a) {
  api::ModesRequest r;
  r.caller = caller_of(a);
  r.beam = read_beam(a);
  r.elements = a.optional_integer("elements");
  r.exact = a.has("exact");
  r.undamped = a.has("undamped");
  r.count = a.optional_integer("count");
  return r;
}

api::SimulateRequest simulate_request_of(const Flags& a) {
  api::SimulateRequest r;
  r.run = model_run_request_of(a);
  r.integrator = a.text_or("integrator", r.integrator);
  r.rtol = a.optional_number("rtol");
  r.atol = a.optional_number("atol");
  r.max_order = a.optional_integer("max-order");
  r.noise_level = a.optional_number("noise-level");
  if (a.has("noise-model")) r.noise_model = a.text("noise-model");
  r.seed = a.optional_integer("seed");
  r.force_column = a.has("force-column");
  r.force_noise_level = a.optional_number("force-noise-level");
  return r;
}

api::SpikesRequest spikes_request_of(const Flags& a) {
  api::SpikesRequest r;
  r.caller = caller_of(a);
  r.spikes = spike_request_of(a);
  r.window = window_request_of(a);
  if (a.has("detrend")) r.detrend = a.text("detrend");
  r.welch = a.optional_integer("welch");
  return r;
}

api::CostEvaluationRequest cost_evaluation_request_of(const Flags& a) { return {caller_of(a), cost_request_of(a)}; }

namespace {

// --bounds KEY=LO:HI,...: the explicit bounds, by key.
std::map<std::string, std::pair<double, double>> bounds_of(const Flags& a) {
  std::map<std::string, std::pair<double, double>> bounds;
  if (!a.has("bounds")) return bounds;
  const std::string where = "beamid " + a.command() + ": ";
  const std::string text = a.text("bounds");
  // An empty item, at the end too (getline yields none after a trailing comma, which was accepted; --shards refuses
  // it).
  if (text.empty() || text.back() == ',')
    throw InputError(where + "--bounds = '" + text +
                     "': an empty item: must read KEY=LO:HI,... without a trailing comma");
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    const auto eq = item.find('='), colon = item.find(':');
    char* end1 = nullptr;
    char* end2 = nullptr;
    if (eq == std::string::npos || colon == std::string::npos || colon < eq)
      throw InputError(where + "--bounds item '" + item + "': must read KEY=LO:HI");
    const std::string lo = item.substr(eq + 1, colon - eq - 1), hi = item.substr(colon + 1);
    const double l = std::strtod(lo.c_str(), &end1), h = std::strtod(hi.c_str(), &end2);
    if (lo.empty() || hi.empty() || *end1 || *end2)
      throw InputError(where + "--bounds item '" + item + "': LO and HI must be numbers");
    // A key given twice was decided by its last item without a word.
    if (!bounds.emplace(item.substr(0, eq), std::pair{l, h}).second)
      throw InputError(where + "--bounds item '" + item + "': " + item.substr(0, eq) +
                       " is bounded twice; give each key once");
  }
  return bounds;
}

}  // namespace

api::FitRequest fit_request_of(const Flags& a, const std::optional<io::TimeSeries>& force) {
  api::FitRequest r;
  r.caller = caller_of(a);
  r.beam_name = a.text("beam");
  r.beam = read_beam(a);
  r.elements = a.integer("elements");
  r.experiment = experiment_request_of(a);
  if (force) {
    r.experiment.force_samples_N = force->values;
    r.experiment.force_channel = force->value_column;
  }
  r.estimate = a.texts("estimate");
  r.of_interest = a.texts("of-interest");
  r.profile = a.texts("profile");
  r.posterior = a.has("posterior");
  r.posterior_steps = a.optional_integer("posterior-steps");
  r.bounds = bounds_of(a);
  r.bound_factor = a.optional_number("bound-factor");
  r.start_scale = a.optional_number("start-scale").value_or(r.start_scale);
  r.cost = cost_request_of(a);
  if (a.has("optimizer")) r.optimizer = a.text("optimizer");
  r.max_evaluations = a.optional_integer("max-evaluations");
  r.strategy = a.text_or("strategy", r.strategy);
  if (a.has("refine")) r.refine = a.text("refine");
  r.scaling = a.text_or("scaling", r.scaling);
  r.starts = a.optional_integer("starts").value_or(r.starts);
  r.seed = a.optional_integer("seed");
  if (a.has("integrator")) r.integrator = a.text("integrator");
  if (a.has("record-weights")) r.record_weights = a.text("record-weights");
  if (a.has("detrend")) r.detrend = a.text("detrend");
  r.welch = a.optional_integer("welch");
  r.windows = a.optional_integer("windows");
  r.sensor_bandwidth_hz = a.optional_number("sensor-bandwidth");
  r.sensor_filter_order = a.optional_integer("sensor-filter-order");
  r.sensor_oversampling = a.optional_integer("sensor-oversampling");
  return r;
}

api::CrbRequest crb_request_of(const Flags& a) {
  api::CrbRequest r;
  r.run = model_run_request_of(a);
  r.estimate = a.texts("estimate");
  r.noise_sd = a.optional_number("noise-sd");
  r.noise_level = a.optional_number("noise-level");
  if (a.has("noise-model")) r.noise_model = a.text("noise-model");
  r.log_step = a.optional_number("log-step");
  return r;
}

api::DesignRequest design_request_of(const Flags& a) {
  api::DesignRequest r;
  // The shared experiment (output, force amplitude); the other experiment flags are the design's lists.
  r.run = {caller_of(a), a.text("beam"), read_beam(a), a.integer("elements"), {}};
  if (a.has("output")) r.run.experiment.output = a.text("output");
  if (a.has("excitation")) r.run.experiment.excitation = a.text("excitation");
  r.run.experiment.force_amplitude_N = a.optional_number("force-amplitude");
  r.estimate = a.texts("estimate");
  r.noise_sd = a.optional_number("noise-sd");
  r.noise_level = a.optional_number("noise-level");
  if (a.has("noise-model")) r.noise_model = a.text("noise-model");
  if (a.has("criterion")) r.criterion = a.text("criterion");
  r.sensors = a.optional_integer("sensors");
  r.sensor_x = a.texts("sensor-x");
  r.force_x = a.texts("force-x");
  r.pulse_width = a.texts("pulse-width");
  r.dt = a.texts("dt");
  r.samples = a.texts("samples");
  return r;
}

api::ModalIdRequest modal_id_request_of(const Flags& a) {
  api::ModalIdRequest r;
  r.caller = caller_of(a);
  r.modes = a.optional_integer("modes");
  r.order = a.optional_integer("order");
  r.min_frequency_hz = a.optional_number("min-frequency");
  r.max_frequency_hz = a.optional_number("max-frequency");
  return r;
}

}  // namespace beamid::apps
