// fit::Objective: one record's model output and cost for a parameter set, with the forms, simulator and DFT plans
// built once (fit/objective.cc); what every optimizer run of fit::fit evaluates (fit/identification.h), and what a
// study's landscape and overlay sweep directly.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "costs/cost.h"
#include "fit/identification.h"
#include "model/beam_parameters.h"

namespace beamid::fit {

// Model output and cost of one parameter set against fixed data, with the forms, simulator and DFT plans built once.
class Objective {
 public:
  // InputError when the options or data are inadmissible (checked before anything runs).
  Objective(const FitOptions& options, const std::vector<double>& data);
  ~Objective();
  struct Output {
    std::vector<double> y;
    costs::Evaluation evaluation;
  };
  // What an evaluation computes of the model's output: `as_cost_needs` leaves y empty where the cost does not read it
  // and computing it is work of its own (a free decay's least-squares synthesis, for the modal cost: 60-80 % of a
  // measured record's evaluation); `always` computes it, for the output a report or table shows.
  enum class Response { as_cost_needs, always };
  // Never throws for admissible options: a failed simulation is an evaluation with that status.
  Output evaluate(const model::BeamParameters& beam, Response response = Response::as_cost_needs);
  // Whether evaluate_with_jacobian is available: a cost with an output Jacobian (costs/cost.h: time, freq-band,
  // spike-smooth with a known amplitude) on a pulse, or with a pole Jacobian (modal) on a simulated record or a free
  // decay; the fast integrator.
  bool has_exact_jacobian() const;
  // evaluate, and the exact d residual / d q (residuals x keys) for the parameters `keys`; `jacobian` is empty when
  // the evaluation failed. InputError unless has_exact_jacobian().
  Output evaluate_with_jacobian(const model::BeamParameters& beam, const std::vector<std::string>& keys,
                                Eigen::MatrixXd& jacobian);
  const costs::Cost& cost() const { return *cost_; }

 private:
  Output evaluate_with_pole_jacobian(const model::BeamParameters& beam, const std::vector<std::string>& keys,
                                     Eigen::MatrixXd& jacobian);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<costs::Cost> cost_;
};

}  // namespace beamid::fit
