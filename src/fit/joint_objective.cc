#include "fit/joint_objective.h"

#include <cmath>

#include "core/errors.h"

namespace beamid::fit {

FitOptions record_options(const FitOptions& options, const Record& record, const ParameterMap& map, int index) {
  FitOptions o = options;
  o.start = record.start;
  o.experiment = record.experiment;
  o.estimate.clear();
  for (const ParameterMap::Local& p : map.acting_on(index)) {
    const EstimatedParameter& e = map.estimated()[static_cast<std::size_t>(p.index)];
    o.estimate.push_back({p.key, e.lower, e.upper});
  }
  if (!record.noise_model.empty()) o.cost.noise_model = record.noise_model;
  if (!record.bin_variance.empty()) o.cost.bin_variance = record.bin_variance;
  if (!record.spike_frequencies_hz.empty()) {
    o.cost.spikes.frequencies_hz = record.spike_frequencies_hz;
    o.cost.spikes.count = static_cast<int>(record.spike_frequencies_hz.size());
  }
  return o;
}

namespace {

// The factor on a record's residuals in a joint fit (joint_objective.h): time-domain residuals relative to the RMS of
// the record's data, the dimensionless costs' as they are. freq-band's bins carry the DFT's 1/Nbar, whose residual
// norm is the time domain's over sqrt(Nbar) (Parseval); freq-ml's are over the bins' noise sd, which restores it.
double record_weight(const std::string& cost, const std::vector<double>& data) {
  if (cost != costs::kTimeCost && !costs::is_band_cost(cost)) return 1;
  double sum = 0;
  for (const double z : data) sum += z * z;
  const double rms = std::sqrt(sum / static_cast<double>(data.size()));
  if (!(rms > 0) || !std::isfinite(rms))
    throw InputError("data: all zero or not finite: a record of a joint fit needs a signal");
  return (cost == costs::kBandCost ? std::sqrt(static_cast<double>(data.size())) : 1.0) / rms;
}

}  // namespace

JointObjective::JointObjective(const FitOptions& options, const std::vector<Record>& records, const ParameterMap& map)
    : map_(map) {
  if (records.empty()) throw InputError("records: none to fit");
  const bool joint = records.size() > 1;
  for (std::size_t r = 0; r < records.size(); ++r) {
    const FitOptions o = record_options(options, records[r], map, static_cast<int>(r));
    try {
      parts_.push_back(std::make_unique<Objective>(o, records[r].data));
      weights_.push_back(joint ? record_weight(o.cost.name, records[r].data) : 1.0);
    } catch (const InputError& error) {
      if (!joint) throw;
      throw InputError("record " + std::to_string(r + 1) + " (" + records[r].name + "): " + error.what());
    }
    names_.push_back(records[r].name);
    residual_count_ += parts_.back()->cost().residual_count();
    exact_jacobian_ = exact_jacobian_ && parts_.back()->has_exact_jacobian();
  }
}

void JointObjective::set_weights(std::vector<double> weights) {
  if (weights.size() != weights_.size()) throw InputError("record weights: one per record");
  for (const double w : weights)
    if (!(std::isfinite(w) && w > 0)) throw InputError("record weights: must be finite and > 0");
  weights_ = std::move(weights);
}

costs::Evaluation JointObjective::stack(std::vector<Objective::Output>& parts) const {
  if (parts_.size() == 1) return parts.front().evaluation;
  costs::Evaluation joint;
  joint.a4.clear();
  for (std::size_t r = 0; r < parts.size(); ++r) {
    const costs::Evaluation& e = parts[r].evaluation;
    if (!e.ok()) {
      joint.status = "record " + std::to_string(r + 1) + " (" + names_[r] + "): " + e.status;
      joint.residuals.resize(0);
      return joint;
    }
    if (e.a4 != "ok") joint.a4 += (joint.a4.empty() ? "" : "; ") + ("record " + std::to_string(r + 1) + ": " + e.a4);
  }
  if (joint.a4.empty()) joint.a4 = "ok";
  joint.residuals.resize(residual_count_);
  Eigen::Index row = 0;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    const Eigen::VectorXd& part = parts[r].evaluation.residuals;
    joint.residuals.segment(row, part.size()) = weights_[r] * part;
    row += part.size();
  }
  joint.value = joint.residuals.squaredNorm();
  return joint;
}

JointObjective::Output JointObjective::evaluate(const std::vector<model::BeamParameters>& beams,
                                                Objective::Response response) {
  Output out;
  for (std::size_t r = 0; r < parts_.size(); ++r) {
    out.records.push_back(parts_[r]->evaluate(beams.at(r), response));
    if (!out.records.back().evaluation.ok()) break;  // the joint cost is undefined: the other records need not run
  }
  out.evaluation = stack(out.records);
  return out;
}

JointObjective::Output JointObjective::evaluate_with_jacobian(const std::vector<model::BeamParameters>& beams,
                                                              const std::vector<int>& active,
                                                              Eigen::MatrixXd& jacobian) {
  jacobian.resize(0, 0);
  Output out;
  std::vector<Eigen::MatrixXd> blocks(parts_.size());
  std::vector<std::vector<Eigen::Index>> columns(parts_.size());  // each block's columns in `active`
  for (std::size_t r = 0; r < parts_.size(); ++r) {
    std::vector<std::string> keys;
    for (std::size_t c = 0; c < active.size(); ++c)
      for (const ParameterMap::Local& p : map_.acting_on(static_cast<int>(r)))
        if (p.index == active[c]) keys.push_back(p.key), columns[r].push_back(static_cast<Eigen::Index>(c));
    // A record no active parameter acts on contributes residuals and zero derivatives.
    out.records.push_back(keys.empty() ? parts_[r]->evaluate(beams.at(r))
                                       : parts_[r]->evaluate_with_jacobian(beams.at(r), keys, blocks[r]));
    if (!out.records.back().evaluation.ok() || (!keys.empty() && blocks[r].size() == 0)) {
      out.evaluation = stack(out.records);
      if (out.evaluation.ok()) out.evaluation.status = "record " + std::to_string(r + 1) + ": no Jacobian";
      return out;
    }
  }
  out.evaluation = stack(out.records);
  if (parts_.size() == 1) {  // exactly the record's own Jacobian
    jacobian = std::move(blocks.front());
    if (jacobian.size() == 0)
      jacobian = Eigen::MatrixXd::Zero(residual_count_, static_cast<Eigen::Index>(active.size()));
    return out;
  }
  jacobian = Eigen::MatrixXd::Zero(residual_count_, static_cast<Eigen::Index>(active.size()));
  Eigen::Index row = 0;
  for (std::size_t r = 0; r < parts_.size(); ++r) {
    const Eigen::Index rows = out.records[r].evaluation.residuals.size();
    for (std::size_t c = 0; c < columns[r].size(); ++c)
      jacobian.block(row, columns[r][c], rows, 1) = weights_[r] * blocks[r].col(static_cast<Eigen::Index>(c));
    row += rows;
  }
  return out;
}

}  // namespace beamid::fit
