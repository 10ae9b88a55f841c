// A model's output as a sensor of finite bandwidth delivers it (signal/sensor_filter.h), for a fit whose model
// includes the measurement chain's anti-alias filter (issue 35: least squares' best practice when the record was
// filtered before sampling): the model simulated `oversampling` times finer (simulation::finer), its output filtered
// and every R-th sample kept, exactly as a study's truth is sensed. The filter is linear (its start, the steady state
// of the first sample, is linear in that sample too), so the sensitivities of the sensed output are the sensed
// sensitivities, column by column, exactly. The beam's poles are the model's whatever the filter: the modal cost reads
// them unchanged.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "signal/sensor_filter.h"
#include "simulation/experiment.h"

namespace beamid::fit {

// The first violated constraint of a filter in a fit's model, or nothing: the filter's own (signal::validation_error
// at the record's step), and an experiment the model simulates from a known start (a pulse, a pluck or a sampled
// force: a free decay's amplitudes are solved against the data, which a filter's transient would not match).
std::optional<std::string> sensed_validation_error(const signal::SensorFilter& sensor,
                                                   const simulation::Experiment& experiment);

// The experiment the model is simulated on: the record's, or `oversampling` times finer when the filter is on.
simulation::Experiment simulated_experiment(const simulation::Experiment& record, const signal::SensorFilter& sensor);

// The output simulated on simulated_experiment's grid, as the sensor delivers it at the record's step dt_s (in place;
// nothing without a filter).
void sense_output(const signal::SensorFilter& sensor, double dt_s, std::vector<double>& y);
// The same for every column of a samples x parameters matrix (d y / d q).
void sense_columns(const signal::SensorFilter& sensor, double dt_s, Eigen::MatrixXd& columns);

}  // namespace beamid::fit
