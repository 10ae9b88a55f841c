// beamid._core, the C++ half of the Python package (python/beamid/__init__.py is the other): the commands' typed
// requests (api/), filled from the flags that the Python keyword arguments spell (sensor_x=0.2 is --sensor-x 0.2),
// parsed by the command line's own parser (apps::parse_flags) and mapped by its own mappings (apps/flag_requests.h). A
// call and the same command line therefore run one body of code with one validation and one set of messages, and give
// the same numbers bit for bit. Results are NumPy arrays and dicts, which python/beamid/values.py turns into the
// package's typed result dataclasses; records may come as arrays (samples, or samples x
// channels) instead of files. InputError and NumericalError become beamid.InputError (a ValueError) and
// beamid.NumericalError (a RuntimeError) carrying the command line's one-line message. The GIL is released around every
// computation, so that Python threads can fit in parallel (the core is thread-safe: the studies run it on threads).
// pybind11 stays in this file: it is the package's adapter.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "api/experiment_request.h"
#include "apps/cli.h"
#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/fit_report.h"
#include "apps/flag_requests.h"
#include "config/beam_file.h"
#include "core/allocator.h"
#include "core/errors.h"
#include "core/limits.h"
#include "io/provenance.h"
#include "io/time_series.h"
#include "model/beam_parameters.h"

namespace py = pybind11;
using namespace beamid;

namespace {

// A vector handed to NumPy without a copy: the array owns it through a capsule.
py::array_t<double> owned_array(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule release(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->size())}, {static_cast<py::ssize_t>(sizeof(double))},
                             owned->data(), release);
}

