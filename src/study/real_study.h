// A real-data study (studies/real-steel.toml): one measured free-decay record fitted with each cost, reported
// against the record's own spectral peaks. There is no truth: what is compared is the model at the estimate with the
// measurement (identified against measured peak frequencies, damping ratios per mode, the identified parameters
// against their nominal values, residuals in time and frequency).
//
//   [study]   name, question
//   [record]  file (relative to the study file), channel, units, start_s, duration_s, resample,
//             peaks_hz: the measured peak frequencies of the modes the model has (the spikes are chosen near them,
//             and data and model are paired by frequency, so torsion modes and mains lines are left out)
//   [beam]    file: a beam TOML ([beam] or [geometry]) giving the nominal values and the starts
//   [fit]     elements, estimate, costs, bounds (a table KEY = [lo, hi]; default [v/2, 2v]), max_evaluations
//
// Writes to results/<name>/: fits.csv (cost, parameter, estimate, standard_error, nominal, ratio), modes.csv
// (cost, mode, measured_frequency_hz, identified_frequency_hz, identified_damping_ratio), overlay.csv,
// spectrum.csv, spikes.csv, manifest.json, provenance.csv, report.md (the REPORT.md block) and timings.csv.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "fit/identification.h"
#include "io/time_series.h"
#include "model/beam_parameters.h"
#include "study/overlay.h"
#include "study/rendered.h"

namespace beamid::study {

struct RealStudySpec {
  std::string path, name, question, file_hash;
  std::string record_file, channel, units = "auto";
  std::optional<double> start_s, duration_s;
  bool resample = false;
  std::vector<double> peaks_hz;
  std::string beam_file;
  int elements = 16;
  std::vector<std::string> estimate;
  std::vector<std::string> costs;
  std::map<std::string, std::pair<double, double>> bounds;
  int max_evaluations = 3000;
  std::string frequency_weight = "relative";  // spike costs (costs/cost.h): a measured record's default
};

// Strict reading, as for synthetic studies (InputError naming file:line, key, value and constraint).
RealStudySpec load_real_study(const std::string& path);

// One cost's fit of the record (a failed fit has its status and nothing else).
struct RealFit {
  std::string cost, status;
  double cost_value = std::numeric_limits<double>::infinity();
  long evaluations = 0;
  double wall_time_s = 0;
  std::vector<fit::ParameterEstimate> parameters;
  std::vector<double> identified_hz, zeta;  // the model's modes paired with each measured peak
  std::optional<Overlay> overlay;
};

struct RealResults {
  io::TimeSeries record;
  model::BeamParameters nominal;
  std::vector<double> measured_hz, measured_zeta;  // 3-bin estimates at the record's peaks near peaks_hz
  std::vector<RealFit> fits;                       // in the order of fit.costs
};

// Imports the record and fits it with each cost (real_execute.cc); progress on `log`.
RealResults compute_real_study(const RealStudySpec& spec, std::ostream& log);
// Every table of the study (real_tables.cc), from its results alone.
RenderedFiles render_real_study(const RealStudySpec& spec, const RealResults& results);
// Computes, renders and writes the tables to `output_dir`. Returns the number of failed fits.
int run_real_study(const RealStudySpec& spec, const std::string& output_dir, std::ostream& log);

}  // namespace beamid::study
