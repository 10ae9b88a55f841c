#include "study/run/execute.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"
#include "core/hash.h"
#include "fit/cramer_rao.h"
#include "fit/identification.h"
#include "fit/objective.h"
#include "fit/sensed_output.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "model/exact_frequencies.h"
#include "signal/noise.h"
#include "signal/sensor_filter.h"
#include "signal/spectrum.h"
#include "simulation/simulator.h"
#include "study/analysis/start_distance.h"
#include "study/run/record_schema.h"
#include "study/tables/overlay.h"

namespace beamid::study {
namespace {

void set(model::BeamParameters& beam, const std::string& key, double v) { model::set_parameter_value(beam, key, v); }
double value(const model::BeamParameters& beam, const std::string& key) { return model::parameter_value(beam, key); }

// The unit's experiment; a sampled force is the unit's pulse at its samples (clean: the truth's, and a noise-free
// fit's).
simulation::Experiment experiment_of(const StudySpec& spec, const Unit& unit) {
  simulation::Experiment e = spec.truth.experiment;
  e.pulse_width_s = unit.pulse_width_s;
  e.samples = unit.samples;
  if (e.excitation == simulation::kSampledForce) e.force_samples_N = simulation::sampled_pulse(e);
  return e;
}

// The clean record of a unit: the truth's samples cut to the unit's record length.
std::vector<double> clean_record(const Record& truth, int samples) {
  std::vector<double> y = truth.numbers("y");
  if (static_cast<int>(y.size()) < samples) throw NumericalError("truth record shorter than the case's record");
  y.resize(static_cast<std::size_t>(samples));
  return y;
}

// The record a unit fits: the clean record plus the study's noise (its colour, the unit's level and seed).
std::vector<double> noisy_record(const StudySpec& spec, const std::vector<double>& clean, const Unit& unit) {
  return signal::add_noise(clean, unit.noise, unit.noise_seed, signal::parse_noise_model(spec.truth.noise_model));
}

// The fit options of a unit with `spikes` spikes: the truth gives the fixed parameters, the bounds [v/F, v F] and,
// for landscape units, the start; a case adds its method and its start factors. The optimizer is the cost's default
// unless the method names one.
fit::FitOptions unit_options(const StudySpec& spec, const Unit& unit, int spikes) {
  const model::BeamParameters beam = spec.truth.parameters;
  fit::FitOptions o;
  o.start = beam;
  o.elements = unit.elements;
  o.experiment = experiment_of(spec, unit);
  o.cost.name = unit.cost;
  o.cost.window.name = spec.fit.window;
  o.cost.frequency_weight = spec.fit.frequency_weight;
  o.cost.spikes.count = spikes;
  o.cost.spikes.rule = spec.fit.spike_rule;
  o.cost.spikes.min_frequency_hz = spec.fit.min_frequency_hz;
  if (spec.fit.max_frequency_hz > 0) o.cost.spikes.max_frequency_hz = spec.fit.max_frequency_hz;
  for (const auto& key : spec.fit.estimate) {
    const double v = value(beam, key);
    o.estimate.push_back(fit::bounds_around(key, v, spec.fit.bound_factor));
  }
  o.scaling = spec.fit.scaling;
  o.optimizer.max_evaluations = spec.fit.max_evaluations;
  o.optimizer.xtol_rel = spec.fit.xtol_rel;
  o.optimizer.method = fit::default_optimizer(unit.cost);
  o.seed = unit.seed;
  o.optimizer.seed = unit.seed;
  if (!unit.method.empty()) {  // cases and start-distance fits
    const MethodSpec& m = spec.method(unit.method);
    o.strategy = m.strategy;
    o.refine = m.refine;
    if (m.optimizer != "default") o.optimizer.method = m.optimizer;
    o.starts = m.starts;
    if (!m.window.empty()) o.cost.window.name = m.window;
    if (!m.frequency_weight.empty()) o.cost.frequency_weight = m.frequency_weight;
    o.cost.eps1_factor = m.eps1_factor;
    o.cost.eps2_factor = m.eps2_factor;
    if (!m.noise_model.empty()) o.cost.noise_model = m.noise_model == "truth" ? spec.truth.noise_model : m.noise_model;
    if (m.sensor_in_model) o.sensor = spec.truth.sensor;
  }
  if (unit.kind == UnitKind::Case)
    for (const auto& [key, factor] : spec.start(unit.start).factor) set(o.start, key, value(o.start, key) * factor);
  return o;
}

// The same for a record: the number of spikes follows the modes in the clean data when fit.spikes is "auto". A noisy
// record's measured force carries the force channel's noise ([truth] force_noise), and drives the fit; an
// errors-in-variables method is given both channels' true noise sds.
fit::FitOptions fit_options(const StudySpec& spec, const Unit& unit, const std::vector<double>& clean,
                            const Record& truth, int& modes, int& spikes) {
  modes = modes_in_data(clean, spec.truth.experiment.dt_s, truth.numbers("mode_frequency_hz"));
  spikes = spec.fit.spikes > 0 ? spec.fit.spikes : std::clamp(modes, 1, spec.fit.max_spikes);
  fit::FitOptions o = unit_options(spec, unit, spikes);
  if (spec.truth.force_noise > 0 && unit.noise > 0) {
    std::vector<double>& force = o.experiment.force_samples_N;
    const double force_sd = spec.truth.force_noise * signal::rms(force);
    force = signal::add_noise(force, spec.truth.force_noise, core::derive_seed(unit.noise_seed, "force"));
    if (!unit.method.empty() && spec.method(unit.method).errors_in_variables) {
      o.cost.noise_sd = unit.noise * signal::rms(clean);
      o.cost.force_noise_sd = force_sd;
    }
  }
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// How a unit's record says it failed: a fit keeps "failed" as its status and the reason as its termination (the
// columns of cases and start-distance fits); the other kinds say "failed: <reason>" in their status.
enum class Failure { AsTermination, InStatus };

// A unit's body run on its record (prefilled with the fields a failure leaves), timed: whatever it throws becomes the
// record's status, never a crash of the study.
template <typename Body>
Record timed(Record r, Failure failure, Body body) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    body(r);
  } catch (const std::exception& e) {
    if (failure == Failure::AsTermination) {
      r.set("status", std::string("failed"));
      r.set("termination", e.what());
    } else {
      r.set("status", std::string("failed: ") + e.what());
    }
  }
  r.set("wall_time_s", seconds_since(t0));
  return r;
}

// A unit that works on the truth's record cannot run when the truth failed; it fails with the truth's reason.
void require_truth(const Record& truth) {
  const std::string status = truth.text("status");
  if (status != "ok")
    throw NumericalError("truth simulation failed: " + (status.rfind("failed: ", 0) == 0 ? status.substr(8) : status));
}

// A fit's outcome in a record (cases and start-distance fits alike).
void record_fit(Record& r, const fit::FitResult& result) {
  r.set("status", result.status);
  r.set("termination", result.termination);
  r.set("cost", result.cost);
  r.set("evaluations", static_cast<double>(result.evaluations));
  for (const auto& p : result.parameters) r.set("estimate." + p.key, p.estimate);
}

// The fields of a fit that has not run (so that a failure before the fit still leaves every column).
void record_unrun_fit(Record& r, const std::vector<std::string>& keys) {
  r.set("status", std::string("failed"));
  r.set("termination", std::string("not run"));
  r.set("cost", std::numeric_limits<double>::infinity());
  r.set("evaluations", 0.0);
  for (const auto& key : keys) r.set("estimate." + key, std::numeric_limits<double>::quiet_NaN());
}

Overlay case_overlay(const StudySpec& spec, const Unit& unit, const Record& truth, const Record& result) {
  const std::vector<double> clean = clean_record(truth, unit.samples);
  const std::vector<double> data = noisy_record(spec, clean, unit);
  int modes = 0, spikes = 0;
  fit::FitOptions o = fit_options(spec, unit, clean, truth, modes, spikes);
  model::BeamParameters estimate = spec.truth.parameters;
  for (const auto& key : spec.fit.estimate) {
    const double v = result.number("estimate." + key);
    if (std::isfinite(v)) set(estimate, key, v);
  }
  return compute_overlay(o, data, estimate);
}

}  // namespace

