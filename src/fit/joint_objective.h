// The cost of a joint fit (fit/identification.h): one Objective (fit/objective.h) per record, each with its own
// experiment, data and beam, and the records' residual vectors stacked, each times its record's weight:
//   r = [w_1 r_1; w_2 r_2; ...],  J = |r|^2 = sum_k w_k^2 J_k,
// w_k = 1 for a single record (the fit is then exactly the single-record fit), and otherwise 1 / RMS(z_k) for the
// time cost, sqrt(Nbar_k) / RMS(z_k) for freq-band and 1 for the dimensionless spike and modal costs.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "fit/identification.h"
#include "fit/objective.h"
#include "fit/parameter_map.h"

namespace beamid::fit {

class JointObjective {
 public:
  // InputError when a record's options or data are inadmissible (Objective's checks, naming the record when there
  // are several). `map` must outlive the objective.
  JointObjective(const FitOptions& options, const std::vector<Record>& records, const ParameterMap& map);

  int records() const { return static_cast<int>(parts_.size()); }
  int residual_count() const { return residual_count_; }
  double weight(int record) const { return weights_[static_cast<std::size_t>(record)]; }
  // Replaces the records' weights (FitOptions::record_weights "noise"); one per record, finite and > 0.
  void set_weights(std::vector<double> weights);
  const Objective& part(int record) const { return *parts_[static_cast<std::size_t>(record)]; }

  struct Output {
    costs::Evaluation evaluation;            // stacked; a single record's own evaluation unchanged
    std::vector<Objective::Output> records;  // each record's output and unweighted evaluation
  };
  // Never throws for admissible options: a failed record makes the joint evaluation fail with its status.
  Output evaluate(const std::vector<model::BeamParameters>& beams,
                  Objective::Response response = Objective::Response::as_cost_needs);
  // Whether every record has an exact Jacobian for the estimated parameters acting on it.
  bool has_exact_jacobian() const { return exact_jacobian_; }
  // evaluate, and d r / d q for the estimated parameters `active` (indices into the map, in that order): a shared
  // parameter's column stacks every record's, a record's own parameter is zero in the other records' rows. `jacobian`
  // is empty when the evaluation failed.
  Output evaluate_with_jacobian(const std::vector<model::BeamParameters>& beams, const std::vector<int>& active,
                                Eigen::MatrixXd& jacobian);

 private:
  costs::Evaluation stack(std::vector<Objective::Output>& parts) const;
  const ParameterMap& map_;
  std::vector<std::unique_ptr<Objective>> parts_;
  std::vector<std::string> names_;
  std::vector<double> weights_;
  int residual_count_ = 0;
  bool exact_jacobian_ = true;
};

// The options of record `record`'s own fit: its start beam and experiment, the estimated parameters acting on it
// under their local keys, and its spike frequencies.
FitOptions record_options(const FitOptions& options, const Record& record, const ParameterMap& map, int index);

}  // namespace beamid::fit
