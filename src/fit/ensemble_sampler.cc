#include "fit/ensemble_sampler.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <thread>

#include "core/errors.h"
#include "core/hash.h"

namespace beamid::fit {

namespace {

// Uniforms and Gaussians as signal/noise.h draws them (portable across standard libraries).
class Stream {
 public:
  explicit Stream(std::uint64_t seed) : engine_(seed) {}
  // ((x >> 11) + 0.5) 2^-53: strictly inside (0, 1), so its logarithm is finite.
  double uniform() { return (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53; }
  double gaussian() {  // Box-Muller, both deviates used in turn
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = uniform(), u2 = uniform();
    const double r = std::sqrt(-2 * std::log(u1));
    spare_ = r * std::sin(2 * std::numbers::pi * u2), has_spare_ = true;
    return r * std::cos(2 * std::numbers::pi * u2);
  }
  int index(int count) { return std::min(count - 1, static_cast<int>(uniform() * count)); }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace

// Acklam's rational approximation (relative error below 1.2e-9), refined by one Halley step on erfc, which leaves it
// within a few ulps (tests: Phi(quantile(p)) = p to 1e-14).
double normal_quantile(double p) {
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01, -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  constexpr double low = 0.02425;
  double x = 0;
  if (p < low) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - low) {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log1p(-p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  const double e = 0.5 * std::erfc(-x / std::numbers::sqrt2) - p;
  const double u = e * std::sqrt(2 * std::numbers::pi) * std::exp(x * x / 2);
  return x - u / (1 + x * u / 2);
}

namespace {

// Blom's normal scores of the values' ranks (ties take their mean rank): the rank normalisation of Vehtari et al.
std::vector<double> normal_scores(const std::vector<double>& values) {
  const std::size_t n = values.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return values[i] < values[j]; });
  std::vector<double> z(n);
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j + 1 < n && values[order[j + 1]] == values[order[i]]) ++j;
    const double rank = 0.5 * static_cast<double>(i + j) + 1;  // 1-based, the ties' mean
    const double score = normal_quantile((rank - 0.375) / (static_cast<double>(n) + 0.25));
    for (std::size_t k = i; k <= j; ++k) z[order[k]] = score;
    i = j + 1;
  }
  return z;
}

// Gelman and Rubin's R-hat of equal-length chains (sample variances with n - 1).
double basic_rhat(const std::vector<std::vector<double>>& chains) {
  const double m = static_cast<double>(chains.size()), n = static_cast<double>(chains.front().size());
  std::vector<double> means, variances;
  for (const auto& c : chains) {
    const double mean = std::accumulate(c.begin(), c.end(), 0.0) / n;
    double ss = 0;
    for (const double v : c) ss += (v - mean) * (v - mean);
    means.push_back(mean), variances.push_back(ss / (n - 1));
  }
  const double grand = std::accumulate(means.begin(), means.end(), 0.0) / m;
  double between = 0;  // B / n
  for (const double mu : means) between += (mu - grand) * (mu - grand);
  between /= m - 1;
  const double within = std::accumulate(variances.begin(), variances.end(), 0.0) / m;
  if (!(within > 0)) return between > 0 ? std::numeric_limits<double>::infinity() : 1.0;
  return std::sqrt(((n - 1) / n * within + between) / within);
}

// Rank-normalised R-hat of split chains (each given as its pooled draws).
double rank_rhat(std::vector<std::vector<double>> chains) {
  std::vector<double> all;
  for (const auto& c : chains) all.insert(all.end(), c.begin(), c.end());
  const std::vector<double> z = normal_scores(all);
  std::size_t at = 0;
  for (auto& c : chains)
    for (double& v : c) v = z[at++];
  return basic_rhat(chains);
}

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

}  // namespace

int SamplerOptions::walkers_for(int dimension) const {
  if (walkers > 0) return walkers;
  const int n = std::max(2 * dimension + 2, 16);
  return n + n % 2;
}

void SamplerOptions::validate(int dimension) const {
  const auto refuse = [](const std::string& name, const std::string& value, const std::string& why) {
    throw InputError("posterior " + name + " = " + value + ": " + why);
  };
  if (chains < 2 || chains > 64) refuse("chains", std::to_string(chains), "must be in 2..64 (R-hat compares chains)");
  if (walkers != 0 && (walkers < 2 * dimension + 2 || walkers % 2 != 0 || walkers > 4096))
    refuse("walkers", std::to_string(walkers),
           "must be even and in " + std::to_string(2 * dimension + 2) +
               "..4096 (an ensemble needs at least 2 d + 2 walkers in d = " + std::to_string(dimension) + ")");
  if (steps < 20 || steps > 1000000) refuse("steps", std::to_string(steps), "must be in 20..1000000");
  if (warmup < 0 || warmup > 1000000) refuse("warmup", std::to_string(warmup), "must be in 0..1000000");
  if (!(stretch > 1 && stretch <= 10)) refuse("stretch", format_number(stretch), "must be in (1, 10]");
  const double draws = static_cast<double>(chains) * walkers_for(dimension) * steps * std::max(dimension, 1);
  if (draws > 2e8)
    refuse("steps", std::to_string(steps),
           "chains x walkers x steps x parameters = " + format_number(draws) + " numbers: more than 2e8 (1.6 GB)");
}

double split_rhat(const std::vector<std::vector<std::vector<double>>>& series) {
  // Each chain's walkers pooled, split in the halves of its steps.
  std::vector<std::vector<double>> bulk;
  for (const auto& chain : series) {
    const std::size_t n = chain.front().size(), half = n / 2;
    std::vector<double> first, second;
    for (const auto& walker : chain) {
      first.insert(first.end(), walker.begin(), walker.begin() + static_cast<long>(half));
      second.insert(second.end(), walker.end() - static_cast<long>(half), walker.end());
    }
    bulk.push_back(std::move(first)), bulk.push_back(std::move(second));
  }
  // The tails: |x - median| of all draws, rank-normalised in turn.
  std::vector<double> all;
  for (const auto& c : bulk) all.insert(all.end(), c.begin(), c.end());
  std::nth_element(all.begin(), all.begin() + static_cast<long>(all.size() / 2), all.end());
  const double median = all[all.size() / 2];
  std::vector<std::vector<double>> folded = bulk;
  for (auto& c : folded)
    for (double& v : c) v = std::abs(v - median);
  return std::max(rank_rhat(bulk), rank_rhat(folded));
}

double autocorrelation_time(const std::vector<std::vector<double>>& walkers) {
  const std::size_t n = walkers.front().size();
  std::vector<std::vector<double>> centred = walkers;
  double variance = 0;
  for (auto& w : centred) {
    const double mean = std::accumulate(w.begin(), w.end(), 0.0) / static_cast<double>(n);
    for (double& v : w) v -= mean, variance += v * v;
  }
  if (!(variance > 0)) return std::numeric_limits<double>::infinity();  // a walker that never moved
  // tau(M) = 1 + 2 sum_{t=1}^{M} rho(t), rho the walkers' mean autocorrelation; the window: the first M >= 5 tau(M).
  double tau = 1;
  for (std::size_t lag = 1; lag < n / 2; ++lag) {
    double c = 0;
    for (const auto& w : centred)
      for (std::size_t i = 0; i + lag < n; ++i) c += w[i] * w[i + lag];
    tau += 2 * c / variance;
    if (static_cast<double>(lag) >= 5 * tau) return tau;
  }
  return std::max(tau, static_cast<double>(n) / 10);  // no window within the run: the run is too short to say
}

double SamplerResult::quantile(int k, double q) const {
  std::vector<double> v(draws.rows());
  for (Eigen::Index i = 0; i < draws.rows(); ++i) v[static_cast<std::size_t>(i)] = draws(i, k);
  std::sort(v.begin(), v.end());
  const double at = std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1);
  const auto i = static_cast<std::size_t>(std::floor(at));
  return i + 1 < v.size() ? v[i] + (at - static_cast<double>(i)) * (v[i + 1] - v[i]) : v[i];
}