namespace {

// The natural frequencies (Hz) and damping ratios of a system's underdamped modes, lowest first, at most `limit`.
std::pair<std::vector<double>, std::vector<double>> mode_lists(
    const galerkin::SecondOrderSystem& system, std::size_t limit = std::numeric_limits<std::size_t>::max()) {
  std::pair<std::vector<double>, std::vector<double>> out;
  for (const auto& m : galerkin::StateSpaceModes(system).underdamped_modes()) {
    if (out.first.size() >= limit) break;
    out.first.push_back(m.frequency_hz);
    out.second.push_back(m.damping_ratio);
  }
  return out;
}

}  // namespace

// The truth's CVODE cross-check stops after this many steps, 6x the most any committed study's check took (168,843,
// the thin beam at N = 48: about 10 s); past it the check covers the samples it reached and says so, instead of
// running for many minutes where the plan said seconds (a pulse as long as the record: 9.5 million steps).
constexpr long kCvodeCheckSteps = 1000000;

Record run_truth(const StudySpec& spec, const Unit& truth) {
  Record record = timed(Record(), Failure::InStatus, [&](Record& r) {
    const model::BeamParameters beam = spec.truth.parameters;
    const galerkin::SplineSpace space(spec.truth.elements);
    const galerkin::BeamForms forms(space, beam.l, beam.support);
    // The truth is the exact modal closed form at N_truth (simulation/modal_simulator.h: no time-stepping error, about
    // 0.05 s at N = 48); it differs from every fitted model by the discretisation N_truth against N, which is what
    // keeps the study clear of the inverse crime. CVODE, an independent integrator of the same equations, checks it
    // once per study: the first truth's agreement (max |y_fast - y_cvode| / max |y|) is recorded and stated in the
    // manifest. At rtol 1e-10 it is CVODE's own error, 1e-8 (displacement) to 1e-7 (acceleration) of max |y|.
    simulation::SimulatorOptions options;
    options.integrator = simulation::kFast;
    const simulation::Experiment experiment = experiment_of(spec, truth);
    // A damping law no fitted model has, when the study asks for one (TruthSpec::modal_damping_ratio).
    const galerkin::SecondOrderSystem system =
        galerkin::with_modal_damping(galerkin::combine(forms, beam), spec.truth.modal_damping_ratio);
    // A sensor of finite bandwidth (TruthSpec::sensor): the truth simulated finer, filtered, and sampled.
    const signal::SensorFilter& sensor = spec.truth.sensor;
    const simulation::Experiment simulated = fit::simulated_experiment(experiment, sensor);
    simulation::Trace trace = simulation::simulate(forms, system, beam.l, simulated, options);
    if (truth.cvode_check && trace.ok()) {
      simulation::SimulatorOptions check;
      check.integrator = simulation::kCvode;
      check.cvode.rtol = spec.truth.rtol;
      check.cvode.max_total_steps = kCvodeCheckSteps;
      const simulation::Trace cvode = simulation::simulate(forms, system, beam.l, simulated, check);
      r.set("cvode_status", cvode.status);
      r.set("cvode_steps", static_cast<double>(cvode.stats.steps));
      // Stopped by its budget, it is compared over the samples it reached (its status says how many).
      if (cvode.ok() || (!cvode.y.empty() && cvode.y.size() < trace.y.size())) {
        double y_max = 0, difference = 0;
        for (std::size_t i = 0; i < cvode.y.size(); ++i) {
          y_max = std::max(y_max, std::abs(trace.y[i]));
          difference = std::max(difference, std::abs(trace.y[i] - cvode.y[i]));
        }
        if (y_max > 0) r.set("cvode_max_difference_over_max_y", difference / y_max);
      }
    }
    // A cut-off below the modes leaves no vibration to fit (0.001 Hz kept 2e-12 of it and every fit ran on nothing:
    // the second adversarial pass of 2026-11-28, P4): the truth fails, saying so.
    double kept = 1;
    if (sensor.cutoff_hz > 0 && trace.ok()) {
      std::vector<double> ideal(static_cast<std::size_t>(experiment.samples));
      for (std::size_t i = 0; i < ideal.size(); ++i)
        ideal[i] = trace.y[i * static_cast<std::size_t>(sensor.oversampling)];
      fit::sense_output(sensor, experiment, trace.y);  // as a fit with the filter in its model senses its own
      kept = signal::rms(trace.y) / signal::rms(ideal);
    }
    const auto [f, zeta] = mode_lists(system);
    // A truth that holds no vibration (sensor or force at the clamp, a pulse of 1e300 s, a step of 1e-300 s) would
    // let every time fit "converge" at cost 0 on nothing; it fails, and its cases with it, saying why.
    double peak = 0;
    for (const double y : trace.y) peak = std::max(peak, std::abs(y));
    // Every mode above the Nyquist frequency: the record holds only their aliases, and the fits' bias tables were
    // artefacts of them, with nothing said (truth.dt_s = 10: the twenty-third pass's P1).
    const double nyquist_hz = 0.5 / experiment.dt_s;
    const bool aliased = !f.empty() && *std::min_element(f.begin(), f.end()) >= nyquist_hz;
    r.set("status",
          !trace.ok() ? trace.status
          : aliased
              ? "failed: every mode of the truth (the first at " + format_value(*std::min_element(f.begin(), f.end())) +
                    " Hz) lies above the record's Nyquist frequency " + format_value(nyquist_hz) +
                    " Hz (truth.dt_s = " + format_value(experiment.dt_s) + "): the record holds only their aliases"
          : !(kept >= 0.01)
              ? "failed: the sensor filter at " + format_value(sensor.cutoff_hz) + " Hz keeps " + format_value(kept) +
                    " of the truth's RMS: it removes the vibration (a cut-off below the modes)"
          : !(peak >= 1e-150 && peak <= 1e150)
              ? "failed: the truth record's peak is " + format_value(peak) +
                    ", outside [1e-150, 1e150]: no vibration to fit (sensor or force at the clamp, or a "
                    "pulse far longer or shorter than the record's step?)"
              : trace.status);
    r.set("y", trace.y);
    r.set("mode_frequency_hz", f);
    r.set("mode_damping_ratio", zeta);
    r.set("integrator", trace.stats.integrator);
  });
  record.set("kind", unit_kind_name(UnitKind::Truth));
  record.set("inputs", inputs_hash(truth));
  return record;
}