py::array_t<double> copied_array(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

py::array_t<double> vector_array(const Eigen::VectorXd& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

// Row-major copy of an Eigen (column-major) matrix.
py::array_t<double> matrix_array(const Eigen::MatrixXd& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto view = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return a;
}

// A beam's parameters as a dict: every [beam] key, then "attachmentK.x/m/J/c" and "support.k_theta/k_w" (infinite:
// rigid), the keys --estimate takes.
py::dict beam_dict(const model::BeamParameters& beam) {
  py::dict d;
  for (const auto& info : model::parameter_table())
    d[py::str(std::string(info.key))] = model::parameter_value(beam, info.key);
  for (std::size_t k = 0; k < beam.attachments.size(); ++k) {  // c is a fixed property, not an estimable key
    const model::Attachment& a = beam.attachments[k];
    const std::string key = model::attachment_key(k);
    d[py::str(key + ".x")] = a.x;
    d[py::str(key + ".m")] = a.m;
    d[py::str(key + ".J")] = a.J;
    d[py::str(key + ".c")] = a.c;
  }
  d["support.k_theta"] = beam.support.k_theta;
  d["support.k_w"] = beam.support.k_w;
  return d;
}

// A record given as an array instead of a --data file, read with the command's import flags (channel, units, window,
// rate) through the same checks as a file (io::array_time_series); several --channel entries give several records.
class ArrayRecord {
 public:
  ArrayRecord(const py::object& data, const py::object& time) {
    // Longer than any record a command takes (core::kMaxSamples): refused before the array is copied as doubles (a
    // broadcast view of 2^28 + 1 samples was first copied, 2 GB in 4.4 s: the twentieth pass's P6).
    if (py::isinstance<py::array>(data)) {
      const py::array given = data.cast<py::array>();
      if (given.ndim() >= 1 && given.shape(0) > core::kMaxSamples)
        throw InputError("data: " + std::to_string(given.shape(0)) + " samples: at most 2^28 (" +
                         std::to_string(core::kMaxSamples) + "); cut the record first");
    }
    values_ = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(data);
    if (!values_ || (values_.ndim() != 1 && values_.ndim() != 2))
      throw InputError("data: must be a 1-D array of samples or a 2-D array of samples x channels");
    if (!time.is_none()) {
      auto t = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(time);
      if (!t || t.ndim() != 1) throw InputError("time: must be a 1-D array of times, s");
      time_.assign(t.data(), t.data() + t.size());
      has_time_ = true;
      // The times are as precise as the type they came in: float32 (or half) widened to double keeps its rounding.
      if (py::isinstance<py::array>(time)) {
        const py::dtype type = time.cast<py::array>().dtype();
        if (type.kind() == 'f' && type.itemsize() <= 4)
          time_precision_ = 2.0 * (type.itemsize() == 4 ? std::numeric_limits<float>::epsilon() : 9.765625e-4);
      }
    }
  }
  // One channel with a command's import options (call without the GIL: it reads the array's memory only).
  io::TimeSeries read(const io::ImportOptions& o) const {
    const std::size_t rows = static_cast<std::size_t>(values_.shape(0));
    const std::size_t columns = values_.ndim() == 2 ? static_cast<std::size_t>(values_.shape(1)) : 1;
    return io::array_time_series("<array>", values_.data(), rows, columns, has_time_ ? &time_ : nullptr, o,
                                 time_precision_);
  }

  // Samples per channel (the array's first dimension).
  double samples() const { return static_cast<double>(values_.shape(0)); }

 private:
  py::array_t<double, py::array::c_style | py::array::forcecast> values_;
  std::vector<double> time_;
  double time_precision_ = 2 * std::numeric_limits<double>::epsilon();
  bool has_time_ = false;
};

std::optional<ArrayRecord> array_record(const py::object& data, const py::object& time) {
  if (data.is_none()) return std::nullopt;
  return ArrayRecord(data, time);
}

// The records of a command (channels; one for record_of): the array when one is given, else the --data file.
std::vector<io::TimeSeries> records_of(const apps::Flags& a, const std::optional<ArrayRecord>& array) {
  if (!array) return apps::read_channels(a);
  return apps::read_channels(a, [&array](const io::ImportOptions& o) { return array->read(o); });
}
// fit's --force-channel from the array, or from the --data file.
std::optional<io::TimeSeries> force_channel_of(const apps::Flags& a, const std::optional<ArrayRecord>& array) {
  if (!array) return apps::read_force_channel(a);
  return apps::read_force_channel(a, [&array](const io::ImportOptions& o) { return array->read(o); });
}

io::TimeSeries record_of(const apps::Flags& a, const std::optional<ArrayRecord>& array) {
  if (!array) return apps::read_data(a);
  return apps::read_data(a, [&array](const io::ImportOptions& o) { return array->read(o); });
}

// A command's flags as the command line parses them; a beam given as a dict comes as TOML text (beam_toml, the
// package's beam_toml()) and is read from memory for --beam (its value, "<beam dict>", names it in messages).
apps::Flags flags_of(const char* command, const std::vector<std::string>& args,
                     const std::optional<std::string>& beam_toml) {
  apps::Flags flags = apps::parse_flags(command, args);
  if (beam_toml) flags.set_inline("beam", *beam_toml);
  return flags;
}

// A command's computation on its parsed flags, run without the GIL (parsing included: it reads beam files).
template <typename Compute>
auto without_gil(const char* command, const std::vector<std::string>& args, Compute compute,
                 const std::optional<std::string>& beam_toml = std::nullopt) {
  py::gil_scoped_release unlocked;
  return compute(flags_of(command, args, beam_toml));
}

// What a computation wrote to its warnings stream, one line each: the Python package raises them as warnings, as the
// command line prints them on stderr (they went to the process's stderr: the fourteenth pass's P8).
py::list warning_lines(const std::ostringstream& warnings) {
  py::list lines;
  std::istringstream in(warnings.str());
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.append(line);
  return lines;
}

py::dict py_simulate(const std::vector<std::string>& args, const std::optional<std::string>& beam_toml) {
  std::ostringstream warned;
  api::SimulateResult r = without_gil(
      "simulate", args,
      [&warned](const apps::Flags& a) { return api::compute_simulate(apps::simulate_request_of(a), warned); },
      beam_toml);
  py::dict d;
  d["warnings"] = warning_lines(warned);
  d["dt_s"] = r.run.experiment.dt_s;
  d["output"] = r.run.experiment.output;
  d["integrator"] = r.trace.stats.integrator;
  d["modes"] = r.trace.stats.modes;
  d["steps"] = r.trace.stats.steps;
  d["y"] = owned_array(std::move(r.y));
  if (!r.force_N.empty()) d["force"] = owned_array(std::move(r.force_N));
  return d;
}

py::dict py_modes(const std::vector<std::string>& args, const std::optional<std::string>& beam_toml) {
  std::ostringstream warned;
  const api::ModesResult r = without_gil(
      "modes", args, [&warned](const apps::Flags& a) { return api::compute_modes(apps::modes_request_of(a), warned); },
      beam_toml);
  py::dict d;
  d["warnings"] = warning_lines(warned);
  d["kind"] = r.kind;
  d["available"] = r.available;
  d["note"] = r.note;
  d["frequency_hz"] = copied_array(r.frequency_hz);
  d["damping_ratio"] = copied_array(r.damping_ratio);
  return d;
}

py::dict py_system(const std::vector<std::string>& args, const std::optional<std::string>& beam_toml) {
  std::ostringstream warned;
  const api::SystemResult r = without_gil(
      "system", args,
      [&warned](const apps::Flags& a) { return api::compute_system(apps::model_run_request_of(a), warned); },
      beam_toml);
  py::dict d;
  d["warnings"] = warning_lines(warned);
  d["beam"] = r.run.beam_name;
  d["length_m"] = r.run.beam.l;
  d["elements"] = r.run.elements;
  d["M"] = matrix_array(r.system.M);
  d["C"] = matrix_array(r.system.C);
  d["K"] = matrix_array(r.system.K);
  d["load"] = vector_array(r.problem.load);
  d["sensor"] = vector_array(r.problem.sensor);
  d["w0"] = vector_array(r.problem.w0);
  d["amplitude_N"] = r.problem.amplitude_N;
  d["pulse_width_s"] = r.problem.pulse_width_s;
  d["derivative"] = r.problem.derivative;
  d["dt_s"] = r.problem.dt_s;
  d["samples"] = r.problem.samples;
  return d;
}

py::dict py_spikes(const std::vector<std::string>& args, const py::object& data, const py::object& time) {
  const auto array = array_record(data, time);
  const api::SpikesResult r = without_gil("spikes", args, [&array](const apps::Flags& a) {
    return api::compute_spikes(apps::spikes_request_of(a), record_of(a, array));
  });
  py::dict d;
  py::list picks, skipped;
  const auto row = [&r](const signal::Spike& s, const signal::MeasuredMode* measured) {
    py::dict p;
    p["bin"] = s.bin;
    p["frequency_hz"] = s.frequency_hz;
    p["magnitude"] = s.magnitude;
    p["n_left"] = s.n_left;
    p["n_right"] = s.n_right;
    const signal::PoleEstimate e = r.subbin(s.bin);
    p["subbin_frequency_hz"] = e.frequency_hz;
    p["decay_rate_1_s"] = e.decay_rate_1_s;
    p["measured_frequency_hz"] = measured ? measured->mode.frequency_hz : std::nan("");
    p["measured_uncertainty_hz"] = measured ? measured->uncertainty_hz : std::nan("");
    return p;
  };
  for (std::size_t k = 0; k < r.picks.size(); ++k) picks.append(row(r.picks[k], &r.measured[k]));
  for (const auto& p : r.peaks)
    if (!p.skipped.empty()) {
      py::dict s = row(p.spike, nullptr);
      s["reason"] = p.skipped;
      skipped.append(s);
    }
  d["picks"] = picks;
  d["skipped"] = skipped;
  d["requested"] = r.requested;
  d["df_hz"] = r.spectrum.df_hz();
  py::list notes;
  if (!r.measured_note.empty()) notes.append(r.measured_note);
  for (const std::string& note : r.notes) notes.append(note);
  d["notes"] = notes;
  return d;
}

py::dict py_cost(const std::vector<std::string>& args, const py::object& data, const py::object& time,
                 const py::object& prediction) {
  const auto array = array_record(data, time);
  std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> predicted;
  if (!prediction.is_none()) {
    predicted = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(prediction);
    if (!*predicted || predicted->ndim() != 1) throw InputError("prediction: must be a 1-D array of samples");
  }
  costs::Evaluation e;
  {
    py::gil_scoped_release unlocked;
    const apps::Flags a = apps::parse_flags("cost", args);
    const io::TimeSeries record = record_of(a, array);
    io::TimeSeries model;
    if (predicted) {  // an array of the data's length at the data's step
      model.path = "<array>";
      model.dt_s = record.dt_s;
      model.values.assign(predicted->data(), predicted->data() + predicted->size());
    } else {
      model = apps::read_prediction(a, record);
    }
    e = api::compute_cost(apps::cost_evaluation_request_of(a), record, model);
  }
  py::dict d;
  d["value"] = e.value;
  d["a4"] = e.a4;
  d["amplitude_scale"] = e.amplitude_scale;
  d["residuals"] = vector_array(e.residuals);
  return d;
}

py::dict parameter_row(const fit::ParameterEstimate& p, double window_sd, double window_se) {
  py::dict d;
  d["parameter"] = p.key;
  d["estimate"] = p.estimate;
  d["standard_error"] = p.standard_error;
  d["start"] = p.start;
  d["lower"] = p.lower;
  d["upper"] = p.upper;
  d["status"] = p.status;
  d["robust_standard_error"] = p.robust_standard_error;
  d["window_sd"] = window_sd;
  d["window_standard_error"] = window_se;
  return d;
}

// What a fit checks before its record is read: the report's paths, and the memory guard on an array's length (reading
// and checking 2^27 samples took 26 s, and then the same guard refused the fit: the twentieth pass's P6; its warnings
// come from the fit's own guard, later).
void check_before_reading(const apps::Flags& a, const std::optional<ArrayRecord>& array) {
  apps::check_report_outputs(a);
  if (!array) return;
  std::ostringstream later;
  api::guard_run_size(apps::caller_of(a), static_cast<int>(a.integer("elements")), array->samples(),
                      core::kRecordBytesPerSample, later);
}

// Whether `event` (None, or a threading.Event) is set; called without the GIL.
bool is_set(const py::object& event) {
  if (event.is_none()) return false;
  py::gil_scoped_acquire locked;
  return event.attr("is_set")().cast<bool>();
}

// fit's report (with a beam dict's TOML), unless the caller was interrupted meanwhile (`abandoned`, below).
void write_report(const apps::Flags& a, const apps::FitReportInput& input, const apps::ModeComparison& modes,
                  const std::optional<std::string>& beam_toml, const py::object& abandoned) {
  if (!a.has("report") || is_set(abandoned)) return;
  apps::FitReportInput with = input;
  with.modes = &modes;
  with.beam_toml = beam_toml ? &*beam_toml : nullptr;
  apps::write_fit_report(a.text("report"), with);
}

// `abandoned`: None, or a threading.Event the package sets when the caller was interrupted (Ctrl-C) while this ran
// on its worker thread: the fit then finishes in the background, but writes no report (an interrupted fit replaced a
// newer fit's report at the same path 12 s later: the twenty-second pass's P1).
// --profile's intervals: their lines among the messages, as on the command line, and their numbers by key.
py::dict profiles_dict(const std::vector<fit::Profile>& profiles, const api::FitNotes& notes, py::list& messages) {
  py::dict out;
  for (const fit::Profile& p : profiles) {
    messages.append(api::profile_line(p, notes));
    py::dict q;
    q["estimate"] = p.estimate;
    q["standard_error"] = p.standard_error;
    q["interval_68"] = py::make_tuple(p.lower68, p.upper68);
    q["interval_95"] = py::make_tuple(p.lower95, p.upper95);
    q["open_below"] = p.open_below;
    q["open_above"] = p.open_above;
    py::list values, statistics;
    for (const fit::ProfilePoint& point : p.points) values.append(point.value), statistics.append(point.statistic);
    q["values"] = values;
    q["statistic"] = statistics;  // (S(v) - S_min) / s^2 at each value: chi^2_1 at the interval's level
    out[py::str(p.key)] = q;
  }
  return out;
}

// --posterior: its lines among the messages, as on the command line, and its numbers: by key, the summaries; the
// draws (rows: every kept draw, columns: the keys' order), the correlation, the evidences and the chains' verdict.
py::object posterior_dict(const std::optional<fit::Posterior>& posterior, py::list& messages) {
  if (!posterior) return py::none();
  const fit::Posterior& p = *posterior;
  for (const std::string& line : api::posterior_lines(p)) messages.append(line);
  py::dict out, parameters;
  py::list keys;
  for (const fit::PosteriorParameter& q : p.parameters) {
    py::dict s;
    s["mean"] = q.mean, s["sd"] = q.sd, s["median"] = q.median;
    s["interval_95"] = py::make_tuple(q.lower95, q.upper95);
    s["rhat"] = q.rhat, s["effective_samples"] = q.effective_samples;
    parameters[py::str(q.key)] = s;
    keys.append(q.key);
  }
  out["keys"] = keys;
  out["parameters"] = parameters;
  out["draws"] = matrix_array(p.samples.draws);
  out["correlation"] = matrix_array(p.correlation);
  out["status"] = p.status;
  out["acceptance"] = p.samples.acceptance;
  out["evaluations"] = p.samples.evaluations;
  out["log_evidence_laplace"] = p.log_evidence_laplace;
  out["log_evidence_sampled"] = py::make_tuple(p.log_evidence_sampled, p.log_evidence_sampled_se);
  return out;
}

// --profile's and --posterior's entries of a fit's dict, their lines among the messages.
void add_uncertainty(py::dict& d, const api::FitComputation& c, const api::FitNotes& notes, py::list& messages) {
  d["profiles"] = profiles_dict(c.profiles, notes, messages);
  d["posterior"] = posterior_dict(c.posterior, messages);
}

py::dict py_fit(const std::vector<std::string>& args, const std::optional<std::string>& beam_toml,
                const py::object& data, const py::object& time, const py::object& abandoned) {
  std::ostringstream warned;
  const auto array = array_record(data, time);
  std::optional<api::FitComputation> c;
  std::vector<io::TimeSeries> channels;
  std::optional<apps::ModeComparison> modes;
  std::string beam_name;
  {
    py::gil_scoped_release unlocked;
    const apps::Flags a = flags_of("fit", args, beam_toml);
    check_before_reading(a, array);
    channels = records_of(a, array);
    c = api::compute_fit(apps::fit_request_of(a, force_channel_of(a, array)), channels, warned);
    beam_name = a.text("beam");
    const apps::FitReportInput input{
        c->options, c->result, channels.front(), beam_name, a.arguments(), channels, c->spread ? &*c->spread : nullptr};
    modes = apps::compare_modes(input);
    write_report(a, input, *modes, beam_toml, abandoned);
  }
  const fit::FitResult& r = c->result;
  py::dict d;
  py::list parameters;
  py::dict estimates;
  const double nan = std::nan("");
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    parameters.append(parameter_row(r.parameters[i], c->spread ? c->spread->sd[i] : nan,
                                    c->spread ? c->spread->standard_error[i] : nan));
    estimates[py::str(r.parameters[i].key)] = r.parameters[i].estimate;
  }
  d["parameters"] = parameters;
  d["estimates"] = estimates;
  d["status"] = r.status;
  d["termination"] = r.termination;
  d["a4"] = r.final_evaluation.a4;
  // What the command says on stderr beside its summary line (api::fit_notes), and (A4) when violated.
  // fit's own lines without the command's name, which the package's warnings add ("beamid fit: beamid fit: ...").
  py::list messages;
  for (const py::handle line : warning_lines(warned)) {
    std::string text = line.cast<std::string>();
    if (text.rfind("beamid fit: ", 0) == 0) text.erase(0, 12);
    messages.append(text);
  }
  const api::FitNotes notes = api::fit_notes(r, c->options.cost);
  for (const std::string& note : notes.lines()) messages.append(note);
  if (r.final_evaluation.a4 != "ok" && notes.pairing.empty()) messages.append(r.final_evaluation.a4);
  if (c->spread) messages.append(api::window_spread_line(*c->spread, r));
  add_uncertainty(d, *c, notes, messages);
  d["cost"] = r.cost;
  d["evaluations"] = r.evaluations;
  d["wall_time_s"] = r.wall_time_s;
  d["covariance_status"] = r.covariance_status;
  d["sandwich_status"] = r.sandwich_status;
  d["correlation"] = matrix_array(r.correlation);
  d["beam"] = beam_dict(r.beam);
  d["model_output"] = copied_array(r.model_output);
  py::dict identifiability;
  identifiability["status"] = r.identifiability.status;
  identifiability["verdict"] = r.identifiability.verdict;
  identifiability["condition"] = r.identifiability.condition;
  identifiability["weakest"] = r.identifiability.combination();
  identifiability["of_interest"] = r.identifiability.keys;  // what the verdict is about
  identifiability["nuisance"] = r.identifiability.nuisance;
  identifiability["on_bound"] = r.identifiability.on_bound;
  d["identifiability"] = identifiability;
  py::list mode_rows;
  for (const auto& p : modes->pairs) {
    py::dict m;
    m["data_hz"] = p.data_hz;
    m["data_damping_ratio"] = p.data_damping_ratio;
    m["model_hz"] = p.model_hz;
    m["model_damping_ratio"] = p.model_damping_ratio;
    m["data_uncertainty_hz"] = p.data_uncertainty_hz;
    m["data_decay_1_s"] = p.data_decay_1_s;
    m["data_decay_uncertainty_1_s"] = p.data_decay_uncertainty_1_s;
    m["model_decay_1_s"] = p.model_decay_1_s;
    mode_rows.append(m);
    if (!p.data_note.empty()) messages.append("the record: " + p.data_note);
  }
  // The CLI's order and set: both misfit notes (the damping one was dropped here: the eighteenth pass's P2).
  for (const std::string& note : modes->notes) messages.append(note);
  for (const std::string& note : {apps::modes_mismatch_note(*modes), apps::damping_mismatch_note(*modes)})
    if (!note.empty()) messages.append(note);
  d["modes"] = mode_rows;
  d["modes_status"] = modes->status;
  d["messages"] = messages;
  py::list records;
  for (const auto& part : r.records) {
    py::dict rec;
    rec["name"] = part.name;
    rec["cost"] = part.evaluation.value;
    rec["status"] = part.evaluation.status;
    rec["weight"] = part.weight;
    rec["amplitude_scale"] = part.evaluation.amplitude_scale;
    records.append(rec);
  }
  d["records"] = records;
  d["commit"] = io::commit_label();
  return d;
}

py::dict py_crb(const std::vector<std::string>& args, const std::optional<std::string>& beam_toml) {
  std::ostringstream warned;
  const api::CrbResult r = without_gil(
      "crb", args, [&warned](const apps::Flags& a) { return api::compute_crb(apps::crb_request_of(a), warned); },
      beam_toml);
  py::dict d;
  d["warnings"] = warning_lines(warned);
  d["parameters"] = r.keys;
  d["value"] = copied_array(r.values);
  d["crb_sd"] = vector_array(r.bound.sd);
  d["crb_relative_sd"] = vector_array(r.bound.relative_sd);
  d["noise_sd"] = r.noise_sd;
  d["method"] = r.bound.method;
  d["covariance"] = matrix_array(r.bound.covariance);
  d["rcond"] = r.bound.rcond;
  return d;
}

py::dict py_design(const std::vector<std::string>& args, const std::optional<std::string>& beam_toml) {
  std::ostringstream warned;
  const api::DesignResult r = without_gil(
      "design", args,
      [&warned](const apps::Flags& a) { return api::compute_design(apps::design_request_of(a), warned); }, beam_toml);
  py::dict d;
  d["warnings"] = warning_lines(warned);
  d["parameters"] = r.options.keys;
  d["criterion_name"] = r.options.criterion;
  d["noise_model"] = r.options.noise_model;
  py::list sensors, status;
  std::vector<double> force, width, dt, criterion;
  std::vector<double> samples;
  Eigen::MatrixXd relative(static_cast<Eigen::Index>(r.rows.size()), static_cast<Eigen::Index>(r.options.keys.size()));
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const fit::DesignRow& row = r.rows[i];
    sensors.append(copied_array(row.candidate.sensors_x_m));
    force.push_back(row.candidate.force_x_m);
    width.push_back(row.candidate.pulse_width_s);
    dt.push_back(row.candidate.dt_s);
    samples.push_back(row.candidate.samples);
    criterion.push_back(row.criterion);
    relative.row(static_cast<Eigen::Index>(i)) = row.relative_sd.transpose();
    status.append(row.status);
  }
  d["sensors_x_m"] = sensors;
  d["force_x_m"] = copied_array(force);
  d["pulse_width_s"] = copied_array(width);
  d["dt_s"] = copied_array(dt);
  d["samples"] = copied_array(samples);
  d["criterion"] = copied_array(criterion);
  d["relative_sd"] = matrix_array(relative);
  d["status"] = status;
  d["commit"] = io::commit_label();
  return d;
}

