// The paper's spike cost (3.5) and the smooth spike cost (costs/cost.h states both), on one shared base: the data's
// spectrum, its spikes and supports, and the weights across spikes.
#include "costs/spike_costs.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/errors.h"

namespace beamid::costs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Shared by the two spike costs: the data spectrum, its spikes and supports, and the weights.
class SpikeCostBase : public Cost {
 public:
  SpikeCostBase(CostOptions options, std::vector<double> data, double dt_s)
      : options_(std::move(options)),
        samples_(data.size()),
        dft_(static_cast<int>(data.size()), dt_s, options_.window) {
    data_ = dft_.transform(data);
    auto spikes = signal::detect_spikes(options_.pick_detrend == signal::kDetrendNone
                                            ? data_
                                            : dft_.transform(signal::detrend(data, options_.pick_detrend)),
                                        options_.spikes);
    for (signal::Spike& s : spikes) {  // picked on the detrended record, read on the record
      s.magnitude = data_.magnitude(s.bin);
      std::tie(s.n_left, s.n_right) = signal::support(data_, s.bin, options_.spikes.support_level);
    }
    if (static_cast<int>(spikes.size()) < options_.spikes.count && !options_.spikes.frequencies_hz.empty())
      throw InputError("cost " + options_.name +
                       ": chosen spike frequencies: " + signal::unmatched_frequencies(spikes, options_.spikes, data_));
    if (static_cast<int>(spikes.size()) < options_.spikes.count)
      throw InputError("cost " + options_.name + ": spikes = " + std::to_string(options_.spikes.count) +
                       ": the data spectrum has only " + std::to_string(spikes.size()) +
                       " local maxima under the peak rule and band");
    const bool smooth = options_.name == kSpikeSmoothCost;
    double support_energy = 0;
    for (const auto& s : spikes) {
      SpikePair p;
      p.data = s;
      p.data_frequency_hz = s.frequency_hz;
      if (smooth) {
        const auto pole = signal::three_bin_estimate(data_, s.bin);
        if (!pole.ok)
          throw InputError("cost spike-smooth: the 3-bin estimate fails at the data spike of bin " +
                           std::to_string(s.bin));
        p.data_frequency_hz = pole.frequency_hz;
        p.data_decay_rate_1_s = pole.decay_rate_1_s;
      }
      for (int j = -s.n_left; j <= s.n_right; ++j) support_energy += std::norm(data_.at(s.bin + j));
      compared_bins_ += s.n_left + s.n_right + 1;
      pairs_.push_back(p);
    }
    const double df = data_.df_hz();
    const double record_s = static_cast<double>(samples_) * dt_s;
    eps1_ = options_.eps1_factor * options_.eps1.value_or(1.0 / (df * df));
    eps2_ = options_.eps2_factor * options_.eps2.value_or(support_energy > 0 ? 1.0 / support_energy : 1.0);
    eps3_ = options_.eps3.value_or(std::pow(record_s / (2 * std::numbers::pi), 2));
    frequency_factors_ = spike_factors(dt_s);
  }

  const CostOptions& options() const override { return options_; }
  const std::vector<SpikePair>& data_spikes() const override { return pairs_; }
  std::string weights() const override {
    std::ostringstream out;
    out.precision(6);
    out << "eps1 = " << eps1_ << " 1/Hz^2, eps2 = " << eps2_ << " 1/(signal unit)^2";
    if (options_.name == kSpikeSmoothCost) out << ", eps3 = " << eps3_ << " s^2";
    out << ", frequency weight " << options_.frequency_weight;
    if (options_.frequency_weight != kAbsoluteWeight) {
      out << " (c_l =";
      for (double c : frequency_factors_) out << " " << c;
      out << ")";
    }
    return out.str();
  }

