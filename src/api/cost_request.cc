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
  const std::string artefacts = request.artefacts.value_or("reject");
  if (artefacts != "reject" && artefacts != "keep")
    refuse(caller, "artefacts", artefacts, "must be one of reject, keep");
  o.reject_artefacts = artefacts == "reject";
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

signal::NoiseModel parsed_noise_model(const Caller& caller, const std::string& text) {
  try {
    return signal::parse_noise_model(text);
  } catch (const signal::NoiseModelError& e) {
    refuse(caller, "noise-model", text, e.constraint);
  }
}

signal::WindowOptions window_options(const WindowRequest& request, const Caller& caller) {
  signal::WindowOptions w;
  w.name = request.name.value_or(w.name);
  w.exponential_end = request.exponential_end.value_or(w.exponential_end);
  // The exponential window's end with another window is read by nothing (spikes took it without a word: the fourth
  // pass's Q359); every command that windows a spectrum comes here.
  if (request.exponential_end && w.name != "exponential")
    refuse(caller, "exponential-end", format_value(*request.exponential_end),
           "is the exponential window's; --window is " + request.name.value_or("rectangular (the default)"));
  if (auto error = signal::validation_error(w)) refuse(caller, *error);
  return w;
}

namespace {

// An option that none of the request's costs reads is refused, naming the costs that do read it.
void refuse_unused(const CostRequest& request, const Caller& caller, const std::vector<std::string>& also) {
  std::vector<std::string> names = also;
  names.insert(names.begin(), request.name);
  std::string named;
  for (const std::string& n : names) named += (named.empty() ? "" : " and ") + n;
  const auto uses = [&](bool costs::CostUses::*field) {
    return std::any_of(names.begin(), names.end(), [&](const std::string& n) { return costs::cost_uses(n).*field; });
  };
  const auto refuse_if = [&](bool given, bool costs::CostUses::*field, const std::string& flag,
                             const std::string& value, const std::string& readers) {
    if (given && !uses(field))
      refuse(caller, flag, value, "is read by " + readers + "; cost " + named + " does not read it");
  };
  const std::string dft_costs = "the DFT costs (spike, spike-smooth, freq-band)";
  const std::string spike_costs = "the spike costs (spike, spike-smooth)";
  refuse_if(request.window.name.has_value(), &costs::CostUses::window, "window", request.window.name.value_or(""),
            dft_costs);
  refuse_if(request.window.exponential_end.has_value(), &costs::CostUses::window, "exponential-end",
            format_value(request.window.exponential_end.value_or(0)), dft_costs);
  refuse_if(request.spikes.rule.has_value(), &costs::CostUses::spike_rule, "spike-rule",
            request.spikes.rule.value_or(""), spike_costs);
  refuse_if(request.spikes.artefacts.has_value(), &costs::CostUses::spike_rule, "artefacts",
            request.spikes.artefacts.value_or(""), spike_costs);
  refuse_if(request.frequency_weight.has_value(), &costs::CostUses::frequency_weight, "frequency-weight",
            request.frequency_weight.value_or(""), spike_costs);
  refuse_if(request.model_poles.has_value(), &costs::CostUses::model_poles, "model-poles",
            request.model_poles.value_or(""), "the spike-smooth cost");
  refuse_if(request.mode_weight.has_value(), &costs::CostUses::mode_weight, "mode-weight",
            request.mode_weight.value_or(""), "the modal cost");
  refuse_if(request.noise_model.has_value(), &costs::CostUses::noise_model, "noise-model",
            request.noise_model.value_or(""), "the time and freq-ml costs");
  for (const auto& [flag, value] :
       {std::pair{"noise-sd", request.noise_sd}, std::pair{"force-noise-sd", request.force_noise_sd}})
    if (value && std::find(names.begin(), names.end(), costs::kMaxLikelihoodCost) == names.end())
      refuse(caller, flag, format_value(*value), "is read by the freq-ml cost; cost " + named + " does not read it");
  if (request.unknown_amplitude && !uses(&costs::CostUses::unknown_amplitude))
    refuse(caller, "--unknown-amplitude frees the amplitude of a cost that compares amplitudes; cost " + named +
                       " compares frequencies and decay rates only");
}

}  // namespace

costs::CostOptions cost_options(const CostRequest& request, const Caller& caller,
                                const std::vector<std::string>& also) {
  costs::CostOptions o;
  o.name = request.name;
  if (costs::cost_names().contains(o.name)) refuse_unused(request, caller, also);
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
  o.mode_weight = request.mode_weight.value_or(o.mode_weight);
  o.frequency_weight = request.frequency_weight.value_or(costs::kRelativeWeight);
  if (request.force_noise_sd && !request.noise_sd)
    refuse(caller, "force-noise-sd", format_value(*request.force_noise_sd),
           "weighs the force's noise against the response's: give --noise-sd too");
  if (request.noise_sd && !request.force_noise_sd)
    refuse(caller, "noise-sd", format_value(*request.noise_sd),
           "is the errors-in-variables form's (with --force-noise-sd); the output-error form takes the level from the "
           "residuals");
  if (request.force_noise_sd && request.unknown_amplitude)
    refuse(caller,
           "--unknown-amplitude with --force-noise-sd: the errors-in-variables weights take the force's noise "
           "through the model at its own amplitude; a measured force fixes it");
  o.noise_sd = request.noise_sd.value_or(0.0);
  o.force_noise_sd = request.force_noise_sd.value_or(0.0);
  if (request.noise_model)
    o.noise_model = costs::is_estimated_noise(*request.noise_model)
                        ? *request.noise_model
                        : parsed_noise_model(caller, *request.noise_model).text();
  // Checked as the cost that reads it: a hybrid's force noise is its freq-ml refinement's (fit/identification.h),
  // not its global cost's (the twenty-second pass's P2).
  costs::CostOptions checked = o;
  if (checked.force_noise_sd > 0 && std::find(also.begin(), also.end(), costs::kMaxLikelihoodCost) != also.end())
    checked.name = costs::kMaxLikelihoodCost;
  if (auto error = costs::validation_error(checked)) refuse(caller, *error);
  return o;
}

}  // namespace beamid::api
