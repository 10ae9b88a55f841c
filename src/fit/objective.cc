// fit::Objective (fit/objective.h): one record's model output and cost, with the forms, simulator and DFT plans
// built once.
#include "fit/objective.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/errors.h"
#include "core/limits.h"
#include "fit/sensed_output.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "simulation/free_decay.h"
#include "simulation/modal_simulator.h"
#include "simulation/sensitivities.h"

namespace beamid::fit {

struct Objective::Impl {
  galerkin::SplineSpace space;
  galerkin::BeamForms forms;
  simulation::Experiment experiment;
  // The sensor's filter in the model (fit/sensed_output.h) and the experiment the model is simulated on: the
  // record's, or finer when the filter is on.
  signal::SensorFilter sensor;
  simulation::Experiment simulated;
  std::unique_ptr<simulation::Simulator> simulator;
  bool needs_poles;
  std::vector<double> data;  // free decay: the amplitudes are solved against it
  // A cost with an output Jacobian (costs/cost.h) on a pulse, by the fast propagator: its Jacobian is that map applied
  // to the exact sensitivities d y / d q (simulation/sensitivities.h). A cost with a pole Jacobian (modal) on a
  // simulated record by the fast propagator: that map applied to the eigenvalue derivatives (galerkin/modes.h).
  bool exact_jacobian = false;
  bool pole_jacobian = false;
  // The sensor's filter carried by the fast simulator's closed form (fit::output_filter); null without a filter or
  // with cvode, which simulates `simulated` and filters it (sense_output).
  std::shared_ptr<const simulation::OutputFilter> filter{};
};

Objective::Objective(const FitOptions& o, const std::vector<double>& data) {
  if (o.elements < core::kMinElements || o.elements > core::kMaxElements)
    throw InputError("elements = " + std::to_string(o.elements) + ": must be an integer in " +
                     std::to_string(core::kMinElements) + ".." + std::to_string(core::kMaxElements));
  if (auto error = model::validation_error(o.start)) throw InputError("start beam: " + *error);
  if (auto error = simulation::validation_error(o.experiment, o.start.l)) throw InputError("experiment: " + *error);
  if (static_cast<int>(data.size()) != o.experiment.samples)
    throw InputError("experiment: samples = " + std::to_string(o.experiment.samples) + ": the data have " +
                     std::to_string(data.size()));
  if (auto error = simulation::validation_error(o.simulator)) throw InputError(*error);
  if (auto error = sensed_validation_error(o.sensor, o.experiment)) throw InputError(*error);
  costs::CostOptions cost_options = o.cost;  // the modal cost identifies the decay after the pulse
  if (o.experiment.excitation == simulation::kPulse)
    cost_options.first_free_sample =
        static_cast<int>(std::min<double>(data.size(), std::floor(o.experiment.pulse_width_s / o.experiment.dt_s) + 1));
  cost_ = costs::make_cost(cost_options, data, o.experiment.dt_s);
  const galerkin::SplineSpace space(o.elements);
  // A transfer function at the DFT bins (freq-ml with a sampled force) is the beam's, not the sensed record's.
  if (o.sensor.cutoff_hz > 0 && cost_->uses_transfer_function())
    throw InputError("sensor filter in the model: the " + o.cost.name +
                     " cost reads the beam's transfer function at the DFT bins, which the filter in the model does not "
                     "reach (fit it without the filter, or with the time or freq-band cost)");
  impl_ =
      std::make_unique<Impl>(Impl{space, galerkin::BeamForms(space, o.start.l, o.start.support), o.experiment, o.sensor,
                                  simulated_experiment(o.experiment, o.sensor), simulation::make_simulator(o.simulator),
                                  o.cost.name == costs::kModalCost || (o.cost.name == costs::kSpikeSmoothCost &&
                                                                       o.cost.model_poles == costs::kEigenvaluePoles),
                                  o.experiment.excitation == "free-decay" ? data : std::vector<double>{}});
  const bool fast = o.simulator.integrator == simulation::kFast;
  // A free decay's poles are the model's, whatever its amplitudes: the modal cost's pole Jacobian holds there too.
  impl_->pole_jacobian = cost_->has_pole_jacobian() && fast;
  if (fast) impl_->filter = output_filter(o.sensor, o.experiment.dt_s);
  std::vector<std::string> keys;
  for (const auto& e : o.estimate) keys.push_back(e.key);
  impl_->exact_jacobian = impl_->pole_jacobian || (cost_->has_output_jacobian() &&
                                                   simulation::has_exact_sensitivities(o.experiment, keys) && fast);
}

bool Objective::has_exact_jacobian() const { return impl_->exact_jacobian; }

Objective::Output Objective::evaluate_with_jacobian(const model::BeamParameters& beam,
                                                    const std::vector<std::string>& keys, Eigen::MatrixXd& jacobian) {
  jacobian.resize(0, 0);
  if (!impl_->exact_jacobian)
    throw InputError("evaluate_with_jacobian: no exact Jacobian for this cost and experiment");
  Output out;
  if (auto error = model::validation_error(beam)) {
    out.evaluation.status = "inadmissible parameters: " + *error;
    return out;
  }
  try {
    if (impl_->pole_jacobian) return evaluate_with_pole_jacobian(beam, keys, jacobian);
    // The exact Jacobian is the fast simulator's: with a sensor, its filter is carried through the closed form.
    simulation::SensitivityTrace s =
        simulation::simulate_with_sensitivities(impl_->forms, beam, impl_->experiment, keys, impl_->filter);
    if (!s.trace.ok()) {
      out.evaluation.status = s.trace.status;
      return out;
    }
    out.y = std::move(s.trace.y);
    out.evaluation = cost_->evaluate(costs::ModelResponse{out.y, s.trace.poles_rad_s});
    if (out.evaluation.ok())
      jacobian = cost_->output_jacobian(costs::ModelResponse{out.y, s.trace.poles_rad_s}, s.dy_dq);
  } catch (const std::exception& error) {
    out.evaluation.status = error.what();
  }
  return out;
}

Objective::Output Objective::evaluate_with_pole_jacobian(const model::BeamParameters& beam,
                                                         const std::vector<std::string>& keys,
                                                         Eigen::MatrixXd& jacobian) {
  // The record and poles exactly as evaluate() gives them (the fast propagator on the same decomposition), and
  // d lambda / d q of the underdamped poles, in the trace's order.
  Output out;
  const galerkin::SecondOrderSystem system = galerkin::combine(impl_->forms, beam);
  std::optional<galerkin::StateSpaceModes> decomposed;
  try {
    decomposed.emplace(system);
  } catch (const NumericalError& error) {  // the status evaluate() gives (the fast simulator's)
    out.evaluation.status = std::string("fast: ") + error.what();
    return out;
  }
  const galerkin::StateSpaceModes& modes = *decomposed;
  // The poles the cost is given, as indices into the modes: a simulated record's underdamped ones in the trace's
  // order, or a free decay's (those below the Nyquist frequency, ascending), whose output the cost does not read.
  std::vector<Eigen::Index> underdamped;
  for (Eigen::Index k = 0; k < modes.size(); ++k)
    if (modes.eigenvalues()(k).imag() > 0) underdamped.push_back(k);
  std::vector<std::complex<double>> poles;
  if (impl_->experiment.excitation == simulation::kFreeDecay) {
    std::vector<std::complex<double>> all;
    for (const Eigen::Index k : underdamped) all.push_back(modes.eigenvalues()(k));
    std::vector<Eigen::Index> kept;
    for (const std::size_t i : simulation::free_decay_pole_indices(all, impl_->experiment.dt_s)) {
      kept.push_back(underdamped[i]);
      poles.push_back(all[i]);
    }
    underdamped = std::move(kept);
    if (poles.empty()) {
      out.evaluation.status = simulation::kNoFreeDecayMode;
      return out;
    }
  } else {
    // The cost reads the poles alone, which the sensor's filter does not move: the record's own grid gives them, and
    // the unfiltered output is not handed on.
    const simulation::ResponseProblem problem =
        simulation::make_problem(impl_->forms, system, impl_->experiment, beam.l);
    simulation::Trace trace = simulation::ModalSimulator().run(modes, system, problem);
    if (!trace.ok()) {
      out.evaluation.status = trace.status;
      return out;
    }
    if (impl_->sensor.cutoff_hz > 0) trace.y.clear();
    out.y = std::move(trace.y);
    poles = std::move(trace.poles_rad_s);
  }
  out.evaluation = cost_->evaluate(costs::ModelResponse{out.y, poles});
  if (!out.evaluation.ok()) return out;
  Eigen::MatrixXcd d_poles(static_cast<Eigen::Index>(underdamped.size()), static_cast<Eigen::Index>(keys.size()));
  for (std::size_t q = 0; q < keys.size(); ++q) {
    const Eigen::VectorXcd d = modes.eigenvalue_derivative(galerkin::parameter_derivative(impl_->forms, beam, keys[q]));
    for (std::size_t i = 0; i < underdamped.size(); ++i)
      d_poles(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(q)) = d(underdamped[i]);
  }
  jacobian = cost_->pole_jacobian(costs::ModelResponse{out.y, poles}, d_poles);
  return out;
}

Objective::~Objective() = default;

Objective::Output Objective::evaluate(const model::BeamParameters& beam, Response response) {
  Output out;
  std::vector<std::complex<double>> poles;
  std::vector<std::complex<double>> frf;
  if (auto error = model::validation_error(beam)) {
    out.evaluation.status = "inadmissible parameters: " + *error;
    return out;
  }
  try {
    const galerkin::SecondOrderSystem system = galerkin::combine(impl_->forms, beam);
    if (impl_->experiment.excitation == "free-decay") {
      // Unknown initial state: the modal amplitudes are solved in closed form against the data.
      std::vector<std::complex<double>> all;
      for (const auto& mode : galerkin::StateSpaceModes(system).underdamped_modes()) all.push_back(mode.lambda);
      if (response == Response::as_cost_needs && !cost_->uses_response()) {
        for (const std::size_t k : simulation::free_decay_pole_indices(all, impl_->experiment.dt_s))
          poles.push_back(all[k]);
        if (poles.empty()) {
          out.evaluation.status = simulation::kNoFreeDecayMode;
          return out;
        }
        out.evaluation = cost_->evaluate(costs::ModelResponse{out.y, poles});
        return out;
      }
      simulation::FreeDecayFit decay =
          simulation::fit_free_decay(all, impl_->experiment.dt_s, impl_->data, impl_->experiment.free_decay_trend);
      if (decay.status != "ok") {
        out.evaluation.status = decay.status;
        return out;
      }
      out.y = std::move(decay.y);
      out.evaluation = cost_->evaluate(costs::ModelResponse{out.y, decay.poles_rad_s});
      return out;
    }
    // With the sensor's filter, the model's output is read as the sensor delivers it: the fast simulator carries the
    // filter through its closed form on the record's grid; cvode runs on the finer grid and the output is filtered. A
    // cost that reads only the poles (modal), which the filter does not move, gets them from the record's grid, and
    // no unfiltered output.
    const bool sensed = impl_->sensor.cutoff_hz > 0 && (response == Response::always || cost_->uses_response());
    const bool fine = sensed && !impl_->filter;
    simulation::ResponseProblem problem =
        simulation::make_problem(impl_->forms, system, fine ? impl_->simulated : impl_->experiment, beam.l);
    problem.frf = cost_->uses_transfer_function();
    if (sensed) problem.output_filter = impl_->filter;
    simulation::Trace trace = impl_->simulator->run(system, problem);
    if (!trace.ok()) {
      out.evaluation.status = trace.status;
      return out;
    }
    if (fine)
      sense_output(impl_->sensor, impl_->experiment, trace.y);
    else if (impl_->sensor.cutoff_hz > 0 && !sensed)
      trace.y.clear();
    out.y = std::move(trace.y);
    poles = std::move(trace.poles_rad_s);
    frf = std::move(trace.frf);
    if (impl_->needs_poles && poles.empty())
      for (const auto& mode : galerkin::StateSpaceModes(system).underdamped_modes()) poles.push_back(mode.lambda);
  } catch (const std::exception& error) {  // NumericalError from a decomposition, or InputError from the load
    out.evaluation.status = error.what();
    return out;
  }
  out.evaluation = cost_->evaluate(costs::ModelResponse{out.y, poles, &frf});
  return out;
}

}  // namespace beamid::fit
