// Portable pseudo-random numbers for synthetic data: the same seed gives the same noise with any C++ standard library.
//
// The engine is std::mt19937_64, whose output sequence the C++ standard fixes. Everything after it is ours, because
// the standard fixes neither std::uniform_real_distribution nor std::normal_distribution:
//   uniform  u = ((x >> 11) + 0.5) 2^-53, in the open interval (0, 1);
//   Gaussian by the Box-Muller transform on two uniforms: g1 = r cos(2 pi u2), g2 = r sin(2 pi u2), r = sqrt(-2 ln u1)
//            (both used, in that order).
// Seeds are mixed with SplitMix64 (core/hash.h) so that nearby seeds (1, 2, 3, ...) give unrelated streams.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/hash.h"

namespace beamid::signal {

// `count` independent standard normal deviates from `seed`.
std::vector<double> gaussian_deviates(std::uint64_t seed, std::size_t count);

// Root mean square of a signal (0 for an empty one).
double rms(const std::vector<double>& signal);

// z_i = y_i + level * rms(y) * g_i: white Gaussian noise whose standard deviation is `level` times the clean signal's
// RMS (level 0 returns y unchanged).
std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed);

// The colour of synthetic noise (issue 33), by name: "white"; "ar:a1,a2,..." the autoregressive process
// e_i = g_i + a1 e_{i-1} + a2 e_{i-2} + ... (stationary: every root of 1 - a1 z - a2 z^2 - ... outside the unit
// circle); "power:alpha" band-limited power-law noise, spectral density ~ 1 / f^alpha from the record's lowest bin,
// 1 / T, to the Nyquist frequency (alpha 0 white, 1 pink or flicker, 2 red or Brownian within the band).
struct NoiseModel {
  std::string kind = "white";  // white | ar | power
  std::vector<double> ar;      // a1..ap (ar)
  double alpha = 0;            // (power)
  std::string text() const;    // the name it was parsed from, canonical ("ar:0.9", "power:1")
};
// NoiseModelError (an InputError) naming the text and the constraint ("noise model 'ar:1.2': not stationary: ..."),
// the constraint alone in its `constraint` for a caller that names the flag or key itself; at most 32 AR
// coefficients, alpha in [0, 4].
struct NoiseModelError : InputError {
  NoiseModelError(const std::string& text, std::string violated)
      : InputError("noise model '" + text + "': " + violated), constraint(std::move(violated)) {}
  std::string constraint;
};
NoiseModel parse_noise_model(const std::string& text);

// `count` deviates of the model with unit variance as a process (AR: its stationary variance, sum of the squared
// impulse response, started in its stationary state by a burn-in until the impulse response is below 1e-12 of its
// peak; power: its expected variance over the band), deterministic per seed. White is gaussian_deviates itself.
std::vector<double> model_deviates(const NoiseModel& model, std::uint64_t seed, std::size_t count);

// The columns of `columns` (samples x k) whitened for the model's noise of unit process variance: W with
// W^T W = X^T R^-1 X, R the noise's correlation matrix, so that the Fisher information of a signal with sensitivities
// X in noise of process sd s is W^T W / s^2 (fit/cramer_rao.h). AR(p): exactly, the first p samples by the Cholesky
// factor of their stationary correlation and every later one by the prediction-error filter over the innovations'
// sd. Power: in the DFT (the model is circulant), each bin divided by its noise sd; the offset bin, where the model
// has no noise, is left out (it carries no information: an unknown offset). White: X itself.
Eigen::MatrixXd whiten(const NoiseModel& model, const Eigen::MatrixXd& columns);
// whiten() prepared once for records of `samples` samples (the AR head's Cholesky factor, the power law's bin scales
// and its DFT plan), for a cost that whitens every model output. Not thread-safe (it owns a DFT plan).
class Whitener {
 public:
  Whitener(NoiseModel model, Eigen::Index samples);
  ~Whitener();
  Whitener(const Whitener&) = delete;
  Whitener& operator=(const Whitener&) = delete;
  // InputError unless columns.rows() == samples.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& columns) const;
  const NoiseModel& model() const { return model_; }

 private:
  struct Plan;
  NoiseModel model_;
  Eigen::Index samples_;
  std::unique_ptr<Plan> plan_;
};

// E|N(k)|^2, k = 0..samples/2, the variance of the noise's DFT bins with the paper's scaling N(k) = (1/Nbar) sum_i
// n_i e^{-j 2 pi k i / Nbar} (signal/spectrum.h, rectangular window), for the model's noise of unit process variance in
// a record of `samples` samples: the weights of the frequency-domain maximum-likelihood cost (costs/least_squares.h).
// White: 1/Nbar. AR, with rho(l) its autocorrelation (Yule-Walker: rho(l) = sum_j a_j rho(l - j) for l >= 1):
//   E|N(k)|^2 = (1/Nbar^2) sum_{|l| < Nbar} (Nbar - |l|) rho(l) e^{-j 2 pi k l / Nbar}        (exact for the record)
// which tends to S(f_k)/Nbar, S the spectral density over the sampling rate, for a long record (the triangle is the
// Fejer kernel's smoothing of S). Power-law noise is circulant by construction, so its bins are independent with
// E|N(k)|^2 = |H_k|^2 / P exactly, and 0 at the offset bin.
std::vector<double> model_bin_variance(const NoiseModel& model, int samples);

// add_noise with coloured noise: standard deviation `level` times the clean signal's RMS (white: add_noise exactly).
std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed,
                              const NoiseModel& model);

}  // namespace beamid::signal
