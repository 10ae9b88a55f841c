// Flags shared by the beamid commands: the experiment flags (simulate, fit) and the estimated-parameter list (fit).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "apps/flags.h"
#include "fit/parameter_map.h"
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
// The experiment those flags describe (defaults of simulation::Experiment), validated for a beam of length_m.
simulation::Experiment read_experiment(const Flags& a, double length_m);
// Before a run whose size the flags set: refuses it when the model of N elements and `samples` samples at
// `bytes_per_sample` would not fit in the machine's memory, and warns on stderr with the estimate when one model
// evaluation would take more than 10 s (model/limits.h has the measured figures).
void guard_run_size(const Flags& a, int elements, double samples, double bytes_per_sample);
// --estimate KEY,... with bounds [v/F, v F] around each nominal value v, or from --bounds KEY=LO:HI,...
std::vector<fit::EstimatedParameter> parse_estimate(const Flags& a, const model::BeamParameters& nominal,
                                                    double factor);

}  // namespace beamid::apps
