// The misfit between a model response y(q) and data z, both sampled at t_i = i dt, i = 0..Nbar-1 (model.md section 4).
//
//   "time"          J_T = sum_i (a y_i - z_i)^2                      (C2 = identity; a = 1, or the closed-form
//                                                                     amplitude a = <y, z>/<y, y> when unknown)
//   "spike"         the paper's (3.5) exactly as written:
//                   J_F = sum_l eps1 |f_{k^u_l} - f_{k^z_l}|^2 + eps2 sum_{j=-n_l..N_l} (s |U(k^u_l + j)| - |Z(k^z_l +
//                   j)|)^2
//   "spike-smooth"  J_S = sum_l [eps1 (f^u_l - f^z_l)^2 + eps3 (sigma^u_l - sigma^z_l)^2
//                                + eps2 sum_j (s |U(k^z_l + j)| - |Z(k^z_l + j)|)^2]
//                   with sub-bin frequencies and decay rates from the 3-bin estimator (signal/spikes.h) on both, or
//                   the model's from its eigenvalues ("eigenvalues"), and magnitudes on the data's bins. The model
//                   peak paired with data spike l is the local maximum of |U| nearest to k^z_l, so pairs do not
//                   swap when model peaks trade heights.
//   "freq-band"     J_B = sum_{k in band} w_k |a U(k) - Z(k)|^2, least squares on the complex DFT bins of
//                   [min_frequency, max_frequency] (costs/least_squares.h); J_T / Nbar on the full band.
//   "freq-ml"       J_ML = sum_{k in band} w_k |a U(k) - Z(k)|^2 / sigma^2(k): freq-band weighted by the noise's
//                   variance at each bin, the frequency-domain maximum-likelihood (output-error) cost for Gaussian
//                   noise (costs/least_squares.h); sigma^2(k) from the noise model ("noise_model").
//   "modal"         relative errors of the model's eigenvalues against the modes the matrix pencil identifies in the
//                   data's free decay (costs/modal_cost.h).
// Data spikes k^z_l and their 20 % supports (n_l, N_l) come from the data only, once; for "spike", model spikes k^u_l
// are found by the same rule on |U| and paired with the data's in order of frequency, as in the paper. A bin outside
// 0..Nbar/2 is read from the full DFT (index modulo Nbar, |U(k)| = |U(Nbar - k)|). s = 1, or with an unknown excitation
// amplitude ("scale-free") s = sum |U||Z| / sum |U|^2 over the compared bins, the least-squares scale of the model's
// magnitudes (frequencies and decay rates do not depend on it). Default weights make every term dimensionless and of
// order one: eps1 = 1/df^2 (frequency errors in bins), eps3 = (T/(2 pi))^2 (decay-rate errors in bins, T = Nbar dt),
// eps2 = 1 / sum_l sum_j |Z(k^z_l + j)|^2. Frequency weighting across spikes ("frequency_weight") multiplies spike
// l's frequency (and decay-rate) residual by c_l, normalised so that mean_l c_l^2 = 1 (eps1 and eps3 keep their
// meaning: a uniform error costs the same under every weighting):
//   "absolute"          c_l = 1: errors in Hz, as the paper's (3.5) writes them; the highest mode dominates.
//   "relative"          c_l ~ 1 / f^z_l: errors as fractions of each mode's frequency, so that a model error that
//                       shifts every mode by the same fraction is not absorbed by the lowest modes.
//   "inverse-variance"  c_l ~ 1 / sd_l, sd_l the Cramér-Rao bound on the frequency of data spike l alone (a damped
//                       mode of the data's 3-bin frequency and decay rate, and of the amplitude that gives the data's
//                       peak magnitude through the same window): the maximum-likelihood weighting of independent
//                       modal estimates. The noise level is common to all spikes, so it cancels in the normalisation.
// Every cost is a sum of squares: value = |r|^2 with a residual vector r of
// fixed length, for Ceres. (A4) (the model shows as many spikes as the data, paired with the right ones) is checked at
// every evaluation: too few model spikes makes the cost undefined (infinite, with the reason in the status); a pairing
// in which a model spike lies nearer to another data spike than to its partner ("jumps modes") is reported but still
// evaluated.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/names.h"
#include "signal/spectrum.h"
#include "signal/spikes.h"

