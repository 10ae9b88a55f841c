#include "costs/least_squares.h"

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/errors.h"
#include "signal/noise.h"

namespace beamid::costs {
namespace {

class TimeCost final : public Cost {
 public:
  // With a coloured noise model, everything is compared after the whitening W (W^T W = R^-1, signal::Whitener), so
  // that |W (a y - z)|^2 is the Gaussian negative log-likelihood's quadratic form: generalised least squares.
  TimeCost(CostOptions options, std::vector<double> data) : options_(std::move(options)), z_(std::move(data)) {
    const signal::NoiseModel noise = signal::parse_noise_model(options_.noise_model);
    if (noise.kind != "white") {
      whitener_ = std::make_unique<signal::Whitener>(noise, static_cast<Eigen::Index>(z_.size()));
      const Eigen::Map<const Eigen::VectorXd> z(z_.data(), static_cast<Eigen::Index>(z_.size()));
      const Eigen::MatrixXd zw = whitener_->apply(z);
      z_.assign(zw.data(), zw.data() + zw.size());
    }
  }
  const CostOptions& options() const override { return options_; }
  int residual_count() const override { return static_cast<int>(z_.size()); }
  const std::vector<SpikePair>& data_spikes() const override { return no_spikes_; }
  std::string weights() const override { return ""; }

  Evaluation evaluate(const ModelResponse& model) override {
    Evaluation e;
    if (auto why = unusable_output(model.y, z_.size())) {
      e.status = *why;
      return e;
    }
    const Eigen::Map<const Eigen::VectorXd> raw(model.y.data(), static_cast<Eigen::Index>(model.y.size()));
    const Eigen::VectorXd y = whitener_ ? Eigen::VectorXd(whitener_->apply(raw)) : Eigen::VectorXd(raw);
    const Eigen::Map<const Eigen::VectorXd> z(z_.data(), static_cast<Eigen::Index>(z_.size()));
    if (options_.unknown_amplitude) {
      // min_a |a y - z|^2: the response is linear in the excitation amplitude.
      const double yy = y.squaredNorm();
      e.amplitude_scale = yy > 0 ? y.dot(z) / yy : 0.0;
    }
    e.residuals = e.amplitude_scale * y - z;
    e.value = e.residuals.squaredNorm();
    return e;
  }
  bool has_output_jacobian() const override { return !options_.unknown_amplitude; }
  Eigen::MatrixXd output_jacobian(const ModelResponse&, const Eigen::MatrixXd& dy) override {
    return whitener_ ? whitener_->apply(dy) : dy;  // r = W (y - z)
  }
  std::optional<double> zero_model_value() const override {
    double sum = 0;
    for (const double z : z_) sum += z * z;
    return sum;
  }

 private:
  CostOptions options_;
  std::vector<double> z_;  // W z with a coloured noise model
  std::unique_ptr<signal::Whitener> whitener_;
  std::vector<SpikePair> no_spikes_;
};

class BandCost final : public Cost {
 public:
  // freq-ml's weights are the noise's variance through the rectangular window: it takes no other (a hybrid's
  // refinement or a study's [fit] window would otherwise reach it through the shared options).
  BandCost(CostOptions options, const std::vector<double>& data, double dt_s)
      : options_(std::move(options)),
        dft_(static_cast<int>(data.size()), dt_s,
             options_.name == kMaxLikelihoodCost ? signal::WindowOptions{} : options_.window) {
    data_ = dft_.transform(data);
    // freq-ml: each bin over its noise variance; a bin without noise (power-law noise's offset) carries no
    // likelihood term and is left out.
    const bool ml = options_.name == kMaxLikelihoodCost;
    const std::vector<double> variance =
        !ml ? std::vector<double>(static_cast<std::size_t>(data_.last_bin() + 1), 1.0)
        : options_.bin_variance.empty()
            ? signal::model_bin_variance(signal::parse_noise_model(options_.noise_model), data_.samples)
            : options_.bin_variance;
    if (variance.size() != static_cast<std::size_t>(data_.last_bin() + 1))
      throw InputError("cost freq-ml: " + std::to_string(variance.size()) + " bin variances for " +
                       std::to_string(data_.last_bin() + 1) + " bins");
    for (int k = 0; k <= data_.last_bin(); ++k) {
      const double f = data_.frequency_hz(k);
      if (f < options_.spikes.min_frequency_hz || f > options_.spikes.max_frequency_hz) continue;
      const double v = variance[static_cast<std::size_t>(k)];
      if (!(v > 0)) continue;
      bins_.push_back(k);
      const bool single = k == 0 || (data_.samples % 2 == 0 && k == data_.last_bin());
      weights_.push_back(std::sqrt((single ? 1.0 : 2.0) / v));
      // Errors in variables: the bin's multiplicity and its response noise variance, the weight per evaluation.
      counts_.push_back(single ? 1.0 : 2.0);
      response_variance_.push_back(options_.noise_sd * options_.noise_sd * v);
    }
    if (bins_.empty())
      throw InputError("cost " + options_.name + ": the band [" + format_value(options_.spikes.min_frequency_hz) +
                       ", " + format_value(options_.spikes.max_frequency_hz) +
                       "] Hz holds no DFT bin (df = " + format_value(data_.df_hz()) + " Hz, Nyquist " +
                       format_value(data_.frequency_hz(data_.last_bin())) + " Hz)");
  }
  const CostOptions& options() const override { return options_; }
  int residual_count() const override { return 2 * static_cast<int>(bins_.size()); }
  const std::vector<SpikePair>& data_spikes() const override { return no_spikes_; }
  std::string weights() const override {
    return "band " + format_value(data_.frequency_hz(bins_.front())) + ".." +
           format_value(data_.frequency_hz(bins_.back())) + " Hz, " + std::to_string(bins_.size()) + " bins" +
           (options_.name == kMaxLikelihoodCost ? ", each over its " + options_.noise_model + " noise variance" : "");
  }

