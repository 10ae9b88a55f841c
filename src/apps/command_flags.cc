#include "apps/command_flags.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "config/beam_file.h"
#include "io/resources.h"
#include "io/time_series.h"
#include "model/errors.h"
#include "model/limits.h"

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
      integer_flag("samples", "number of samples Nbar (default 4096)", 2, model::kMaxSamples),
      number_flag("sensor-x", "sensor position xbar, m (default: the tip)"),
      text_flag("output", simulation::output_names().alternatives() + " (default displacement)"),
      text_flag("excitation", simulation::excitation_names().alternatives() +
                                  " (free-decay: fit only, unknown initial state, amplitudes solved) (default pulse)"),
      number_flag("force-x", "force position x_f, m (default: the tip)"),
      number_flag("force-amplitude", "pulse peak F0, or pluck static load P0, N (default 1)"),
      number_flag("pulse-width", "pulse width tau, s (default 0.01; pulse only)")};
}

simulation::Experiment read_experiment(const Flags& a, double length_m) {
  simulation::Experiment e;
  e.dt_s = a.optional_number("dt").value_or(e.dt_s);
  e.samples = a.optional_integer("samples").value_or(e.samples);
  // fit takes a list, one position per --channel: the experiment holds the first (the caller places the others).
  if (a.has("sensor-x")) e.sensor_x_m = a.numbers("sensor-x").front();
  e.output = a.text_or("output", e.output);
  e.excitation = a.text_or("excitation", e.excitation);
  e.force_x_m = a.optional_number("force-x");
  e.force_amplitude_N = a.optional_number("force-amplitude").value_or(e.force_amplitude_N);
  e.pulse_width_s = a.optional_number("pulse-width").value_or(e.pulse_width_s);
  if (e.excitation == simulation::kPluck && a.has("pulse-width"))
    throw InputError("beamid " + a.command() + ": --pulse-width applies to --excitation pulse only");
  if (auto error = simulation::validation_error(e, length_m)) throw InputError("beamid " + a.command() + ": " + *error);
  return e;
}

void guard_run_size(const Flags& a, int elements, double samples, double bytes_per_sample) {
  const double n = elements;
  const double bytes = model::kModelBytesPerElement2 * n * n + bytes_per_sample * samples;
  io::check_memory("beamid " + a.command() + ": N = " + std::to_string(elements) + " and " +
                       std::to_string(static_cast<long long>(samples)) + " samples",
                   bytes, std::cerr);
  const double seconds = model::kSecondsPerEvaluationAtN200 * std::pow(n / 200, 3);
  if (seconds > 10)
    std::cerr << "beamid " << a.command() << ": N = " << elements << ": one model evaluation takes about "
              << io::seconds_text(seconds) << " here (it grows as N^3)\n";
}

std::vector<fit::EstimatedParameter> parse_estimate(const Flags& a, const model::BeamParameters& nominal,
                                                    double factor) {
  const std::string where = "beamid " + a.command() + ": ";
  std::map<std::string, std::pair<double, double>> explicit_bounds;
  if (a.has("bounds")) {
    std::stringstream list(a.text("bounds"));
    std::string item;
    while (std::getline(list, item, ',')) {
      const auto eq = item.find('='), colon = item.find(':');
      char* end1 = nullptr;
      char* end2 = nullptr;
      if (eq == std::string::npos || colon == std::string::npos || colon < eq)
        throw InputError(where + "--bounds item '" + item + "': must read KEY=LO:HI");
      const std::string lo = item.substr(eq + 1, colon - eq - 1), hi = item.substr(colon + 1);
      const double l = std::strtod(lo.c_str(), &end1), h = std::strtod(hi.c_str(), &end2);
      if (lo.empty() || hi.empty() || *end1 || *end2)
        throw InputError(where + "--bounds item '" + item + "': LO and HI must be numbers");
      explicit_bounds[item.substr(0, eq)] = {l, h};
    }
  }
  std::vector<fit::EstimatedParameter> estimate;
  std::stringstream keys(a.text("estimate"));
  std::string key;
  while (std::getline(keys, key, ',')) {
    if (!model::describe_parameter(nominal, key))
      throw InputError(where + "--estimate = '" + a.text("estimate") + "': '" + key +
                       "' is not a parameter of this beam (valid: " + model::estimable_keys(nominal) + ")");
    fit::EstimatedParameter p{key, 0, 0};
    if (auto b = explicit_bounds.find(key); b != explicit_bounds.end()) {
      std::tie(p.lower, p.upper) = b->second;
      explicit_bounds.erase(b);
    } else {
      const double v = model::parameter_value(nominal, key);
      if (!(v > 0))
        throw InputError(where + "--estimate " + key + ": the --beam value is " + format_value(v) +
                         ", so --bound-factor gives no range: give --bounds " + key + "=LO:HI");
      p.lower = v / factor;
      p.upper = v * factor;
    }
    estimate.push_back(p);
  }
  if (!explicit_bounds.empty())
    throw InputError(where + "--bounds names '" + explicit_bounds.begin()->first + "', which is not in --estimate");
  return estimate;
}

}  // namespace beamid::apps