namespace beamid::costs {

// The costs by name (the registry every reader of a cost name uses).
inline const std::string kTimeCost = "time";
inline const std::string kSpikeCost = "spike";
inline const std::string kSpikeSmoothCost = "spike-smooth";
inline const std::string kBandCost = "freq-band";         // costs/least_squares.h
inline const std::string kModalCost = "modal";            // costs/modal_cost.h
inline const std::string kMaxLikelihoodCost = "freq-ml";  // costs/least_squares.h
const core::NameSet& cost_names();

// The noise models a fit estimates (CostOptions::noise_model; fit/noise_estimation.h): from its own residuals, or
// from repeated records of one experiment. A cost alone cannot: it takes the result (an AR model, bin variances).
inline const std::string kEstimatedNoise = "estimated";
inline const std::string kRepeatedNoise = "repeated";
bool is_estimated_noise(const std::string& noise_model);

// The spike costs' frequency weightings by name (above).
inline const std::string kAbsoluteWeight = "absolute";
inline const std::string kRelativeWeight = "relative";
inline const std::string kInverseVarianceWeight = "inverse-variance";
const core::NameSet& frequency_weight_names();

// How the modal cost weighs its modes, by name (costs/modal_cost.h).
inline const std::string kRelativeModeWeight = "relative";
inline const std::string kMeasuredModeWeight = "measured";
const core::NameSet& mode_weight_names();

// Where spike-smooth takes the model's poles from, by name.
inline const std::string kDftPoles = "dft";
inline const std::string kEigenvaluePoles = "eigenvalues";
const core::NameSet& model_pole_names();

struct CostOptions {
  std::string name = "time";                       // "time" | "spike" | "spike-smooth"
  signal::SpikeOptions spikes;                     // NM, peak rule, band, support level
  signal::WindowOptions window;                    // applied to data and model alike
  std::optional<double> eps1, eps2, eps3;          // nothing: the defaults above
  double eps1_factor = 1, eps2_factor = 1;         // multiply eps1 and eps2, given or default (a study's variants)
  bool unknown_amplitude = false;                  // time: solve a in closed form; spike costs: scale-free magnitudes
  std::string model_poles = kDftPoles;             // spike-smooth: "dft" (3-bin on U) | "eigenvalues"
  int first_free_sample = 0;                       // modal: the free decay starts here (after the excitation)
  std::string frequency_weight = kAbsoluteWeight;  // spike costs: across spikes (above)
  std::string mode_weight = kRelativeModeWeight;   // modal: its residuals' weights (costs/modal_cost.h)
  // Spike costs: the data's spikes are picked on the record less its offset ("mean") or offset and linear trend
  // ("linear", signal/spikes.h), so that their leakage into the lowest bins is not taken for a mode; the picked
  // bins' magnitudes and supports are then read from the record as it is, which the model is compared with.
  std::string pick_detrend = "none";
  // The noise the least-squares costs assume (signal/noise.h: white, ar:a1,..., power:alpha): "time" is then least
  // squares on the record prewhitened by it (generalised least squares, the time-domain maximum likelihood), and
  // "freq-ml" weighs each bin by its variance (signal::model_bin_variance). Its level does not matter: the estimate
  // depends on the noise's colour alone, and the standard errors take the level from the residuals.
  // "estimated": a fit estimates the model from the residuals of its own white-noise fit first (fit/identification.h:
  // time an AR model, freq-ml each bin's variance by the local polynomial method) and fits again with it.
  std::string noise_model = "white";
  // freq-ml: the noise's variance at each bin 0..Nbar/2 as given (a fit's estimate), in place of the model's.
  std::vector<double> bin_variance;
  // freq-ml with a measured force (its errors-in-variables form, costs/least_squares.h): the response's noise sd (its
  // process sd, in the record's units; the colour is noise_model's) and the force channel's white noise sd, N. Both 0:
  // the output-error form.
  double noise_sd = 0, force_noise_sd = 0;
};
// First violated constraint ("cost = 'x': must be one of time, spike, spike-smooth"), or nothing.
std::optional<std::string> validation_error(const CostOptions& options);
bool is_spike_cost(const std::string& name);
// The costs on the complex DFT bins of a band (freq-band, freq-ml).
bool is_band_cost(const std::string& name);
// Which of the options a cost reads, so that one it does not read is refused rather than ignored (a --window hann on
// the time cost gave the same fit as without it). The DFT costs (spike, spike-smooth, freq-band) read the window; the
// spike costs pick peaks by a rule with artefacts skipped and weigh frequencies; spike-smooth alone may take its model
// poles from the eigenvalues; every cost but modal (frequencies and decay rates only) may leave the amplitude free.
struct CostUses {
  bool window = false, spike_rule = false, frequency_weight = false, model_poles = false, unknown_amplitude = false;
  bool mode_weight = false, noise_model = false;
};
CostUses cost_uses(const std::string& name);

// What the model produced: the sampled output and, when known, its underdamped eigenvalues (rad/s).
struct ModelResponse {
  ModelResponse(const std::vector<double>& y_in, const std::vector<std::complex<double>>& poles,
                const std::vector<std::complex<double>>* transfer_function = nullptr)
      : y(y_in), poles_rad_s(poles), frf(transfer_function) {}
  const std::vector<double>& y;
  const std::vector<std::complex<double>>& poles_rad_s;
  // With a sampled force, when the cost asks for it (Cost::uses_transfer_function): the sampled system's transfer
  // function from the force's samples to the output's at the DFT bins 0..Nbar/2 (simulation::Trace::frf); else null.
  const std::vector<std::complex<double>>* frf;
};

// One data spike beside its model partner (a row of the spike table in a fit report).
struct SpikePair {
  signal::Spike data;
  double data_frequency_hz = 0;  // f^z_l: k^z df (spike) or the 3-bin estimate (spike-smooth)
  double data_decay_rate_1_s = std::numeric_limits<double>::quiet_NaN();
  bool has_model = false;
  int model_bin = -1;  // k^u_l (-1 with "eigenvalues")
  double model_frequency_hz = std::numeric_limits<double>::quiet_NaN();
  double model_decay_rate_1_s = std::numeric_limits<double>::quiet_NaN();
  double model_magnitude = std::numeric_limits<double>::quiet_NaN();  // s |U| at the compared peak bin
  bool jumps = false;                                                 // the model spike is nearer to another data spike
};

struct Evaluation {
  double value = std::numeric_limits<double>::infinity();
  Eigen::VectorXd residuals;     // value = residuals.squaredNorm() when ok
  std::string status = "ok";     // "ok", or why the cost is undefined here
  double amplitude_scale = 1;    // a (time) or s (spike costs)
  std::vector<SpikePair> pairs;  // spike costs
  std::string a4 = "ok";         // "ok" or the (A4) violation in words
  // freq-ml's errors-in-variables form: the share of the weighted residual's sum of squares its free transient terms
  // take out (least_squares.cc), NaN for every other cost. About (terms) / (residuals) when the forced response
  // explains the record; near 1 when the terms, which span every mode's free decay, fit what the force should have.
  double transient_share = std::numeric_limits<double>::quiet_NaN();
  bool ok() const { return status == "ok"; }
};

class Cost {
 public:
  virtual ~Cost() = default;
  virtual const CostOptions& options() const = 0;
  // Length of the residual vector.
  virtual int residual_count() const = 0;
  // Never throws for a finite or non-finite y: a non-finite sample gives value = inf with the status saying so.
  virtual Evaluation evaluate(const ModelResponse& model) = 0;
  // The data's spikes (empty for "time").
  virtual const std::vector<SpikePair>& data_spikes() const = 0;
  // "eps1 = ..., eps2 = ..." as used (empty for "time").
  virtual std::string weights() const = 0;
  // Whether evaluate reads the model's output y (every cost but modal, which compares eigenvalues alone): a free
  // decay's least-squares synthesis of y, a record-sized QR, is skipped for a cost that does not (fit/objective.h).
  virtual bool uses_response() const { return true; }
  // Whether evaluate reads ModelResponse::frf (freq-ml in its errors-in-variables form).
  virtual bool uses_transfer_function() const { return false; }
  // Whether output_jacobian is available: time and freq-band with a known amplitude (residuals linear in y), and
  // spike-smooth with a known amplitude and the model's poles from its DFT (by the chain rule through the 3-bin
  // estimator and the magnitudes).
  virtual bool has_output_jacobian() const { return false; }
  // d r / d q at the model output `model` (whose evaluation must be ok) from the output's sensitivities dy (samples x
  // p). The discrete choices (the model's peak bins) are held, as they are constant almost everywhere.
  virtual Eigen::MatrixXd output_jacobian(const ModelResponse& model, const Eigen::MatrixXd& dy);
  // Whether pole_jacobian is available: the costs of the model's eigenvalues alone (modal).
  virtual bool has_pole_jacobian() const { return false; }
  // d r / d q at `model` (whose evaluation must be ok) from d lambda_k / d q of its poles (poles x p, in the order of
  // model.poles_rad_s). The pairing of data and model modes is held, as it is constant almost everywhere.
  virtual Eigen::MatrixXd pole_jacobian(const ModelResponse& model, const Eigen::MatrixXcd& d_poles);
  // The value a zero model attains, for the least-squares costs (time: sum z_i^2; freq-band: sum over the band of
  // w_k |Z(k)|^2, the record's energy in the band by Parseval): the baseline a fit's explained fraction
  // 1 - J / J(0) is measured against. Nothing for the costs that compare features (spikes, modes), which have none.
  virtual std::optional<double> zero_model_value() const { return std::nullopt; }
};

// Why a model output cannot be compared with `samples` data samples (its length, a non-finite value), or nothing: the
// evaluation is then undefined, never a crash.
std::optional<std::string> unusable_output(const std::vector<double>& y, std::size_t samples);

// The cost of `options` against the data record z sampled at dt_s. InputError when the options are invalid or the
// data do not support them (fewer local maxima than spikes requested, a 3-bin estimate that fails).
std::unique_ptr<Cost> make_cost(const CostOptions& options, std::vector<double> data, double dt_s);

}  // namespace beamid::costs