int modes_in_data(const std::vector<double>& clean, double dt_s, const std::vector<double>& mode_frequency_hz) {
  signal::Dft dft(static_cast<int>(clean.size()), dt_s);
  const signal::Spectrum s = dft.transform(clean);
  std::vector<double> peak;
  for (double f : mode_frequency_hz) {
    const long k = std::lround(f / s.df_hz());
    if (k < 1 || k + 1 > s.last_bin()) continue;  // at or above Nyquist: not resolvable
    peak.push_back(std::max({s.magnitude(k - 1), s.magnitude(k), s.magnitude(k + 1)}));
  }
  if (peak.empty()) return 0;
  const double largest = *std::max_element(peak.begin(), peak.end());
  return static_cast<int>(std::count_if(peak.begin(), peak.end(), [&](double p) { return p >= 1e-2 * largest; }));
}

void validate_plan(const StudySpec& spec, const Plan& plan) {
  for (const Unit& u : plan.units) {
    if (u.kind == UnitKind::Frequencies || u.kind == UnitKind::Bound) continue;  // no fit
    try {
      fit::validate(unit_options(spec, u, spec.fit.spikes > 0 ? spec.fit.spikes : spec.fit.max_spikes));
    } catch (const InputError& e) {
      throw InputError(spec.path + ": " + unit_kind_name(u.kind) + " " + u.id + " (N = " + std::to_string(u.elements) +
                       ", cost " + u.cost + (u.method.empty() ? "" : ", method " + u.method) + "): " + e.what());
    }
  }
}