namespace {

struct Chain {
  Eigen::MatrixXd kept;  // steps * walkers rows (step-major), d columns
  std::vector<double> kept_log_density;
  long accepted = 0, proposed = 0, evaluations = 0;
};

Chain run_chain(const LogDensity& log_density, const Eigen::VectorXd& center, const Eigen::VectorXd& scale,
                const SamplerOptions& o, int chain) {
  const auto d = static_cast<int>(center.size());
  const int walkers = o.walkers_for(d), half = walkers / 2;
  Stream stream(core::mix64(o.seed ^ core::mix64(static_cast<std::uint64_t>(chain) + 1)));
  Eigen::MatrixXd x(walkers, d);
  std::vector<double> lp(static_cast<std::size_t>(walkers));
  Chain out;
  for (int w = 0; w < walkers; ++w) {
    int tries = 0;
    do {
      if (++tries > kMaxStartTries) {
        std::ostringstream s;
        s.precision(6);
        s << "posterior: no walker start with a finite log density in " << kMaxStartTries << " draws about the center ["
          << center.transpose() << "] (the estimate on a bound, or the model failing "
          << "around it)";
        throw InputError(s.str());
      }
      for (int k = 0; k < d; ++k) x(w, k) = center(k) + scale(k) * stream.gaussian();
      lp[static_cast<std::size_t>(w)] = log_density(x.row(w).transpose());
      ++out.evaluations;
    } while (!std::isfinite(lp[static_cast<std::size_t>(w)]));
  }
  out.kept.resize(static_cast<Eigen::Index>(o.steps) * walkers, d);
  out.kept_log_density.resize(static_cast<std::size_t>(o.steps) * static_cast<std::size_t>(walkers));
  const double a = o.stretch;
  for (int step = 0; step < o.warmup + o.steps; ++step) {
    const bool keep = step >= o.warmup;
    for (int side = 0; side < 2; ++side) {
      for (int k = side * half; k < (side + 1) * half; ++k) {
        const int j = (1 - side) * half + stream.index(half);
        const double u = stream.uniform();
        const double z = ((a - 1) * u + 1) * ((a - 1) * u + 1) / a;
        const Eigen::VectorXd y = x.row(j).transpose() + z * (x.row(k) - x.row(j)).transpose();
        const double lpy = log_density(y);
        ++out.evaluations;
        const double log_ratio = (d - 1) * std::log(z) + lpy - lp[static_cast<std::size_t>(k)];
        const bool accept = std::isfinite(lpy) && std::log(stream.uniform()) < log_ratio;
        if (accept) x.row(k) = y.transpose(), lp[static_cast<std::size_t>(k)] = lpy;
        if (keep) out.proposed++, out.accepted += accept ? 1 : 0;
      }
    }
    if (keep) {
      const Eigen::Index row = static_cast<Eigen::Index>(step - o.warmup) * walkers;
      out.kept.middleRows(row, walkers) = x;
      std::copy(lp.begin(), lp.end(), out.kept_log_density.begin() + row);
    }
  }
  return out;
}

// The status of a run from its diagnostics: the first failing check, or "converged".
std::string convergence_status(const SamplerResult& r, const std::vector<std::string>& names) {
  const auto name = [&](Eigen::Index k) {
    return k < static_cast<Eigen::Index>(names.size()) ? names[static_cast<std::size_t>(k)]
                                                       : "x" + std::to_string(k + 1);
  };
  for (Eigen::Index k = 0; k < r.rhat.size(); ++k)
    if (!(r.rhat(k) < kMaxRhat))
      return "not converged: " + name(k) + "'s R-hat is " + format_number(r.rhat(k)) + " (< " +
             format_number(kMaxRhat) + " asked: the chains disagree; run longer, or look for several modes)";
  for (Eigen::Index k = 0; k < r.rhat.size(); ++k)
    if (!(r.effective_samples(k) >= kMinEffectiveSamples))
      return "not converged: " + name(k) + "'s effective sample size is " + format_number(r.effective_samples(k)) +
             " (>= " + format_number(kMinEffectiveSamples) + " asked; run longer)";
  for (Eigen::Index k = 0; k < r.rhat.size(); ++k)
    if (!(r.steps >= kMinStepsPerTau * r.tau(k)))
      return "not converged: " + std::to_string(r.steps) + " steps are fewer than " + format_number(kMinStepsPerTau) +
             " autocorrelation times of " + name(k) + " (" + format_number(r.tau(k)) +
             " steps each), too few to trust them; run longer";
  return "converged";
}

}  // namespace

