#include "simulation/simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "simulation/cvode_simulator.h"
#include "simulation/modal_simulator.h"

namespace beamid::simulation {

const core::NameSet& integrator_names() {
  static const core::NameSet names({{kFast, "the exact modal closed form (modal_simulator.h)"},
                                    {kCvode, "SUNDIALS CVODE, BDF, the reference (cvode_simulator.h)"}});
  return names;
}

std::optional<std::string> validation_error(const SimulatorOptions& o) {
  if (auto error = integrator_names().violation("integrator", o.integrator)) return error;
  // A looser tolerance leaves errors of its own size in the response (0.5 was 84 % off the exact one, exit 0); below
  // 1e-14 double precision cannot meet it and CVODE fails in its own words (the third pass's P229, P230).
  if (!(o.cvode.rtol >= 1e-14 && o.cvode.rtol <= 1e-3))
    return "cvode.rtol = " + format_value(o.cvode.rtol) +
           ": must be in [1e-14, 1e-3] (looser leaves errors of its size; tighter than double precision can meet)";
  if (!(o.cvode.atol >= 0 && std::isfinite(o.cvode.atol)))
    return "cvode.atol = " + format_value(o.cvode.atol) + ": must be finite and >= 0";
  if (o.cvode.linear_solver != "structured" && o.cvode.linear_solver != "dense")
    return "cvode.linear_solver = '" + o.cvode.linear_solver + "': must be one of structured, dense";
  if (o.cvode.max_order < 1 || o.cvode.max_order > 5)
    return "cvode.max_order = " + std::to_string(o.cvode.max_order) + ": must be in 1..5";
  if (o.cvode.max_steps_per_sample < 1)
    return "cvode.max_steps_per_sample = " + std::to_string(o.cvode.max_steps_per_sample) + ": must be >= 1";
  if (o.cvode.max_total_steps < 0)
    return "cvode.max_total_steps = " + std::to_string(o.cvode.max_total_steps) + ": must be >= 0 (0: no budget)";
  return std::nullopt;
}

std::unique_ptr<Simulator> make_simulator(const SimulatorOptions& options) {
  if (auto error = validation_error(options)) throw InputError(*error);
  if (options.integrator == kCvode) return std::make_unique<CvodeSimulator>(options.cvode);
  if (options.integrator == kFast) return std::make_unique<ModalSimulator>();
  throw std::logic_error("integrator '" + options.integrator + "' is in integrator_names() but has no simulator");
}

ResponseProblem make_problem(const galerkin::BeamForms& forms, const galerkin::SecondOrderSystem& system,
                             const Experiment& e) {
  return make_problem(forms, system, e, forms.length_m);
}

ResponseProblem make_problem(const galerkin::BeamForms& forms, const galerkin::SecondOrderSystem& system,
                             const Experiment& e, double length_m) {
  if (auto error = validation_error(e, length_m)) throw InputError(*error);
  if (e.excitation == kFreeDecay)
    throw InputError(
        "excitation = 'free-decay': the initial state is unknown, so it can be fitted but not simulated "
        "(use pulse or pluck)");
  ResponseProblem p;
  p.load = galerkin::point_load(forms, e.force_x_m.value_or(length_m), length_m);
  p.sensor = galerkin::point_load(forms, e.sensor_x_m.value_or(length_m), length_m);
  p.derivative = output_derivative(e.output);
  p.dt_s = e.dt_s;
  p.samples = e.samples;
  if (e.excitation == kPulse) {
    p.amplitude_N = e.force_amplitude_N;
    p.pulse_width_s = e.pulse_width_s;
    p.w0 = Eigen::VectorXd::Zero(p.load.size());
  } else if (e.excitation == kSampledForce) {
    p.force_samples_N = e.force_samples_N;
    for (const double f : e.force_samples_N) p.amplitude_N = std::max(p.amplitude_N, std::abs(f));
    p.w0 = Eigen::VectorXd::Zero(p.load.size());
  } else {
    // Static deflection under the load: K w0 = P0 f (K is SPD for admissible parameters).
    Eigen::LLT<Eigen::MatrixXd> k(system.K);
    if (k.info() != Eigen::Success) throw NumericalError("stiffness matrix K is not positive definite");
    p.w0 = k.solve(e.force_amplitude_N * p.load);
  }
  return p;
}

Trace simulate(const galerkin::BeamForms& forms, const model::BeamParameters& beam, const Experiment& experiment,
               const SimulatorOptions& options) {
  return simulate(forms, galerkin::combine(forms, beam), beam.l, experiment, options);
}

Trace simulate(const galerkin::BeamForms& forms, const galerkin::SecondOrderSystem& system, double length_m,
               const Experiment& experiment, const SimulatorOptions& options) {
  Trace trace = make_simulator(options)->run(system, make_problem(forms, system, experiment, length_m));
  // A response beyond double's range (an absurd force amplitude on a soft beam) is a failure, never a record of inf
  // and NaN samples handed on as if it were one.
  const auto bad = std::find_if(trace.y.begin(), trace.y.end(), [](double v) { return !std::isfinite(v); });
  if (trace.ok() && bad != trace.y.end())
    trace.status =
        "the output is not finite from t = " + format_value(experiment.dt_s * (bad - trace.y.begin())) +
        " s on (the response overflows double: force_amplitude_N = " + format_value(experiment.force_amplitude_N) + ")";
  return trace;
}

}  // namespace beamid::simulation
