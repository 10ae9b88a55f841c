// Inside the record readers (io/time_series.h), not for other code: one channel's samples as a format's reader found
// them, before the checks every format shares (time_series.cc: uniform time base, clipping, window, units, rate);
// the text formats are read in text_records.cc, the array and UFF ones in binary_records.cc.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/time_series.h"

namespace beamid::io {

// One channel's samples with their times, as a reader found them, before the checks every format shares.
struct Samples {
  TimeSeries series;  // path, format, column names and the file's unit
  std::vector<double> t, v;
  bool time_in_file = false;   // t read from the file (checked for uniformity), else t0 + i dt
  double time_resolution = 0;  // the file's resolution of its times (a text column's last printed decimal)
  std::function<std::string(std::size_t)> where;  // sample i's place: "path:line" or "path: sample i"
  long declared_samples = 0;                      // LVM "Samples" of the segment header (0: not given)
};

// A field as an error message shows it: at most `limit` characters, bytes that are not printable ASCII as \xNN.
std::string shown(const std::string& text, std::size_t limit = 40);
// The channel a reader's names offer: by name, or by 1-based index; the only one when none is asked for.
std::size_t choose_channel(const std::vector<std::string>& names, const ImportOptions& o, const std::string& path,
                           const std::string& what);

// The first byte of `text` that no text record holds (a control character other than tab, line feed, carriage return
// and form feed), as the one-line refusal of a binary file of no format beamid reads; nothing for text.
std::optional<std::string> binary_text_problem(std::string_view text, const std::string& path);
// Whether `path` ends as a plain text table (.txt, .dat, .tsv, .asc, any case): numbers separated by whitespace.
bool is_plain_text_path(const std::string& path);
// CSV, LabVIEW .lvm or a plain text table (by the ending of `path`).
Samples text_samples(const std::string& text, const std::string& path, const ImportOptions& o);
// An array of samples x channels (either way round: the samples run along the longer dimension) with its time base
// from --sample-rate, or from a time vector of the same length, or from its channel o.time_channel, either stored to
// `time_relative_precision`.
Samples array_samples(const std::string& path, const std::string& format, const std::string& what, std::size_t rows,
                      std::size_t columns, const std::function<double(std::size_t, std::size_t)>& at,
                      const std::vector<double>* time, double time_relative_precision, const ImportOptions& o);
// A time record of a UFF file (its datasets 58).
Samples uff_samples(const std::string& bytes, const std::string& path, const ImportOptions& o);

}  // namespace beamid::io