Record run_case(const StudySpec& spec, const Unit& unit, const Record& truth) {
  Record prefilled;
  record_unrun_fit(prefilled, spec.fit.estimate);
  prefilled.set("a4", std::string("-"));
  const model::BeamParameters beam = spec.truth.parameters;
  for (const auto& key : spec.fit.estimate) {
    prefilled.set("standard_error." + key, std::numeric_limits<double>::quiet_NaN());
    prefilled.set("relative_error." + key, std::numeric_limits<double>::quiet_NaN());
  }
  return timed(std::move(prefilled), Failure::AsTermination, [&](Record& r) {
    require_truth(truth);
    const std::vector<double> clean = clean_record(truth, unit.samples);
    const std::vector<double> data = noisy_record(spec, clean, unit);
    int modes = 0, spikes = 0;
    const fit::FitOptions o = fit_options(spec, unit, clean, truth, modes, spikes);
    r.set("modes_in_data", static_cast<double>(modes));
    r.set("spikes", static_cast<double>(costs::is_spike_cost(unit.cost) ? spikes : 0));
    const fit::FitResult result = fit::fit(o, data);
    record_fit(r, result);
    r.set("best_start", static_cast<double>(result.best_start));
    r.set("a4", result.final_evaluation.a4);
    for (const auto& p : result.parameters) {
      const double t = value(beam, p.key);
      r.set("standard_error." + p.key, p.standard_error);
      r.set("relative_error." + p.key, (p.estimate - t) / t);
    }
    if (unit.overlay) {  // the fit in time and frequency, for the overlay plots
      try {
        store_overlay(r, case_overlay(spec, unit, truth, r));
      } catch (const std::exception& e) {
        r.set("overlay.status", std::string("failed: ") + e.what());
      }
    }
  });
}

