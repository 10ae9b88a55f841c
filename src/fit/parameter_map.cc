#include "fit/parameter_map.h"

#include <algorithm>
#include <cmath>

#include "model/errors.h"

namespace beamid::fit {

ParameterMap::ParameterMap(const model::BeamParameters& beam, std::vector<EstimatedParameter> estimated,
                           std::string scaling)
    : base_(beam), estimated_(std::move(estimated)), scaling_(std::move(scaling)) {
  if (scaling_ != "linear" && scaling_ != "log")
    throw InputError("scaling = '" + scaling_ + "': must be one of linear, log");
  if (estimated_.empty()) throw InputError("estimate: no parameter to estimate");
  for (const auto& e : estimated_) {
    const std::optional<model::ParameterDescription> info = model::describe_parameter(beam, e.key);
    if (!info)
      throw InputError("estimate: '" + e.key +
                       "' is not a parameter of this beam (valid: " + model::estimable_keys(beam) + ")");
    if (std::count_if(estimated_.begin(), estimated_.end(), [&](const auto& o) { return o.key == e.key; }) > 1)
      throw InputError("estimate: '" + e.key + "' is listed twice");
    const std::string where = "bounds of " + e.key + " [" + format_value(e.lower) + ", " + format_value(e.upper) + "]";
    if (!(std::isfinite(e.lower) && std::isfinite(e.upper) && e.lower < e.upper))
      throw InputError(where + ": must be finite with lower < upper");
    if (e.lower < 0 || (e.lower == 0 && (info->strictly_positive || scaling_ == "log")))
      throw InputError(where + ": lower must be " +
                       std::string(info->strictly_positive || scaling_ == "log" ? "> 0" : ">= 0") +
                       (scaling_ == "log" ? " (log scaling)" : ""));
    const double given = model::parameter_value(beam, e.key);
    reference_.push_back(given > 0 ? given : (e.lower > 0 ? std::sqrt(e.lower * e.upper) : e.upper));
  }
}

double ParameterMap::value(int i, double x) const {
  const double r = reference(i);
  return scaling_ == "log" ? r * std::exp(x) : r * x;
}

model::BeamParameters ParameterMap::estimate(const Eigen::VectorXd& x) const {
  model::BeamParameters b = base_;
  for (int i = 0; i < size(); ++i) {
    const auto& e = estimated_[static_cast<std::size_t>(i)];
    model::set_parameter_value(b, e.key, std::clamp(value(i, x(i)), e.lower, e.upper));
  }
  return b;
}

double ParameterMap::coordinate(int i, double p) const {
  const double r = reference(i);
  return scaling_ == "log" ? std::log(p / r) : p / r;
}

double ParameterMap::derivative(int i, double x) const { return scaling_ == "log" ? value(i, x) : reference(i); }

model::BeamParameters ParameterMap::beam(const Eigen::VectorXd& x) const {
  model::BeamParameters b = base_;
  for (int i = 0; i < size(); ++i)
    model::set_parameter_value(b, estimated_[static_cast<std::size_t>(i)].key, value(i, x(i)));
  return b;
}

Eigen::VectorXd ParameterMap::coordinates(const model::BeamParameters& b) const {
  Eigen::VectorXd x(size());
  for (int i = 0; i < size(); ++i)
    x(i) = coordinate(i, model::parameter_value(b, estimated_[static_cast<std::size_t>(i)].key));
  return x;
}

Eigen::VectorXd ParameterMap::lower() const {
  Eigen::VectorXd x(size());
  for (int i = 0; i < size(); ++i) x(i) = coordinate(i, estimated_[static_cast<std::size_t>(i)].lower);
  return x;
}

Eigen::VectorXd ParameterMap::upper() const {
  Eigen::VectorXd x(size());
  for (int i = 0; i < size(); ++i) x(i) = coordinate(i, estimated_[static_cast<std::size_t>(i)].upper);
  return x;
}

std::vector<int> ParameterMap::with_roles(const std::vector<std::string>& roles) const {
  std::vector<int> indices;
  for (int i = 0; i < size(); ++i)
    if (std::find(roles.begin(), roles.end(), model::parameter_role(estimated_[static_cast<std::size_t>(i)].key)) !=
        roles.end())
      indices.push_back(i);
  return indices;
}

}  // namespace beamid::fit
