// The experiment of a request (the command line's --dt, --samples, --sensor-x, --output, --excitation, --force-x,
// --force-amplitude, --pulse-width) as a user gives it: an unset optional takes simulation::Experiment's default.
// Beside it, the guard every request that sizes a model run passes before it runs.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "api/request.h"
#include "simulation/experiment.h"

namespace beamid::api {

struct ExperimentRequest {
  std::optional<double> dt_s;               // --dt
  std::optional<int> samples;               // --samples
  std::vector<double> sensor_x_m;           // --sensor-x: one position (fit: one per channel; empty: the tip)
  std::optional<std::string> output;        // --output
  std::optional<std::string> excitation;    // --excitation
  std::optional<double> force_x_m;          // --force-x
  std::optional<double> force_amplitude_N;  // --force-amplitude
  std::optional<double> pulse_width_s;      // --pulse-width (pulse only)
  // fit --force-channel: the record's measured force, which drives the model (excitation "force"), and its column.
  std::vector<double> force_samples_N;
  std::string force_channel;
};

// The experiment the request describes, validated for a beam of length_m; the sensor is the first of sensor_x_m
// (a joint fit places the others). InputError naming the field, value and constraint.
simulation::Experiment experiment_of(const ExperimentRequest& request, double length_m, const Caller& caller);

// InputError unless the Galerkin order N lies in the project's range (core/limits.h).
void check_elements(const Caller& caller, int elements);
// Before a run whose size a request sets: refuses it (InputError) when the model of N elements and `samples` samples
// at `bytes_per_sample` would not fit in the machine's memory, and warns on `warnings` with the estimate when one
// model evaluation would take more than 10 s (core/limits.h has the measured figures).
void guard_run_size(const Caller& caller, int elements, double samples, double bytes_per_sample,
                    std::ostream& warnings);

}  // namespace beamid::api
