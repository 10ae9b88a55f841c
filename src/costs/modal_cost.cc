#include "costs/modal_cost.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "signal/measured_modes.h"

namespace beamid::costs {
namespace {

class ModalCost final : public Cost {
 public:
  ModalCost(CostOptions options, const std::vector<double>& data, double dt_s) : options_(std::move(options)) {
    const auto first = static_cast<std::size_t>(std::max(0, options_.first_free_sample));
    if (first >= data.size()) throw InputError("cost modal: the record ends before its free decay begins");
    const std::vector<double> decay(data.begin() + static_cast<std::ptrdiff_t>(first), data.end());
    signal::PencilOptions p;
    p.min_frequency_hz = options_.spikes.min_frequency_hz;
    p.max_frequency_hz = options_.spikes.max_frequency_hz;
    const auto& wanted = options_.spikes.frequencies_hz;
    p.modes = options_.spikes.count;
    std::vector<signal::IdentifiedMode> found;
    int heavy = 0;  // poles left out as the excitation or noise (signal::lightly_damped_modes)
    const bool measured = options_.mode_weight == kMeasuredModeWeight;
    std::vector<signal::MeasuredMode> uncertain;  // the same modes with their uncertainty, when weighted by it
    try {
      if (measured) {
        signal::MeasureOptions m;
        m.pencil = p;
        m.wanted_hz = wanted;
        m.window = options_.spikes.frequency_window;
        const signal::MeasuredModes r = signal::measure_modes(decay, dt_s, m);
        uncertain = r.modes;
        heavy = r.heavily_damped;
        for (const auto& u : uncertain) found.push_back(u.mode);
      } else {
        found = signal::lightly_damped_modes(decay, dt_s, p, wanted, options_.spikes.frequency_window, &heavy);
      }
    } catch (const InputError& e) {
      throw InputError(std::string("cost modal: ") + e.what());
    }
    if (wanted.empty() && static_cast<int>(found.size()) < options_.spikes.count)  // modes_near has one per choice
      throw InputError("cost modal: the record shows " + std::to_string(found.size()) + " decaying mode(s) in the " +
                       "band, fewer than the " + std::to_string(options_.spikes.count) + " asked for" +
                       (heavy > 0 ? " (and " + std::to_string(heavy) +
                                        " pole(s) damped beyond zeta = " + format_value(signal::kHeavilyDampedRatio) +
                                        ", the excitation or noise rather than modes)"
                                  : ""));
    // Two chosen frequencies that find one mode would count it twice, and the fit then trusts it twice over (2.46,
    // 2.46 put cDI 39 % off with a standard error of 5e-14: the fifteenth pass's P4), as beamid real refuses.
    for (std::size_t a = 0; a < found.size(); ++a)
      for (std::size_t b = a + 1; b < found.size(); ++b)
        if (found[a].lambda == found[b].lambda)
          throw InputError("cost modal: spike frequencies " +
                           (a < wanted.size() && b < wanted.size()
                                ? format_value(wanted[a]) + " and " + format_value(wanted[b]) + " Hz"
                                : std::string("two")) +
                           " find the same mode (" + format_rounded(found[a].frequency_hz, 6) +
                           " Hz): list each measured mode once");
    for (std::size_t l = 0; l < found.size(); ++l) {
      const signal::IdentifiedMode& m = found[l];
      // The residuals' divisors (costs/modal_cost.h): |lambda| for both, or the measured uncertainties, at least
      // kUncertaintyFloor |lambda| (a noise-free record's u is round-off, and the pencil is exact to ~1e-9 there).
      const double magnitude = std::abs(m.lambda);
      frequency_scale_.push_back(
          measured ? std::max(2 * std::numbers::pi * uncertain[l].uncertainty_hz, kUncertaintyFloor * magnitude)
                   : magnitude);
      decay_scale_.push_back(measured ? std::max(uncertain[l].decay_uncertainty_1_s, kUncertaintyFloor * magnitude)
                                      : magnitude);
      SpikePair pair;
      pair.data_frequency_hz = m.frequency_hz;
      pair.data_decay_rate_1_s = -m.lambda.real();
      pair.data.frequency_hz = m.frequency_hz;
      pair.data.magnitude = m.amplitude;
      pairs_.push_back(pair);
      lambda_.push_back(m.lambda);
    }
  }
  const CostOptions& options() const override { return options_; }
  int residual_count() const override { return 2 * static_cast<int>(lambda_.size()); }
  const std::vector<SpikePair>& data_spikes() const override { return pairs_; }
  std::string weights() const override {
    return options_.mode_weight == kMeasuredModeWeight
               ? "frequency and decay-rate errors over each mode's measured uncertainty (noise, drift, close poles)"
               : "relative frequency and decay-rate errors (per |lambda| of the mode)";
  }