Record run_landscape(const StudySpec& spec, const Unit& unit, const Record& truth) {
  Record prefilled;
  prefilled.set("status", std::string("ok"));
  return timed(std::move(prefilled), Failure::InStatus, [&](Record& r) {
    require_truth(truth);
    const std::vector<double> clean = clean_record(truth, unit.samples);
    int modes = 0, spikes = 0;
    fit::FitOptions o = fit_options(spec, unit, clean, truth, modes, spikes);
    r.set("modes_in_data", static_cast<double>(modes));
    // A noisy landscape sees the record of the sweep's replicate 0 at its noise level (the same draw as its cases).
    const std::vector<double> data = noisy_record(spec, clean, unit);
    const model::BeamParameters beam = spec.truth.parameters;
    const double F = unit.range_factor > 1 ? unit.range_factor : spec.landscape.range_factor;
    // Log-spaced axis v F^(2j/(P-1) - 1), j = 0..P-1: the middle point (P odd) is the true value.
    const auto axis = [&](const std::string& key, int points) {
      std::vector<double> x(static_cast<std::size_t>(points));
      for (int j = 0; j < points; ++j)
        x[static_cast<std::size_t>(j)] = value(beam, key) * std::pow(F, 2.0 * j / (points - 1) - 1);
      return x;
    };
    if (unit.kind == UnitKind::Slice || unit.kind == UnitKind::Grid) {
      fit::Objective objective(o, data);
      const auto cost_at = [&](const model::BeamParameters& b) {
        const double c = objective.evaluate(b).evaluation.value;
        return std::isfinite(c) ? c : std::numeric_limits<double>::infinity();
      };
      if (unit.kind == UnitKind::Slice) {
        const std::vector<double> x = axis(unit.parameters[0], unit.points);
        std::vector<double> c;
        for (double v : x) {
          model::BeamParameters b = beam;
          set(b, unit.parameters[0], v);
          c.push_back(cost_at(b));
        }
        r.set("x", x);
        r.set("cost", c);
      } else {
        const std::vector<double> x = axis(unit.parameters[0], unit.points);
        const std::vector<double> y = axis(unit.parameters[1], unit.points);
        std::vector<double> c;
        for (double u : x)
          for (double v : y) {
            model::BeamParameters b = beam;
            set(b, unit.parameters[0], u);
            set(b, unit.parameters[1], v);
            c.push_back(cost_at(b));
          }
        r.set("x", x);
        r.set("y", y);
        r.set("cost", c);
      }
    } else {  // multistart: index -1 starts at the truth (the reference minimum), others at random points
      if (unit.index >= 0) {
        Eigen::VectorXd lower(static_cast<int>(o.estimate.size())), upper(lower.size());
        for (std::size_t i = 0; i < o.estimate.size(); ++i) {
          lower[static_cast<int>(i)] = std::log(o.estimate[i].lower);
          upper[static_cast<int>(i)] = std::log(o.estimate[i].upper);
        }
        // One Latin hypercube (in log coordinates) per cost, shared by its multistart units; this unit takes point k.
        const auto points = fit::space_filling_starts(lower, upper, spec.landscape.multistarts, "lhs",
                                                      core::derive_seed(spec.seed, "multistart;" + unit.cost));
        for (std::size_t i = 0; i < o.estimate.size(); ++i)
          set(o.start, o.estimate[i].key, std::exp(points[static_cast<std::size_t>(unit.index)][static_cast<int>(i)]));
      }
      for (const auto& e : o.estimate) r.set("start." + e.key, value(o.start, e.key));
      const fit::FitResult result = fit::fit(o, data);
      r.set("status", result.status);
      r.set("cost", result.cost);
      r.set("evaluations", static_cast<double>(result.evaluations));
      for (const auto& p : result.parameters) r.set("estimate." + p.key, p.estimate);
    }
  });
}

