// Reading a sampled record: CSV (as written by `beamid simulate`, or a DAQ export with a header line naming the
// columns: time in seconds first, then one or more channels) or LabVIEW measurement text (.lvm: "***End_of_Header***"
// blocks, tab- or comma-separated, X_Columns One, Multi or No; the channel names from the column header line, units
// from Y_Unit_Label); NumPy .npy (io/npy.h) and MATLAB .mat v5/v7.3 (io/mat_file.h) arrays of samples x channels
// either way round, whose time base is --sample-rate (or a .mat time vector); UFF dataset 58, ASCII or binary
// (io/uff58.h), one channel per time record, named by its ID line, with its unit. The format is recognised from the
// content (NumPy's magic, "MATLAB" in a MAT-file's header, UFF's "-1" delimiter), else from the ending (.lvm, else
// CSV); a binary file of another kind is an error saying which formats are read.
//
// The file must be a regular text file of at most 1 GiB (a folder, a device such as /dev/zero, or a binary file is
// named as such at once, before anything large is read).
// Checked, each violation an InputError naming the file, line, column, value and constraint:
//   every field of the chosen channel and of the time column a finite number (NaN, "inf" or an empty field stop it);
//   at least 8 samples; a uniform time base t_i = t_0 + i dt with dt = (t_last - t_0)/(n - 1), to within one unit
//   of the last printed decimal of the time column (DAQ exports round or truncate times: the ARTS record prints 6
//   decimals of a 605.47 us step, and 0.0096875 appears as 0.009687) or 1e-6 dt, whichever is larger; unless `resample`
//   is set, which instead interpolates the record by a cubic spline onto the uniform grid with the mean step (and says
//   so in `notes`); no clipping: the largest |value| held for 3 or more consecutive samples means the DAQ range was
//   exceeded.
// Then the window is cut out (from the sample nearest to start_s, round(duration_s / dt) samples), for records in
// g values are converted to m/s^2 (1 g = 9.80665 m/s^2, the standard gravity of ISO 80000-3), and with a resample
// rate the record is resampled by windowed-sinc interpolation (a low-pass at 0.45 of the new rate first when the rate
// falls).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace beamid::io {

struct ImportOptions {
  std::string channel;            // name or 1-based index among the signal columns; "": the only one
  std::string units = "auto";     // "auto": convert to SI when the file states g or mm (io/units.h); "g": in g; "as-is"
  std::optional<double> start_s;  // first sample: the one nearest to this time (default: the first)
  std::optional<double> duration_s;      // round(duration / dt) samples from there (default: to the last)
  bool resample = false;                 // interpolate a non-uniform time base instead of refusing it
  std::optional<double> sample_rate_hz;  // the time base of a record that has none (.npy, .mat without a time)
  std::string variable, time_variable;   // .mat: the record's and its time vector's dotted paths
  // .npy, .mat, arrays: the channel (1-based, as --channel counts them) that holds the time in s, instead of a
  // --sample-rate; --channel then chooses among the others. "": none.
  std::string time_channel;
  std::optional<double> resample_rate_hz;  // band-limited resampling onto this rate after everything else
  // The channel is an excitation (--force-channel): a hammer's force rests between its hits, so a run at its rest
  // level is no dropout (as for any channel in a force unit, N, kN or lbf).
  bool excitation = false;
  // What a file of several channels is told when none is chosen (a prediction has no --channel of its own).
  std::string channel_advice = "choose one with --channel NAME or --channel INDEX";
};

struct TimeSeries {
  std::string path;
  std::string format;                     // "csv" | "lvm" | "npy" | "mat v5" | "mat v7.3" | "uff58"
  std::string time_column, value_column;  // names as in the file
  std::string unit;                       // of `values` after conversion ("m/s^2", or as the file says, or "")
  double t0_s = 0;                        // time of values[0]
  double dt_s = 0;
  std::vector<double> values;
  std::string notes;  // what was done to the record (window, conversion, resampling)
  // Set by a --resample-rate below the record's rate: the top of its low-pass's pass band; a pole above it is
  // distorted by the filter, or made by its edge from a removed peak's tail (modal-id and spikes say so). Infinity
  // otherwise.
  double pass_band_hz = std::numeric_limits<double>::infinity();
};

// The format from the content, else from the ending (above).
TimeSeries read_time_series(const std::string& path, const ImportOptions& options = {});
// The same from bytes in memory; `path` names it in messages and its ending (.lvm) chooses a text format (a .mat
// file is opened by libmatio from `path`).
TimeSeries parse_time_series(const std::string& text, const std::string& path, const ImportOptions& options = {});

// A record already in memory (the Python package): `rows` x `columns` doubles in row-major order, the samples along
// the longer dimension (as for .npy; the channel by options.channel, a 1-based index), the time base from
// options.sample_rate_hz or `time` (one time per sample, s, uniform to double precision); then the checks and steps
// every format shares (above). `name` stands for the file in messages; the format reads "array".
// `time_relative_precision`: the precision of the times as they were given, 2 eps of their type (a float32 time vector
// widened to double keeps float32's 2.4e-7, and was refused as a time base that jumps: the thirteenth pass's 8).
TimeSeries array_time_series(const std::string& name, const double* values, std::size_t rows, std::size_t columns,
                             const std::vector<double>* time, const ImportOptions& options = {},
                             double time_relative_precision = 2 * std::numeric_limits<double>::epsilon());

// A record's quantum: its smallest non-zero step between neighbours (round-off small for floating-point values,
// infinite for a constant record). Under kFineQuantisation steps over its peak (10 bits over its range) a record is
// coarsely quantised: the reader's rules for clipping and dropouts allow for it, and api::quantisation_note says so.
double record_quantum(const std::vector<double>& values);
inline constexpr double kFineQuantisation = 512;

}  // namespace beamid::io
