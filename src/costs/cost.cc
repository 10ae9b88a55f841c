#include "costs/cost.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "costs/least_squares.h"
#include "costs/modal_cost.h"
#include "costs/spike_costs.h"
#include "signal/noise.h"

namespace beamid::costs {
namespace {

bool all_finite(const std::vector<double>& y) {
  for (double v : y)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

Eigen::MatrixXd Cost::output_jacobian(const ModelResponse&, const Eigen::MatrixXd&) {
  throw InputError("cost " + options().name + ": no output Jacobian with these options");
}

Eigen::MatrixXd Cost::pole_jacobian(const ModelResponse&, const Eigen::MatrixXcd&) {
  throw InputError("cost " + options().name + ": no pole Jacobian");
}

std::optional<std::string> unusable_output(const std::vector<double>& y, std::size_t samples) {
  if (y.size() != samples)
    return "the model gave " + std::to_string(y.size()) + " samples for " + std::to_string(samples) + " data samples";
  if (!all_finite(y)) return "the model output is not finite";
  return std::nullopt;
}

const core::NameSet& cost_names() {
  static const core::NameSet names(
      {{kTimeCost, "least squares on the sampled time history"},
       {kSpikeCost, "the paper's DFT spike cost (3.5), as written"},
       {kSpikeSmoothCost, "sub-bin frequencies, decay rates and magnitudes of the spikes"},
       {kBandCost, "least squares on the complex DFT bins of a frequency band (the transient modelled)"},
       {kMaxLikelihoodCost, "freq-band weighted by the noise's variance at each bin (maximum likelihood)"},
       {kModalCost, "relative eigenvalue errors against the modes the matrix pencil identifies in the data"}});
  return names;
}

const core::NameSet& frequency_weight_names() {
  static const core::NameSet names(
      {{kAbsoluteWeight, "frequency errors in Hz, as the paper's (3.5) writes them"},
       {kRelativeWeight, "frequency errors as fractions of each mode's frequency"},
       {kInverseVarianceWeight, "each spike by the inverse of its frequency's Cramér-Rao variance"}});
  return names;
}

const core::NameSet& mode_weight_names() {
  static const core::NameSet names(
      {{kRelativeModeWeight, "frequency and decay-rate errors as fractions of each mode's |lambda|"},
       {kMeasuredModeWeight, "each mode's errors over its measured uncertainty (noise, drift, close poles)"}});
  return names;
}

const core::NameSet& model_pole_names() {
  static const core::NameSet names({{kDftPoles, "the 3-bin estimate on the model's own DFT, as on the data's"},
                                    {kEigenvaluePoles, "the model's eigenvalues"}});
  return names;
}

bool is_spike_cost(const std::string& name) { return name == kSpikeCost || name == kSpikeSmoothCost; }
bool is_band_cost(const std::string& name) { return name == kBandCost || name == kMaxLikelihoodCost; }
bool is_estimated_noise(const std::string& noise_model) {
  return noise_model == kEstimatedNoise || noise_model == kRepeatedNoise;
}

CostUses cost_uses(const std::string& name) {
  CostUses u;
  // freq-ml's weights are the noise's variance through the rectangular window (signal::model_bin_variance).
  u.window = is_spike_cost(name) || name == kBandCost;
  u.spike_rule = is_spike_cost(name);
  u.frequency_weight = is_spike_cost(name);
  u.model_poles = name == kSpikeSmoothCost;
  u.unknown_amplitude = name != kModalCost;
  u.mode_weight = name == kModalCost;
  u.noise_model = name == kTimeCost || name == kMaxLikelihoodCost;
  return u;
}

std::optional<std::string> validation_error(const CostOptions& o) {
  if (auto error = cost_names().violation("cost", o.name)) return error;
  if (auto error = signal::validation_error(o.spikes)) return error;
  if (auto error = signal::validation_error(o.window)) return error;
  if (auto error = frequency_weight_names().violation("frequency_weight", o.frequency_weight)) return error;
  if (auto error = signal::detrend_names().violation("detrend", o.pick_detrend)) return error;
  const std::pair<const char*, std::optional<double>> eps[] = {{"eps1", o.eps1}, {"eps2", o.eps2}, {"eps3", o.eps3}};
  // At most 1e100: a weight of 1e308 overflowed the cost to inf, which the fit then reported as a result. At least
  // 1e-100 unless 0: eps3 = 1e-300 with the other weights 0 bypassed the all-zero refusal below, and its term,
  // weighed by sqrt(eps3) = 1e-150, is zero in double precision all the same.
  for (const auto& [key, value] : eps)
    if (value && !(std::isfinite(*value) && (*value == 0 || (*value >= 1e-100 && *value <= 1e100))))
      return std::string(key) + " = " + format_value(*value) + ": must be 0 or in [1e-100, 1e100]";
  // Every term weighted 0 makes the spike cost 0 everywhere, and a fit of it "converges" at its start.
  const auto zero = [](const std::optional<double>& w) { return w && *w == 0; };
  if (is_spike_cost(o.name) && zero(o.eps1) && zero(o.eps2) && (o.name != "spike-smooth" || zero(o.eps3)))
    return std::string(o.name == "spike-smooth" ? "eps1 = eps2 = eps3 = 0" : "eps1 = eps2 = 0") +
           ": every term of the " + o.name + " cost would weigh nothing; at least one weight must be > 0";
  const std::pair<const char*, double> factors[] = {{"eps1_factor", o.eps1_factor}, {"eps2_factor", o.eps2_factor}};
  for (const auto& [key, value] : factors)
    if (!(std::isfinite(value) && value > 0))
      return std::string(key) + " = " + format_value(value) + ": must be finite and > 0";
  if (auto error = model_pole_names().violation("model_poles", o.model_poles)) return error;
  if (auto error = mode_weight_names().violation("mode_weight", o.mode_weight)) return error;
  const std::pair<const char*, double> sds[] = {{"noise_sd", o.noise_sd}, {"force_noise_sd", o.force_noise_sd}};
  // Squared, each must stay a normal double: 1e160 overflowed every bin's weight to 0 and the fit "converged" at its
  // start with cost 0; 1e-200 underflowed it (the adversarial pass's P1, P2).
  for (const auto& [key, value] : sds)
    if (!(value == 0 || (value >= 1e-150 && value <= 1e150)))
      return std::string(key) + " = " + format_value(value) + ": must be 0 or in [1e-150, 1e150]";
  if (o.force_noise_sd > 0 && !(o.noise_sd > 0))
    return "force_noise_sd = " + format_value(o.force_noise_sd) +
           ": the errors-in-variables form weighs the force's noise against the response's: give noise_sd > 0 too";
  if (o.force_noise_sd > 0 && o.name != kMaxLikelihoodCost)
    return "force_noise_sd = " + format_value(o.force_noise_sd) + ": is read by the freq-ml cost only";
  if (is_estimated_noise(o.noise_model) && o.force_noise_sd > 0)
    return "noise_model = '" + o.noise_model +
           "' with force_noise_sd: the errors-in-variables form needs the response's noise given (a model and "
           "noise_sd)";
  if (!is_estimated_noise(o.noise_model)) try {
      signal::parse_noise_model(o.noise_model);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  return std::nullopt;
}

std::unique_ptr<Cost> make_cost(const CostOptions& options, std::vector<double> data, double dt_s) {
  if (auto error = validation_error(options)) throw InputError(*error);
  if (data.size() < 8) throw InputError("data: " + std::to_string(data.size()) + " samples: at least 8 are needed");
  for (std::size_t i = 0; i < data.size(); ++i)
    if (!std::isfinite(data[i]))
      throw InputError("data: sample " + std::to_string(i) + " = " + format_value(data[i]) + ": must be finite");
  // An estimated noise model is resolved by the fit (a model for time, bin variances for freq-ml) before a cost is
  // made.
  if (is_estimated_noise(options.noise_model) && cost_uses(options.name).noise_model &&
      !(options.name == kMaxLikelihoodCost && !options.bin_variance.empty()))
    throw InputError("noise_model = '" + options.noise_model + "': a fit estimates it (from its own residuals or " +
                     "from repeated records); cost " + options.name +
                     " alone needs a model (white, ar:a1,..., power:alpha)");
  if (options.name == kTimeCost) return make_time_cost(options, std::move(data));
  if (options.name == kSpikeCost) return make_spike_cost(options, std::move(data), dt_s);
  if (options.name == kBandCost || options.name == kMaxLikelihoodCost)
    return make_band_cost(options, std::move(data), dt_s);
  if (options.name == kModalCost) return make_modal_cost(options, std::move(data), dt_s);
  if (options.name == kSpikeSmoothCost) return make_smooth_spike_cost(options, std::move(data), dt_s);
  throw std::logic_error("make_cost: cost '" + options.name + "' is in cost_names() but has no constructor");
}

}  // namespace beamid::costs
