#include "fit/cramer_rao.h"

#include <cmath>
#include <limits>

#include "core/errors.h"
#include "fit/sensed_output.h"
#include "galerkin/second_order_system.h"
#include "simulation/sensitivities.h"

namespace beamid::fit {
namespace {

Eigen::VectorXd as_vector(const std::vector<double>& y) {
  return Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
}

// Central difference of the model along ln q_k with step h.
Eigen::VectorXd central_difference(const LogModel& model, const Eigen::VectorXd& log_q, int k, double h) {
  Eigen::VectorXd plus = log_q, minus = log_q;
  plus(k) += h;
  minus(k) -= h;
  const std::vector<double> yp = model(plus), ym = model(minus);
  if (yp.size() != ym.size()) throw NumericalError("Cramér-Rao bound: the model's sample count changed");
  return (as_vector(yp) - as_vector(ym)) / (2 * h);
}

struct Derivative {
  Eigen::VectorXd value;
  double relative_error = 0;  // Ridders' error estimate over max |value|
};

// Ridders' extrapolation (Ridders 1982; Press et al., Numerical Recipes section 5.7) of the central differences at
// h_i = h0 / 2^i: column j of the Neville tableau cancels the h^2j terms, and the entry whose two neighbours agree
// best is taken, with that disagreement as the error estimate. The search runs from steps where curvature dominates
// (a step in ln omega of h shifts the phase of a mode by h omega t, which reaches radians over a long record) down
// to steps where round-off does, and stops when the tableau's diagonal starts to grow again.
Derivative ridders(const LogModel& model, const Eigen::VectorXd& log_q, int k, const SensitivityOptions& options) {
  constexpr int kLevels = 12;
  constexpr double kShrink = 2, kSafe = 2;
  std::vector<Eigen::VectorXd> previous, current;  // rows i-1 and i of the tableau
  Derivative best;
  double best_error = std::numeric_limits<double>::infinity();
  double h = options.log_step;
  for (int i = 0; i < kLevels; ++i, h /= kShrink) {
    current.assign(1, central_difference(model, log_q, k, h));
    double factor = kShrink * kShrink;
    for (int j = 1; j <= i; ++j, factor *= kShrink * kShrink) {
      current.push_back((factor * current[j - 1] - previous[j - 1]) / (factor - 1));
      const double error = std::max((current[j] - current[j - 1]).cwiseAbs().maxCoeff(),
                                    (current[j] - previous[j - 1]).cwiseAbs().maxCoeff());
      if (error <= best_error) best_error = error, best.value = current[j];
    }
    if (i > 0 && (current[i] - previous[i - 1]).cwiseAbs().maxCoeff() >= kSafe * best_error) break;
    previous = current;
  }
  const double size = best.value.cwiseAbs().maxCoeff();
  best.relative_error = size > 0 ? best_error / size : 0.0;
  return best;
}

// The bound from b.sensitivities, b.values and b.noise_sd.
CramerRaoBound bound_from_sensitivities(CramerRaoBound b) {
  const Eigen::Index p = b.sensitivities.cols();
  if (b.sensitivities.rows() < p)
    throw InputError("Cramér-Rao bound: " + std::to_string(b.sensitivities.rows()) + " samples for " +
                     std::to_string(p) + " parameters: need at least as many samples as parameters");
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(b.sensitivities, Eigen::ComputeFullV);  // V is p x p
  const Eigen::VectorXd s = svd.singularValues();
  b.rcond = s(0) > 0 ? s(p - 1) / s(0) : 0.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Below ~1e-12 the smallest singular value is round-off in the sensitivities: no parameter combination is then
  // determined by the data, and the bound would be an artefact of that round-off.
  if (!(b.rcond > 1e-12)) {
    b.status = "singular Fisher information (rcond of the sensitivities " + format_value(b.rcond) +
               "): some combination of the parameters does not change the output";
    b.relative_sd = Eigen::VectorXd::Constant(p, nan);
    b.sd = b.relative_sd;
    b.null_direction = svd.matrixV().col(p - 1);
    for (Eigen::Index k = 0; k < p; ++k) b.null_dimension += s(0) > 0 && s(k) / s(0) > 1e-12 ? 0 : 1;
    return b;
  }
  // F^-1 = sigma^2 (J^T J)^-1 = sigma^2 V S^-2 V^T.
  const Eigen::MatrixXd v = svd.matrixV();
  b.covariance = b.noise_sd * b.noise_sd * v * s.array().square().inverse().matrix().asDiagonal() * v.transpose();
  b.relative_sd = b.covariance.diagonal().cwiseSqrt();
  b.sd = b.relative_sd.cwiseProduct(b.values);
  return b;
}

void check_noise(double noise_sd) {
  if (!(noise_sd > 0) || !std::isfinite(noise_sd))
    throw InputError("Cramér-Rao bound: noise sd = " + format_value(noise_sd) + ": must be finite and > 0");
}

}  // namespace

CramerRaoBound cramer_rao_bound(const LogModel& model, const Eigen::VectorXd& log_q, double noise_sd,
                                const SensitivityOptions& options) {
  check_noise(noise_sd);
  if (!log_q.allFinite()) throw InputError("Cramér-Rao bound: every parameter must be finite and > 0");
  if (!(options.log_step > 0 && options.log_step <= 0.1))
    throw InputError("Cramér-Rao bound: log step = " + format_value(options.log_step) + ": must lie in (0, 0.1]");
  const Eigen::Index p = log_q.size();
  CramerRaoBound b;
  b.values = log_q.array().exp();
  b.noise_sd = noise_sd;
  for (Eigen::Index k = 0; k < p; ++k) {
    const Derivative d = ridders(model, log_q, static_cast<int>(k), options);
    if (k == 0) b.sensitivities.resize(d.value.size(), p);  // the sample count, from the model's own output
    if (d.value.size() != b.sensitivities.rows())
      throw NumericalError("Cramér-Rao bound: the model's sample count changed");
    b.sensitivities.col(k) = d.value;
    b.step_agreement = std::max(b.step_agreement, d.relative_error);
  }

  return bound_from_sensitivities(std::move(b));
}

CramerRaoBound beam_cramer_rao_bound(const model::BeamParameters& beam, int elements,
                                     const simulation::Experiment& experiment, const std::vector<std::string>& keys,
                                     double noise_sd, const simulation::SimulatorOptions& simulator,
                                     const SensitivityOptions& options, const signal::SensorFilter& sensor) {
  if (auto error = sensed_validation_error(sensor, experiment)) throw InputError("Cramér-Rao bound: " + *error);
  const simulation::Experiment simulated = simulated_experiment(experiment, sensor);
  if (keys.empty()) throw InputError("Cramér-Rao bound: no parameter to bound");
  Eigen::VectorXd log_q(static_cast<Eigen::Index>(keys.size()));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (!model::describe_parameter(beam, keys[k]))
      throw InputError("Cramér-Rao bound: parameter '" + keys[k] +
                       "': not a parameter of this beam (valid: " + model::estimable_keys(beam) + ")");
    for (std::size_t j = 0; j < k; ++j)
      if (keys[j] == keys[k]) throw InputError("Cramér-Rao bound: parameter '" + keys[k] + "' is given twice");
    const double value = model::parameter_value(beam, keys[k]);
    if (!(value > 0))
      throw InputError("Cramér-Rao bound: " + keys[k] + " = " + format_value(value) +
                       ": must be > 0 (the bound is relative, in ln " + keys[k] + ")");
    log_q(static_cast<Eigen::Index>(k)) = std::log(value);
  }
  const galerkin::SplineSpace space(elements);
  const galerkin::BeamForms forms(space, beam.l, beam.support);
  if (simulation::has_exact_sensitivities(experiment, keys) && simulator.integrator == simulation::kFast) {
    check_noise(noise_sd);
    // The sensor's filter carried through the closed form (fit::output_filter): the record's own grid.
    simulation::SensitivityTrace s =
        simulation::simulate_with_sensitivities(forms, beam, experiment, keys, output_filter(sensor, experiment.dt_s));
    if (!s.trace.ok()) throw NumericalError("Cramér-Rao bound: the model could not be evaluated: " + s.trace.status);
    CramerRaoBound b;
    b.keys = keys;
    b.method = "exact";
    b.noise_sd = noise_sd;
    b.values.resize(log_q.size());  // the beam's own values, not exp(ln q)
    for (std::size_t k = 0; k < keys.size(); ++k)
      b.values(static_cast<Eigen::Index>(k)) = model::parameter_value(beam, keys[k]);
    b.sensitivities = s.dy_dq * b.values.asDiagonal();  // d y / d ln q = q d y / d q
    return bound_from_sensitivities(std::move(b));
  }
  const LogModel model = [&](const Eigen::VectorXd& x) {
    model::BeamParameters b = beam;
    for (std::size_t k = 0; k < keys.size(); ++k)
      model::set_parameter_value(b, keys[k], std::exp(x(static_cast<Eigen::Index>(k))));
    simulation::Trace trace = simulation::simulate(forms, b, simulated, simulator);
    if (!trace.ok()) throw NumericalError("Cramér-Rao bound: the model could not be evaluated: " + trace.status);
    sense_output(sensor, experiment, trace.y);
    return std::move(trace.y);
  };
  CramerRaoBound b = cramer_rao_bound(model, log_q, noise_sd, options);
  b.keys = keys;
  return b;
}

CramerRaoBound coloured_bound(const CramerRaoBound& b, const signal::NoiseModel& model) {
  if (model.kind == "white") return b;
  CramerRaoBound whitened = b;
  whitened.sensitivities = signal::whiten(model, b.sensitivities);
  whitened.status = "ok";
  whitened = bound_from_sensitivities(std::move(whitened));
  whitened.sensitivities = b.sensitivities;
  whitened.noise_model = model.text();
  return whitened;
}

}  // namespace beamid::fit
