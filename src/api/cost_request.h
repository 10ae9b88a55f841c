// The spectrum and cost choices of a request, as a user gives them (the command line's --spikes ... --frequency-weight,
// Python's keywords of the same names): what `spikes`, `cost` and `fit` share. An unset optional takes the default of
// signal::SpikeOptions, signal::WindowOptions or costs::CostOptions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "api/request.h"
#include "costs/cost.h"
#include "signal/noise.h"
#include "signal/spectrum.h"
#include "signal/spikes.h"

namespace beamid::api {

struct SpikeRequest {
  std::optional<int> count;                // --spikes NM
  std::optional<std::string> rule;         // --spike-rule: largest | prominence
  std::optional<double> min_frequency_hz;  // --min-frequency
  std::optional<double> max_frequency_hz;  // --max-frequency
  std::vector<double> frequencies_hz;      // --spike-frequencies (then count, if given, must equal their number)
  // --artefacts: reject | keep (default reject: a record read from a file is a measured one)
  std::optional<std::string> artefacts;
};

struct WindowRequest {
  std::optional<std::string> name;        // --window: rectangular | hann | exponential
  std::optional<double> exponential_end;  // --exponential-end
};

struct CostRequest {
  std::string name;  // --cost (required where a cost is computed)
  SpikeRequest spikes;
  WindowRequest window;
  std::optional<double> eps1, eps2, eps3;  // --eps1, --eps2, --eps3
  bool unknown_amplitude = false;          // --unknown-amplitude
  std::optional<std::string> model_poles;  // --model-poles: dft | eigenvalues
  std::optional<std::string> mode_weight;  // --mode-weight: relative | measured (modal)
  // --frequency-weight. A record read from a file is a measured record as far as beamid knows: errors relative to
  // each mode's frequency, so that the highest fitted mode does not dominate (costs/cost.h); the studies' synthetic
  // records keep the paper's Hz.
  // (unset: relative).
  std::optional<std::string> frequency_weight;
  std::optional<std::string> noise_model;  // --noise-model: the noise time and freq-ml assume (default white)
  // --noise-sd and --force-noise-sd: freq-ml's errors-in-variables form with a measured force (costs/cost.h)
  std::optional<double> noise_sd, force_noise_sd;
};

// The options a request gives, validated (InputError naming the field, value and constraint).
signal::SpikeOptions spike_options(const SpikeRequest& request, const Caller& caller);
signal::WindowOptions window_options(const WindowRequest& request, const Caller& caller);
// --noise-model, parsed (signal/noise.h); its error with the constraint alone after the flag ("noise model 'x':
// constraint").
signal::NoiseModel parsed_noise_model(const Caller& caller, const std::string& text);
// `also`: the other costs the same request configures (a hybrid fit's refinement), so that an option either cost
// reads is not refused as unused.
costs::CostOptions cost_options(const CostRequest& request, const Caller& caller,
                                const std::vector<std::string>& also = {});

}  // namespace beamid::api