 protected:
  // Least-squares scale of the model magnitudes against the data's on the compared bins (1 unless scale-free).
  double magnitude_scale(const signal::Spectrum& u, const std::vector<int>& model_centres) const {
    if (!options_.unknown_amplitude) return 1.0;
    double uz = 0, uu = 0;
    for (std::size_t l = 0; l < pairs_.size(); ++l)
      for (int j = -pairs_[l].data.n_left; j <= pairs_[l].data.n_right; ++j) {
        const double mu = u.magnitude(model_centres[l] + j);
        uz += mu * data_.magnitude(pairs_[l].data.bin + j);
        uu += mu * mu;
      }
    return uu > 0 ? uz / uu : 0.0;
  }

  // Model spikes by the data's rule, or the (A4) violation.
  std::optional<std::vector<signal::Spike>> model_spikes(const signal::Spectrum& u, Evaluation& e) const {
    if (!options_.spikes.frequencies_hz.empty()) {
      // Chosen spikes are paired by frequency: the model's spike for data spike l is the local maximum of |U|
      // nearest to k^z_l (however far: a model far off still has its modes, and the frequency term says how far).
      const auto maxima = signal::local_maxima(u);
      std::vector<signal::Spike> spikes;
      for (const auto& p : pairs_) {
        int best = -1;
        for (int k : maxima)
          if (best < 0 || std::abs(k - p.data.bin) < std::abs(best - p.data.bin)) best = k;
        if (best < 0) break;
        signal::Spike m;
        m.bin = best;
        m.frequency_hz = u.frequency_hz(best);
        m.magnitude = u.magnitude(best);
        spikes.push_back(m);
      }
      if (spikes.size() == pairs_.size()) return spikes;
    }
    auto spikes = signal::detect_spikes(u, options_.spikes);
    if (spikes.size() < pairs_.size()) {
      e.status = e.a4 = "(A4) violated: the model spectrum shows " + std::to_string(spikes.size()) +
                        " spikes, the data " + std::to_string(pairs_.size());
      return std::nullopt;
    }
    return spikes;
  }

  // The model's spectrum with the evaluation's pairs initialised, or nothing (with the status) when the model output
  // cannot be compared.
  std::optional<signal::Spectrum> model_spectrum(const ModelResponse& model, Evaluation& e) {
    e.pairs = pairs_;
    if (auto why = unusable_output(model.y, samples_)) {
      e.status = *why;
      return std::nullopt;
    }
    return dft_.transform(model.y);
  }

  // Marks pairs whose model frequency is nearer to another data spike than to its partner.
  static void check_pairing(Evaluation& e) {
    for (std::size_t l = 0; l < e.pairs.size(); ++l) {
      const double f = e.pairs[l].model_frequency_hz;
      const double own = std::abs(f - e.pairs[l].data_frequency_hz);
      for (std::size_t m = 0; m < e.pairs.size(); ++m)
        if (m != l && std::abs(f - e.pairs[m].data_frequency_hz) < own) e.pairs[l].jumps = true;
    }
    report_jumps(e, "(A4) pairing jumps modes at spike(s) ");
  }

  // e.a4 = prefix + the 1-based numbers of the pairs marked as jumping, when there are any.
  static void report_jumps(Evaluation& e, const std::string& prefix) {
    std::string jumped;
    for (std::size_t l = 0; l < e.pairs.size(); ++l)
      if (e.pairs[l].jumps) jumped += (jumped.empty() ? "" : ", ") + std::to_string(l + 1);
    if (!jumped.empty()) e.a4 = prefix + jumped;
  }

  void append_magnitudes(const signal::Spectrum& u, const std::vector<int>& model_centres, Evaluation& e,
                         Eigen::Index& row) const {
    const double w = std::sqrt(eps2_);
    for (std::size_t l = 0; l < pairs_.size(); ++l) {
      const auto& s = pairs_[l].data;
      for (int j = -s.n_left; j <= s.n_right; ++j)
        e.residuals(row++) = w * (e.amplitude_scale * u.magnitude(model_centres[l] + j) - data_.magnitude(s.bin + j));
      e.pairs[l].model_magnitude = e.amplitude_scale * u.magnitude(model_centres[l]);
    }
  }

