// The residuals' derivative by central differences, the yardstick of the exact Jacobians' tests.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "fit/objective.h"
#include "model/beam_parameters.h"

namespace beamid::fit::testing {

// (r(q + h) - r(q - h)) / 2h for the parameter `key` of `at`, h = relative_step x its value: exact to O(h^2) of the
// residuals' third derivative.
inline Eigen::VectorXd residual_central_difference(Objective& objective, const model::BeamParameters& at,
                                                   const std::string& key, double relative_step = 1e-5) {
  double model::BeamParameters::*member = model::find_parameter(key)->member;
  const double h = relative_step * at.*member;
  model::BeamParameters up = at, down = at;
  up.*member += h;
  down.*member -= h;
  return (objective.evaluate(up).evaluation.residuals - objective.evaluate(down).evaluation.residuals) / (2 * h);
}

}  // namespace beamid::fit::testing