  Evaluation evaluate(const ModelResponse& model) override {
    Evaluation e;
    if (model.y.size() != static_cast<std::size_t>(data_.samples)) {
      e.status = "the model gave " + std::to_string(model.y.size()) + " samples for " + std::to_string(data_.samples) +
                 " data samples";
      return e;
    }
    for (double v : model.y)
      if (!std::isfinite(v)) {
        e.status = "the model output is not finite";
        return e;
      }
    const signal::Spectrum u = dft_.transform(model.y);
    if (uses_transfer_function() && !errors_in_variables_weights(model, e)) return e;
    if (options_.unknown_amplitude) {
      // min_a sum_k w_k^2 |a U - Z|^2 over the band: a = Re <U, Z> / <U, U>.
      double uz = 0, uu = 0;
      for (std::size_t b = 0; b < bins_.size(); ++b) {
        const auto k = static_cast<std::size_t>(bins_[b]);
        const double w2 = weights_[b] * weights_[b];
        uz += w2 * std::real(std::conj(u.half[k]) * data_.half[k]);
        uu += w2 * std::norm(u.half[k]);
      }
      e.amplitude_scale = uu > 0 ? uz / uu : 0.0;
    }
    e.residuals.resize(residual_count());
    for (std::size_t b = 0; b < bins_.size(); ++b) {
      const auto k = static_cast<std::size_t>(bins_[b]);
      const std::complex<double> r = weights_[b] * (e.amplitude_scale * u.half[k] - data_.half[k]);
      e.residuals(static_cast<Eigen::Index>(2 * b)) = r.real();
      e.residuals(static_cast<Eigen::Index>(2 * b + 1)) = r.imag();
    }
    if (uses_transfer_function() && !project_out_transient(model, e)) return e;
    e.value = e.residuals.squaredNorm();
    return e;
  }

  std::optional<double> zero_model_value() const override {
    double sum = 0;
    for (std::size_t b = 0; b < bins_.size(); ++b)
      sum += weights_[b] * weights_[b] * std::norm(data_.half[static_cast<std::size_t>(bins_[b])]);
    return sum;
  }

