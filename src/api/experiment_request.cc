#include "api/experiment_request.h"

#include <cmath>
#include <ostream>

#include "core/errors.h"
#include "core/limits.h"
#include "io/resources.h"

namespace beamid::api {

simulation::Experiment experiment_of(const ExperimentRequest& request, double length_m, const Caller& caller) {
  simulation::Experiment e;
  e.dt_s = request.dt_s.value_or(e.dt_s);
  e.samples = request.samples.value_or(e.samples);
  if (!request.sensor_x_m.empty()) e.sensor_x_m = request.sensor_x_m.front();
  e.output = request.output.value_or(e.output);
  e.excitation = request.excitation.value_or(e.excitation);
  e.force_x_m = request.force_x_m;
  e.force_amplitude_N = request.force_amplitude_N.value_or(e.force_amplitude_N);
  e.pulse_width_s = request.pulse_width_s.value_or(e.pulse_width_s);
  if (!request.force_samples_N.empty()) {
    // A measured force drives the model: it sets the excitation, its amplitude and its shape.
    if (request.excitation && *request.excitation != simulation::kSampledForce)
      refuse(caller, "excitation", *request.excitation,
             "--force-channel '" + request.force_channel + "' drives the model with the record's force (excitation " +
                 simulation::kSampledForce + ")");
    for (const auto& [flag, given] : {std::pair{"force-amplitude", request.force_amplitude_N.has_value()},
                                      std::pair{"pulse-width", request.pulse_width_s.has_value()}})
      if (given)
        refuse(caller, std::string("--") + flag + " describes a modelled pulse; --force-channel '" +
                           request.force_channel + "' gives the measured force");
    e.excitation = simulation::kSampledForce;
    e.force_samples_N = request.force_samples_N;
    e.samples = static_cast<int>(request.force_samples_N.size());  // the record's; checked against the response's
  } else if (e.excitation == simulation::kSampledForce) {
    refuse(caller, "excitation", e.excitation, "needs the record's force: give --force-channel NAME (fit)");
  }
  if (e.excitation == simulation::kPluck && request.pulse_width_s)
    refuse(caller, "--pulse-width applies to --excitation pulse only");
  // A free decay has no force: its initial state is solved from the record (simulation/experiment.h), and a force
  // position, amplitude or pulse width given with it was ignored without a word.
  if (e.excitation == simulation::kFreeDecay)
    for (const auto& [flag, given] : {std::pair{"force-x", request.force_x_m.has_value()},
                                      std::pair{"force-amplitude", request.force_amplitude_N.has_value()},
                                      std::pair{"pulse-width", request.pulse_width_s.has_value()}})
      if (given)
        refuse(caller, std::string("--") + flag +
                           " describes the force of --excitation pulse or pluck; a free decay has none (its initial "
                           "state is solved from the record)");
  if (auto error = simulation::validation_error(e, length_m)) refuse(caller, *error);
  return e;
}

void check_elements(const Caller& caller, int elements) {
  if (elements < core::kMinElements || elements > core::kMaxElements)
    refuse(caller, "elements", std::to_string(elements),
           "must be an integer in " + std::to_string(core::kMinElements) + ".." + std::to_string(core::kMaxElements));
}

void guard_run_size(const Caller& caller, int elements, double samples, double bytes_per_sample,
                    std::ostream& warnings) {
  const double n = elements;
  const double bytes = core::kModelBytesPerElement2 * n * n + bytes_per_sample * samples;
  io::check_memory(caller.label + ": N = " + std::to_string(elements) + " and " +
                       std::to_string(static_cast<long long>(samples)) + " samples",
                   bytes, warnings);
  const double seconds = core::seconds_per_evaluation(n);
  if (seconds > 10)
    warnings << caller.label << ": N = " << elements << ": one model evaluation takes about "
             << io::seconds_text(seconds) << " here (it grows as N^3)\n";
}

}  // namespace beamid::api
