// What the commands share on the command line's side: reading --data (and a --channel list) and --beam, and the
// experiment flags' specs. The flags' values become typed requests in apps/flag_requests.h.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

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
// fit --force-channel NAME: that column of the record, read with the response's import flags (the same cut and
// resampling), or nothing without the flag. InputError naming the command and the flag.
std::optional<io::TimeSeries> read_force_channel(const Flags& a, const RecordReader& read);
std::optional<io::TimeSeries> read_force_channel(const Flags& a);
// --prediction (cost): one signal column beside its time, read as it is but for --start and --duration, which cut it
// as they cut --data (the other import flags are the record's); a file of several columns is told so, not sent to
// --channel. With a window, the two files' times must start together (each is cut by its own clock: a prediction
// from t = 0.5 s was cut 500 samples off the data, the fourteenth pass's P6); without one, a prediction that starts
// elsewhere than `data` (the record as read) is said on stderr.
io::TimeSeries read_prediction(const Flags& a, const io::TimeSeries& data);
// --beam: a preset or a beam/geometry TOML file (config/beam_file.h), or TOML text given inline (Flags::set_inline);
// its errors name the command and the flag.
model::BeamParameters read_beam(const Flags& a);
// Before anything runs: InputError naming the flag when an output file's path cannot be written: empty, an existing
// folder, device, pipe or link (io::replaceable_output_problem), a folder that does not exist, or one the user may
// not write in; so that a long computation is not lost at its end.
void check_output_file(const Flags& a, const std::string& flag);
// Before anything runs: InputError when a file the command would write (`outputs`, with their suffixes: --report
// writes REPORT and REPORT.spectra.csv, each through a .tmp beside it) is one of the files it reads (`inputs`:
// --data, --beam), so that an output never overwrites an input.
void refuse_overwriting_inputs(const Flags& a, const std::vector<std::string>& output_flags,
                               const std::vector<std::string>& suffixes, const std::vector<std::string>& input_flags);
// --dt, --samples, --sensor-x, --output, --excitation, --force-x, --force-amplitude, --pulse-width
std::vector<FlagSpec> experiment_flag_specs();

}  // namespace beamid::apps
