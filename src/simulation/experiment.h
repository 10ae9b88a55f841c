// What is done to the beam and what is measured (model.md section 3).
//   excitation "pulse": P(t) = F0 sin^2(pi t / tau) for 0 <= t <= tau, 0 after, at x_f; zero initial state.
//   excitation "pluck": released at t = 0, at rest, from the static deflection K w0 = F0 beta(x_f) (a tip load when
//                       x_f = l); no force afterwards.
//   excitation "free-decay": a record that starts after an impact or a release, from an unknown state; it can be
//                       fitted (simulation/free_decay.h) but not simulated.
//   excitation "force": a sampled force F_i at t_i = i dt (a record's measured force channel: an impact hammer's),
//                       linear between samples (first-order hold), at x_f; zero initial state.
//   sensor at xbar: displacement, velocity or acceleration of u; samples t_i = i dt, i = 0..Nbar-1.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/names.h"

namespace beamid::simulation {

class OutputFilter;  // simulation/output_filter.h

// Excitations and sensor outputs by name (the registries every reader of these names uses).
inline const std::string kPulse = "pulse";
inline const std::string kPluck = "pluck";
inline const std::string kFreeDecay = "free-decay";
inline const std::string kSampledForce = "force";
const core::NameSet& excitation_names();
inline const std::string kDisplacement = "displacement";
inline const std::string kVelocity = "velocity";
inline const std::string kAcceleration = "acceleration";
const core::NameSet& output_names();

struct Experiment {
  std::string excitation = "pulse";     // "pulse" | "pluck" | "free-decay"
  std::optional<double> force_x_m;      // x_f; default: the tip (x = l)
  double force_amplitude_N = 1.0;       // F0 (pulse peak) or P0 (pluck static load)
  double pulse_width_s = 0.01;          // tau (pulse only)
  std::optional<double> sensor_x_m;     // xbar; default: the tip
  std::string output = "displacement";  // "displacement" | "velocity" | "acceleration"
  double dt_s = 1e-3;                   // sampling interval
  int samples = 4096;                   // Nbar
  // Free decay only: a linear trend fitted beside the constant (simulation/free_decay.h; fit --detrend linear with the
  // time or freq-band cost): a sensor that drifts during the record.
  bool free_decay_trend = false;
  // Sampled force only: F_i, N, one per sample (force_amplitude_N and pulse_width_s are not read).
  std::vector<double> force_samples_N;
};

// The experiment sampled `factor` times finer over the same time (dt_s / factor, samples x factor): what a sensor
// of finite bandwidth is simulated on before its filter and decimation (signal/sensor_filter.h). A sampled force is
// given as the simulator holds it (ResponseProblem::force_N: linear between its samples, held after the last).
Experiment finer(const Experiment& experiment, int factor);

// The sin^2 pulse's force at every sample, F0 sin^2(pi t_i / tau) for t_i <= tau and 0 after (force_amplitude_N,
// pulse_width_s, dt_s, samples): what a force channel records of the pulse, to drive excitation "force" with.
std::vector<double> sampled_pulse(const Experiment& experiment);

// First violated constraint as "key = value: constraint", e.g. "pulse_width_s = -1: must be > 0", or nothing.
// length_m is the beam length (positions must lie in [0, l]).
std::optional<std::string> validation_error(const Experiment& experiment, double length_m);

// 0, 1, 2 for displacement, velocity, acceleration (InputError for another name).
int output_derivative(const std::string& output);
// CSV column name with unit: "displacement_m", "velocity_m_s", "acceleration_m_s2".
std::string output_column(const std::string& output);

// The experiment as the linear-algebra problem both integrators solve:
//   M w'' + C w' + K w = load * P(t),  P(t) = amplitude sin^2(pi t / tau) on [0, tau] (none when tau = 0),
//   w(0) = w0, w'(0) = 0,  y_i = sensor^T (d/dt)^derivative w (t_i).
struct ResponseProblem {
  Eigen::VectorXd load;                 // generalised load of a unit force at x_f
  double amplitude_N = 0;               // F0 of the pulse (0 for a pluck); a sampled force's largest |F_i| (a scale)
  double pulse_width_s = 0;             // tau (0 for a pluck)
  std::vector<double> force_samples_N;  // a sampled force: P(t) is these, linear between samples (else empty)
  bool frf = false;                     // a sampled force: also its transfer function at the DFT bins (Trace::frf)
  Eigen::VectorXd w0;                   // initial displacement state
  Eigen::VectorXd sensor;               // [beta(xbar); 0]
  int derivative = 0;
  double dt_s = 0;
  int samples = 0;
  // A filter on the output and its decimation (a sensor's anti-alias filter in a fitted model): the trace is the
  // output filtered on the grid dt_s / R and every R-th sample kept, on this grid (dt_s, samples). The fast simulator
  // carries it through its closed form; cvode refuses it. None: the output as it is.
  std::shared_ptr<const OutputFilter> output_filter;

  // P(t) of the pulse or the sampled force, N.
  double force_N(double t_s) const;
};

}  // namespace beamid::simulation
