#include "simulation/experiment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "core/limits.h"

namespace beamid::simulation {

const core::NameSet& excitation_names() {
  static const core::NameSet names({{kPulse, "F0 sin^2(pi t/tau) on [0, tau] at x_f, from rest"},
                                    {kPluck, "released at rest from the static deflection under F0 at x_f"},
                                    {kFreeDecay, "a record from an unknown state (fit only)"},
                                    {kSampledForce,
                                     "a record's force channel at x_f, linear between samples (fit "
                                     "--force-channel), from rest"}});
  return names;
}

const core::NameSet& output_names() {
  static const core::NameSet names({{kDisplacement, "m"}, {kVelocity, "m/s"}, {kAcceleration, "m/s^2"}});
  return names;
}

std::optional<std::string> validation_error(const Experiment& e, double length_m) {
  const auto bad = [](const std::string& key, double value, const std::string& constraint) {
    return key + " = " + format_value(value) + ": " + constraint;
  };
  if (auto error = excitation_names().violation("excitation", e.excitation)) return error;
  if (auto error = output_names().violation("output", e.output)) return error;
  const std::string on_beam = "must lie on the beam, 0 <= x <= l = " + format_value(length_m);
  if (e.force_x_m && !(*e.force_x_m >= 0 && *e.force_x_m <= length_m)) return bad("force_x_m", *e.force_x_m, on_beam);
  if (e.sensor_x_m && !(*e.sensor_x_m >= 0 && *e.sensor_x_m <= length_m))
    return bad("sensor_x_m", *e.sensor_x_m, on_beam);
  // The model is linear: the amplitude only scales the response. 1e12 N is 1e5 times a rocket engine's thrust; beyond,
  // the samples of a soft beam's acceleration can overflow double.
  if (!(std::abs(e.force_amplitude_N) <= 1e12))
    return bad("force_amplitude_N", e.force_amplitude_N, "must be finite and at most 1e12 N in magnitude");
  if (e.excitation == kPulse && !(e.pulse_width_s > 0 && std::isfinite(e.pulse_width_s)))
    return bad("pulse_width_s", e.pulse_width_s, "must be finite and > 0");
  // Narrower than 1e-12 s a pulse is an impulse at any step beamid takes (dt >= 1e-9 s), and a denormal width
  // overflowed its frequency 2 pi / width, blamed on the amplitude (the fourteenth pass's P7).
  if (e.excitation == kPulse && e.pulse_width_s < 1e-12)
    return bad("pulse_width_s", e.pulse_width_s,
               "must be at least 1e-12 s (narrower is an impulse at any dt >= 1e-9 s)");
  // A force smaller than 1e-150 N, or one within 1e-9 l of the clamp, gives a response below what a record holds
  // (1e-150, io/time_series.cc): 1e-320 passed the check that refuses 0 and wrote a record of zeros (its P15).
  if (e.force_amplitude_N != 0 && std::abs(e.force_amplitude_N) < 1e-150)
    return bad("force_amplitude_N", e.force_amplitude_N, "must be 0 or at least 1e-150 N in magnitude");
  if (!(e.dt_s > 0 && std::isfinite(e.dt_s))) return bad("dt_s", e.dt_s, "must be finite and > 0");
  // The records' own floor (io/time_series.cc): a rate above 1 GHz is a unit mistake, and simulate wrote records at
  // dt = 1e-300 s that no reader takes (the third pass's P209).
  if (e.dt_s < 1e-9) return bad("dt_s", e.dt_s, "must be at least 1e-9 s (a rate of at most 1 GHz; is dt in seconds?)");
  if (e.samples < 2) return "samples = " + std::to_string(e.samples) + ": must be >= 2";
  if (e.excitation == kSampledForce) {
    if (e.force_samples_N.size() != static_cast<std::size_t>(e.samples))
      return "excitation = 'force': needs the force at every sample (" + std::to_string(e.samples) + "), has " +
             std::to_string(e.force_samples_N.size()) + " (a record's force channel: fit --force-channel)";
    for (std::size_t i = 0; i < e.force_samples_N.size(); ++i)
      if (!(std::abs(e.force_samples_N[i]) <= 1e12))
        return "force sample " + std::to_string(i) + " = " + format_value(e.force_samples_N[i]) +
               ": must be finite and at most 1e12 N in magnitude";
  } else if (!e.force_samples_N.empty()) {
    return "excitation = '" + e.excitation + "': a sampled force is read by excitation 'force' only";
  }
  // A beam's free vibration dies out in minutes; a record of more than 1e6 s (11 days) is a unit mistake.
  if (e.dt_s * e.samples > 1e6)
    return bad("dt_s", e.dt_s,
               "the record, dt x samples = " + format_value(e.dt_s * e.samples) +
                   " s, must last at most 1e6 s (is dt in seconds?)");
  return std::nullopt;
}

int output_derivative(const std::string& output) {
  if (output == kDisplacement) return 0;
  if (output == kVelocity) return 1;
  if (output == kAcceleration) return 2;
  throw InputError("output = '" + output + "': must be one of displacement, velocity, acceleration");
}

std::string output_column(const std::string& output) {
  switch (output_derivative(output)) {
    case 0:
      return "displacement_m";
    case 1:
      return "velocity_m_s";
    default:
      return "acceleration_m_s2";
  }
}

Experiment finer(const Experiment& e, int factor) {
  if (factor < 1) throw InputError("finer: factor = " + std::to_string(factor) + ": must be >= 1");
  if (static_cast<long long>(e.samples) * factor > core::kMaxSamples)
    throw InputError("finer: " + std::to_string(e.samples) + " samples " + std::to_string(factor) +
                     " times finer: more than " + std::to_string(core::kMaxSamples));
  Experiment fine = e;
  fine.dt_s = e.dt_s / factor;
  fine.samples = e.samples * factor;
  if (!e.force_samples_N.empty()) {
    ResponseProblem held;
    held.force_samples_N = e.force_samples_N;
    held.dt_s = e.dt_s;
    fine.force_samples_N.resize(static_cast<std::size_t>(fine.samples));
    for (std::size_t j = 0; j < fine.force_samples_N.size(); ++j)
      fine.force_samples_N[j] = held.force_N(static_cast<double>(j) * fine.dt_s);
  }
  return fine;
}

std::vector<double> sampled_pulse(const Experiment& e) {
  ResponseProblem pulse;
  pulse.amplitude_N = e.force_amplitude_N;
  pulse.pulse_width_s = e.pulse_width_s;
  std::vector<double> f(static_cast<std::size_t>(std::max(e.samples, 0)));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = pulse.force_N(static_cast<double>(i) * e.dt_s);
  return f;
}

double ResponseProblem::force_N(double t_s) const {
  if (!force_samples_N.empty()) {
    if (!(t_s >= 0)) return 0;
    const double x = t_s / dt_s;
    const auto i = static_cast<std::size_t>(std::min<double>(std::floor(x), force_samples_N.size() - 1));
    if (i + 1 >= force_samples_N.size()) return force_samples_N.back();
    const double f = x - static_cast<double>(i);
    return (1 - f) * force_samples_N[i] + f * force_samples_N[i + 1];
  }
  if (pulse_width_s <= 0 || t_s < 0 || t_s > pulse_width_s) return 0;
  const double s = std::sin(std::numbers::pi * t_s / pulse_width_s);
  return amplitude_N * s * s;
}

}  // namespace beamid::simulation