  // With a noisy measured force u = u0 + n_u, the model driven by u leaves Y - Yhat = N_Y - (its response to n_u) +
  // (the model error at u0). Over the record that response's DFT is exactly G(z_k) N_u(k) + sum_m t_m / (1 - e_m
  // z_k^-1) (simulation/modal_simulator.h): a part whose bins are independent, of variance |G|^2 sd_F^2 / Nbar, and
  // the transient of the modal states at the record's ends, which is random (the noise's) and common to every bin.
  // Pintelon and Schoukens' errors-in-variables cost (System Identification, 2nd ed., ch. 7 and 8) weighs each bin
  // by sigma_Y^2(k) + |G(z_k)|^2 sd_F^2 / Nbar and takes the transient as free: its coefficients (one complex per
  // underdamped mode, with its conjugate's conjugate so that the transient is real, and two real for the stiff and
  // the fast modes, whose e_m ~ 0 makes their terms a constant and a z^-1 term: project_out_transient) are solved by
  // weighted linear least squares and projected out, so that what remains is independent across bins. Weighing instead
  // by the exact variance of the bins over the record, without the transient, left that common part in every bin: the
  // cost at the truth then scattered 10 times more than independent bins would (thin beam, 4096 samples) and the
  // damping estimates were as biased as output error's, in the other direction. The weights depend on the parameters:
  // no output Jacobian.
  bool uses_transfer_function() const override { return options_.force_noise_sd > 0; }
  bool has_output_jacobian() const override { return !options_.unknown_amplitude && !uses_transfer_function(); }
  // r is linear in y: d r = the band's bins of DFT(d y).
  Eigen::MatrixXd output_jacobian(const ModelResponse&, const Eigen::MatrixXd& dy) override {
    Eigen::MatrixXd dr(residual_count(), dy.cols());
    std::vector<double> column(static_cast<std::size_t>(dy.rows()));
    for (Eigen::Index c = 0; c < dy.cols(); ++c) {
      Eigen::Map<Eigen::VectorXd>(column.data(), dy.rows()) = dy.col(c);
      const signal::Spectrum du = dft_.transform(column);  // the DFT is linear: d U = DFT(d y)
      for (std::size_t b = 0; b < bins_.size(); ++b) {
        const std::complex<double> d = weights_[b] * du.half[static_cast<std::size_t>(bins_[b])];
        dr(static_cast<Eigen::Index>(2 * b), c) = d.real();
        dr(static_cast<Eigen::Index>(2 * b + 1), c) = d.imag();
      }
    }
    return dr;
  }

