#include "fit/experiment_design.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "fit/cramer_rao.h"
#include "galerkin/second_order_system.h"
#include "signal/noise.h"
#include "simulation/simulator.h"

namespace beamid::fit {
namespace {

// C(n, k), saturated at kMaxDesignCandidates + 1.
long long subsets(long long n, long long k) {
  if (k < 0 || k > n) return 0;
  long long c = 1;
  for (long long i = 1; i <= k; ++i) {
    c = c * (n - k + i) / i;  // exact: a product of i consecutive integers is divisible by i!
    if (c > kMaxDesignCandidates) return kMaxDesignCandidates + 1;
  }
  return c;
}

// One channel of one setup: its Fisher information in ln q, or why it has none.
struct Channel {
  Eigen::MatrixXd information;
  std::string status = "ok";
};

Channel channel_information(const DesignOptions& o, const simulation::Experiment& e, const signal::NoiseModel& noise) {
  Channel c;
  try {
    double sigma = o.noise_sd;
    if (!(sigma > 0)) {  // a fraction of this channel's clean RMS
      const galerkin::SplineSpace space(o.elements);
      const simulation::Trace clean =
          simulation::simulate(galerkin::BeamForms(space, o.beam.l, o.beam.support), o.beam, e, {});
      if (!clean.ok()) throw NumericalError("the model could not be evaluated: " + clean.status);
      sigma = o.noise_level * signal::rms(clean.y);
      if (!(sigma > 0)) throw NumericalError("the clean output is zero here (a sensor or the force at the clamp)");
    }
    const CramerRaoBound b = beam_cramer_rao_bound(o.beam, o.elements, e, o.keys, sigma);
    const Eigen::MatrixXd w = noise.kind == "white" ? b.sensitivities : signal::whiten(noise, b.sensitivities);
    c.information = w.transpose() * w / (sigma * sigma);
  } catch (const std::exception& error) {  // NumericalError, or an InputError of this one experiment
    c.status = error.what();
  }
  return c;
}

// The row of a candidate from its summed information: the criterion and every key's bound, or "singular".
void bound_row(const DesignOptions& o, const Eigen::MatrixXd& information, DesignRow& row) {
  const auto p = information.rows();
  row.relative_sd = Eigen::VectorXd::Constant(p, std::numeric_limits<double>::quiet_NaN());
  row.criterion = std::numeric_limits<double>::quiet_NaN();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(information);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  // Singular to double precision: the data do not determine some combination of the keys (the same 1e-12 of the
  // largest as fit::CramerRaoBound's null directions).
  if (!(lambda(0) > 1e-12 * lambda(p - 1))) {
    row.status = "singular Fisher information: these channels do not determine every parameter of interest";
    return;
  }
  const Eigen::MatrixXd covariance =
      eigen.eigenvectors() * lambda.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  row.relative_sd = covariance.diagonal().cwiseSqrt();
  if (o.criterion == kDOptimal)
    row.criterion = std::exp(-lambda.array().log().sum() / (2.0 * static_cast<double>(p)));
  else if (o.criterion == kAOptimal)
    row.criterion = std::sqrt(covariance.trace() / static_cast<double>(p));
  else
    row.criterion = row.relative_sd(std::find(o.keys.begin(), o.keys.end(), o.criterion) - o.keys.begin());
}

}  // namespace

long long candidate_count(const DesignOptions& o) {
  long long n = subsets(static_cast<long long>(o.sensor_positions_m.size()), o.sensor_count);
  for (const std::size_t size :
       {o.force_positions_m.size(), o.pulse_widths_s.size(), o.dts_s.size(), o.samples.size()}) {
    n *= static_cast<long long>(size);
    if (n > kMaxDesignCandidates) return kMaxDesignCandidates + 1;
  }
  return n;
}

std::optional<std::string> validation_error(const DesignOptions& o) {
  if (o.keys.empty()) return "parameters of interest: none given";
  for (const std::string& key : o.keys)
    if (!model::describe_parameter(o.beam, key))
      return "parameter '" + key + "': not a parameter of this beam (valid: " + model::estimable_keys(o.beam) + ")";
  if (o.sensor_positions_m.empty()) return "sensor positions: none given";
  if (o.force_positions_m.empty() || o.pulse_widths_s.empty() || o.dts_s.empty() || o.samples.empty())
    return "force positions, pulse widths, sampling intervals and record lengths: each needs at least one value";
  if (o.sensor_count < 1 || o.sensor_count > static_cast<int>(o.sensor_positions_m.size()))
    return "sensor count = " + std::to_string(o.sensor_count) + ": must be in 1.." +
           std::to_string(o.sensor_positions_m.size()) + " (the positions given)";
  if (o.criterion != kDOptimal && o.criterion != kAOptimal &&
      std::find(o.keys.begin(), o.keys.end(), o.criterion) == o.keys.end())
    return "criterion = '" + o.criterion + "': must be D, A or one of the parameters of interest";
  if ((o.noise_sd > 0) == (o.noise_level > 0))
    return "noise: give exactly one of an absolute sd > 0 and a fraction of the RMS > 0";
  if (!(std::isfinite(o.noise_sd) && std::isfinite(o.noise_level) && o.noise_sd >= 0 && o.noise_level >= 0))
    return "noise: the sd and the fraction must be finite and >= 0";
  if (candidate_count(o) > kMaxDesignCandidates)
    return "more than " + std::to_string(kMaxDesignCandidates) +
           " candidates (the sensor positions' subsets times the other choices): fewer positions or a smaller "
           "sensor count";
  return std::nullopt;
}

std::vector<DesignRow> rank_designs(const DesignOptions& o) {
  if (auto error = validation_error(o)) throw InputError("design: " + *error);
  const signal::NoiseModel noise = signal::parse_noise_model(o.noise_model);
  const auto p = static_cast<Eigen::Index>(o.keys.size());
  const auto positions = static_cast<int>(o.sensor_positions_m.size());
  std::vector<DesignRow> rows;
  for (const double force : o.force_positions_m)
    for (const double tau : o.pulse_widths_s)
      for (const double dt : o.dts_s)
        for (const int samples : o.samples) {
          simulation::Experiment e = o.base;
          e.force_x_m = force;
          e.pulse_width_s = tau;
          e.dt_s = dt;
          e.samples = samples;
          std::vector<Channel> channels;  // every position's, once
          for (const double x : o.sensor_positions_m) {
            e.sensor_x_m = x;
            channels.push_back(channel_information(o, e, noise));
          }
          // Every K-subset of the positions, in lexicographic order of their indices.
          std::vector<int> pick(static_cast<std::size_t>(o.sensor_count));
          for (int i = 0; i < o.sensor_count; ++i) pick[static_cast<std::size_t>(i)] = i;
          while (true) {
            DesignRow row;
            row.candidate = {{}, force, tau, dt, samples};
            Eigen::MatrixXd information = Eigen::MatrixXd::Zero(p, p);
            for (const int i : pick) {
              row.candidate.sensors_x_m.push_back(o.sensor_positions_m[static_cast<std::size_t>(i)]);
              const Channel& c = channels[static_cast<std::size_t>(i)];
              if (c.status != "ok" && row.status == "ok") row.status = c.status;
              if (c.status == "ok") information += c.information;
            }
            if (row.status == "ok") {
              bound_row(o, information, row);
            } else {
              row.criterion = std::numeric_limits<double>::quiet_NaN();
              row.relative_sd = Eigen::VectorXd::Constant(p, std::numeric_limits<double>::quiet_NaN());
            }
            rows.push_back(std::move(row));
            int k = o.sensor_count - 1;  // the next subset: advance the last index that can move
            while (k >= 0 && pick[static_cast<std::size_t>(k)] == positions - o.sensor_count + k) --k;
            if (k < 0) break;
            ++pick[static_cast<std::size_t>(k)];
            for (int j = k + 1; j < o.sensor_count; ++j)
              pick[static_cast<std::size_t>(j)] = pick[static_cast<std::size_t>(j - 1)] + 1;
          }
        }
  std::stable_sort(rows.begin(), rows.end(), [](const DesignRow& a, const DesignRow& b) {
    const bool a_ok = a.status == "ok", b_ok = b.status == "ok";
    if (a_ok != b_ok) return a_ok;
    return a_ok && a.criterion < b.criterion;
  });
  return rows;
}

}  // namespace beamid::fit
