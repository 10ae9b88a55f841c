// The one place where physical parameter values and the optimizer's dimensionless coordinates meet.
//   scaling "linear": x_i = p_i / r_i;   scaling "log": x_i = ln(p_i / r_i),
// with r_i the reference value of parameter i (its value in the given beam, or the geometric mean of its bounds
// when that value is 0). Coordinates are then of order one whatever the units (EI ~ 0.5 N m^2, kAG ~ 7e5 N).
// Parameters that are not estimated keep the given beam's values.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "model/beam_parameters.h"

namespace beamid::fit {

struct EstimatedParameter {
  std::string key;   // an estimable key of the beam (model::describe_parameter)
  double lower = 0;  // physical bounds: 0 <= lower < upper (lower > 0 for log scaling and for > 0 keys)
  double upper = 0;
};

class ParameterMap {
 public:
  // InputError naming the key, bound and constraint for an unknown or repeated key, or bad bounds.
  ParameterMap(const model::BeamParameters& beam, std::vector<EstimatedParameter> estimated,
               std::string scaling = "linear");

  int size() const { return static_cast<int>(estimated_.size()); }
  const std::vector<EstimatedParameter>& estimated() const { return estimated_; }
  const std::string& scaling() const { return scaling_; }
  double reference(int i) const { return reference_[static_cast<std::size_t>(i)]; }

  // Physical beam for coordinates x (the fixed parameters as given).
  model::BeamParameters beam(const Eigen::VectorXd& x) const;
  // The same, with every estimated value clamped into its bounds: what a fit reports. The optimizers keep their
  // coordinates inside the coordinate bounds, but the map back (r x, r e^x) and a bounded optimizer's last step can
  // land a few ulps (LM: slightly more) outside; the reported estimate never does.
  model::BeamParameters estimate(const Eigen::VectorXd& x) const;
  // Coordinates of a beam's estimated values.
  Eigen::VectorXd coordinates(const model::BeamParameters& beam) const;
  double value(int i, double x) const;       // p_i(x_i)
  double coordinate(int i, double p) const;  // x_i(p_i)
  double derivative(int i, double x) const;  // dp_i / dx_i, for propagating a covariance
  Eigen::VectorXd lower() const;             // bounds in coordinates
  Eigen::VectorXd upper() const;
  // Indices of the estimated parameters whose role (model::ParameterInfo::role) is in `roles`.
  std::vector<int> with_roles(const std::vector<std::string>& roles) const;

 private:
  model::BeamParameters base_;
  std::vector<EstimatedParameter> estimated_;
  std::vector<double> reference_;
  std::string scaling_;
};

}  // namespace beamid::fit
