#include "fit/parameter_map.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace beamid::fit {

EstimatedParameter bounds_around(const std::string& key, double nominal, double factor) {
  return {key, nominal / factor, nominal * factor};
}

std::optional<std::pair<int, std::string>> record_key(const std::string& key) {
  const std::string prefix = "record";
  const auto dot = key.find('.');
  if (key.rfind(prefix, 0) != 0 || dot == std::string::npos) return std::nullopt;
  const std::string number = key.substr(prefix.size(), dot - prefix.size());
  const bool digits = !number.empty() && number.size() <= 6 && number.front() != '0' &&
                      std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits || dot + 1 == key.size())
    throw InputError("estimate: '" + key + "': a record's own parameter is recordK.KEY with K = 1, 2, ...");
  return std::make_pair(std::stoi(number) - 1, key.substr(dot + 1));
}

std::string local_key(const std::string& key) {
  const auto split = record_key(key);
  return split ? split->second : key;
}

ParameterMap::ParameterMap(const model::BeamParameters& beam, std::vector<EstimatedParameter> estimated,
                           std::string scaling)
    : ParameterMap(std::vector<model::BeamParameters>{beam}, std::move(estimated), std::move(scaling)) {}

ParameterMap::ParameterMap(std::vector<model::BeamParameters> records, std::vector<EstimatedParameter> estimated,
                           std::string scaling)
    : base_(std::move(records)), estimated_(std::move(estimated)), scaling_(std::move(scaling)) {
  if (base_.empty()) throw InputError("records: none to fit");
  if (scaling_ != "linear" && scaling_ != "log")
    throw InputError("scaling = '" + scaling_ + "': must be one of linear, log");
  if (estimated_.empty()) throw InputError("estimate: no parameter to estimate");
  const int count = static_cast<int>(base_.size());
  for (const auto& e : estimated_) {
    const auto split = record_key(e.key);
    const int r = split ? split->first : -1;
    const std::string local = split ? split->second : e.key;
    if (r >= count)
      throw InputError("estimate: '" + e.key + "': there " +
                       (count == 1 ? "is 1 record" : "are " + std::to_string(count) + " records"));
    std::optional<model::ParameterDescription> info;
    for (int k = (r >= 0 ? r : 0); k < (r >= 0 ? r + 1 : count); ++k) {
      info = model::describe_parameter(base_[static_cast<std::size_t>(k)], local);
      if (!info)
        throw InputError("estimate: '" + e.key + "' is not a parameter of " +
                         (count == 1 ? std::string("this beam") : "record " + std::to_string(k + 1) + "'s beam") +
                         " (valid: " + model::estimable_keys(base_[static_cast<std::size_t>(k)]) + ")");
    }
    if (std::count_if(estimated_.begin(), estimated_.end(), [&](const auto& o) { return o.key == e.key; }) > 1)
      throw InputError("estimate: '" + e.key + "' is listed twice");
    if (r < 0)
      for (const auto& o : estimated_)
        if (o.key != e.key && local_key(o.key) == local)
          throw InputError("estimate: '" + o.key + "' and '" + e.key +
                           "': a parameter is either shared by every record or estimated per record, not both");
    const std::string where = "bounds of " + e.key + " [" + format_value(e.lower) + ", " + format_value(e.upper) + "]";
    if (!(std::isfinite(e.lower) && std::isfinite(e.upper) && e.lower < e.upper))
      throw InputError(where + ": must be finite with lower < upper");
    if (e.lower < 0 || (e.lower == 0 && (info->strictly_positive || scaling_ == "log")))
      throw InputError(where + ": lower must be " +
                       std::string(info->strictly_positive || scaling_ == "log" ? "> 0" : ">= 0") +
                       (scaling_ == "log" ? " (log scaling)" : ""));
    const double given = model::parameter_value(base_[static_cast<std::size_t>(std::max(r, 0))], local);
    reference_.push_back(given > 0 ? given : (e.lower > 0 ? std::sqrt(e.lower * e.upper) : e.upper));
    record_.push_back(r);
  }
}

std::vector<ParameterMap::Local> ParameterMap::acting_on(int record) const {
  std::vector<Local> local;
  for (int i = 0; i < size(); ++i)
    if (record_[static_cast<std::size_t>(i)] < 0 || record_[static_cast<std::size_t>(i)] == record)
      local.push_back({i, local_key(estimated_[static_cast<std::size_t>(i)].key)});
  return local;
}

double ParameterMap::value(int i, double x) const {
  const double r = reference(i);
  return scaling_ == "log" ? r * std::exp(x) : r * x;
}

std::vector<model::BeamParameters> ParameterMap::estimates(const Eigen::VectorXd& x) const {
  std::vector<model::BeamParameters> beams = base_;
  for (std::size_t r = 0; r < beams.size(); ++r)
    for (const Local& p : acting_on(static_cast<int>(r))) {
      const auto& e = estimated_[static_cast<std::size_t>(p.index)];
      model::set_parameter_value(beams[r], p.key, std::clamp(value(p.index, x(p.index)), e.lower, e.upper));
    }
  return beams;
}

double ParameterMap::coordinate(int i, double p) const {
  const double r = reference(i);
  return scaling_ == "log" ? std::log(p / r) : p / r;
}

double ParameterMap::derivative(int i, double x) const { return scaling_ == "log" ? value(i, x) : reference(i); }

std::vector<model::BeamParameters> ParameterMap::beams(const Eigen::VectorXd& x) const {
  std::vector<model::BeamParameters> beams = base_;
  for (std::size_t r = 0; r < beams.size(); ++r)
    for (const Local& p : acting_on(static_cast<int>(r)))
      model::set_parameter_value(beams[r], p.key, value(p.index, x(p.index)));
  return beams;
}

Eigen::VectorXd ParameterMap::coordinates(const model::BeamParameters& b) const {
  std::vector<model::BeamParameters> beams = base_;
  beams.front() = b;
  return coordinates(beams);
}

Eigen::VectorXd ParameterMap::coordinates(const std::vector<model::BeamParameters>& beams) const {
  Eigen::VectorXd x(size());
  for (int i = 0; i < size(); ++i) {
    const int r = std::max(record_[static_cast<std::size_t>(i)], 0);
    x(i) = coordinate(i, model::parameter_value(beams.at(static_cast<std::size_t>(r)),
                                                local_key(estimated_[static_cast<std::size_t>(i)].key)));
  }
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
    if (std::find(roles.begin(), roles.end(),
                  model::parameter_role(local_key(estimated_[static_cast<std::size_t>(i)].key))) != roles.end())
      indices.push_back(i);
  return indices;
}

}  // namespace beamid::fit
