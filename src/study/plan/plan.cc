#include "study/plan/plan.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "core/limits.h"
#include "io/text.h"
#include "model/beam_parameters.h"
#include "signal/noise.h"

namespace beamid::study {
namespace {

// Numbers in canonical strings are written by io::round_trip() (they round-trip, so distinct values stay distinct).
void identify(Unit& u, const StudySpec& spec) {
  const std::uint64_t h = core::fnv1a64(u.canonical);
  u.id = io::hex64(h);
  u.seed = core::mix64(spec.seed ^ h);
}

// The truth beam as it enters a unit's identity: a preset by its name; a beam file by its path and a hash of the
// values read from it, so that editing the file changes the ids of every unit that used it, and their stored records
// are recomputed instead of reused (the store keys records by id). Preset studies keep their ids.
std::string beam_identity(const TruthSpec& t) {
  if (t.beam_path.empty()) return t.beam;
  const model::BeamParameters& b = t.parameters;
  std::ostringstream values;
  for (const auto& info : model::parameter_table())
    values << info.key << "=" << io::round_trip(model::parameter_value(b, info.key)) << ";";
  for (const model::Attachment& a : b.attachments)
    values << "attachment=" << io::round_trip(a.x) << "," << io::round_trip(a.m) << "," << io::round_trip(a.J) << ","
           << io::round_trip(a.c) << ";";
  values << "k_theta=" << io::round_trip(b.support.k_theta) << ";k_w=" << io::round_trip(b.support.k_w);
  return t.beam + "#" + io::hex64(core::fnv1a64(values.str()));
}

std::string truth_text(const StudySpec& spec, double pulse_width_s) {
  const auto& t = spec.truth;
  const auto& e = t.experiment;
  std::ostringstream os;
  os << "beam=" << beam_identity(t) << ";N_truth=" << t.elements << ";rtol=" << io::round_trip(t.rtol)
     << ";integrator=fast"
     << ";dt_s=" << io::round_trip(e.dt_s) << ";samples=" << e.samples << ";excitation=" << e.excitation
     << ";force_x_m=" << (e.force_x_m ? io::round_trip(*e.force_x_m) : "tip")
     << ";force_amplitude_N=" << io::round_trip(e.force_amplitude_N)
     << ";pulse_width_s=" << io::round_trip(pulse_width_s)
     << ";sensor_x_m=" << (e.sensor_x_m ? io::round_trip(*e.sensor_x_m) : "tip") << ";output=" << e.output;
  // The records' noise colour, named only when not white (the units of white-noise studies keep their identity).
  if (t.noise_model != "white") os << ";noise_model=" << t.noise_model;
  if (t.force_noise > 0) os << ";force_noise=" << io::round_trip(t.force_noise);
  if (t.modal_damping_ratio > 0) os << ";modal_damping_ratio=" << io::round_trip(t.modal_damping_ratio);
  if (t.sensor.cutoff_hz > 0)
    os << ";sensor_bandwidth_hz=" << io::round_trip(t.sensor.cutoff_hz) << ";sensor_filter_order=" << t.sensor.order
       << ";oversampling=" << t.sensor.oversampling;
  return os.str();
}

// A method as it enters a unit's identity (refine only for the hybrid strategy, so that older ids stay).
// A method without overrides of [fit] keeps the text it had before overrides existed (its units' ids stay valid).
std::string method_text(const MethodSpec& m) {
  return m.strategy + "/" + m.optimizer + "/" + std::to_string(m.starts) +
         (m.strategy == "hybrid" ? "/refine:" + m.refine : std::string()) +
         (m.window.empty() ? std::string() : "/window:" + m.window) +
         (m.frequency_weight.empty() ? std::string() : "/frequency_weight:" + m.frequency_weight) +
         (m.eps1_factor == 1 ? std::string() : "/eps1_factor:" + io::round_trip(m.eps1_factor)) +
         (m.eps2_factor == 1 ? std::string() : "/eps2_factor:" + io::round_trip(m.eps2_factor)) +
         (m.noise_model.empty() ? std::string() : "/noise_model:" + m.noise_model) +
         (m.errors_in_variables ? "/errors_in_variables" : "") + (m.sensor_in_model ? "/sensor_in_model" : "");
}

std::string fit_text(const StudySpec& spec) {
  const auto& f = spec.fit;
  std::ostringstream os;
  os << "estimate=";
  for (std::size_t i = 0; i < f.estimate.size(); ++i) os << (i ? "," : "") << f.estimate[i];
  os << ";spikes=" << (f.spikes == 0 ? "auto" + std::to_string(f.max_spikes) : std::to_string(f.spikes))
     << ";spike_rule=" << f.spike_rule << ";band_hz=" << io::round_trip(f.min_frequency_hz) << ":"
     << io::round_trip(f.max_frequency_hz) << ";window=" << f.window
     << ";bound_factor=" << io::round_trip(f.bound_factor) << ";scaling=" << f.scaling
     << ";max_evaluations=" << f.max_evaluations << ";xtol_rel=" << io::round_trip(f.xtol_rel);
  // Named only when not the default, so that the units of studies written before the key keep their identity.
  if (f.frequency_weight != "absolute") os << ";frequency_weight=" << f.frequency_weight;
  // The success tolerances are not part of a unit's identity: they judge a result and do not change it.
  return os.str();
}

// The noise realisation of a record: (study seed, truth, record length, noise level, replicate) only, so that every
// cost, N, method and start sees the same noisy record (common random numbers).
std::uint64_t record_noise_seed(const StudySpec& spec, const Unit& truth, int samples, double noise, int replicate) {
  return core::mix64(spec.seed ^
                     core::fnv1a64("noise;" + truth.canonical + ";record_samples=" + std::to_string(samples) +
                                   ";noise=" + io::round_trip(noise) + ";replicate=" + std::to_string(replicate)));
}

}  // namespace

const std::string& unit_kind_name(UnitKind kind) {
  static const std::map<UnitKind, std::string> names = {
      {UnitKind::Truth, "truth"},           {UnitKind::Case, "case"},
      {UnitKind::Slice, "slice"},           {UnitKind::Grid, "grid"},
      {UnitKind::Multistart, "multistart"}, {UnitKind::Frequencies, "frequencies"},
      {UnitKind::Start, "start"},           {UnitKind::Bound, "bound"}};
  return names.at(kind);
}

namespace {

// A unit of `kind` on truth ti's record of `samples` samples (its canonical text and id are the caller's).
Unit unit_on(UnitKind kind, const Plan& plan, std::size_t ti, int samples) {
  Unit u;
  u.kind = kind;
  u.truth = static_cast<int>(ti);
  u.pulse_width_s = plan.truths[ti].pulse_width_s;
  u.samples = samples;
  return u;
}

// One truth record per pulse width; the first is also integrated with CVODE.
void plan_truths(const StudySpec& spec, Plan& plan) {
  for (double tau : spec.sweep.pulse_width_s) {
    Unit t;
    t.kind = UnitKind::Truth;
    t.pulse_width_s = tau;
    t.samples = spec.truth.experiment.samples;
    t.canonical = "truth;" + truth_text(spec, tau);
    identify(t, spec);
    t.cvode_check = plan.truths.empty();
    plan.truths.push_back(t);
  }
}

// The cases: the Cartesian product of the sweep (a noise-free case once, replicate 0).
void plan_cases(const StudySpec& spec, const std::string& fit, Plan& plan) {
  for (std::size_t ti = 0; ti < plan.truths.size(); ++ti)
    for (int samples : spec.sweep.samples)
      for (double noise : spec.sweep.noise)
        for (int rep = 0; rep < (noise == 0 ? 1 : spec.sweep.replicates); ++rep)
          for (int n : spec.sweep.elements)
            for (const auto& cost : spec.sweep.cost)
              for (const auto& method_name : spec.sweep.method)
                for (const auto& start_name : spec.sweep.start) {
                  Unit u = unit_on(UnitKind::Case, plan, ti, samples);
                  u.elements = n;
                  u.cost = cost;
                  u.noise = noise;
                  u.replicate = rep;
                  u.method = method_name;
                  u.start = start_name;
                  std::ostringstream os;
                  os << "case;" << plan.truths[ti].canonical << ";record_samples=" << samples
                     << ";noise=" << io::round_trip(noise) << ";replicate=" << rep << ";N=" << n << ";cost=" << cost
                     << ";" << fit << ";method=" << method_text(spec.method(method_name)) << ";start=";
                  for (const auto& [key, factor] : spec.start(start_name).factor)
                    os << key << ":" << io::round_trip(factor) << ",";
                  u.canonical = os.str();
                  identify(u, spec);
                  u.noise_seed = record_noise_seed(spec, plan.truths[ti], samples, noise, rep);
                  plan.units.push_back(u);
                }
}

// The landscape units of one experiment (truth ti, record length), fitted N and noise level: slices always; the
// wide grids and the multi-starts for the first experiment, N and noise only (`first`); the fine (zoom) grids for
// every N and noise of the first experiment.
void plan_landscape_setting(const StudySpec& spec, const std::string& fit, std::size_t ti, int samples, int n,
                            double noise, bool first_experiment, bool first, Plan& plan) {
  const auto& l = spec.landscape;
  // A noise-free unit's text is what it was before noise levels existed (its id, and a resumed store, stay valid).
  const std::string noise_text = noise == 0 ? "" : ";noise=" + io::round_trip(noise);
  const auto base = [&](double range_factor) {
    return plan.truths[ti].canonical + ";record_samples=" + std::to_string(samples) + ";N=" + std::to_string(n) + ";" +
           fit + ";range_factor=" + io::round_trip(range_factor) + noise_text;
  };
  const auto add = [&](Unit u) {
    u.truth = static_cast<int>(ti);
    u.pulse_width_s = plan.truths[ti].pulse_width_s;
    u.samples = samples;
    u.elements = n;
    u.noise = noise;
    u.noise_seed = noise == 0 ? 0 : record_noise_seed(spec, plan.truths[ti], samples, noise, 0);
    identify(u, spec);
    plan.units.push_back(u);
  };
  for (const auto& cost : l.cost) {
    for (const auto& key : spec.fit.estimate) {
      Unit u;
      u.kind = UnitKind::Slice;
      u.cost = cost;
      u.parameters = {key};
      u.range_factor = l.range_factor;
      u.points = l.points;
      u.canonical = "slice;" + base(l.range_factor) + ";cost=" + cost + ";parameter=" + key +
                    ";points=" + std::to_string(l.points);
      add(u);
    }
    if (!first_experiment) continue;
    for (const auto& [a, b] : l.pairs)
      for (const bool zoom : {false, true}) {
        if (zoom ? l.zoom_range_factor <= 1 : !first) continue;
        Unit u;
        u.kind = UnitKind::Grid;
        u.cost = cost;
        u.parameters = {a, b};
        u.zoom = zoom;
        u.range_factor = zoom ? l.zoom_range_factor : l.range_factor;
        u.points = zoom ? l.zoom_points : l.grid_points;
        u.canonical = "grid;" + base(u.range_factor) + ";cost=" + cost + ";parameters=" + a + "," + b +
                      ";points=" + std::to_string(u.points);
        add(u);
      }
    if (!first) continue;
    // Index -1 starts at the truth: with the random starts it gives the reference minimum of the cost.
    for (int k = l.multistarts > 0 ? -1 : 0; k < l.multistarts; ++k) {
      Unit u;
      u.kind = UnitKind::Multistart;
      u.cost = cost;
      u.index = k;
      u.canonical = "multistart;" + base(l.range_factor) + ";cost=" + cost + ";start=" +
                    (k < 0 ? std::string("truth") : std::to_string(k) + "/" + std::to_string(l.multistarts));
      add(u);
    }
  }
}

// Slices for every experiment (truth x record length), fitted N and noise level, so basin widths can be set against
// the number of modes, the discretisation and the noise (plan_landscape_setting).
void plan_landscape(const StudySpec& spec, const std::string& fit, Plan& plan) {
  const auto& l = spec.landscape;
  bool first_experiment = true;
  for (std::size_t ti = 0; ti < plan.truths.size(); ++ti)
    for (int samples : spec.sweep.samples) {
      for (int n : l.elements)
        for (double noise : l.noise) {
          const bool first = first_experiment && n == l.elements.front() && noise == l.noise.front();
          plan_landscape_setting(spec, fit, ti, samples, n, noise, first_experiment, first, plan);
        }
      first_experiment = false;
    }
}

// The Cramér-Rao bounds: with outputs.efficiency, of every noisy experiment and N of the sweep (no noise, no bound);
// with start_distance.records > 1, of every experiment the start-distance runs use, at its N and noise (the fits from
// the truth over the records are set against it: start_distance.h, ReferenceErrors). Each setting once.
void plan_bounds(const StudySpec& spec, Plan& plan) {
  const auto& d = spec.start_distance;
  for (std::size_t ti = 0; ti < plan.truths.size(); ++ti)
    for (std::size_t si = 0; si < spec.sweep.samples.size(); ++si) {
      const int samples = spec.sweep.samples[si];
      // (noise, N) in the sweep's order, then the start distance's when it is not among them.
      std::vector<std::pair<double, int>> settings;
      if (spec.outputs.efficiency)
        for (double noise : spec.sweep.noise)
          for (int n : spec.sweep.elements)
            if (noise > 0) settings.emplace_back(noise, n);
      const bool starts_here = d.every_experiment || (ti == 0 && si == 0);
      if (d.enabled && d.records > 1 && d.noise > 0 && starts_here &&
          std::find(settings.begin(), settings.end(), std::pair(d.noise, d.elements)) == settings.end())
        settings.emplace_back(d.noise, d.elements);
      for (const auto& [noise, n] : settings) {
        Unit u = unit_on(UnitKind::Bound, plan, ti, samples);
        u.elements = n;
        u.noise = noise;
        std::ostringstream os;
        os << "bound;" << plan.truths[ti].canonical << ";record_samples=" << samples
           << ";noise=" << io::round_trip(noise) << ";N=" << n << ";estimate=";
        for (const auto& key : spec.fit.estimate) os << key << ",";
        u.canonical = os.str();
        identify(u, spec);
        plan.units.push_back(u);
      }
    }
}

// Every start-distance run from the truth (index -1: the reference minimum), then from every offset in every
// direction, on each of start_distance.records noise records per experiment (record r is the sweep's replicate-r
// draw at start_distance.noise): the first experiment's, or every one's.
void plan_starts(const StudySpec& spec, const std::string& fit, Plan& plan) {
  const auto& d = spec.start_distance;
  for (std::size_t ti = 0; ti < (d.every_experiment ? plan.truths.size() : 1); ++ti)
    for (std::size_t si = 0; si < (d.every_experiment ? spec.sweep.samples.size() : 1); ++si)
      for (int record = 0; record < d.records; ++record) {
        const Unit& truth = plan.truths[ti];
        const int samples = spec.sweep.samples[si];
        const std::string base = truth.canonical + ";record_samples=" + std::to_string(samples) +
                                 ";noise=" + io::round_trip(d.noise) + ";N=" + std::to_string(d.elements) + ";" + fit;
        // With one record, the unit's text is what it was before records existed (a resumed store stays valid).
        const std::string record_text =
            d.records > 1 ? ";record=" + std::to_string(record) + "/" + std::to_string(d.records) : std::string();
        const std::uint64_t noise_seed = record_noise_seed(spec, truth, samples, d.noise, record);
        for (const auto& [cost, method] : d.runs)
          for (int oi = -1; oi < static_cast<int>(d.offsets.size()); ++oi)
            for (int k = oi < 0 ? -1 : 0; k < (oi < 0 ? 0 : d.directions); ++k) {
              Unit u = unit_on(UnitKind::Start, plan, ti, samples);
              u.elements = d.elements;
              u.cost = cost;
              u.method = method;
              u.noise = d.noise;
              u.replicate = record;
              u.index = k;
              u.offset = oi < 0 ? 0.0 : d.offsets[static_cast<std::size_t>(oi)];
              u.noise_seed = noise_seed;
              // The direction's identity is its index among `directions` and its record (its seed derives from the
              // study seed, the record and the index alone, so every run, offset and experiment shares them).
              u.canonical = "start;" + base + ";cost=" + cost + ";method=" + method_text(spec.method(method)) +
                            (k < 0 ? std::string(";start=truth")
                                   : ";offset=" + io::round_trip(u.offset) + ";direction=" + std::to_string(k) + "/" +
                                         std::to_string(d.directions)) +
                            record_text;
              identify(u, spec);
              plan.units.push_back(u);
            }
      }
}

// The overlay case of each cost: its fit is also shown in time and frequency (overlay.csv, spectrum.csv).
void mark_overlays(const StudySpec& spec, Plan& plan) {
  for (const auto& cost : spec.sweep.cost)
    for (Unit& u : plan.units)
      if (u.kind == UnitKind::Case && u.cost == cost && u.elements == spec.outputs.overlay_elements &&
          u.noise == spec.outputs.overlay_noise && u.replicate == 0 && u.method == spec.sweep.method.front() &&
          u.start == spec.sweep.start.front() && u.pulse_width_s == spec.sweep.pulse_width_s.front() &&
          u.samples == spec.sweep.samples.front()) {
        u.overlay = true;
        break;
      }
}

// The Galerkin frequencies of the truth beam at each N of the sweep, beside the exact ones.
void plan_frequencies(const StudySpec& spec, Plan& plan) {
  for (int n : spec.sweep.elements) {
    Unit u;
    u.kind = UnitKind::Frequencies;
    u.elements = n;
    u.canonical = "frequencies;beam=" + beam_identity(spec.truth) + ";N=" + std::to_string(n);
    identify(u, spec);
    plan.units.push_back(u);
  }
}

}  // namespace

Plan make_plan(const StudySpec& spec) {
  // The sweep's size before it is planned (core::kMaxStudyUnits): truths x record lengths x noise draws x N x costs x
  // methods x starts.
  const auto& w = spec.sweep;
  double draws = 0;
  for (double noise : w.noise) draws += noise == 0 ? 1 : w.replicates;
  const double cases = static_cast<double>(std::max<std::size_t>(1, w.pulse_width_s.size())) *
                       static_cast<double>(w.samples.size()) * draws * static_cast<double>(w.elements.size()) *
                       static_cast<double>(w.cost.size()) * static_cast<double>(w.method.size()) *
                       static_cast<double>(w.start.size());
  if (cases > core::kMaxStudyUnits)
    throw InputError(spec.path + ": [sweep] makes " + io::round_trip(cases) + " cases: more than the " +
                     io::round_trip(core::kMaxStudyUnits) +
                     " units a study may plan (about 1 s and 1 KB each); split it into several study files");
  const auto& d = spec.start_distance;
  const double starts = d.enabled
                            ? static_cast<double>(d.runs.size()) *
                                  static_cast<double>(d.offsets.size() * static_cast<std::size_t>(d.directions) + 1) *
                                  d.records * static_cast<double>(std::max<std::size_t>(1, w.pulse_width_s.size())) *
                                  static_cast<double>(w.samples.size())
                            : 0.0;
  if (starts > core::kMaxStudyUnits)
    throw InputError(spec.path + ": [start_distance] makes up to " + io::round_trip(starts) + " fits: more than the " +
                     io::round_trip(core::kMaxStudyUnits) +
                     " units a study may plan (about 1 s and 1 KB each); lower records, directions or offsets");
  Plan plan;
  plan_truths(spec, plan);
  const std::string fit = fit_text(spec);
  plan_cases(spec, fit, plan);
  if (spec.landscape.enabled) plan_landscape(spec, fit, plan);
  plan_bounds(spec, plan);
  if (spec.start_distance.enabled) plan_starts(spec, fit, plan);
  mark_overlays(spec, plan);
  plan_frequencies(spec, plan);
  return plan;
}

std::vector<const Unit*> shard(const std::vector<Unit>& units, int k, int n) {
  std::vector<const Unit*> out;
  for (std::size_t i = static_cast<std::size_t>(k - 1); i < units.size(); i += static_cast<std::size_t>(n))
    out.push_back(&units[i]);
  return out;
}

}  // namespace beamid::study
