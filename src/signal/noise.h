// Portable pseudo-random numbers for synthetic data: the same seed gives the same noise with any C++ standard library.
//
// The engine is std::mt19937_64, whose output sequence the C++ standard fixes. Everything after it is ours, because
// the standard fixes neither std::uniform_real_distribution nor std::normal_distribution:
//   uniform  u = ((x >> 11) + 0.5) 2^-53, in the open interval (0, 1);
//   Gaussian by the Box-Muller transform on two uniforms: g1 = r cos(2 pi u2), g2 = r sin(2 pi u2), r = sqrt(-2 ln u1)
//            (both used, in that order).
// Seeds are mixed with SplitMix64 (core/hash.h) so that nearby seeds (1, 2, 3, ...) give unrelated streams.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

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
// InputError naming the text and the constraint ("noise model 'ar:1.2': not stationary (a root of ... inside the unit
// circle)"); at most 32 AR coefficients, alpha in [0, 4].
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

// add_noise with coloured noise: standard deviation `level` times the clean signal's RMS (white: add_noise exactly).
std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed,
                              const NoiseModel& model);

}  // namespace beamid::signal
