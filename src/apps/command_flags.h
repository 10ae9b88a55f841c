// Flags shared by the beamid commands: the experiment flags (simulate, fit) and the estimated-parameter list (fit).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "api/experiment_request.h"
#include "api/fit_request.h"
#include "apps/flags.h"
#include "io/time_series.h"
#include "model/beam_parameters.h"
#include "simulation/experiment.h"

namespace beamid::apps {

// --data with the import flags (channel, units, start, duration, resample): the record, or an InputError naming the
// command and the flag.
io::TimeSeries read_data(const Flags& a);
// The same for a --channel list (fit): one record per channel, in the order given, each with the import flags.
std::vector<io::TimeSeries> read_channels(const Flags& a);
// The same with the record read by `read` from each channel's import options instead of from the --data file (the
// Python package reads an array it holds: io::array_time_series).
using RecordReader = std::function<io::TimeSeries(const io::ImportOptions&)>;
io::TimeSeries read_data(const Flags& a, const RecordReader& read);
std::vector<io::TimeSeries> read_channels(const Flags& a, const RecordReader& read);
// --beam: a preset or a beam/geometry TOML file (config/beam_file.h); its errors name the command and the flag.
model::BeamParameters read_beam(const Flags& a);
// A model run as the flags describe it: --beam, --elements N and the experiment flags, with the run's size guarded
// (guard_run_size with `bytes_per_sample`, 0 for a run that simulates no samples).
struct ModelRun {
  std::string beam_name;
  model::BeamParameters beam;
  int elements = 0;
  simulation::Experiment experiment;
};
ModelRun read_model_run(const Flags& a, double bytes_per_sample);
// --dt, --samples, --sensor-x, --output, --excitation, --force-x, --force-amplitude, --pulse-width
std::vector<FlagSpec> experiment_flag_specs();
// The experiment request those flags describe (api/experiment_request.h).
api::ExperimentRequest experiment_request_of(const Flags& a);
// The experiment they describe (simulation::Experiment's defaults), validated for a beam of length_m.
simulation::Experiment read_experiment(const Flags& a, double length_m);
// The label a command's errors start with: "beamid <command>".
api::Caller caller_of(const Flags& a);
// api::guard_run_size for the command, its warnings on stderr.
void guard_run_size(const Flags& a, int elements, double samples, double bytes_per_sample);
// beamid fit's request from its flags (the records are read apart: read_channels).
api::FitRequest fit_request_of(const Flags& a);

}  // namespace beamid::apps
