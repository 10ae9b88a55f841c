#include "api/model_requests.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>

#include "api/cost_request.h"
#include "api/model_notes.h"
#include "core/errors.h"
#include "core/limits.h"
#include "fit/identifiability.h"
#include "galerkin/modes.h"
#include "model/exact_frequencies.h"
#include "signal/noise.h"
#include "simulation/sensitivities.h"

namespace beamid::api {

ModelRun model_run(const ModelRunRequest& request, double bytes_per_sample, std::ostream& warnings) {
  check_elements(request.caller, request.elements);
  ModelRun run{request.beam_name, request.beam, request.elements, {}};
  run.experiment = experiment_of(request.experiment, run.beam.l, request.caller);
  guard_run_size(request.caller, run.elements, bytes_per_sample > 0 ? run.experiment.samples : 0, bytes_per_sample,
                 warnings);
  if (const std::string note = attachment_convergence_note(run.beam, run.elements); !note.empty())
    warnings << request.caller.label << ": " << note << "\n";
  return run;
}

namespace {

// "--count K: the Galerkin model at N = n has S <what>: S printed" when count asks for more than the model has.
std::string fewer_modes_note(const ModesResult& r, int elements, const std::string& what) {
  if (!r.requested || *r.requested <= r.available) return "";
  return "--count " + std::to_string(*r.requested) + ": the Galerkin model at N = " + std::to_string(elements) +
         " has " + std::to_string(r.available) + " " + what + ": " + std::to_string(r.available) + " printed";
}

// The exact (determinant) frequencies of the beam (model/exact_frequencies.h).
void exact_modes(const ModesRequest& request, ModesResult& r) {
  r.kind = "exact";
  const auto omega = model::timoshenko_frequencies_rad_s(request.beam, r.requested.value_or(4));
  if (r.requested && static_cast<int>(omega.size()) < *r.requested)
    refuse(request.caller, "--count = " + std::to_string(*r.requested) + ": only " + std::to_string(omega.size()) +
                               " modes lie below the shear cut-off");
  for (const double w : omega) r.frequency_hz.push_back(w / (2 * std::numbers::pi));
  r.available = static_cast<int>(omega.size());
}

}  // namespace

ModesResult compute_modes(const ModesRequest& request, std::ostream& warnings) {
  ModesResult r;
  r.requested = request.count;
  if (r.requested && *r.requested < 1) refuse(request.caller, "count", std::to_string(*r.requested), "must be >= 1");
  if (!request.exact && !request.elements)
    refuse(request.caller, "give one of --elements N (Galerkin) and --exact (determinant)");
  if (request.exact) {
    exact_modes(request, r);
    return r;
  }
  const int n = *request.elements;
  check_elements(request.caller, n);
  guard_run_size(request.caller, n, 0, 0, warnings);
  const galerkin::SplineSpace space(n);
  const galerkin::SecondOrderSystem system = galerkin::assemble(space, request.beam);
  const auto add_note = [&r](const std::string& note) {
    if (!note.empty()) r.note += (r.note.empty() ? "" : "; ") + note;
  };
  if (request.undamped) {
    r.kind = "undamped";
    const Eigen::VectorXd omega = galerkin::undamped_modes(system).omega_rad_s;
    r.available = static_cast<int>(omega.size());
    const int shown = std::min(r.requested.value_or(r.available), r.available);
    r.note = fewer_modes_note(r, n, "modes");
    add_note(attachment_convergence_note(request.beam, n));
    for (int k = 0; k < shown; ++k) {
      r.frequency_hz.push_back(omega(k) / (2 * std::numbers::pi));
      r.damping_ratio.push_back(0.0);
    }
    return r;
  }
  r.kind = "damped";
  const galerkin::StateSpaceModes state_space(system);
  const auto modes = state_space.underdamped_modes();
  r.available = static_cast<int>(modes.size());
  const int shown = std::min(r.requested.value_or(r.available), r.available);
  r.note = fewer_modes_note(r, n, "underdamped modes");
  add_note(attachment_convergence_note(request.beam, n));
  add_note(nearly_defective_note(state_space.eigenvector_rcond()));
  // Overdamped modes (real pole pairs) have no frequency and are not listed. The Galerkin model's highest modes
  // always are (Kelvin-Voigt damping grows as omega^2); said when one lies among the listed ones, i.e. when more
  // undamped modes lie below the highest listed frequency than underdamped ones are listed, since the rows'
  // numbers then skip it (with cDI = 0.05 "mode 2" was at 4564 Hz, bending modes 2-8 overdamped: the third pass's
  // P178, P179).
  if (shown > 0) {
    const Eigen::VectorXd omega = galerkin::undamped_modes(system).omega_rad_s;
    const double highest_rad_s = 2 * std::numbers::pi * modes[static_cast<std::size_t>(shown - 1)].frequency_hz;
    const auto below = static_cast<int>(
        std::count_if(omega.data(), omega.data() + omega.size(), [&](double w) { return w < highest_rad_s; }));
    // Air damping (gamma) overdamps the lowest modes instead, and moves the rest: with gamma = 50 "mode 1" was at
    // 11.3 Hz, zeta 0.63, above the undamped beam's second mode, so that the count above missed it (the fourth pass's
    // Q311). An undamped mode well below the lowest listed one (under 0.9 of its |lambda|; damping moves a lightly
    // damped mode's |lambda| by far less) has no underdamped counterpart: it is overdamped. (Counting real poles
    // instead took the shear relaxation poles, kAG / kAcs, for overdamped modes: the fifth pass's R211.)
    const double lowest_rad_s = 2 * std::numbers::pi * modes.front().frequency_hz;
    const auto missing_below = static_cast<int>(
        std::count_if(omega.data(), omega.data() + omega.size(), [&](double w) { return w < 0.9 * lowest_rad_s; }));
    if (below > shown)
      r.note += std::string(r.note.empty() ? "" : "; ") + std::to_string(below - shown) +
                " mode(s) of the undamped beam below " + format_rounded(highest_rad_s / (2 * std::numbers::pi)) +
                " Hz are overdamped here (real poles, no oscillation) and not listed: 'mode' numbers the underdamped "
                "modes only (--undamped lists the undamped beam's)";
    else if (missing_below > 0)
      r.note += std::string(r.note.empty() ? "" : "; ") + "the damping overdamps " + std::to_string(missing_below) +
                " mode(s) of the undamped beam below " + format_rounded(lowest_rad_s / (2 * std::numbers::pi)) +
                " Hz here (real poles, no oscillation): 'mode' numbers the underdamped modes only (--undamped lists "
                "the undamped beam's)";
  }
  for (int k = 0; k < shown; ++k) {
    r.frequency_hz.push_back(modes[static_cast<std::size_t>(k)].frequency_hz);
    r.damping_ratio.push_back(modes[static_cast<std::size_t>(k)].damping_ratio);
  }
  return r;
}

namespace {
// Why a simulated response is zero at every sample, for simulate and crb.
constexpr const char* kZeroResponse =
    "the response is zero at every sample: the sensor or the force is at a rigid clamp (--sensor-x, --force-x 0) or "
    "the force is 0 (--force-amplitude)";

}  // namespace

namespace {

// The force channel of a simulated pulse test: P(t_i) (`clean`), and with its own white noise (the seed's second
// stream) as returned.
std::vector<double> force_channel(const SimulateRequest& request, const simulation::Experiment& e,
                                  std::vector<double>& clean) {
  const Caller& caller = request.run.caller;
  if (e.excitation != simulation::kPulse)
    refuse(caller, "--force-column records a pulse's force; --excitation " + e.excitation + " has none after t = 0");
  const double level = request.force_noise_level.value_or(0.0);
  if (!(level >= 0 && level <= 10))
    refuse(caller, "force-noise-level", format_value(level), "must be in [0, 10] (times the force's RMS)");
  const std::vector<double> f = simulation::sampled_pulse(e);
  // A pulse narrower than the step falls between the samples: a column of zeros, which drives nothing (the adversarial
  // pass's P5: it was reported as a force at the clamp).
  if (e.force_amplitude_N != 0 && std::all_of(f.begin(), f.end(), [](double v) { return v == 0; }))
    refuse(caller, "pulse-width", format_value(e.pulse_width_s),
           "falls between the force column's samples (dt = " + format_value(e.dt_s) +
               " s): every one is 0; give a pulse of at least 2 dt");
  const auto seed = static_cast<std::uint64_t>(request.seed.value_or(1));
  clean = f;
  return signal::add_noise(f, level, core::derive_seed(seed, "force"));
}

}  // namespace

SimulateResult compute_simulate(const SimulateRequest& request, std::ostream& warnings) {
  const Caller& caller = request.run.caller;
  SimulateResult r{model_run(request.run, core::kSimulateBytesPerSample, warnings), {}, {}, {}};
  simulation::SimulatorOptions options;
  options.integrator = request.integrator;
  // CVODE's tolerances and order do nothing to the exact propagator: said, not ignored.
  if (options.integrator != simulation::kCvode)
    for (const auto& [flag, given] :
         {std::pair{"rtol", request.rtol.has_value()}, std::pair{"atol", request.atol.has_value()},
          std::pair{"max-order", request.max_order.has_value()}})
      if (given)
        refuse(caller, std::string("--") + flag + " is CVODE's (--integrator cvode); --integrator " +
                           options.integrator + " is exact and has no tolerance or order");
  options.cvode.rtol = request.rtol.value_or(options.cvode.rtol);
  options.cvode.atol = request.atol.value_or(options.cvode.atol);
  options.cvode.max_order = request.max_order.value_or(options.cvode.max_order);
  options.cvode.progress = &warnings;
  if (auto error = simulation::validation_error(options)) refuse(caller, *error);
  // A synthetic lab record: white noise of noise_level times the clean signal's RMS (signal/noise.h).
  const double noise = request.noise_level.value_or(0.0);
  if (!(noise >= 0 && noise <= 10))
    refuse(caller, "noise-level", format_value(noise), "must be in [0, 10] (times the signal's RMS)");
  if (request.seed && !request.noise_level)
    refuse(caller, "seed", std::to_string(*request.seed), "seeds the noise: give --noise-level too");
  if (request.noise_model && !request.noise_level)
    refuse(caller, "noise-model", *request.noise_model, "colours the noise: give --noise-level too");
  const signal::NoiseModel noise_model =
      request.noise_model ? parsed_noise_model(caller, *request.noise_model) : signal::NoiseModel{};
  if (request.seed && *request.seed < 0)
    refuse(caller, "seed", std::to_string(*request.seed), "must be an integer >= 0");
  if (request.force_noise_level && !request.force_column)
    refuse(caller, "force-noise-level", format_value(*request.force_noise_level),
           "is noise on the force column: give --force-column too");
  if (request.force_column) {
    // The response to the force as recorded (its samples, linear between them): what a fit with --force-channel
    // models, so that such a record is no test of the interpolation (the continuous pulse differs from it by up to
    // 0.4 % of EI at 4 samples a pulse). The column carries the force's own noise; the model saw the clean samples.
    std::vector<double> clean;
    r.force_N = force_channel(request, r.run.experiment, clean);
    r.run.experiment.excitation = simulation::kSampledForce;
    r.run.experiment.force_samples_N = std::move(clean);
  }
  const galerkin::SplineSpace space(r.run.elements);
  const galerkin::BeamForms forms(space, r.run.beam.l, r.run.beam.support);
  r.trace = simulation::simulate(forms, r.run.beam, r.run.experiment, options);
  if (!r.trace.ok()) throw NumericalError(caller.label + ": " + r.trace.status);
  // A response that is zero everywhere is no record (every reader refuses a constant one, and a study refuses such a
  // truth): the sensor or the force at a rigid clamp, or no force (the third pass's P216, P218, P219).
  if (std::all_of(r.trace.y.begin(), r.trace.y.end(), [](double v) { return v == 0; }))
    refuse(caller, std::string(kZeroResponse) + "; nothing is written");
  if (r.trace.stats.integrator == simulation::kFast)
    if (const std::string note = nearly_defective_note(r.trace.stats.eigenvector_rcond); !note.empty())
      warnings << caller.label << ": " << note << "\n";
  r.y = signal::add_noise(r.trace.y, noise, static_cast<std::uint64_t>(request.seed.value_or(1)), noise_model);
  return r;
}

SystemResult compute_system(const ModelRunRequest& request, std::ostream& warnings) {
  SystemResult r{model_run(request, 0, warnings), {}, {}};
  const galerkin::SplineSpace space(r.run.elements);
  const galerkin::BeamForms forms(space, r.run.beam.l, r.run.beam.support);
  r.system = galerkin::combine(forms, r.run.beam);
  r.problem = simulation::make_problem(forms, r.system, r.run.experiment);
  return r;
}

namespace {

// The noise sd the bound assumes: noise_sd, or noise_level times the RMS of the clean record at the beam's values.
double crb_noise_sd(const CrbRequest& request, const ModelRun& run) {
  const Caller& caller = request.run.caller;
  if (request.noise_sd) {
    // Within [1e-150, 1e150], as a record's values are: beyond, the bound underflowed to 0 or overflowed to inf.
    if (!(*request.noise_sd >= 1e-150 && *request.noise_sd <= 1e150))
      refuse(caller, "noise-sd", format_value(*request.noise_sd), "must lie in [1e-150, 1e150] (in the output's unit)");
    return *request.noise_sd;
  }
  const double level = *request.noise_level;
  if (!(level > 0)) refuse(caller, "noise-level", format_value(level), "must be > 0");
  const galerkin::SplineSpace space(run.elements);
  const simulation::Trace clean =
      simulation::simulate(galerkin::BeamForms(space, run.beam.l, run.beam.support), run.beam, run.experiment, {});
  if (!clean.ok()) throw NumericalError(caller.label + ": the model could not be evaluated: " + clean.status);
  const double sigma = level * signal::rms(clean.y);
  if (!(sigma > 0))
    refuse(caller, "noise-level", format_value(level),
           "the clean signal is zero, so a fraction of its RMS is no noise level");
  return sigma;
}

}  // namespace

CrbResult compute_crb(const CrbRequest& request, std::ostream& warnings) {
  const Caller& caller = request.run.caller;
  CrbResult r{model_run(request.run, core::kSimulateBytesPerSample, warnings), {}, {}, 0, {}, {}};
  const model::BeamParameters& beam = r.run.beam;
  std::string listed;  // the --estimate list as given, for its errors
  for (const std::string& key : request.estimate) listed += (listed.empty() ? "" : ",") + key;
  for (const std::string& key : request.estimate) {
    if (!model::describe_parameter(beam, key))
      refuse(caller, "estimate", listed,
             "'" + key + "' is not a parameter of this beam (valid: " + model::estimable_keys(beam) + ")");
    r.keys.push_back(key);
  }
  if (r.keys.empty()) refuse(caller, "estimate", listed, "must name at least one parameter");
  // The bound is of a simulated experiment; a free decay's initial state is unknown (the error blamed --estimate:
  // the fourth pass's Q291).
  if (r.run.experiment.excitation == simulation::kFreeDecay)
    refuse(caller, "excitation", simulation::kFreeDecay,
           "the bound is computed for a simulated experiment, and a free decay's initial state is unknown: use "
           "pulse or pluck");
  if (!request.noise_sd && !request.noise_level)
    refuse(caller, "give one of --noise-sd S (absolute) and --noise-level L (fraction of the RMS)");
  r.options.log_step = request.log_step.value_or(r.options.log_step);
  // At least 1e-8: a central difference in ln q of h has a rounding error of eps/h, which drowns the sensitivity below
  // that (a step of 1e-300 was reported as an unidentifiable parameter).
  if (!(r.options.log_step >= 1e-8 && r.options.log_step <= 0.1))
    refuse(caller, "log-step", format_value(r.options.log_step), "must lie in [1e-8, 0.1]");
  // The pulse's sensitivities are exact (the tangent equations, fit/cramer_rao.cc): no step is taken, and a given
  // --log-step was ignored without a word.
  if (request.log_step && simulation::has_exact_sensitivities(r.run.experiment, r.keys))
    refuse(caller, "log-step", format_value(*request.log_step),
           "sets the finite-difference step; these sensitivities are exact (the tangent equations of the pulse "
           "response), with no step");
  r.noise_sd = crb_noise_sd(request, r.run);
  try {
    r.bound = fit::beam_cramer_rao_bound(beam, r.run.elements, r.run.experiment, r.keys, r.noise_sd, {}, r.options);
  } catch (const InputError& error) {
    refuse(caller, "estimate", listed, error.what());
  }
  if (request.noise_model) r.bound = fit::coloured_bound(r.bound, parsed_noise_model(caller, *request.noise_model));
  // Every sensitivity 0: the output is zero whatever the parameters (the fourth pass's Q299-Q305: "singular Fisher
  // information" for a zero force or a sensor at the clamp, where simulate names the cause).
  if (r.bound.sensitivities.size() > 0 && r.bound.sensitivities.cwiseAbs().maxCoeff() == 0)
    refuse(caller, kZeroResponse);
  if (r.bound.status != "ok") {
    // Named: the direction in ln q along which the output does not change (the twenty-second pass's P7).
    const Eigen::VectorXd& v = r.bound.null_direction;
    const std::string along =
        v.size() == static_cast<Eigen::Index>(r.keys.size())
            ? " (the output does not change along " + fit::combination_text(r.keys, {v.data(), v.data() + v.size()}) +
                  (r.bound.null_dimension > 1 ? ", nor along " + std::to_string(r.bound.null_dimension - 1) +
                                                    " other direction(s) independent of it"
                                              : "") +
                  ": estimate fewer of them, or fix one)"
            : "";
    throw NumericalError(caller.label + ": " + r.bound.status + along);
  }
  // A bound that is 0 or infinite is no bound (a force of 1e-300 N against a noise of 0.01 printed inf): said.
  for (Eigen::Index i = 0; i < r.bound.sd.size(); ++i)
    if (!(r.bound.sd(i) > 0 && std::isfinite(r.bound.sd(i))))
      throw NumericalError(caller.label + ": the bound on " + r.keys[static_cast<std::size_t>(i)] + " is " +
                           format_value(r.bound.sd(i)) + ": the signal and the noise sd differ by more than double " +
                           "can hold (check --noise-sd against the output's size and the force amplitude)");
  for (const std::string& key : r.keys) r.values.push_back(model::parameter_value(beam, key));
  // The sensitivities come from the same modal closed form as the fast response (crb said "exact (modal closed
  // form)" at a damping ratio of 0.999999, where that form is 3e-4 off: the thirteenth pass's problem 5).
  if (const std::string note = nearly_defective_note(beam, r.run.elements); !note.empty())
    warnings << caller.label << ": " << note << "\n";
  return r;
}

}  // namespace beamid::api
