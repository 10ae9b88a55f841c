// A model's output as a sensor of finite bandwidth delivers it (signal/sensor_filter.h), for a fit whose model
// includes the measurement chain's anti-alias filter (issue 35: least squares' best practice when the record was
// filtered before sampling): the model's output filtered on a grid `oversampling` times finer and every R-th sample
// kept, exactly as a study's truth is sensed (the truth simulated finer and filtered sample by sample; a fitted model
// by the fast simulator's closed form, output_filter). The filter is linear (its start, the steady state of the first
// sample, is linear in that sample too), so the sensitivities of the sensed output are the sensed sensitivities,
// exactly. The beam's poles are the model's whatever the filter: the modal cost reads
// them unchanged.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "signal/sensor_filter.h"
#include "simulation/experiment.h"
#include "simulation/output_filter.h"

namespace beamid::fit {

// The first violated constraint of a filter in a fit's model, or nothing: the filter's own (signal::validation_error
// at the record's step); a model simulated from a known start (a pulse or a pluck: a free decay's amplitudes are
// solved against the data, which the filter's transient would not match); no measured force (a data-acquisition
// system filters its force channel as it filters the response, and the beam is linear, so the recorded response is
// already the model's response to the recorded force: a filter in the model would count it twice); and a fine record
// within the simulator's limits (dt / R >= 1e-9 s, Nbar R <= core::kMaxSamples).
std::optional<std::string> sensed_validation_error(const signal::SensorFilter& sensor,
                                                   const simulation::Experiment& experiment);

// The experiment the model is simulated on: the record's, or `oversampling` times finer when the filter is on.
simulation::Experiment simulated_experiment(const simulation::Experiment& record, const signal::SensorFilter& sensor);

// What the sensor measured before t = 0, the filter's starting level (signal::sense): a displacement's first sample
// (at rest, or a pluck's static deflection), 0 for a velocity or an acceleration (at rest before a release or a force).
std::optional<double> level_before(const simulation::Experiment& record, const std::vector<double>& output);

// The output simulated on simulated_experiment's grid, as the sensor delivers it on the record's (in place; nothing
// without a filter): the truth's sensing, and a model run by cvode.
void sense_output(const signal::SensorFilter& sensor, const simulation::Experiment& record, std::vector<double>& y);

// The sensor's filter as the fast simulator carries it through its closed form on the record's own grid (issue 32:
// simulation/output_filter.h, the same output as simulating finer and sense_output, to round-off, at the cost of a
// run on the record's grid); null without a filter.
std::shared_ptr<const simulation::OutputFilter> output_filter(const signal::SensorFilter& sensor, double dt_s);

}  // namespace beamid::fit
