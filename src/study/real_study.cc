#include "study/real_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "fit/identification.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "io/provenance.h"
#include "io/time_series.h"
#include "model/beam_toml.h"
#include "model/errors.h"
#include "model/toml_reader.h"
#include "signal/noise.h"
#include "signal/spectrum.h"
#include "signal/spikes.h"
#include "study/outputs.h"

namespace beamid::study {
namespace fs = std::filesystem;
namespace {

using model::TableReader;

const toml::table& table_of(const toml::table& root, const std::string& name, const std::string& source) {
  const toml::node* node = root.get(name);
  if (node == nullptr) throw InputError(source + ":1: missing table [" + name + "]");
  if (!node->is_table())
    throw InputError(source + ":" + std::to_string(node->source().begin.line) + ": " + name + " must be a table");
  return *node->as_table();
}

std::string g3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}


}  // namespace

RealStudySpec load_real_study(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the study file");
  std::ostringstream text;
  text << in.rdbuf();
  toml::table root;
  try {
    root = toml::parse(text.str(), path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                     std::string(e.description()));
  }
  for (auto&& [key, node] : root)
    if (key.str() != "study" && key.str() != "record" && key.str() != "beam" && key.str() != "fit")
      throw InputError(path + ":" + std::to_string(key.source().begin.line) + ": unknown table [" +
                       std::string(key.str()) + "]: valid tables are study, record, beam, fit");
  const fs::path dir = fs::path(path).parent_path();
  const auto relative = [&](const std::string& f) { return fs::path(f).is_absolute() ? f : (dir / f).string(); };
  RealStudySpec s;
  s.path = path;
  s.file_hash = hex64(signal::fnv1a64(text.str()));
  const auto positive = [](double v) { return v > 0; };
  {
    TableReader r(table_of(root, "study", path), "study.", path);
    s.name = r.string("name", std::nullopt);
    s.question = r.string("question", std::nullopt);
    r.finish({"name", "question"});
  }
  {
    TableReader r(table_of(root, "record", path), "record.", path);
    s.record_file = relative(r.string("file", std::nullopt));
    if (!fs::exists(s.record_file)) r.fail("file", "'" + s.record_file + "'", "must be an existing record file");
    s.channel = r.string("channel", "");
    s.units = r.string("units", s.units, {"auto", "g", "as-is"});
    if (r.has("start_s")) s.start_s = r.number("start_s", std::nullopt, [](double v) { return v >= 0; }, "must be >= 0");
    if (r.has("duration_s")) s.duration_s = r.number("duration_s", std::nullopt, positive, "must be > 0");
    if (const toml::node* n = r.get("resample")) {
      if (!n->is_boolean()) r.fail("resample", TableReader::text(*n), "must be true or false");
      s.resample = *n->value<bool>();
    }
    s.peaks_hz = r.numbers("peaks_hz", positive, "must be > 0 (Hz)");
    if (s.peaks_hz.empty()) r.fail("peaks_hz", "[]", "must list the measured peak frequencies of the modes to fit");
    std::sort(s.peaks_hz.begin(), s.peaks_hz.end());
    r.finish({"file", "channel", "units", "start_s", "duration_s", "resample", "peaks_hz"});
  }
  {
    TableReader r(table_of(root, "beam", path), "beam.", path);
    s.beam_file = relative(r.string("file", std::nullopt));
    r.finish({"file"});
  }
  {
    TableReader r(table_of(root, "fit", path), "fit.", path);
    s.elements = r.integer("elements", s.elements, 1, 200);
    std::vector<std::string> keys;
    for (const auto& info : model::parameter_table()) keys.emplace_back(info.key);
    s.estimate = r.strings("estimate", true, keys);
    s.costs = r.strings("costs", true, {"time", "spike", "spike-smooth"});
    s.max_evaluations = r.integer("max_evaluations", s.max_evaluations, 10, 1000000);
    if (const toml::node* n = r.get("bounds")) {
      const toml::table* t = n->as_table();
      if (t == nullptr) r.fail("bounds", TableReader::text(*n), "must be a table KEY = [lo, hi]");
      for (auto&& [key, value] : *t) {
        const std::string k(key.str());
        const toml::array* a = value.as_array();
        const auto line = path + ":" + std::to_string(value.source().begin.line) + ": fit.bounds." + k;
        if (std::find(s.estimate.begin(), s.estimate.end(), k) == s.estimate.end())
          throw InputError(line + ": '" + k + "' is not in fit.estimate");
        if (a == nullptr || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
          throw InputError(line + " = " + TableReader::text(value) + ": must be [lower, upper]");
        const double lo = *(*a)[0].value<double>(), hi = *(*a)[1].value<double>();
        if (!(lo >= 0 && hi > lo)) throw InputError(line + " = [" + format_value(lo) + ", " + format_value(hi) + "]: must have 0 <= lower < upper");
        s.bounds[k] = {lo, hi};
      }
    }
    r.finish({"elements", "estimate", "costs", "max_evaluations", "bounds"});
  }
  model::load_beam_toml(s.beam_file);  // checked before anything runs
  return s;
}

int run_real_study(const RealStudySpec& spec, const std::string& output_dir, std::ostream& log) {
  const fs::path dir(output_dir);
  io::ImportOptions import;
  import.channel = spec.channel;
  import.units = spec.units;
  import.start_s = spec.start_s;
  import.duration_s = spec.duration_s;
  import.resample = spec.resample;
  const io::TimeSeries record = io::read_time_series(spec.record_file, import);
  const model::BeamParameters nominal = model::load_beam_toml(spec.beam_file);
  log << "beamid real " << spec.path << " (commit " << io::commit_label() << "): " << record.values.size()
      << " samples at " << g3(1 / record.dt_s) << " Hz from " << spec.record_file << " (" << record.notes << ") "
      << spec.costs.size() << " fits at N = " << spec.elements << "\n";

  fit::FitOptions base;
  base.start = nominal;
  base.elements = spec.elements;
  base.experiment.excitation = "free-decay";
  base.experiment.dt_s = record.dt_s;
  base.experiment.samples = static_cast<int>(record.values.size());
  base.cost.spikes.frequencies_hz = spec.peaks_hz;
  base.cost.spikes.count = static_cast<int>(spec.peaks_hz.size());
  base.optimizer.max_evaluations = spec.max_evaluations;
  for (const auto& key : spec.estimate) {
    const double v = nominal.*(model::find_parameter(key)->member);
    const auto b = spec.bounds.count(key) ? spec.bounds.at(key) : std::make_pair(v / 2, v * 2);
    base.estimate.push_back({key, b.first, b.second});
  }

  std::ostringstream fits, modes, timings, md;
  fits << "cost,status,cost_value,evaluations,parameter,estimate,standard_error,nominal,ratio_to_nominal\n";
  modes << "cost,mode,measured_frequency_hz,identified_frequency_hz,identified_damping_ratio\n";
  timings << "cost,wall_time_s\n";
  std::vector<std::pair<std::string, Overlay>> overlays;
  std::vector<double> measured;         // the data's sub-bin peak frequencies near peaks_hz
  std::vector<double> measured_zeta;    // and damping ratios, sigma / |lambda| from the 3-bin decay rates
  {
    signal::Dft dft(static_cast<int>(record.values.size()), record.dt_s);
    const signal::Spectrum z = dft.transform(record.values);
    for (const auto& s : signal::detect_spikes(z, base.cost.spikes)) {
      const auto e = signal::three_bin_estimate(z, s.bin);
      measured.push_back(e.ok ? e.frequency_hz : s.frequency_hz);
      const double w = 2 * std::numbers::pi * measured.back();
      measured_zeta.push_back(e.ok ? e.decay_rate_1_s / std::hypot(e.decay_rate_1_s, w) : std::nan(""));
    }
  }
  if (measured.size() != spec.peaks_hz.size())
    throw InputError(spec.path + ": record.peaks_hz: " + std::to_string(spec.peaks_hz.size() - measured.size()) +
                     " of the peaks have no local maximum of the record's spectrum within 5 %");
  struct Outcome {
    std::string cost, status;
    std::vector<double> estimate, identified_hz, zeta;
    double ei_ratio = 0;
  };
  std::vector<Outcome> outcomes;
  int failed = 0;
  for (const auto& cost : spec.costs) {
    fit::FitOptions o = base;
    o.cost.name = cost;
    o.optimizer.method = fit::default_optimizer(cost);
    const auto t0 = std::chrono::steady_clock::now();
    Outcome out;
    out.cost = cost;
    fit::FitResult r;
    try {
      r = fit::fit(o, record.values);
      out.status = r.status;
    } catch (const std::exception& e) {
      out.status = std::string("failed: ") + e.what();
    }
    timings << cost << "," << full(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) << "\n";
    log << cost << ": " << out.status << ", cost " << g3(r.cost) << ", " << r.evaluations << " evaluations\n";
    if (out.status.rfind("failed", 0) == 0) {
      ++failed;
      fits << cost << "," << json_string(out.status) << ",inf,0,,,,,\n";
      outcomes.push_back(out);
      continue;
    }
    for (const auto& p : r.parameters) {
      const double v = nominal.*(model::find_parameter(p.key)->member);
      fits << cost << "," << r.status << "," << full(r.cost) << "," << r.evaluations << "," << p.key << ","
           << full(p.estimate) << "," << full(p.standard_error) << "," << full(v) << "," << full(p.estimate / v) << "\n";
      out.estimate.push_back(p.estimate);
      if (p.key == "EI") out.ei_ratio = p.estimate / v;
    }
    // Identified modes: the Galerkin modes at the estimate nearest to each measured peak (paired by frequency).
    const galerkin::SplineSpace space(spec.elements);
    const auto damped = galerkin::StateSpaceModes(galerkin::assemble(space, r.beam)).underdamped_modes();
    for (std::size_t m = 0; m < measured.size(); ++m) {
      const galerkin::DampedMode* best = nullptr;
      for (const auto& d : damped)
        if (best == nullptr || std::abs(d.frequency_hz - measured[m]) < std::abs(best->frequency_hz - measured[m])) best = &d;
      out.identified_hz.push_back(best->frequency_hz);
      out.zeta.push_back(best->damping_ratio);
      modes << cost << "," << m + 1 << "," << full(measured[m]) << "," << full(best->frequency_hz) << ","
            << full(best->damping_ratio) << "\n";
    }
    // Residuals in time and frequency.
    fit::Objective objective(o, record.values);
    const auto at = objective.evaluate(r.beam);
    Overlay ov;
    signal::Dft dft(static_cast<int>(record.values.size()), record.dt_s);
    const signal::Spectrum zs = dft.transform(record.values);
    const bool have = at.y.size() == record.values.size();
    const signal::Spectrum us = have ? dft.transform(at.y) : zs;
    for (std::size_t i = 0; i < record.values.size(); ++i) {
      ov.t_s.push_back(static_cast<double>(i) * record.dt_s);
      ov.data.push_back(record.values[i]);
      ov.model.push_back(have ? at.y[i] : std::numeric_limits<double>::quiet_NaN());
    }
    for (int k = 0; k <= zs.last_bin(); ++k) {
      ov.frequency_hz.push_back(zs.frequency_hz(k));
      ov.data_magnitude.push_back(zs.magnitude(k));
      ov.model_magnitude.push_back(have ? us.magnitude(k) : std::numeric_limits<double>::quiet_NaN());
    }
    for (const auto& p : objective.cost().data_spikes()) {
      ov.spike_bins.push_back(p.data.bin);
      ov.support_left.push_back(p.data.n_left);
      ov.support_right.push_back(p.data.n_right);
    }
    overlays.emplace_back(cost, std::move(ov));
    outcomes.push_back(out);
  }

  // report.md: the generated block.
  md << "*Study `" << spec.name << "` (`" << spec.path << "`), commit " << io::commit_label() << ": "
     << record.values.size() << " samples at " << g3(1 / record.dt_s) << " Hz of `" << record.value_column << "` ("
     << record.notes.substr(0, record.notes.size() >= 2 ? record.notes.size() - 2 : 0) << "), free decay with unknown initial state (mode amplitudes solved in closed form), "
     << "Galerkin N = " << spec.elements << "; estimated ";
  for (std::size_t i = 0; i < spec.estimate.size(); ++i) md << (i ? ", " : "") << spec.estimate[i];
  md << "; the other parameters at their nominal values (`" << fs::path(spec.beam_file).filename().string() << "`).*\n\n";
  md << "Computed claims:\n\n";
  for (const auto& o : outcomes) {
    if (o.identified_hz.empty()) {
      md << "- `[false]` " << o.cost << " fits the record (" << o.status << ")\n";
      continue;
    }
    int within = 0;
    double worst = 0;
    for (std::size_t m = 0; m < measured.size(); ++m) {
      const double e = std::abs(o.identified_hz[m] / measured[m] - 1);
      worst = std::max(worst, e);
      within += e <= 0.015 ? 1 : 0;
    }
    md << "- `[" << (within == static_cast<int>(measured.size()) ? "true" : "false") << "]` " << o.cost
       << ": every identified frequency within 1.5 % of its measured peak (" << within << "/" << measured.size()
       << "; worst " << g3(100 * worst) << " %)\n";
  }
  md << "\n| cost | status |";
  for (const auto& k : spec.estimate) md << " " << k << " (x nominal) |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < spec.estimate.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& o : outcomes) {
    md << "| " << o.cost << " | " << o.status << " |";
    for (std::size_t i = 0; i < spec.estimate.size(); ++i) {
      if (i >= o.estimate.size()) {
        md << " - |";
        continue;
      }
      const double v = nominal.*(model::find_parameter(spec.estimate[i])->member);
      md << " " << g3(o.estimate[i]) << " (" << g3(o.estimate[i] / v) << ") |";
    }
    md << "\n";
  }
  md << "\n| mode | measured f (Hz) | measured zeta |";
  for (const auto& o : outcomes) md << " " << o.cost << " f (Hz) | " << o.cost << " zeta |";
  md << "\n|---|---|---|";
  for (std::size_t i = 0; i < outcomes.size(); ++i) md << "---|---|";
  md << "\n";
  for (std::size_t m = 0; m < measured.size(); ++m) {
    md << "| " << m + 1 << " | " << g3(measured[m]) << " | " << g3(measured_zeta[m]) << " |";
    for (const auto& o : outcomes)
      md << " " << (m < o.identified_hz.size() ? g3(o.identified_hz[m]) : "-") << " | "
         << (m < o.zeta.size() ? g3(o.zeta[m]) : "-") << " |";
    md << "\n";
  }
  md << "\nPlots: [residuals in time and frequency](plots/" << spec.name << "/overlay.png), [the record's spectrum "
     << "with the chosen spikes](plots/" << spec.name << "/spectrum.png).\n";

  std::ostringstream manifest;
  manifest << "{\n  \"study\": " << json_string(spec.name) << ",\n  \"question\": " << json_string(spec.question)
           << ",\n  \"study_file\": " << json_string(spec.path) << ",\n  \"study_file_fnv1a64\": \"" << spec.file_hash
           << "\",\n  \"record\": " << json_string(spec.record_file) << ",\n  \"record_notes\": "
           << json_string(record.notes) << ",\n  \"commit\": \"" << io::commit() << "\",\n  \"dirty\": "
           << (io::dirty() ? "true" : "false") << ",\n  \"beamid_version\": \"" << io::version()
           << "\",\n  \"compiler\": " << json_string(compiler()) << ",\n  \"libraries\": " << library_versions_json()
           << "\n}\n";
  write_file(dir / "manifest.json", manifest.str());
  write_file(dir / "provenance.csv", "key,value\nstudy," + spec.name + "\ncases," + std::to_string(spec.costs.size()) +
                                         "\ncommit," + io::commit_label() + "\n");
  write_file(dir / "fits.csv", fits.str());
  write_file(dir / "modes.csv", modes.str());
  write_file(dir / "timings.csv", timings.str());
  write_file(dir / "report.md", md.str());
  write_overlay_files(dir, overlays);
  log << "tables written to " << output_dir << "\n";
  return failed;
}

}  // namespace beamid::study
