#include "apps/command_flags.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>

#include "config/beam_file.h"
#include "core/errors.h"
#include "core/limits.h"
#include "io/files.h"
#include "io/time_series.h"

namespace beamid::apps {

model::BeamParameters read_beam(const Flags& a) {
  try {
    if (const std::string* text = a.inline_content("beam")) return config::parse_beam_toml(*text, a.text("beam"));
    return config::resolve_beam(a.text("beam"));
  } catch (const InputError& error) {
    throw InputError("beamid " + a.command() + ": --beam: " + error.what());
  }
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
  if (a.has("time-channel")) o.time_channel = std::to_string(a.integer("time-channel"));
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
      // An import flag's own error names the flag, not the record (--duration = '0': must be > 0).
      const std::string what = e.what();
      throw InputError("beamid " + a.command() + ": " + (what.rfind("--", 0) == 0 ? "" : "--data: ") + what);
    }
    // One column twice (by index and name, or twice the same) would count its data twice in a joint fit and
    // shrink the standard errors by sqrt(2): refused. Two columns are the same when their names and their samples
    // are (columns that share a name, as LVM and UFF channels may, are told apart by their data).
    // --resample's interpolation error is said where the record is used (it was in the notes only Python showed),
    // and so is a time column too coarse to know the step by (time_series.h).
    for (const auto& [note, prefix] :
         {std::pair{"resampled by a cubic spline", "--resample: "}, std::pair{"the time column's values near", ""}})
      if (const auto at = records.back().notes.find(note); at != std::string::npos && records.size() == 1)
        std::cerr << "beamid " << a.command() << ": " << prefix
                  << records.back().notes.substr(at, records.back().notes.find("; ", at) - at) << "\n";
    for (std::size_t k = 0; k + 1 < records.size(); ++k)
      if (records[k].value_column == records.back().value_column && records[k].values == records.back().values)
        a.require(false, "channel",
                  "names the column '" + records.back().value_column + "' twice (channels " + std::to_string(k + 1) +
                      " and " + std::to_string(records.size()) + ")");
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

std::optional<io::TimeSeries> read_force_channel(const Flags& a, const RecordReader& read) {
  if (!a.has("force-channel")) return std::nullopt;
  io::ImportOptions o = read_import_options(a);
  o.channel = a.text("force-channel");
  o.excitation = true;
  for (const std::string& channel : a.texts("channel"))
    a.require(channel != o.channel, "force-channel", "names a response --channel too: the force drives the model");
  try {
    return read(o);
  } catch (const InputError& e) {
    throw InputError("beamid " + a.command() + ": --force-channel = '" + o.channel + "': " + e.what());
  }
}

std::optional<io::TimeSeries> read_force_channel(const Flags& a) { return read_force_channel(a, file_reader(a)); }

io::TimeSeries read_data(const Flags& a, const RecordReader& read) {
  a.require(a.texts("channel").size() <= 1, "channel", "must name one channel (several are for beamid fit)");
  return read_channels(a, read).front();
}

io::TimeSeries read_data(const Flags& a) { return read_data(a, file_reader(a)); }

namespace {

// The first sample's time of the --data and --prediction files as they have it, before --start and --duration cut
// them (--data with its other import flags), and the prediction's step; nothing when a file cannot be read (the
// prediction's own read names it).
struct FirstTimes {
  double data_s, prediction_s, prediction_dt_s;
};
std::optional<FirstTimes> first_times(const Flags& a, io::ImportOptions prediction) {
  io::ImportOptions data = read_import_options(a);
  const std::vector<std::string> channels = a.texts("channel");
  if (!channels.empty()) data.channel = channels.front();
  for (io::ImportOptions* o : {&data, &prediction}) o->start_s.reset(), o->duration_s.reset();
  try {
    const io::TimeSeries whole = io::read_time_series(a.text("prediction"), prediction);
    return FirstTimes{io::read_time_series(a.text("data"), data).t0_s, whole.t0_s, whole.dt_s};
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace

io::TimeSeries read_prediction(const Flags& a, const io::TimeSeries& data) {
  io::ImportOptions o;
  o.channel_advice = "a prediction holds one, the model's output beside its time (--channel chooses among --data's)";
  // The window cuts both records alike: it cut only --data, and the two then differed in length, an error that blamed
  // the prediction (the thirteenth adversarial pass's problem 13).
  o.start_s = a.optional_number("start");
  o.duration_s = a.optional_number("duration");
  const bool window = o.start_s || o.duration_s;
  io::TimeSeries prediction;
  try {
    // With a window the two files' first times must agree, checked before the cut, whose own error hid the cause
    // (the fifteenth pass's P8).
    if (const std::optional<FirstTimes> first = window ? first_times(a, o) : std::nullopt)
      a.require(std::abs(first->data_s - first->prediction_s) <= 0.5 * first->prediction_dt_s, "prediction",
                "starts at t = " + format_value(first->prediction_s) + " s and --data at " +
                    format_value(first->data_s) +
                    " s: --start and --duration cut each by its own times, so the two must start together");
    prediction = io::read_time_series(a.text("prediction"), o);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind("beamid ", 0) == 0) throw;
    throw InputError("beamid " + a.command() + ": --prediction: " + what);
  }
  // Without a window the records are paired sample by sample, and a prediction that starts elsewhere is said.
  if (!window && !(std::abs(data.t0_s - prediction.t0_s) <= 0.5 * prediction.dt_s))
    std::cerr << "beamid " << a.command() << ": --prediction starts at t = " << format_value(prediction.t0_s)
              << " s and --data at " << format_value(data.t0_s)
              << " s: the two are compared sample by sample, as if they started together\n";
  return prediction;
}

namespace {

// Whether writing `output` would replace the existing file `input`: the same inode when both exist, else the same
// normalised absolute path (false when either cannot be normalised: the write itself will then say why it fails). An
// input that is not an existing file (a preset name) cannot be overwritten.
bool overwrites(const std::filesystem::path& output, const std::filesystem::path& input) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(input, error)) return false;
  if (std::filesystem::exists(output, error)) return std::filesystem::equivalent(output, input, error) && !error;
  std::error_code e1, e2;
  const auto a = std::filesystem::weakly_canonical(output, e1), b = std::filesystem::weakly_canonical(input, e2);
  return !e1 && !e2 && a == b;
}

}  // namespace

void check_output_file(const Flags& a, const std::string& flag) {
  if (!a.has(flag)) return;
  const std::string path = a.text(flag);
  a.require(!path.empty(), flag, "must name a file");
  a.require(path.back() != '/', flag, "names a folder; give a file name");
  const std::string problem = io::replaceable_output_problem(path);
  a.require(problem.empty(), flag, problem + "; an output replaces only a regular file");
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::filesystem::path folder = parent.empty() ? std::filesystem::path(".") : parent;
  std::error_code ec;
  a.require(!std::filesystem::exists(folder, ec) || io::is_existing_folder(folder), flag,
            "'" + folder.string() + "' is a file, not a folder");
  a.require(io::is_existing_folder(folder), flag, "its folder '" + folder.string() + "' does not exist");
  // The OS's reason is read after the call: both as arguments of one call, their order is unspecified, and the
  // reason read first said "(Success)" for a read-only folder (the eleventh pass's WR_8).
  errno = 0;
  const bool writable = ::access(folder.c_str(), W_OK) == 0;
  const std::string reason = std::strerror(errno);
  a.require(writable, flag, "cannot write in folder '" + folder.string() + "' (" + reason + ")");
  // As root, access() says yes in /proc too, and `fit --report /proc/x.md` fitted before it failed: a probe file.
  const std::string unwritable = io::unwritable_folder_problem(folder);
  a.require(unwritable.empty(), flag, unwritable);
}

void refuse_overwriting_inputs(const Flags& a, const std::vector<std::string>& output_flags,
                               const std::vector<std::string>& suffixes, const std::vector<std::string>& input_flags) {
  for (const std::string& output : output_flags) {
    if (!a.has(output)) continue;
    for (const std::string& suffix : suffixes)
      for (const std::string& input : input_flags)
        if (a.has(input) && overwrites(a.text(output) + suffix, a.text(input)))
          a.require(false, output,
                    "would overwrite the --" + input + " file" + (suffix.empty() ? "" : " (with " + suffix + ")") +
                        ": an output never replaces an input; choose another path");
  }
}

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

}  // namespace beamid::apps