  // The weighting factors c_l of the data spikes (cost.h), mean square 1.
  std::vector<double> spike_factors(double dt_s) {
    std::vector<double> c(pairs_.size(), 1.0);
    if (options_.frequency_weight == kRelativeWeight)
      for (std::size_t l = 0; l < pairs_.size(); ++l) c[l] = 1.0 / pairs_[l].data_frequency_hz;
    if (options_.frequency_weight == kInverseVarianceWeight)
      for (std::size_t l = 0; l < pairs_.size(); ++l) c[l] = 1.0 / spike_frequency_sd(pairs_[l].data, dt_s);
    double mean_square = 0;
    for (double v : c) mean_square += v * v / static_cast<double>(c.size());
    for (double& v : c) v /= std::sqrt(mean_square);
    return c;
  }

  // The bound on data spike s's frequency for unit noise (cost.h, "inverse-variance"): the spike's own 3-bin pole
  // (the exponential window's added decay removed) and the amplitude A = |Z(k)| / |W(k)|, W the DFT of the unit mode
  // e^{-alpha t} cos(2 pi f t) through the same window.
  double spike_frequency_sd(const signal::Spike& s, double dt_s) {
    const auto pole = signal::three_bin_estimate(data_, s.bin);
    if (!pole.ok)
      throw InputError("cost " + options_.name + ": frequency_weight = '" + kInverseVarianceWeight +
                       "': the 3-bin estimate fails at the data spike of bin " + std::to_string(s.bin));
    const double record_s = static_cast<double>(samples_) * dt_s;
    const double added = signal::window_decay_rate(options_.window, record_s);
    const double decay = std::max(0.0, pole.decay_rate_1_s - added);
    std::vector<double> unit(samples_);
    for (std::size_t i = 0; i < samples_; ++i) {
      const double t = static_cast<double>(i) * dt_s;
      unit[i] = std::exp(-decay * t) * std::cos(2 * std::numbers::pi * pole.frequency_hz * t);
    }
    const double amplitude = data_.magnitude(s.bin) / dft_.transform(unit).magnitude(s.bin);
    const double sd = signal::damped_mode_frequency_sd(amplitude, decay, dt_s, static_cast<int>(samples_), 1.0);
    if (!(std::isfinite(sd) && sd > 0))
      throw InputError("cost " + options_.name + ": frequency_weight = '" + kInverseVarianceWeight +
                       "': the data spike of bin " + std::to_string(s.bin) + " has no finite frequency bound");
    return sd;
  }

  CostOptions options_;
  std::size_t samples_;
  signal::Dft dft_;
  signal::Spectrum data_;
  std::vector<SpikePair> pairs_;
  int compared_bins_ = 0;
  double eps1_ = 1, eps2_ = 1, eps3_ = 1;
  std::vector<double> frequency_factors_;  // c_l
};

class SpikeCost final : public SpikeCostBase {
 public:
  using SpikeCostBase::SpikeCostBase;
  int residual_count() const override { return static_cast<int>(pairs_.size()) + compared_bins_; }

