#include "fit/posterior.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>

#include "core/errors.h"
#include "core/hash.h"
#include "fit/joint_objective.h"

namespace beamid::fit {

namespace {

// The options whose cost is the fit's last: a hybrid's refinement, run directly.
FitOptions final_options(const FitOptions& options) {
  FitOptions o = options;
  if (o.strategy == kHybrid) {
    o.cost.name = o.refine;
  }
  o.strategy = kDirect;
  return o;
}

// ln of the likelihood with the noise level integrated out (posterior.h): ln Gamma(m/2) - ln 2 - (m/2) ln(pi S).
double marginal_log_likelihood(double cost, int residuals) {
  const double m = residuals;
  return std::lgamma(m / 2) - std::numbers::ln2 - m / 2 * std::log(std::numbers::pi * cost);
}

// One chain's log density in the sampler's coordinates x: ln L(q(x)) + ln pi(q(x)) + sum_i ln |dq_i / dx_i|, -inf
// outside the bounds or where the model fails. Each holds its own objective (its workspace is not shared).
class Density {
 public:
  Density(const FitOptions& options, const std::vector<Record>& records, const ParameterMap& map)
      : map_(map), objective_(std::make_shared<JointObjective>(options, records, map)) {
    lower_ = map.lower(), upper_ = map.upper();
    for (const EstimatedParameter& e : map.estimated()) log_prior_ -= std::log(e.upper - e.lower);
  }
  double operator()(const Eigen::VectorXd& x) const {
    if ((x.array() < lower_.array()).any() || (x.array() > upper_.array()).any())
      return -std::numeric_limits<double>::infinity();
    const costs::Evaluation e = objective_->evaluate(map_.beams(x)).evaluation;
    if (!e.ok() || !(e.value > 0) || !std::isfinite(e.value)) return -std::numeric_limits<double>::infinity();
    double log_jacobian = 0;
    for (Eigen::Index i = 0; i < x.size(); ++i)
      log_jacobian += std::log(std::abs(map_.derivative(static_cast<int>(i), x(i))));
    return marginal_log_likelihood(e.value, objective_->residual_count()) + log_prior_ + log_jacobian;
  }
  int residuals() const { return objective_->residual_count(); }

