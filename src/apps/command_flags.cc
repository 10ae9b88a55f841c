#include "apps/command_flags.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

#include "config/beam_file.h"
#include "io/time_series.h"
#include "core/errors.h"
#include "core/limits.h"

namespace beamid::apps {

model::BeamParameters read_beam(const Flags& a) {
  try {
    return config::resolve_beam(a.text("beam"));
  } catch (const InputError& error) {
    throw InputError("beamid " + a.command() + ": --beam: " + error.what());
  }
}

ModelRun read_model_run(const Flags& a, double bytes_per_sample) {
  ModelRun run{a.text("beam"), read_beam(a), a.integer("elements"), {}};
  run.experiment = read_experiment(a, run.beam.l);
  guard_run_size(a, run.elements, bytes_per_sample > 0 ? run.experiment.samples : 0, bytes_per_sample);
  return run;
}

namespace {

// The import flags (channel aside): units, start, duration, resample, sample rate, variables, resample rate.
io::ImportOptions read_import_options(const Flags& a) {
  io::ImportOptions o;
  o.units = a.text_or("units", o.units);
  o.start_s = a.optional_number("start");
  o.duration_s = a.optional_number("duration");
  o.resample = a.has("resample");
  o.sample_rate_hz = a.optional_number("sample-rate");
  o.variable = a.text_or("variable", "");
  o.time_variable = a.text_or("time-variable", "");
  o.resample_rate_hz = a.optional_number("resample-rate");
  return o;
}

}  // namespace

std::vector<io::TimeSeries> read_channels(const Flags& a, const RecordReader& read) {
  io::ImportOptions o = read_import_options(a);
  std::vector<std::string> channels = a.texts("channel");
  if (channels.empty()) channels.emplace_back();  // the only signal column
  std::vector<io::TimeSeries> records;
  for (const std::string& channel : channels) {
    o.channel = channel;
    try {
      records.push_back(read(o));
    } catch (const InputError& e) {
      throw InputError("beamid " + a.command() + ": --data: " + e.what());
    }
  }
  return records;
}

namespace {

// The --data file, read with one channel's import options.
RecordReader file_reader(const Flags& a) {
  return [&a](const io::ImportOptions& o) { return io::read_time_series(a.text("data"), o); };
}

}  // namespace

std::vector<io::TimeSeries> read_channels(const Flags& a) { return read_channels(a, file_reader(a)); }

io::TimeSeries read_data(const Flags& a, const RecordReader& read) {
  a.require(a.texts("channel").size() <= 1, "channel", "must name one channel (several are for beamid fit)");
  return read_channels(a, read).front();
}

io::TimeSeries read_data(const Flags& a) { return read_data(a, file_reader(a)); }

std::vector<FlagSpec> experiment_flag_specs() {
  return {
      number_flag("dt", "sampling interval, s (default 1e-3)"),
      integer_flag("samples", "number of samples Nbar (default 4096)", 2, core::kMaxSamples),
      number_flag("sensor-x", "sensor position xbar, m (default: the tip)"),
      text_flag("output", simulation::output_names().alternatives() + " (default displacement)"),
      text_flag("excitation", simulation::excitation_names().alternatives() +
                                  " (free-decay: fit only, unknown initial state, amplitudes solved) (default pulse)"),
      number_flag("force-x", "force position x_f, m (default: the tip)"),
      number_flag("force-amplitude", "pulse peak F0, or pluck static load P0, N (default 1)"),
      number_flag("pulse-width", "pulse width tau, s (default 0.01; pulse only)")};
}

api::Caller caller_of(const Flags& a) { return {"beamid " + a.command()}; }

api::ExperimentRequest experiment_request_of(const Flags& a) {
  api::ExperimentRequest e;
  e.dt_s = a.optional_number("dt");
  e.samples = a.optional_integer("samples");
  // fit takes a list, one position per --channel; the other commands one position.
  e.sensor_x_m = a.numbers("sensor-x");
  if (a.has("output")) e.output = a.text("output");
  if (a.has("excitation")) e.excitation = a.text("excitation");
  e.force_x_m = a.optional_number("force-x");
  e.force_amplitude_N = a.optional_number("force-amplitude");
  e.pulse_width_s = a.optional_number("pulse-width");
  return e;
}

simulation::Experiment read_experiment(const Flags& a, double length_m) {
  return api::experiment_of(experiment_request_of(a), length_m, caller_of(a));
}

void guard_run_size(const Flags& a, int elements, double samples, double bytes_per_sample) {
  api::guard_run_size(caller_of(a), elements, samples, bytes_per_sample, std::cerr);
}

}  // namespace beamid::apps
