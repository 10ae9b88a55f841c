#include "fit/sensed_output.h"

#include <cstdint>

#include "core/errors.h"
#include "core/limits.h"

namespace beamid::fit {

std::optional<std::string> sensed_validation_error(const signal::SensorFilter& sensor,
                                                   const simulation::Experiment& experiment) {
  if (auto error = signal::validation_error(sensor, experiment.dt_s)) return error;
  if (!(sensor.cutoff_hz > 0)) return std::nullopt;
  if (experiment.excitation == simulation::kFreeDecay)
    return "sensor filter in the model: a free decay's amplitudes are solved against the data from an unknown state, "
           "which the filter's transient would not match (give a pulse or a pluck)";
  if (experiment.excitation == simulation::kSampledForce)
    return "sensor filter in the model: with a measured force, the acquisition's filter is on the force channel "
           "too, so the recorded response is the model's to the recorded force already (the beam is linear); a "
           "filter in the model would count it twice";
  const std::int64_t fine = static_cast<std::int64_t>(experiment.samples) * sensor.oversampling;
  if (fine > core::kMaxSamples)
    return "sensor filter in the model: the model simulated " + std::to_string(sensor.oversampling) +
           " times finer would hold " + std::to_string(fine) + " samples: at most " +
           std::to_string(core::kMaxSamples) + " (a shorter record, or a lower --sensor-oversampling)";
  if (experiment.dt_s / sensor.oversampling < 1e-9)
    return "sensor filter in the model: the model's step dt / " + std::to_string(sensor.oversampling) + " = " +
           format_value(experiment.dt_s / sensor.oversampling) + " s: must be at least 1e-9 s (a lower oversampling)";
  return std::nullopt;
}

simulation::Experiment simulated_experiment(const simulation::Experiment& record, const signal::SensorFilter& sensor) {
  return sensor.cutoff_hz > 0 ? simulation::finer(record, sensor.oversampling) : record;
}

std::optional<double> level_before(const simulation::Experiment& record, const std::vector<double>& output) {
  if (record.output == simulation::kDisplacement) return output.empty() ? 0.0 : output.front();
  return 0.0;
}

void sense_output(const signal::SensorFilter& sensor, const simulation::Experiment& record, std::vector<double>& y) {
  if (sensor.cutoff_hz > 0) y = signal::sense(sensor, y, record.dt_s, level_before(record, y));
}

std::shared_ptr<const simulation::OutputFilter> output_filter(const signal::SensorFilter& sensor, double dt_s) {
  if (!(sensor.cutoff_hz > 0)) return nullptr;
  signal::FilterStateSpace f = signal::state_space(sensor, dt_s);
  return std::make_shared<const simulation::OutputFilter>(std::move(f.a), std::move(f.b), std::move(f.c), f.d,
                                                          sensor.oversampling);
}

}  // namespace beamid::fit