  Evaluation evaluate(const ModelResponse& model) override {
    Evaluation e;
    const auto spectrum = model_spectrum(model, e);
    if (!spectrum) return e;
    const signal::Spectrum& u = *spectrum;
    const auto spikes = model_spikes(u, e);
    if (!spikes) return e;
    std::vector<int> centres;
    for (std::size_t l = 0; l < pairs_.size(); ++l) {
      const auto& s = (*spikes)[l];
      centres.push_back(s.bin);
      e.pairs[l].has_model = true;
      e.pairs[l].model_bin = s.bin;
      e.pairs[l].model_frequency_hz = s.frequency_hz;
    }
    check_pairing(e);
    e.amplitude_scale = magnitude_scale(u, centres);
    e.residuals.resize(residual_count());
    Eigen::Index row = 0;
    const double w = std::sqrt(eps1_);
    for (std::size_t l = 0; l < pairs_.size(); ++l)
      e.residuals(row++) = w * frequency_factors_[l] * (e.pairs[l].model_frequency_hz - pairs_[l].data.frequency_hz);
    append_magnitudes(u, centres, e, row);  // |U(k^u_l + j)| against |Z(k^z_l + j)|
    e.value = e.residuals.squaredNorm();
    return e;
  }
};

class SmoothSpikeCost final : public SpikeCostBase {
 public:
  using SpikeCostBase::SpikeCostBase;
  int residual_count() const override { return 2 * static_cast<int>(pairs_.size()) + compared_bins_; }

  Evaluation evaluate(const ModelResponse& model) override {
    Evaluation e;
    const auto spectrum = model_spectrum(model, e);
    if (!spectrum) return e;
    const signal::Spectrum& u = *spectrum;
    if (options_.model_poles == kEigenvaluePoles) {
      if (!poles_from_eigenvalues(model.poles_rad_s, u, e)) return e;
    } else {
      const std::vector<int> maxima = signal::local_maxima(u);
      if (maxima.empty()) {
        e.status = e.a4 = "(A4) violated: the model spectrum has no local maximum";
        return e;
      }
      for (std::size_t l = 0; l < pairs_.size(); ++l) {
        const int bin = partner_bin(u, maxima, pairs_[l].data);
        const auto pole = signal::three_bin_estimate(u, bin);
        if (!pole.ok) {
          e.status = "the 3-bin estimate fails at model spike bin " + std::to_string(bin);
          return e;
        }
        e.pairs[l].has_model = true;
        e.pairs[l].model_bin = bin;
        e.pairs[l].model_frequency_hz = pole.frequency_hz;
        e.pairs[l].model_decay_rate_1_s = pole.decay_rate_1_s;
      }
      check_pairing(e);
    }
    // Magnitudes on the data's own bins k^z_l + j: no re-indexing, so no staircase.
    std::vector<int> centres;
    for (const auto& p : pairs_) centres.push_back(p.data.bin);
    e.amplitude_scale = magnitude_scale(u, centres);
    e.residuals.resize(residual_count());
    Eigen::Index row = 0;
    for (std::size_t l = 0; l < pairs_.size(); ++l) {
      const double c = frequency_factors_[l];
      e.residuals(row++) = std::sqrt(eps1_) * c * (e.pairs[l].model_frequency_hz - pairs_[l].data_frequency_hz);
      e.residuals(row++) = std::sqrt(eps3_) * c * (e.pairs[l].model_decay_rate_1_s - pairs_[l].data_decay_rate_1_s);
    }
    append_magnitudes(u, centres, e, row);
    e.value = e.residuals.squaredNorm();
    return e;
  }