// The fitted model's modes a fit from the truth records: at most 6 are fitted (fit.spikes), 8 leave a margin.
constexpr std::size_t kRecordedModes = 8;

Record run_start(const StudySpec& spec, const Unit& unit, const Record& truth) {
  Record prefilled;
  record_unrun_fit(prefilled, spec.fit.estimate);
  prefilled.set("frequency_offset", 0.0);
  prefilled.set("shrunk", 0.0);
  for (const auto& key : spec.fit.estimate) prefilled.set("start." + key, std::numeric_limits<double>::quiet_NaN());
  return timed(std::move(prefilled), Failure::AsTermination, [&](Record& r) {
    require_truth(truth);
    const std::vector<double> clean = clean_record(truth, unit.samples);
    const std::vector<double> data = noisy_record(spec, clean, unit);
    int modes = 0, spikes = 0;
    fit::FitOptions o = fit_options(spec, unit, clean, truth, modes, spikes);
    r.set("fitted_modes", static_cast<double>(spikes));
    r.set("modes_in_data", static_cast<double>(modes));
    if (unit.index >= 0) {
      // The fitted modes: the spikes of a spike cost; for the others the same number, so that every run is started
      // at the same frequency offset of the same modes.
      const galerkin::SplineSpace space(unit.elements);
      const galerkin::BeamForms forms(space, spec.truth.parameters.l, spec.truth.parameters.support);
      // With several records, each draws its own directions (one record: the index alone names it, as before).
      const std::string direction_name =
          "start-direction;" + std::to_string(unit.index) +
          (spec.start_distance.records > 1 ? ";record=" + std::to_string(unit.replicate) : std::string());
      const Eigen::VectorXd u =
          random_direction(core::derive_seed(spec.seed, direction_name), static_cast<int>(spec.fit.estimate.size()));
      const OffsetStart s =
          offset_start(forms, spec.truth.parameters, spec.fit.estimate, spikes, u, unit.offset, spec.fit.bound_factor);
      for (const auto& key : spec.fit.estimate) set(o.start, key, value(s.start, key));
      r.set("frequency_offset", s.frequency_offset);
      r.set("shrunk", s.shrunk ? 1.0 : 0.0);
    }
    for (const auto& key : spec.fit.estimate) r.set("start." + key, value(o.start, key));
    const fit::FitResult result = fit::fit(o, data);
    record_fit(r, result);
    // A fit from the truth also records its model's damped modes, so that the tables can judge frequency and damping
    // per mode against the truth's own (issue 35: under a damping law the model lacks, cDI and gamma have no true
    // value, but every mode's damping ratio has).
    if (unit.index < 0 && result.status != "failed") {
      const auto [f, zeta] =
          mode_lists(galerkin::assemble(galerkin::SplineSpace(unit.elements), result.beam), kRecordedModes);
      r.set("fitted_mode_frequency_hz", f);
      r.set("fitted_mode_damping_ratio", zeta);
    }
  });
}

