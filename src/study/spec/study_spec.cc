#include "study/spec/study_spec.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "config/beam_file.h"
#include "config/document.h"
#include "core/errors.h"
#include "core/limits.h"
#include "costs/cost.h"
#include "fit/identification.h"
#include "fit/optimizer.h"
#include "fit/sensed_output.h"
#include "io/files.h"
#include "io/text.h"
#include "model/beam_parameters.h"
#include "signal/noise.h"

namespace beamid::study {
namespace {

using config::Node;
using config::Table;

const auto positive = [](double v) { return v > 0; };
const auto non_negative = [](double v) { return v >= 0; };
constexpr int kMaxInt = std::numeric_limits<int>::max();

std::vector<std::string> cost_names() { return costs::cost_names().names(); }

void read_experiment(Table& r, simulation::Experiment& e) {
  e.dt_s = r.number("dt_s", e.dt_s, positive, "must be > 0");
  e.samples = r.integer("samples", e.samples, core::kMinStudySamples, core::kMaxStudySamples);
  // Simulable: a pulse, a pluck, or the pulse's samples as a force channel records them ("force").
  e.excitation =
      r.string("excitation", e.excitation, {simulation::kPulse, simulation::kPluck, simulation::kSampledForce});
  // At the clamp (x = 0) a force does no work and a sensor reads nothing: every case failed, exit 0, the reason only
  // in cases.csv (the eleventh pass's TF_24).
  // Denormal positions and amplitudes passed "> 0" and failed every case (the fourteenth pass's P7, P15): the floors
  // are simulation::validation_error's (1e-12 s, 1e-150 N), and 1e-9 m from the clamp.
  constexpr const char* kAtTheClamp =
      "must be a finite position of at least 1e-9 m (at the clamp, x = 0, a force does no work and a sensor reads 0)";
  const auto off_clamp = [](double x) { return x >= 1e-9; };
  if (r.has("force_x_m")) e.force_x_m = r.number("force_x_m", std::nullopt, off_clamp, kAtTheClamp);
  e.force_amplitude_N = r.number(
      "force_amplitude_N", e.force_amplitude_N, [](double a) { return a >= 1e-150; }, "must be at least 1e-150 N");
  e.pulse_width_s = r.number(
      "pulse_width_s", e.pulse_width_s, [](double w) { return w >= 1e-12; },
      "must be at least 1e-12 s (narrower is an impulse at any dt >= 1e-9 s)");
  if (r.has("sensor_x_m")) e.sensor_x_m = r.number("sensor_x_m", std::nullopt, off_clamp, kAtTheClamp);
  e.output = r.string("output", e.output, simulation::output_names().names());
}

}  // namespace

const StartSpec& StudySpec::start(const std::string& n) const {
  for (const auto& s : starts)
    if (s.name == n) return s;
  throw InputError(path + ": no start named '" + n + "'");
}

const MethodSpec& StudySpec::method(const std::string& n) const {
  for (const auto& m : methods)
    if (m.name == n) return m;
  throw InputError(path + ": no method named '" + n + "'");
}

namespace {

// [study]: the name, the question and the seed.
void read_study_table(const config::Document& document, StudySpec& spec) {
  Table r = document.required("study");
  spec.name = r.string("name", std::nullopt);
  if (const std::string problem = io::study_name_problem(spec.name); !problem.empty())
    r.fail("name", "'" + spec.name + "'", problem);
  spec.question = r.string("question", std::nullopt);
  // An integer as every other integer key is (7.0 and 1e3 were taken as seeds: the twenty-eighth pass's adv64 P3),
  // below 2^53 so that Python and JSON readers keep it exactly.
  const std::optional<config::Node> seed = r.get("seed");
  if (!seed) throw InputError(r.where() + ": [study] is missing key 'seed'");
  const std::optional<std::int64_t> value = seed->integer();
  constexpr std::int64_t kLargestSeed = (std::int64_t{1} << 53) - 1;
  if (!value) r.fail("seed", seed->text(), "must be an integer in 0..2^53 - 1");
  if (*value < 0 || *value > kLargestSeed) r.fail("seed", std::to_string(*value), "must be an integer in 0..2^53 - 1");
  spec.seed = static_cast<std::uint64_t>(*value);
  r.finish({"name", "question", "seed"});
}

// A noise model's text at `key`, canonical ("ar:0.9"); the parser's constraint at the key's line otherwise.
std::string noise_model_of(Table& r, const std::string& key) {
  const std::string text = r.string(key, std::nullopt);
  try {
    return signal::parse_noise_model(text).text();
  } catch (const signal::NoiseModelError& e) {
    r.fail(key, "'" + text + "'", e.constraint);
  }
}

// [truth]: the beam, N_truth, the integrator's tolerance and the experiment, validated on the beam.
void read_truth(const config::Document& document, const std::string& directory, StudySpec& spec) {
  Table r = document.required("truth");
  TruthSpec& t = spec.truth;
  t.beam = r.string("beam", std::nullopt);
  if (!model::is_preset(t.beam)) {
    std::filesystem::path p(t.beam);
    if (p.is_relative()) p = std::filesystem::path(directory) / p;
    t.beam_path = p.string();
    if (!io::is_existing_file(p))
      r.fail("beam", "'" + t.beam + "'",
             "must be a preset (" + Table::join(model::preset_names()) + ") or an existing beam TOML file");
  }
  // A control study fits the truth's own model (an inverse crime on purpose): what remains is the estimator's own
  // bias and variance, the yardstick for the studies whose truth is finer than every fit.
  t.control = r.boolean("control", false);
  t.elements =
      r.integer("elements", 48, t.control ? core::kMinElements : core::kMinTruthElements, core::kMaxTruthElements);
  t.rtol = r.number(
      "rtol", 1e-10, [](double v) { return v >= 1e-13 && v <= 1e-6; }, "must be in [1e-13, 1e-6] (tight: the truth)");
  read_experiment(r, t.experiment);
  if (r.has("noise_model")) t.noise_model = noise_model_of(r, "noise_model");
  t.force_noise = r.number(
      "force_noise", 0.0, [](double v) { return v >= 0 && v <= 10; }, "must be in [0, 10] (times the force's RMS)");
  if (t.force_noise > 0 && t.experiment.excitation != simulation::kSampledForce)
    r.fail("force_noise", format_value(t.force_noise),
           "is noise on a measured force channel: needs excitation = 'force' (excitation is '" +
               t.experiment.excitation + "')");
  t.modal_damping_ratio = r.number(
      "modal_damping_ratio", 0.0, [](double v) { return v >= 0 && v <= 0.5; }, "must be in [0, 0.5]");
  if (t.modal_damping_ratio > 0 && t.control)
    r.fail("modal_damping_ratio", format_value(t.modal_damping_ratio),
           "gives the truth a damping law no fitted model has; control = true fits the truth's own model");
  t.sensor.cutoff_hz = r.number("sensor_bandwidth_hz", 0.0, non_negative, "must be >= 0 (0: an ideal sensor)");
  t.sensor.order = r.integer("sensor_filter_order", 4, 1, 8);
  if (r.has("sensor_filter_order") && !(t.sensor.cutoff_hz > 0))
    r.fail("sensor_filter_order", std::to_string(t.sensor.order),
           "is the sensor filter's: needs sensor_bandwidth_hz > 0 (an ideal sensor has no filter)");
  if (auto error = signal::validation_error(t.sensor, t.experiment.dt_s))
    r.fail("sensor_bandwidth_hz", format_value(t.sensor.cutoff_hz), error->substr(error->find(": ") + 2));
  // The truth is simulated oversampling times finer: 2^24 fine samples (128 MB a record) at most.
  constexpr long kMaxFineSamples = 1L << 24;
  if (t.sensor.cutoff_hz > 0 && static_cast<long>(t.experiment.samples) * t.sensor.oversampling > kMaxFineSamples)
    r.fail("samples", std::to_string(t.experiment.samples),
           "with sensor_bandwidth_hz the truth is simulated " + std::to_string(t.sensor.oversampling) +
               " times finer: at most " + std::to_string(kMaxFineSamples / t.sensor.oversampling) + " samples");
  if (t.sensor.cutoff_hz > 0 && t.control)
    r.fail("sensor_bandwidth_hz", format_value(t.sensor.cutoff_hz),
           "filters the truth's output as the fitted model does only with a method's sensor_in_model; control = true "
           "fits the truth's own model");
  r.finish({"beam", "elements", "control", "rtol", "dt_s", "samples", "excitation", "force_x_m", "force_amplitude_N",
            "pulse_width_s", "sensor_x_m", "output", "noise_model", "force_noise", "modal_damping_ratio",
            "sensor_bandwidth_hz", "sensor_filter_order"});
  t.parameters = t.beam_path.empty() ? model::preset(t.beam) : config::load_beam_toml(t.beam_path);
  const model::BeamParameters& beam = t.parameters;
  simulation::Experiment checked = t.experiment;
  if (checked.excitation == simulation::kSampledForce) checked.force_samples_N = simulation::sampled_pulse(checked);
  if (auto e = simulation::validation_error(checked, beam.l)) {
    // The message starts with the offending key ("force_x_m = 0.9: ..."): point at its line.
    const std::string key = e->substr(0, e->find(' '));
    throw InputError(r.where(key) + ": truth." + *e);
  }
}

// [fit]: what is estimated, the spikes and band, the bounds and the optimizer's budget and tolerances.
void read_fit(const config::Document& document, StudySpec& spec) {
  Table r = document.required("fit");
  FitSpec& f = spec.fit;
  std::vector<std::string> keys;
  for (const auto& info : model::parameter_table()) keys.emplace_back(info.key);
  f.estimate = r.strings("estimate", true, keys);
  if (const auto n = r.get("spikes")) {
    if (n->is_string()) {
      if (*n->string() != "auto") r.fail("spikes", n->text(), "must be an integer >= 1 or 'auto'");
      f.spikes = 0;
    } else {
      f.spikes = r.integer("spikes", 3, 1, core::kMaxSpikes);
    }
  }
  f.max_spikes = r.integer("max_spikes", f.max_spikes, 1, core::kMaxSpikes);
  // max_spikes bounds spikes = "auto" only: beside a given count it was read by nothing, even when it contradicted it
  // (spikes = 3, max_spikes = 2: the twenty-first pass's P8).
  if (r.has("max_spikes") && f.spikes > 0)
    r.fail("max_spikes", std::to_string(f.max_spikes),
           "is read only with spikes = \"auto\" (it bounds the count chosen), and spikes = " +
               std::to_string(f.spikes) + " is given: leave max_spikes out");
  f.spike_rule = r.string("spike_rule", f.spike_rule, {"largest", "prominence"});
  f.min_frequency_hz = r.number("min_frequency_hz", 0.0, non_negative, "must be >= 0");
  f.max_frequency_hz = r.number("max_frequency_hz", 0.0, non_negative, "must be >= 0 (0: up to Nyquist)");
  if (f.max_frequency_hz > 0 && f.max_frequency_hz <= f.min_frequency_hz)
    r.fail("max_frequency_hz", format_value(f.max_frequency_hz), "must exceed fit.min_frequency_hz");
  // The band lies below the record's Nyquist frequency, as beamid real requires: above it the spike costs took the
  // aliases of the truth's higher modes for modes (the twenty-fourth pass's adv56 P4).
  const double nyquist_hz = 0.5 / spec.truth.experiment.dt_s;
  if (f.max_frequency_hz > nyquist_hz)
    r.fail("max_frequency_hz", format_value(f.max_frequency_hz),
           "must be at most the truth record's Nyquist frequency " + format_value(nyquist_hz) +
               " Hz (truth.dt_s = " + format_value(spec.truth.experiment.dt_s) + ")");
  if (f.min_frequency_hz >= nyquist_hz)
    r.fail("min_frequency_hz", format_value(f.min_frequency_hz),
           "must be below the truth record's Nyquist frequency " + format_value(nyquist_hz) + " Hz");
  f.window = r.string("window", f.window, {"rectangular", "hann", "exponential"});
  f.frequency_weight = r.string("frequency_weight", f.frequency_weight, costs::frequency_weight_names().names());
  f.bound_factor = r.number(
      "bound_factor", f.bound_factor, [](double v) { return v > 1; }, "must be > 1");
  f.scaling = r.string("scaling", f.scaling, {"linear", "log"});
  f.max_evaluations = r.integer("max_evaluations", f.max_evaluations, 10, core::kMaxEvaluations);
  f.xtol_rel = r.number(
      "xtol_rel", f.xtol_rel, [](double v) { return v > 0 && v < 1; }, "must be in (0, 1)");
  f.success_tolerance = r.number("success_tolerance", f.success_tolerance, positive, "must be > 0");
  f.damping_tolerance = r.number("damping_tolerance", f.success_tolerance, positive, "must be > 0");
  r.finish({"estimate", "spikes", "max_spikes", "spike_rule", "min_frequency_hz", "max_frequency_hz", "window",
            "frequency_weight", "bound_factor", "scaling", "max_evaluations", "xtol_rel", "success_tolerance",
            "damping_tolerance"});
}

// A start's or a method's name is a value of the tables' rows (cases.csv, summary.csv) and part of a run's name
// ("time/direct"): a non-empty word of letters, digits, '-', '_', '.' and '+'. A comma, a quote or a newline in one
// broke the tables' rows, and an empty one was taken (the twenty-second pass's P3).
void check_row_name(const Table& parent, const std::string& table, const std::string& name) {
  if (!name.empty() && name.size() <= 64 &&
      name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_.+") == std::string::npos)
    return;
  std::string shown;
  for (const char c : name.substr(0, 64))
    shown += std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c) : "?";
  throw InputError(parent.where(name) + ": [" + table + ".'" + shown + "']: " +
                   "its name must be a word of 1-64 letters, digits, '-', '_', '.' or '+' (it names rows of the "
                   "tables)");
}

// [starts.NAME] and [methods.NAME].
void read_starts_and_methods(const config::Document& document, StudySpec& spec) {
  // [starts.NAME]: a factor for every estimated key, strictly inside the bounds.
  if (const auto starts = document.table("starts", false)) {
    for (const auto& [n, node] : starts->entries()) {
      check_row_name(*starts, "starts", n);
      Table r = node.table("starts." + n + ".", "starts." + n);
      StartSpec s{n, {}};
      r.only_keys(spec.fit.estimate);
      for (const auto& key : spec.fit.estimate)
        s.factor[key] = r.number(
            key, std::nullopt, [&](double v) { return v > 1 / spec.fit.bound_factor && v < spec.fit.bound_factor; },
            "must lie strictly inside the bounds, (1/F, F) with F = fit.bound_factor = " +
                format_value(spec.fit.bound_factor));
      r.finish(spec.fit.estimate);
      spec.starts.push_back(s);
    }
  }
  if (const auto methods = document.table("methods", false)) {
    std::vector<std::string> optimizers = fit::optimizer_names().names();
    optimizers.insert(optimizers.begin(), "default");
    for (const auto& [n, node] : methods->entries()) {
      check_row_name(*methods, "methods", n);
      Table r = node.table("methods." + n + ".", "methods." + n);
      MethodSpec m;
      m.name = n;
      m.strategy = r.string("strategy", m.strategy, fit::strategy_names().names());
      m.optimizer = r.string("optimizer", m.optimizer, optimizers);
      m.starts = r.integer("starts", 1, 1, core::kMaxStarts);
      m.refine = r.string("refine", m.refine, {costs::kTimeCost, costs::kBandCost, costs::kMaxLikelihoodCost});
      if (r.has("refine") && m.strategy != fit::kHybrid)
        r.fail("refine", "'" + m.refine + "'", "applies to strategy = 'hybrid' only");
      if (r.has("window")) m.window = r.string("window", std::nullopt, {"rectangular", "hann", "exponential"});
      if (r.has("frequency_weight"))
        m.frequency_weight = r.string("frequency_weight", std::nullopt, costs::frequency_weight_names().names());
      const auto positive_factor = [](double v) { return v > 0 && v <= 1e6; };
      m.eps1_factor = r.number("eps1_factor", 1.0, positive_factor, "must be in (0, 1e6]");
      m.eps2_factor = r.number("eps2_factor", 1.0, positive_factor, "must be in (0, 1e6]");
      if (r.has("noise_model")) {
        const std::string text = r.string("noise_model", std::nullopt);
        m.noise_model = text == "truth" || text == costs::kEstimatedNoise ? text : noise_model_of(r, "noise_model");
      }
      m.errors_in_variables = r.boolean("errors_in_variables", false);
      if (m.errors_in_variables && m.noise_model == costs::kEstimatedNoise)
        r.fail("errors_in_variables", "true",
               "weighs each bin by the response's noise given: with noise_model = 'estimated' it has none (give "
               "'truth' or a model)");
      if (m.errors_in_variables && spec.truth.force_noise <= 0)
        r.fail("errors_in_variables", "true",
               "weighs the force channel's noise: needs [truth] excitation = 'force' and force_noise > 0");
      m.sensor_in_model = r.boolean("sensor_in_model", false);
      if (m.sensor_in_model && !(spec.truth.sensor.cutoff_hz > 0))
        r.fail("sensor_in_model", "true",
               "puts the truth's sensor filter in the fitted model: needs [truth] sensor_bandwidth_hz > 0");
      if (m.sensor_in_model)
        if (auto error = fit::sensed_validation_error(spec.truth.sensor, spec.truth.experiment))
          r.fail("sensor_in_model", "true", *error);
      r.finish({"strategy", "optimizer", "starts", "refine", "window", "frequency_weight", "eps1_factor", "eps2_factor",
                "noise_model", "errors_in_variables", "sensor_in_model"});
      spec.methods.push_back(m);
    }
  }
}

// [sweep]: the Cartesian product of the cases (fitted N coarser than the truth's up to finest_fit).
void read_sweep(const config::Document& document, const std::string& source, int finest_fit, StudySpec& spec) {
  Table r = document.required("sweep");
  SweepSpec& s = spec.sweep;
  s.elements = r.integers("elements", true, 1, finest_fit);
  s.cost = r.strings("cost", true, cost_names());
  s.noise = r.numbers(
      "noise", [](double v) { return v >= 0 && v <= 1; }, "must be in [0, 1] (a fraction of the clean RMS)");
  if (s.noise.empty()) s.noise = {0.0};
  s.replicates = r.integer("replicates", 1, 1, 100000);
  std::vector<std::string> method_names, start_names;
  for (const auto& m : spec.methods) method_names.push_back(m.name);
  for (const auto& st : spec.starts) start_names.push_back(st.name);
  if (method_names.empty()) throw InputError(source + ":1: no [methods.NAME] table: a study needs at least one method");
  if (start_names.empty()) throw InputError(source + ":1: no [starts.NAME] table: a study needs at least one start");
  s.method = r.strings("method", true, method_names);
  s.start = r.strings("start", true, start_names);
  s.pulse_width_s = r.numbers("pulse_width_s", positive, "must be > 0");
  if (s.pulse_width_s.empty()) s.pulse_width_s = {spec.truth.experiment.pulse_width_s};
  s.samples = r.integers("samples", false, 16, spec.truth.experiment.samples);
  if (s.samples.empty()) s.samples = {spec.truth.experiment.samples};
  r.finish({"elements", "cost", "noise", "replicates", "method", "start", "pulse_width_s", "samples"});
}

// [landscape]: slices, grids and multi-starts of the costs through the truth.
void read_landscape(const config::Document& document, int finest_fit, StudySpec& spec) {
  if (auto landscape = document.table("landscape", false)) {
    Table& r = *landscape;
    LandscapeSpec& l = spec.landscape;
    l.enabled = true;
    // elements: one order (16) or a list ([8, 16]).
    if (const auto node = r.get("elements"); node && !node->is_array())
      l.elements = {r.integer("elements", std::nullopt, 1, finest_fit)};
    else if (node)
      l.elements = r.integers("elements", true, 1, finest_fit);
    l.noise = r.numbers(
        "noise", [](double v) { return v >= 0 && v <= 1; }, "must be in [0, 1] (a fraction of the clean RMS)");
    if (l.noise.empty()) l.noise = {0.0};
    l.cost = r.strings("cost", true, cost_names());
    // At most 100: a slice over [v/100, 100 v] already spans four decades of the parameter; 1e300 was accepted and
    // gave inf and NaN slices.
    l.range_factor = r.number(
        "range_factor", l.range_factor, [](double v) { return v > 1 && v <= 100; }, "must be in (1, 100]");
    l.points = r.integer("points", l.points, 5, 4001);
    l.grid_points = r.integer("grid_points", l.grid_points, 3, 401);
    l.multistarts = r.integer("multistarts", l.multistarts, 0, 10000);
    l.zoom_range_factor = r.number(
        "zoom_range_factor", 0.0, [](double v) { return v > 1 && v <= 100; }, "must be in (1, 100]");
    l.zoom_points = r.integer("zoom_points", l.zoom_points, 3, 401);
    if (const auto pairs = r.array("pairs", false)) {
      for (const Node& item : *pairs) {
        const std::vector<Node> p = item.elements();
        const auto bad = [&](const std::string& why) { r.element_fail("pairs", item, item.text(), why); };
        if (!item.is_array() || p.size() != 2 || !p[0].is_string() || !p[1].is_string())
          bad("must be a pair of parameter names, [\"EI\", \"rho\"]");
        const std::string a = *p[0].string(), b = *p[1].string();
        for (const auto& k : {a, b})
          if (std::find(spec.fit.estimate.begin(), spec.fit.estimate.end(), k) == spec.fit.estimate.end())
            bad("'" + k + "' is not in fit.estimate");
        if (a == b) bad("the two names must differ");
        l.pairs.emplace_back(a, b);
      }
    }
    if (l.zoom_range_factor > 1 && l.pairs.empty())
      r.fail("zoom_range_factor", format_value(l.zoom_range_factor), "needs landscape.pairs (the grids it zooms)");
    r.finish({"elements", "noise", "cost", "range_factor", "points", "pairs", "grid_points", "zoom_range_factor",
              "zoom_points", "multistarts"});
  }
}

// [start_distance]: the runs, offsets and directions of the start-distance curves.
void read_start_distance(const config::Document& document, int finest_fit, StudySpec& spec) {
  if (auto table = document.table("start_distance", false)) {
    Table& r = *table;
    StartDistanceSpec& d = spec.start_distance;
    d.enabled = true;
    d.elements = r.integer("elements", d.elements, 1, finest_fit);
    d.offsets = r.numbers(
        "offsets", [](double v) { return v > 0 && v < 1; }, "must be in (0, 1) (relative frequency offsets)");
    if (d.offsets.empty()) r.fail("offsets", "[]", "must list at least one offset");
    if (!std::is_sorted(d.offsets.begin(), d.offsets.end())) r.fail("offsets", "[...]", "must be in increasing order");
    d.directions = r.integer("directions", d.directions, 1, 100000);
    d.noise = r.number(
        "noise", 0.0, [](double v) { return v >= 0 && v <= 1; }, "must be in [0, 1] (a fraction of the clean RMS)");
    d.records = r.integer("records", d.records, 1, 100000);
    if (d.records > 1 && d.noise == 0)
      r.fail("records", std::to_string(d.records),
             "must be 1 when noise = 0 (noise-free records are all the same record)");
    d.agreement = r.number(
        "agreement", d.agreement, [](double v) { return v > 0 && v < 1; }, "must be in (0, 1)");
    d.damping_agreement = r.number(
        "damping_agreement", d.damping_agreement, [](double v) { return v > 0 && v < 1; }, "must be in (0, 1)");
    std::vector<std::string> method_names;
    for (const auto& m : spec.methods) method_names.push_back(m.name);
    // Runs as "cost/method": not every pairing is meaningful (a hybrid's cost is its global stage).
    const auto runs = r.array("runs", true);
    for (const Node& item : *runs) {
      const auto bad = [&](const std::string& why) { r.element_fail("runs", item, item.text(), why); };
      if (!item.is_string()) bad("must be a string \"cost/method\"");
      const std::string text = *item.string();
      const auto slash = text.find('/');
      if (slash == std::string::npos) bad("must be \"cost/method\", e.g. \"time/direct\"");
      const std::string cost = text.substr(0, slash), method = text.substr(slash + 1);
      if (!costs::cost_names().contains(cost)) bad("cost '" + cost + "' must be one of " + costs::cost_names().list());
      if (std::find(method_names.begin(), method_names.end(), method) == method_names.end())
        bad("method '" + method + "' must be one of the [methods.NAME] tables (" + Table::join(method_names) + ")");
      if (std::find(d.runs.begin(), d.runs.end(), std::pair(cost, method)) != d.runs.end()) bad("is listed twice");
      d.runs.emplace_back(cost, method);
    }
    d.every_experiment = r.string("experiments", "first", {"first", "all"}) == "all";
    r.finish({"elements", "offsets", "directions", "records", "noise", "agreement", "damping_agreement", "runs",
              "experiments"});
  }
}

// [outputs]: the overlay case, the efficiency bounds and the bias decomposition.
void read_outputs(const config::Document& document, StudySpec& spec) {
  if (auto outputs = document.table("outputs", false)) {
    Table& r = *outputs;
    OutputsSpec& o = spec.outputs;
    o.overlay_elements = r.integer("overlay_elements", 0, 0, kMaxInt);
    if (o.overlay_elements != 0 && std::find(spec.sweep.elements.begin(), spec.sweep.elements.end(),
                                             o.overlay_elements) == spec.sweep.elements.end())
      r.fail("overlay_elements", std::to_string(o.overlay_elements), "must be one of sweep.elements");
    o.overlay_noise = r.number("overlay_noise", 0.0, non_negative, "must be >= 0");
    if (std::find(spec.sweep.noise.begin(), spec.sweep.noise.end(), o.overlay_noise) == spec.sweep.noise.end())
      r.fail("overlay_noise", format_value(o.overlay_noise), "must be one of sweep.noise");
    o.efficiency = r.boolean("efficiency", false);
    o.bias_decomposition = r.boolean("bias_decomposition", false);
    // The bound takes the force as known; with its channel noisy it is not the bound of these records.
    if (o.efficiency && spec.truth.force_noise > 0)
      r.fail("efficiency", "true",
             "compares with the bound for a known force; [truth] force_noise = " +
                 format_value(spec.truth.force_noise) + " makes the force channel noisy");
    if (o.bias_decomposition &&
        std::find(spec.sweep.noise.begin(), spec.sweep.noise.end(), 0.0) == spec.sweep.noise.end())
      r.fail("bias_decomposition", "true", "needs 0 in sweep.noise (the noise-free fit is the bias of the minimum)");
    r.finish({"overlay_elements", "overlay_noise", "efficiency", "bias_decomposition"});
  }
  if (spec.outputs.overlay_elements == 0)
    spec.outputs.overlay_elements = *std::max_element(spec.sweep.elements.begin(), spec.sweep.elements.end());
}

}  // namespace

// A method's window, frequency weight or eps factors apply only to the costs that read them (costs::cost_uses): in a
// study whose methods run only the time cost they were ignored without a word (the second adversarial pass's N459,
// N460). The costs a method runs: the sweep's (when the sweep lists it), its start-distance runs', a hybrid's refine.
void check_method_overrides(const config::Document& document, const StudySpec& spec) {
  // The [fit] table's, against every cost the study runs (sweep, landscape, start distance, hybrid refines): a
  // frequency weight in a study of only the time cost was read by nothing (the fourth pass's Q534).
  if (const std::optional<Table> fit = document.table("fit", false)) {
    std::vector<std::string> all = spec.sweep.cost;
    all.insert(all.end(), spec.landscape.cost.begin(), spec.landscape.cost.end());
    for (const auto& [cost, method] : spec.start_distance.runs) all.push_back(cost);
    for (const MethodSpec& m : spec.methods)
      if (m.strategy == fit::kHybrid) all.push_back(m.refine);
    std::string listed;
    for (const std::string& c : all)
      if (listed.find(c) == std::string::npos) listed += (listed.empty() ? "" : ", ") + c;
    using Reads = bool (*)(const std::string&);
    const Reads window = [](const std::string& c) { return costs::cost_uses(c).window; };
    const Reads spike = [](const std::string& c) { return costs::is_spike_cost(c); };
    const Reads picks = [](const std::string& c) { return costs::is_spike_cost(c) || c == costs::kModalCost; };
    const Reads band = [](const std::string& c) {
      return costs::is_spike_cost(c) || c == costs::kModalCost || costs::is_band_cost(c);
    };
    // The spikes' number and band too (the fifth pass's R345-R361).
    for (const auto& [key, reads, readers] :
         {std::tuple{"window", window, "the DFT costs (spike, spike-smooth, freq-band)"},
          std::tuple{"frequency_weight", spike, "the spike costs (spike, spike-smooth)"},
          std::tuple{"spike_rule", spike, "the spike costs (spike, spike-smooth)"},
          std::tuple{"spikes", picks, "the spike costs and modal"},
          std::tuple{"max_spikes", picks, "the spike costs and modal"},
          std::tuple{"min_frequency_hz", band, "the spike costs, modal and freq-band"},
          std::tuple{"max_frequency_hz", band, "the spike costs, modal and freq-band"}})
      if (!all.empty() && fit->has(key) && std::none_of(all.begin(), all.end(), reads))
        throw InputError(fit->where(key) + ": fit." + key + " is read by " + readers + "; this study runs only " +
                         listed);
  }
  std::optional<Table> methods = document.table("methods", false);
  if (!methods) return;
  for (const MethodSpec& m : spec.methods) {
    std::vector<std::string> runs;
    if (std::find(spec.sweep.method.begin(), spec.sweep.method.end(), m.name) != spec.sweep.method.end())
      runs = spec.sweep.cost;
    for (const auto& [cost, method] : spec.start_distance.runs)
      if (method == m.name) runs.push_back(cost);
    if (m.strategy == fit::kHybrid) runs.push_back(m.refine);
    if (runs.empty()) continue;
    std::string listed;
    for (const std::string& c : runs) listed += (listed.empty() ? "" : ", ") + c;
    const auto read_by = [&](bool costs::CostUses::*field) {
      return std::any_of(runs.begin(), runs.end(), [&](const std::string& c) { return costs::cost_uses(c).*field; });
    };
    const Table r = methods->table(m.name).value();
    for (const auto& [key, field, readers] :
         {std::tuple{"window", &costs::CostUses::window, "the DFT costs (spike, spike-smooth, freq-band)"},
          std::tuple{"frequency_weight", &costs::CostUses::frequency_weight, "the spike costs (spike, spike-smooth)"},
          std::tuple{"eps1_factor", &costs::CostUses::frequency_weight, "the spike costs (spike, spike-smooth)"},
          std::tuple{"eps2_factor", &costs::CostUses::frequency_weight, "the spike costs (spike, spike-smooth)"},
          std::tuple{"noise_model", &costs::CostUses::noise_model, "the time and freq-ml costs"}})
      if (r.has(key) && !read_by(field))
        throw InputError(r.where(key) + ": methods." + m.name + "." + key + " is read by " + readers +
                         "; this method runs only " + listed);
    // A noise model names what the method's fits assume: a cost that would run white under that name is refused
    // (a window is applied where it is read; a likelihood is not half-applied).
    if (m.errors_in_variables)
      for (const std::string& c : runs)
        if (c != costs::kMaxLikelihoodCost)
          throw InputError(r.where("errors_in_variables") + ": methods." + m.name +
                           ".errors_in_variables is freq-ml's form; this method also runs " + c);
    if (r.has("noise_model"))
      for (const std::string& c : runs)
        if (!costs::cost_uses(c).noise_model)
          throw InputError(r.where("noise_model") + ": methods." + m.name +
                           ".noise_model is read by the time and freq-ml costs; this method also runs " + c +
                           ", whose fits would be white under its name: give that cost a method of its own");
  }
}

StudySpec parse_study(const std::string& text, const std::string& source, const std::string& directory) {
  const config::Document document = config::Document::parse(text, source);
  const Table root = document.root();
  root.only_tables({"study", "truth", "fit", "starts", "methods", "sweep", "landscape", "start_distance", "outputs"});
  StudySpec spec;
  spec.path = source;
  spec.file_hash = io::hex64(core::fnv1a64(text));
  read_study_table(document, spec);
  read_truth(document, directory, spec);
  // Fitted orders: coarser than the truth's (no inverse crime), or up to it in a control study.
  const int finest_fit = spec.truth.control ? spec.truth.elements : spec.truth.elements - 1;
  read_fit(document, spec);
  read_starts_and_methods(document, spec);
  read_sweep(document, source, finest_fit, spec);
  read_landscape(document, finest_fit, spec);
  read_start_distance(document, finest_fit, spec);
  check_method_overrides(document, spec);
  read_outputs(document, spec);
  return spec;
}

StudySpec load_study(const std::string& path) {
  const std::string text = io::read_file(path, "cannot read the study file", config::kMaxFileBytes);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_study(text, path, dir.empty() ? "." : dir);
}

}  // namespace beamid::study