 private:
  const ParameterMap& map_;
  std::shared_ptr<JointObjective> objective_;
  Eigen::VectorXd lower_, upper_;
  double log_prior_ = 0;
};

// ln of the multivariate Student t density with `nu` degrees of freedom, location mu, scale matrix from its
// Cholesky factor L (scale = L L').
double student_log_density(const Eigen::VectorXd& x, const Eigen::VectorXd& mu, const Eigen::MatrixXd& l, double nu) {
  const double d = static_cast<double>(x.size());
  const Eigen::VectorXd w = l.triangularView<Eigen::Lower>().solve(x - mu);
  const double log_det = 2 * l.diagonal().array().log().sum();
  return std::lgamma((nu + d) / 2) - std::lgamma(nu / 2) - d / 2 * std::log(nu * std::numbers::pi) - log_det / 2 -
         (nu + d) / 2 * std::log1p(w.squaredNorm() / nu);
}

// The sampled evidence (posterior.h): importance sampling from a Student t about the draws, in coordinates.
void sampled_evidence(const Density& density, const Eigen::MatrixXd& coordinates, int draws, std::uint64_t seed,
                      Posterior& out) {
  const Eigen::VectorXd mu = coordinates.colwise().mean().transpose();
  const Eigen::MatrixXd centred = coordinates.rowwise() - mu.transpose();
  const Eigen::MatrixXd scale = 2.0 * centred.transpose() * centred / static_cast<double>(coordinates.rows() - 1) *
                                (kEvidenceDegreesOfFreedom - 2.0) / kEvidenceDegreesOfFreedom;
  const Eigen::LLT<Eigen::MatrixXd> llt(scale);
  if (llt.info() != Eigen::Success) {
    out.evidence_note = "the draws' covariance is singular: no sampled evidence";
    return;
  }
  const Eigen::MatrixXd l = llt.matrixL();
  std::mt19937_64 engine(core::mix64(seed ^ 0x65766964656e6365ULL));  // "evidence"
  const auto uniform = [&engine] { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; };
  const auto gaussian = [&] {
    return std::sqrt(-2 * std::log(uniform())) * std::cos(2 * std::numbers::pi * uniform());
  };
  const auto d = coordinates.cols();
  std::vector<double> log_weights;
  for (int i = 0; i < draws; ++i) {
    Eigen::VectorXd g(d);
    for (Eigen::Index k = 0; k < d; ++k) g(k) = gaussian();
    double chi2 = 0;
    for (int k = 0; k < kEvidenceDegreesOfFreedom; ++k) chi2 += std::pow(gaussian(), 2);
    const Eigen::VectorXd x = mu + l * g / std::sqrt(chi2 / kEvidenceDegreesOfFreedom);
    const double lp = density(x);
    log_weights.push_back(std::isfinite(lp) ? lp - student_log_density(x, mu, l, kEvidenceDegreesOfFreedom)
                                            : -std::numeric_limits<double>::infinity());
  }
  const double top = *std::max_element(log_weights.begin(), log_weights.end());
  if (!std::isfinite(top)) {
    out.evidence_note = "no importance draw had a finite likelihood: no sampled evidence";
    return;
  }
  double sum = 0, sum2 = 0;
  for (const double lw : log_weights) {
    const double w = std::exp(lw - top);
    sum += w, sum2 += w * w;
  }
  const double n = draws, mean = sum / n, variance = std::max(0.0, sum2 / n - mean * mean);
  out.log_evidence_sampled = top + std::log(mean);
  out.log_evidence_sampled_se = std::sqrt(variance / n) / mean;  // delta method: sd of ln of the mean
}

// The Laplace evidence (posterior.h), or NaN with the reason.
void laplace_evidence(const FitResult& best, const ParameterMap& map, int residuals, Posterior& out) {
  const auto p = static_cast<Eigen::Index>(best.parameters.size());
  Eigen::VectorXd se(p);
  for (Eigen::Index i = 0; i < p; ++i) se(i) = best.parameters[static_cast<std::size_t>(i)].standard_error;
  if (!se.allFinite() || best.correlation.rows() != p) {
    out.evidence_note = "an estimate on a bound or no formal covariance: no Laplace evidence";
    return;
  }
  const double m = residuals;
  const Eigen::MatrixXd covariance = se.asDiagonal() * best.correlation * se.asDiagonal() * ((m - p) / m);
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  if (llt.info() != Eigen::Success) {
    out.evidence_note = "the formal covariance is not positive definite: no Laplace evidence";
    return;
  }
  const double log_det = 2 * Eigen::MatrixXd(llt.matrixL()).diagonal().array().log().sum();
  double log_prior = 0;
  for (const EstimatedParameter& e : map.estimated()) log_prior -= std::log(e.upper - e.lower);
  out.log_evidence_laplace = marginal_log_likelihood(best.cost, residuals) + log_prior +
                             static_cast<double>(p) / 2 * std::log(2 * std::numbers::pi) + log_det / 2;
}

// v to 2 significant digits of `resolution` (a posterior sd): an interval of 0.4910 +- 3e-5 reads [0.49097, 0.49103]
// rather than [0.491, 0.491].
std::string number(double v, double resolution) {
  const double digits =
      std::isfinite(resolution) && resolution > 0 && v != 0 ? std::ceil(std::log10(std::abs(v) / resolution)) + 2 : 4;
  std::ostringstream s;
  s.precision(static_cast<int>(std::clamp(digits, 3.0, 15.0)));
  s << v;
  return s.str();
}

}  // namespace

void PosteriorOptions::validate(int dimension) const {
  sampler.validate(dimension);
  if (threads < 1 || threads > 4096)
    throw InputError("posterior threads = " + std::to_string(threads) + ": must be in 1..4096");
  if (importance_draws < 0 || importance_draws > 10000000)
    throw InputError("posterior importance draws = " + std::to_string(importance_draws) + ": must be in 0..10000000");
}

std::string posterior_problem(const FitOptions& options, const std::vector<Record>& records) {
  const FitOptions o = final_options(options);
  const std::string& cost = o.cost.name;
  if (cost != costs::kTimeCost && !costs::is_band_cost(cost))
    return "the cost '" + cost +
           "' is no likelihood (its terms are weighed by convention, not by the noise): the posterior takes a "
           "least-squares cost (time, freq-band, freq-ml), or a hybrid refined by one";
  if (costs::is_estimated_noise(o.cost.noise_model))
    return "the noise model '" + o.cost.noise_model +
           "' is estimated from the fit's residuals, which the posterior does not carry: give it by name "
           "(white, ar:a1,..., power:alpha)";
  if (o.cost.force_noise_sd > 0)
    return "the errors-in-variables form (a noisy force) fixes the noise levels, which the posterior integrates out";
  if (options.record_weights == kNoiseWeights && records.size() > 1)
    return "the records are weighted by their noise (--record-weights noise): one noise level for all of them is "
           "what the posterior integrates out; use the default weights";
  return "";
}

std::string Posterior::line(std::size_t k) const {
  const PosteriorParameter& p = parameters[k];
  const double r = p.sd;
  return p.key + ": mean " + number(p.mean, r) + " sd " + number(p.sd, 0) + ", 95 % [" + number(p.lower95, r) + ", " +
         number(p.upper95, r) + "] (fit " + number(p.estimate, r) + " +- " + number(p.standard_error, 0) + "), R-hat " +
         number(p.rhat, 0) + ", ESS " + std::to_string(std::lround(p.effective_samples));
}

Posterior posterior(const FitOptions& options, const std::vector<Record>& records, const FitResult& best,
                    const PosteriorOptions& posterior_options) {
  if (const std::string problem = posterior_problem(options, records); !problem.empty())
    throw InputError("posterior: " + problem);
  if (best.status == "failed") throw InputError("posterior: the fit failed, so there is no estimate to start from");
  const auto started = std::chrono::steady_clock::now();
  const FitOptions o = final_options(options);
  std::vector<model::BeamParameters> beams;
  for (const RecordResult& r : best.records) beams.push_back(r.beam);
  std::vector<Record> at_estimate = records;
  for (std::size_t r = 0; r < at_estimate.size() && r < beams.size(); ++r) at_estimate[r].start = beams[r];
  const ParameterMap map(beams, o.estimate, o.scaling);
  const int d = map.size();
  posterior_options.validate(d);
  // The walkers' start: the estimate, a formal standard error apart in coordinates (dx = dq / (dq/dx)).
  const Eigen::VectorXd center = map.coordinates(beams);
  Eigen::VectorXd scale(d);
  std::vector<std::string> names;
  for (int i = 0; i < d; ++i) {
    const ParameterEstimate& e = best.parameters[static_cast<std::size_t>(i)];
    const double dq =
        std::isfinite(e.standard_error) && e.standard_error > 0 ? e.standard_error : (e.upper - e.lower) / 100;
    scale(i) = dq / std::abs(map.derivative(i, center(i)));
    names.push_back(e.key);
  }
  const Density first(o, at_estimate, map);
  Posterior out;
  out.residuals = first.residuals();
  const SamplerResult coordinates = sample_ensemble([&]() { return LogDensity(Density(o, at_estimate, map)); }, center,
                                                    scale, posterior_options.sampler, names, posterior_options.threads);
  out.status = coordinates.status;
  // The draws in the parameters' own values.
  out.samples = coordinates;
  for (Eigen::Index row = 0; row < out.samples.draws.rows(); ++row)
    for (int i = 0; i < d; ++i) out.samples.draws(row, i) = map.value(i, coordinates.draws(row, i));
  SamplerResult& s = out.samples;
  s.mean = s.draws.colwise().mean().transpose();
  const Eigen::MatrixXd centred = s.draws.rowwise() - s.mean.transpose();
  s.covariance = centred.transpose() * centred / static_cast<double>(s.draws.rows() - 1);
  s.sd = s.covariance.diagonal().cwiseSqrt();
  out.correlation = s.covariance.array() / (s.sd * s.sd.transpose()).array();
  for (int i = 0; i < d; ++i) {
    const ParameterEstimate& e = best.parameters[static_cast<std::size_t>(i)];
    out.parameters.push_back({e.key, e.estimate, e.standard_error, s.mean(i), s.sd(i), s.quantile(i, 0.5),
                              s.quantile(i, 0.025), s.quantile(i, 0.975), s.rhat(i), s.effective_samples(i)});
  }
  laplace_evidence(best, map, out.residuals, out);
  if (posterior_options.importance_draws > 0)
    sampled_evidence(first, coordinates.draws, posterior_options.importance_draws, posterior_options.sampler.seed, out);
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace beamid::fit