  bool has_output_jacobian() const override { return !options_.unknown_amplitude && options_.model_poles == kDftPoles; }
  // The chain rule through the DFT (linear), the 3-bin estimator at the model's peak bins (held fixed) and the
  // magnitudes, d|U| = Re(conj(U) dU) / |U|.
  Eigen::MatrixXd output_jacobian(const ModelResponse& model, const Eigen::MatrixXd& dy) override {
    const signal::Spectrum u = dft_.transform(model.y);
    const std::vector<int> maxima = signal::local_maxima(u);
    std::vector<int> bins;
    for (const auto& pair : pairs_) bins.push_back(partner_bin(u, maxima, pair.data));
    Eigen::MatrixXd dr(residual_count(), dy.cols());
    std::vector<double> column(static_cast<std::size_t>(dy.rows()));
    for (Eigen::Index q = 0; q < dy.cols(); ++q) {
      Eigen::Map<Eigen::VectorXd>(column.data(), dy.rows()) = dy.col(q);
      const signal::Spectrum du = dft_.transform(column);
      Eigen::Index row = 0;
      for (std::size_t l = 0; l < pairs_.size(); ++l) {
        const signal::PoleEstimate change = signal::three_bin_change(u, du, bins[l]);
        dr(row++, q) = std::sqrt(eps1_) * frequency_factors_[l] * change.frequency_hz;
        dr(row++, q) = std::sqrt(eps3_) * frequency_factors_[l] * change.decay_rate_1_s;
      }
      for (const auto& pair : pairs_)
        for (int j = -pair.data.n_left; j <= pair.data.n_right; ++j) {
          const std::complex<double> value = u.at(pair.data.bin + j);
          const double size = std::abs(value);
          dr(row++, q) =
              size > 0 ? std::sqrt(eps2_) * std::real(std::conj(value) * du.at(pair.data.bin + j)) / size : 0;
        }
    }
    return dr;
  }

 private:
  // The model's partner of a data spike: the local maximum of |U| nearest to the data spike's bin (the higher one on
  // a tie). Unlike ranking the model's own NM largest maxima, this does not re-pair when two model peaks trade
  // places in height, so the cost stays continuous while the model peak moves.
  static int partner_bin(const signal::Spectrum& u, const std::vector<int>& maxima, const signal::Spike& d) {
    int best = -1;
    for (int k : maxima) {
      const int distance = std::abs(k - d.bin), best_distance = best < 0 ? 0 : std::abs(best - d.bin);
      if (best < 0 || distance < best_distance || (distance == best_distance && u.magnitude(k) > u.magnitude(best)))
        best = k;
    }
    return best;
  }

  // Each data spike takes the model pole whose frequency, aliased into [0, fs/2], is nearest to it; the decay rate
  // gets the exponential window's added alpha/T, which the data's 3-bin estimate contains too.
  bool poles_from_eigenvalues(const std::vector<std::complex<double>>& poles, const signal::Spectrum& u,
                              Evaluation& e) const {
    if (poles.empty()) {
      e.status = "model_poles = 'eigenvalues': the model response carries no eigenvalues";
      return false;
    }
    const double fs = 1.0 / u.dt_s;
    const double record_s = u.samples * u.dt_s;
    const double added = signal::window_decay_rate(options_.window, record_s);
    std::vector<int> chosen;
    for (std::size_t l = 0; l < pairs_.size(); ++l) {
      int best = -1;
      double best_distance = kInf, best_f = 0;
      for (std::size_t k = 0; k < poles.size(); ++k) {
        double f = std::fmod(poles[k].imag() / (2 * std::numbers::pi), fs);
        if (f > fs / 2) f = fs - f;
        const double d = std::abs(f - pairs_[l].data_frequency_hz);
        if (d < best_distance) best_distance = d, best = static_cast<int>(k), best_f = f;
      }
      for (int c : chosen)
        if (c == best) e.pairs[l].jumps = true;
      chosen.push_back(best);
      e.pairs[l].has_model = true;
      e.pairs[l].model_frequency_hz = best_f;
      e.pairs[l].model_decay_rate_1_s = -poles[static_cast<std::size_t>(best)].real() + added;
    }
    report_jumps(e, "(A4) two data spikes take the same model mode at spike(s) ");
    return true;
  }
};

}  // namespace

std::unique_ptr<Cost> make_spike_cost(const CostOptions& options, std::vector<double> data, double dt_s) {
  return std::make_unique<SpikeCost>(options, std::move(data), dt_s);
}

std::unique_ptr<Cost> make_smooth_spike_cost(const CostOptions& options, std::vector<double> data, double dt_s) {
  return std::make_unique<SmoothSpikeCost>(options, std::move(data), dt_s);
}

}  // namespace beamid::costs