 private:
  CostOptions options_;
  signal::Dft dft_;
  signal::Spectrum data_;
  // The errors-in-variables weights at this evaluation's transfer function, or false with the status set.
  bool errors_in_variables_weights(const ModelResponse& model, Evaluation& e) {
    if (!model.frf || model.frf->size() != static_cast<std::size_t>(data_.last_bin() + 1)) {
      e.status = "the errors-in-variables form needs the model's transfer function (a measured force, fast)";
      return false;
    }
    const double force_variance = options_.force_noise_sd * options_.force_noise_sd / data_.samples;
    for (std::size_t b = 0; b < bins_.size(); ++b) {
      const double gain = std::norm((*model.frf)[static_cast<std::size_t>(bins_[b])]);
      weights_[b] = std::sqrt(counts_[b] / (response_variance_[b] + gain * force_variance));
    }
    return true;
  }
  // e.residuals minus their weighted least-squares fit by the transient terms (above), in place; false with the status
  // set when those terms would take up more than half of the band's residuals (a narrow band or a short record: what
  // is left would be fitted by the transient, not by the model).
  //
  // A mode whose e = exp(lambda dt) is below kFastTransient in magnitude (a heavily damped mode far above the band)
  // has the transient t (1 + e z^-1 + e^2 z^-2 + ...): within e^2 < 1e-6 of its size, a constant and a z^-1 term. All
  // such modes are taken together by two fixed columns, the constant and z^-1 (real coefficients: the samples 0 and
  // 1 of the transient), not each by its own pair. Their own columns lay within round-off of those two and of each
  // other, so that the rank the pivoted QR found, and with it the cost, jumped by a chi-square term (0.2-0.6) between
  // parameters 1e-10 apart; finite-difference Jacobians stepped across the jumps, the standard errors came out 20-160
  // times below the Cramer-Rao bound and fits stopped "converged" 12 % off (the twenty-first pass's P1). A mode kept
  // has its own pair, at least e^2 = 1e-6 of it outside the fixed columns, far above the rank threshold.
  static constexpr double kFastTransient = 1e-3;
  bool project_out_transient(const ModelResponse& model, Evaluation& e) const {
    Eigen::VectorXd& r = e.residuals;
    const auto rows = static_cast<Eigen::Index>(2 * bins_.size());
    const double dt = 1 / (data_.samples * data_.df_hz());
    std::vector<std::complex<double>> kept;  // e of the modes with their own pair of columns
    for (const std::complex<double>& pole : model.poles_rad_s)
      if (const std::complex<double> decay = std::exp(pole * dt); std::abs(decay) >= kFastTransient)
        kept.push_back(decay);
    const auto modes = static_cast<Eigen::Index>(kept.size());
    Eigen::MatrixXd basis(rows, 2 * modes + 2);
    for (std::size_t b = 0; b < bins_.size(); ++b) {
      const auto row = static_cast<Eigen::Index>(2 * b);
      const std::complex<double> z_inverse = std::polar(1.0, -2 * std::numbers::pi * bins_[b] / data_.samples);
      basis(row, 0) = weights_[b];  // the constant (real): the stiff and the fast modes' sample 0
      basis(row + 1, 0) = 0;
      basis(row, 1) = weights_[b] * z_inverse.real();  // z^-1 (real coefficient): the fast modes' sample 1
      basis(row + 1, 1) = weights_[b] * z_inverse.imag();
      for (Eigen::Index m = 0; m < modes; ++m) {
        const std::complex<double> decay = kept[static_cast<std::size_t>(m)];
        const std::complex<double> one = 1.0 / (1.0 - decay * z_inverse),
                                   other = 1.0 / (1.0 - std::conj(decay) * z_inverse);
        // t (1/(1 - e z^-1)) + conj(t) (1/(1 - conj(e) z^-1)), t = alpha + j beta: alpha (one + other) + j beta (one -
        // other).
        const std::complex<double> alpha = weights_[b] * (one + other),
                                   beta = weights_[b] * std::complex<double>(0, 1) * (one - other);
        basis(row, 2 + 2 * m) = alpha.real();
        basis(row + 1, 2 + 2 * m) = alpha.imag();
        basis(row, 3 + 2 * m) = beta.real();
        basis(row + 1, 3 + 2 * m) = beta.imag();
      }
    }
    // The projection, smooth in the parameters. Within a band the terms of modes far outside it are nearly a
    // constant and z^-1, and of each other (the band's limits left them within 1e-9 of dependent, and a rank decided
    // at a threshold flipped with round-off again: the cost scattered by 1e-6 of itself from step to step, 20 times
    // its curvature in gamma, and fits "converged" 4-11 % off: the twenty-second pass's P1). So the columns are
    // scaled to unit length and each direction of their SVD is taken out by the factor s^2 / (s^2 + mu^2), mu =
    // kSoftRank: a direction well inside the terms' span (s >> mu) wholly, one within round-off of the others (s <<
    // mu) not at all, and in between continuously; a direction's own round-off, eps / s, is then at most 1e-10.
    for (Eigen::Index c = 0; c < basis.cols(); ++c)
      if (const double norm = basis.col(c).norm(); norm > 0) basis.col(c) /= norm;
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(basis, Eigen::ComputeThinU);
    const Eigen::VectorXd& s = svd.singularValues();
    const Eigen::VectorXd along = svd.matrixU().transpose() * r;
    const double before = r.squaredNorm();
    double taken = 0;  // the terms' effective number, sum of the factors
    for (Eigen::Index i = 0; i < s.size(); ++i) {
      const double factor = s(i) * s(i) / (s(i) * s(i) + kSoftRank * kSoftRank);
      r -= factor * along(i) * svd.matrixU().col(i);
      taken += factor;
    }
    if (2 * taken > static_cast<double>(rows)) {
      e.status = "the errors-in-variables form takes out " + format_rounded(taken, 3) +
                 " transient terms (one per mode), more than half of the band's " + std::to_string(rows) +
                 " residuals: widen the band (--min-frequency, --max-frequency) or give a longer record";
      return false;
    }
    e.transient_share = before > 0 ? 1 - r.squaredNorm() / before : 0;
    return true;
  }
  static constexpr double kSoftRank = 1e-6;

  std::vector<int> bins_;
  std::vector<double> weights_;                     // sqrt(w_k)
  std::vector<double> counts_, response_variance_;  // errors in variables: w_k and sigma_Y^2(k)
  std::vector<SpikePair> no_spikes_;
};

}  // namespace

std::unique_ptr<Cost> make_time_cost(const CostOptions& options, std::vector<double> data) {
  return std::make_unique<TimeCost>(options, std::move(data));
}

std::unique_ptr<Cost> make_band_cost(const CostOptions& options, std::vector<double> data, double dt_s) {
  return std::make_unique<BandCost>(options, data, dt_s);
}

}  // namespace beamid::costs