SamplerResult sample_ensemble(const LogDensity& log_density, const Eigen::VectorXd& center,
                              const Eigen::VectorXd& scale, const SamplerOptions& options,
                              const std::vector<std::string>& names) {
  return sample_ensemble([&log_density]() { return log_density; }, center, scale, options, names, 1);
}

SamplerResult sample_ensemble(const DensityFactory& factory, const Eigen::VectorXd& center,
                              const Eigen::VectorXd& scale, const SamplerOptions& options,
                              const std::vector<std::string>& names, int threads) {
  const auto d = static_cast<int>(center.size());
  if (d < 1) throw InputError("posterior: no parameter to sample");
  if (scale.size() != center.size() || !center.allFinite() || !scale.allFinite() || (scale.array() <= 0).any())
    throw InputError("posterior: the start's center and scale must be finite, of one size, the scale > 0");
  options.validate(d);
  SamplerResult r;
  r.chains = options.chains, r.walkers = options.walkers_for(d), r.steps = options.steps;
  // Chain c runs on thread c mod threads; a chain's exception (a start refused) is rethrown, the first chain's first.
  std::vector<Chain> chains(static_cast<std::size_t>(options.chains));
  std::vector<std::exception_ptr> errors(chains.size());
  const int workers = std::clamp(threads, 1, options.chains);
  const auto work = [&](int first) {
    for (int c = first; c < options.chains; c += workers) {
      try {
        chains[static_cast<std::size_t>(c)] = run_chain(factory(), center, scale, options, c);
      } catch (...) {
        errors[static_cast<std::size_t>(c)] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  long accepted = 0, proposed = 0;
  for (const Chain& c : chains) accepted += c.accepted, proposed += c.proposed, r.evaluations += c.evaluations;
  r.acceptance = proposed > 0 ? static_cast<double>(accepted) / static_cast<double>(proposed) : 0;
  const Eigen::Index per_chain = static_cast<Eigen::Index>(r.steps) * r.walkers;
  r.draws.resize(per_chain * r.chains, d);
  for (int c = 0; c < r.chains; ++c) {
    r.draws.middleRows(c * per_chain, per_chain) = chains[static_cast<std::size_t>(c)].kept;
    const auto& l = chains[static_cast<std::size_t>(c)].kept_log_density;
    r.log_density.insert(r.log_density.end(), l.begin(), l.end());
  }
  r.mean = r.draws.colwise().mean().transpose();
  const Eigen::MatrixXd centred = r.draws.rowwise() - r.mean.transpose();
  r.covariance = centred.transpose() * centred / static_cast<double>(r.draws.rows() - 1);
  r.sd = r.covariance.diagonal().cwiseSqrt();
  r.rhat.resize(d), r.tau.resize(d), r.effective_samples.resize(d);
  for (int k = 0; k < d; ++k) {
    std::vector<std::vector<std::vector<double>>> series(static_cast<std::size_t>(r.chains));
    double tau_sum = 0;
    for (int c = 0; c < r.chains; ++c) {
      auto& walkers = series[static_cast<std::size_t>(c)];
      walkers.assign(static_cast<std::size_t>(r.walkers), std::vector<double>(static_cast<std::size_t>(r.steps)));
      const Eigen::MatrixXd& kept = chains[static_cast<std::size_t>(c)].kept;
      for (int s = 0; s < r.steps; ++s)
        for (int w = 0; w < r.walkers; ++w)
          walkers[static_cast<std::size_t>(w)][static_cast<std::size_t>(s)] =
              kept(static_cast<Eigen::Index>(s) * r.walkers + w, k);
      tau_sum += autocorrelation_time(walkers);
    }
    r.rhat(k) = split_rhat(series);
    r.tau(k) = tau_sum / r.chains;
    r.effective_samples(k) = static_cast<double>(r.draws.rows()) / r.tau(k);
  }
  r.status = convergence_status(r, names);
  r.converged = r.status == "converged";
  return r;
}

}  // namespace beamid::fit