  Evaluation evaluate(const ModelResponse& model) override {
    Evaluation e;
    e.pairs = pairs_;
    if (model.poles_rad_s.empty()) {
      e.status = "cost modal: the model gave no eigenvalues (--integrator fast computes them; cvode does not)";
      return e;
    }
    e.residuals.resize(residual_count());
    const std::vector<int> partner = partners(model);
    for (std::size_t l = 0; l < lambda_.size(); ++l) {
      const double target = std::abs(lambda_[l]);
      const std::complex<double> u = model.poles_rad_s[static_cast<std::size_t>(partner[l])];
      e.residuals(static_cast<Eigen::Index>(2 * l)) = (std::abs(u) - target) / frequency_scale_[l];
      e.residuals(static_cast<Eigen::Index>(2 * l + 1)) = (u.real() - lambda_[l].real()) / decay_scale_[l];
      e.pairs[l].has_model = true;
      e.pairs[l].model_frequency_hz = std::abs(u) / (2 * std::numbers::pi);
      e.pairs[l].model_decay_rate_1_s = -u.real();
    }
    for (std::size_t l = 0; l < lambda_.size(); ++l)
      for (std::size_t m = 0; m < l; ++m)
        if (partner[l] == partner[m]) {
          e.pairs[l].jumps = true;
          e.a4 = "(A4) two identified modes pair with one model mode (spikes " + std::to_string(m + 1) + " and " +
                 std::to_string(l + 1) + ")";
        }
    e.value = e.residuals.squaredNorm();
    return e;
  }
  bool uses_response() const override { return false; }
  bool has_pole_jacobian() const override { return true; }
  Eigen::MatrixXd pole_jacobian(const ModelResponse& model, const Eigen::MatrixXcd& d_poles) override {
    // r_2l = (|u| - |z|)/s_f and r_2l+1 = (Re u - Re z)/s_d for the partner u of data mode z (s the divisors):
    // d|u| = Re(conj(u) du)/|u|.
    if (d_poles.rows() != static_cast<Eigen::Index>(model.poles_rad_s.size()))
      throw InputError("cost modal: " + std::to_string(d_poles.rows()) + " pole derivatives for " +
                       std::to_string(model.poles_rad_s.size()) + " poles");
    const std::vector<int> partner = partners(model);
    Eigen::MatrixXd j(residual_count(), d_poles.cols());
    for (std::size_t l = 0; l < lambda_.size(); ++l) {
      const std::complex<double> u = model.poles_rad_s[static_cast<std::size_t>(partner[l])];
      for (Eigen::Index q = 0; q < d_poles.cols(); ++q) {
        const std::complex<double> du = d_poles(partner[l], q);
        j(static_cast<Eigen::Index>(2 * l), q) = (std::conj(u) * du).real() / std::abs(u) / frequency_scale_[l];
        j(static_cast<Eigen::Index>(2 * l + 1), q) = du.real() / decay_scale_[l];
      }
    }
    return j;
  }

 private:
  // For each data mode, the model pole nearest to it in natural frequency (pairing by frequency, not by rank).
  std::vector<int> partners(const ModelResponse& model) const {
    std::vector<int> partner(lambda_.size());
    for (std::size_t l = 0; l < lambda_.size(); ++l) {
      const double target = std::abs(lambda_[l]);
      std::size_t best = 0;
      for (std::size_t k = 1; k < model.poles_rad_s.size(); ++k)
        if (std::abs(std::abs(model.poles_rad_s[k]) - target) < std::abs(std::abs(model.poles_rad_s[best]) - target))
          best = k;
      partner[l] = static_cast<int>(best);
    }
    return partner;
  }

  CostOptions options_;
  std::vector<SpikePair> pairs_;
  std::vector<std::complex<double>> lambda_;
  std::vector<double> frequency_scale_, decay_scale_;  // the residuals' divisors per mode, rad/s and 1/s
};

}  // namespace

std::unique_ptr<Cost> make_modal_cost(const CostOptions& options, std::vector<double> data, double dt_s) {
  return std::make_unique<ModalCost>(options, data, dt_s);
}

}  // namespace beamid::costs
