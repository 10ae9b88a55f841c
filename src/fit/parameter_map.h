// The one place where physical parameter values and the optimizer's dimensionless coordinates meet.
//   scaling "linear": x_i = p_i / r_i;   scaling "log": x_i = ln(p_i / r_i),
// with r_i the reference value of parameter i (its value in the given beam, or the geometric mean of its bounds
// when that value is 0). Coordinates are then of order one whatever the units (EI ~ 0.5 N m^2, kAG ~ 7e5 N).
// Parameters that are not estimated keep the given beam's values.
//
// A joint fit of several records (fit/identification.h) has one beam per record. An estimated key then names either
// a parameter shared by every record ("EI": one value, set in every record's beam) or one record's own parameter
// ("record2.l": record 2's length only; records are numbered from 1 in the order given). The reference value of a
// shared key is record 1's.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/beam_parameters.h"

namespace beamid::fit {

struct EstimatedParameter {
  std::string key;   // an estimable key of the beam (model::describe_parameter), or recordK.KEY (above)
  double lower = 0;  // physical bounds: 0 <= lower < upper (lower > 0 for log scaling and for > 0 keys)
  double upper = 0;
};

// The default bounds of an estimated parameter: [v/F, v F] around its nominal value v > 0, a factor F > 1 either
// way, so that log coordinates see a box symmetric about the nominal value. The one statement of that rule: the
// command line (api/fit_request.h), the synthetic studies (fit.bound_factor) and the real-record studies (F = 2)
// all take their bounds from it.
EstimatedParameter bounds_around(const std::string& key, double nominal, double factor);

// "record2.l" -> {1, "l"} (the 0-based record and the beam's own key); nothing for a key without the prefix. A
// malformed prefix ("record0.l", "record.l", "recordx.l") is an InputError naming the key.
std::optional<std::pair<int, std::string>> record_key(const std::string& key);
// The beam's own key of an estimated key: "record2.l" -> "l", "EI" -> "EI".
std::string local_key(const std::string& key);

class ParameterMap {
 public:
  // InputError naming the key, bound and constraint for an unknown or repeated key, or bad bounds.
  ParameterMap(const model::BeamParameters& beam, std::vector<EstimatedParameter> estimated,
               std::string scaling = "linear");
  // Several records (at least one): InputError also for a record number beyond their count, a shared key that some
  // record's beam does not have, and a key estimated both shared and for one record.
  ParameterMap(std::vector<model::BeamParameters> records, std::vector<EstimatedParameter> estimated,
               std::string scaling = "linear");

  int size() const { return static_cast<int>(estimated_.size()); }
  const std::vector<EstimatedParameter>& estimated() const { return estimated_; }
  const std::string& scaling() const { return scaling_; }
  double reference(int i) const { return reference_[static_cast<std::size_t>(i)]; }

  int records() const { return static_cast<int>(base_.size()); }
  // Physical beam of record 1 (of the only record) for coordinates x (the fixed parameters as given).
  model::BeamParameters beam(const Eigen::VectorXd& x) const { return beams(x).front(); }
  // Every record's beam for coordinates x.
  std::vector<model::BeamParameters> beams(const Eigen::VectorXd& x) const;
  // The same, with every estimated value clamped into its bounds: what a fit reports. The optimizers keep their
  // coordinates inside the coordinate bounds, but the map back (r x, r e^x) and a bounded optimizer's last step can
  // land a few ulps (LM: slightly more) outside; the reported estimate never does.
  model::BeamParameters estimate(const Eigen::VectorXd& x) const { return estimates(x).front(); }
  std::vector<model::BeamParameters> estimates(const Eigen::VectorXd& x) const;
  // Coordinates of the estimated values of record 1's beam (of every record's: a shared key is read from record 1).
  Eigen::VectorXd coordinates(const model::BeamParameters& beam) const;
  Eigen::VectorXd coordinates(const std::vector<model::BeamParameters>& beams) const;
  // The estimated parameters that act on record r (0-based): their indices and the record's own keys.
  struct Local {
    int index = 0;
    std::string key;
  };
  std::vector<Local> acting_on(int record) const;
  double value(int i, double x) const;       // p_i(x_i)
  double coordinate(int i, double p) const;  // x_i(p_i)
  double derivative(int i, double x) const;  // dp_i / dx_i, for propagating a covariance
  Eigen::VectorXd lower() const;             // bounds in coordinates
  Eigen::VectorXd upper() const;
  // Indices of the estimated parameters whose role (model::ParameterInfo::role of the local key) is in `roles`.
  std::vector<int> with_roles(const std::vector<std::string>& roles) const;

 private:
  std::vector<model::BeamParameters> base_;
  std::vector<int> record_;  // per estimated parameter: its record (0-based), or -1 when shared
  std::vector<EstimatedParameter> estimated_;
  std::vector<double> reference_;
  std::string scaling_;
};

}  // namespace beamid::fit