py::dict py_modal_id(const std::vector<std::string>& args, const py::object& data, const py::object& time) {
  const auto array = array_record(data, time);
  const api::ModalIdResult r = without_gil("modal-id", args, [&array](const apps::Flags& a) {
    return api::compute_modal_id(apps::modal_id_request_of(a), record_of(a, array));
  });
  std::vector<double> f, zeta, amplitude, phase, f_sd, drift, low, high, uncertainty, zeta_u;
  for (const auto& measured : r.measured) {
    const auto& m = measured.mode;
    f.push_back(m.frequency_hz);
    zeta.push_back(m.damping_ratio);
    amplitude.push_back(m.amplitude);
    phase.push_back(m.phase_rad);
    f_sd.push_back(m.frequency_sd_hz);
    drift.push_back(measured.drift_hz);
    low.push_back(measured.span_low_hz);
    high.push_back(measured.span_high_hz);
    uncertainty.push_back(measured.uncertainty_hz);
    zeta_u.push_back(measured.damping_ratio_uncertainty());
  }
  py::dict d;
  d["frequency_hz"] = copied_array(f);
  d["damping_ratio"] = copied_array(zeta);
  d["amplitude"] = copied_array(amplitude);
  d["phase_rad"] = copied_array(phase);
  d["frequency_sd_hz"] = copied_array(f_sd);
  d["drift_hz"] = copied_array(drift);
  d["span_low_hz"] = copied_array(low);
  d["span_high_hz"] = copied_array(high);
  d["frequency_uncertainty_hz"] = copied_array(uncertainty);
  d["damping_ratio_uncertainty"] = copied_array(zeta_u);
  d["notes"] = r.notes;
  return d;
}

