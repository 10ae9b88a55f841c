#include "api/cost_request.h"

#include <algorithm>
#include <string_view>
#include <utility>

#include "core/errors.h"

namespace beamid::api {

signal::SpikeOptions spike_options(const SpikeRequest& request, const Caller& caller) {
  signal::SpikeOptions o;
  o.count = request.count.value_or(o.count);
  o.rule = request.rule.value_or(o.rule);
  o.min_frequency_hz = request.min_frequency_hz.value_or(o.min_frequency_hz);
  if (request.artefacts != "reject" && request.artefacts != "keep")
    refuse(caller, "artefacts", request.artefacts, "must be one of reject, keep");
  o.reject_artefacts = request.artefacts == "reject";
  o.max_frequency_hz = request.max_frequency_hz.value_or(o.max_frequency_hz);
  if (!request.frequencies_hz.empty()) {
    o.frequencies_hz = request.frequencies_hz;
    std::string listed;  // the list as given, for its error
    for (const double f : request.frequencies_hz) listed += (listed.empty() ? "" : ",") + format_value(f);
    for (const double f : o.frequencies_hz)
      if (!(f > 0))
        refuse(caller, "spike-frequencies", listed, "must be a comma-separated list of frequencies > 0 in Hz");
    std::sort(o.frequencies_hz.begin(), o.frequencies_hz.end());
    if (request.count && *request.count != static_cast<int>(o.frequencies_hz.size()))
      refuse(caller, "spikes", std::to_string(*request.count),
             "must equal the number of --spike-frequencies (or be left out)");
    o.count = static_cast<int>(o.frequencies_hz.size());
  }
  if (auto error = signal::validation_error(o)) refuse(caller, *error);
  return o;
}

signal::WindowOptions window_options(const WindowRequest& request, const Caller& caller) {
  signal::WindowOptions w;
  w.name = request.name.value_or(w.name);
  w.exponential_end = request.exponential_end.value_or(w.exponential_end);
  if (auto error = signal::validation_error(w)) refuse(caller, *error);
  return w;
}

costs::CostOptions cost_options(const CostRequest& request, const Caller& caller) {
  costs::CostOptions o;
  o.name = request.name;
  o.spikes = spike_options(request.spikes, caller);
  o.window = window_options(request.window, caller);
  // A weight the chosen cost has no term for would be ignored without a word: eps1 and eps2 weigh the spike costs'
  // frequency and magnitude terms, eps3 spike-smooth's decay rates (costs/cost.h).
  const std::pair<const char*, std::optional<double>> weights[] = {
      {"eps1", request.eps1}, {"eps2", request.eps2}, {"eps3", request.eps3}};
  for (const auto& [key, value] : weights) {
    const bool smooth_only = std::string_view(key) == "eps3";
    if (value && (smooth_only ? request.name != costs::kSpikeSmoothCost : !costs::is_spike_cost(request.name)))
      refuse(caller, key, format_value(*value),
             std::string("weighs a term of ") +
                 (smooth_only ? "the spike-smooth cost" : "the spike costs (spike, spike-smooth)") + "; cost " +
                 request.name + " has none");
  }
  o.eps1 = request.eps1;
  o.eps2 = request.eps2;
  o.eps3 = request.eps3;
  o.unknown_amplitude = request.unknown_amplitude;
  o.model_poles = request.model_poles.value_or(o.model_poles);
  o.frequency_weight = request.frequency_weight;
  if (auto error = costs::validation_error(o)) refuse(caller, *error);
  return o;
}

}  // namespace beamid::api