Record run_bound(const StudySpec& spec, const Unit& unit, const Record& truth) {
  Record prefilled;
  prefilled.set("status", std::string("failed"));
  prefilled.set("noise_sd", std::numeric_limits<double>::quiet_NaN());
  for (const auto& key : spec.fit.estimate)
    prefilled.set("relative_sd." + key, std::numeric_limits<double>::quiet_NaN());
  return timed(std::move(prefilled), Failure::InStatus, [&](Record& r) {
    require_truth(truth);
    // The noise the cases add: level x RMS of the clean record (signal/noise.h).
    const double noise_sd = unit.noise * signal::rms(clean_record(truth, unit.samples));
    // Of the record as the truth's sensor delivers it (its filter, when it has one, in the model).
    fit::CramerRaoBound b = fit::beam_cramer_rao_bound(spec.truth.parameters, unit.elements, experiment_of(spec, unit),
                                                       spec.fit.estimate, noise_sd, {}, {}, spec.truth.sensor);
    // In the records' coloured noise of that process sd, the bound of the whitened sensitivities.
    if (spec.truth.noise_model != "white")
      b = fit::coloured_bound(b, signal::parse_noise_model(spec.truth.noise_model));
    r.set("status", b.status);
    r.set("method", b.method);
    r.set("noise_sd", noise_sd);
    r.set("rcond", b.rcond);
    for (std::size_t i = 0; i < b.keys.size(); ++i)
      r.set("relative_sd." + b.keys[i], b.relative_sd(static_cast<Eigen::Index>(i)));
  });
}

Record run_frequencies(const StudySpec& spec, int elements) {
  Record r;
  const auto t0 = std::chrono::steady_clock::now();
  r.set("status", std::string("ok"));
  const model::BeamParameters& beam = spec.truth.parameters;
  std::vector<double> exact;
  try {
    for (double w : model::timoshenko_frequencies_rad_s(beam, 4)) exact.push_back(w / (2 * M_PI));
  } catch (const std::exception& e) {
    r.set("status", std::string("failed: exact frequencies: ") + e.what());
  }
  r.set("exact_hz", exact);
  {
    const int n = elements;
    std::vector<double> f;
    try {
      const galerkin::SplineSpace space(n);
      const auto modes = galerkin::undamped_modes(galerkin::assemble(space, beam));
      for (std::size_t m = 0; m < exact.size() && static_cast<int>(m) < modes.omega_rad_s.size(); ++m)
        f.push_back(modes.omega_rad_s[static_cast<int>(m)] / (2 * M_PI));
    } catch (const std::exception& e) {
      r.set("status", "failed: N = " + std::to_string(n) + ": " + e.what());
    }
    r.set("galerkin_hz", f);
  }
  r.set("wall_time_s", seconds_since(t0));
  return r;
}

Record run_unit(const StudySpec& spec, const Unit& unit, const Record& truth) {
  Record r = unit.kind == UnitKind::Case          ? run_case(spec, unit, truth)
             : unit.kind == UnitKind::Frequencies ? run_frequencies(spec, unit.elements)
             : unit.kind == UnitKind::Start       ? run_start(spec, unit, truth)
             : unit.kind == UnitKind::Bound       ? run_bound(spec, unit, truth)
                                                  : run_landscape(spec, unit, truth);
  r.set("kind", unit_kind_name(unit.kind));
  r.set("inputs", inputs_hash(unit));
  return r;
}

}  // namespace beamid::study