py::dict py_read_record(const std::vector<std::string>& args) {
  io::TimeSeries s = without_gil("modal-id", args, [](const apps::Flags& a) { return apps::read_data(a); });
  py::dict d;
  d["path"] = s.path;
  d["format"] = s.format;
  d["channel"] = s.value_column;
  d["unit"] = s.unit;
  d["t0_s"] = s.t0_s;
  d["dt_s"] = s.dt_s;
  d["notes"] = s.notes;
  d["values"] = owned_array(std::move(s.values));
  return d;
}

// A command's flags as the registry states them (apps/registry.cc): name, kind (text, number, integer, switch),
// help, whether required, and an integer's range; what the package builds its functions' signatures from.
py::list command_flags(const std::string& name) {
  const auto& all = apps::commands();
  const auto it = std::find_if(all.begin(), all.end(), [&](const apps::Command& c) { return c.name == name; });
  if (it == all.end()) throw InputError("no command '" + name + "'");
  py::list flags;
  for (const apps::FlagSpec& f : it->flags) {
    py::dict d;
    d["name"] = f.name;
    d["kind"] = f.kind == apps::FlagKind::Number    ? "number"
                : f.kind == apps::FlagKind::Integer ? "integer"
                : f.kind == apps::FlagKind::Switch  ? "switch"
                                                    : "text";
    d["help"] = f.help;
    d["required"] = f.required;
    d["min"] = f.min;
    d["max"] = f.max;
    flags.append(d);
  }
  return flags;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "beamid's C++ core (use the beamid package, not this module)";
  // The allocator keeps freed memory, as the program's does (core/allocator.h: a forward run 1.8x faster without the
  // page faults of a trimmed heap); the Python process then holds its peak heap until it exits (README, Python).
  beamid::core::keep_freed_memory();
  // The exception types live as long as the process, never destroyed: py::register_exception keeps them in
  // function-local statics whose destructors decref after the interpreter has finalized, which can crash at exit
  // (seen once in CI: "Segmentation fault" after the last test passed). Leaked on purpose, translated by hand.
  static const auto* input_error = new py::exception<InputError>(m, "InputError", PyExc_ValueError);
  static const auto* numerical_error = new py::exception<NumericalError>(m, "NumericalError", PyExc_RuntimeError);
  static const auto* output_error = new py::exception<OutputError>(m, "OutputError", PyExc_OSError);
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error->ptr(), e.what());
    } catch (const NumericalError& e) {
      PyErr_SetString(numerical_error->ptr(), e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(output_error->ptr(), e.what());
    }
  });
  m.def("version", [] { return io::version() + " (commit " + io::commit_label() + ")"; });
  m.def("presets", [] { return model::preset_names(); });
  m.def("command_help", &apps::command_help);
  m.def("command_flags", &command_flags);
  m.def("beam", [](const std::string& spec) { return beam_dict(config::resolve_beam(spec)); });
  m.def("parse_beam", [](const std::string& text, const std::string& name) {
    return beam_dict(config::parse_beam_toml(text, name));
  });
  m.def("simulate", &py_simulate);
  m.def("modes", &py_modes);
  m.def("system", &py_system);
  m.def("spikes", &py_spikes);
  m.def("cost", &py_cost);
  m.def("fit", &py_fit);
  m.def("crb", &py_crb);
  m.def("design", &py_design);
  m.def("modal_id", &py_modal_id);
  m.def("read_record", &py_read_record);
}
