// Free decay with an unknown initial state (a record that starts after an impact or a release): the response is
//   y(t_i) = c0 + sum_k [a_k e^{sigma_k t_i} cos(omega_k t_i) + b_k e^{sigma_k t_i} sin(omega_k t_i)]
// over the underdamped modes lambda_k = sigma_k + j omega_k of the model whose frequency lies below the Nyquist
// frequency, plus a constant c0 (a sensor offset) and, when asked, a linear trend c1 t / T (T the record's length: a
// sensor that drifts; without it a drift of 0.3 t on a 1 % noise record took the time cost's standard errors up 100x
// and mode 1 49 of its uncertainties off: the eighteenth adversarial pass's P5). The amplitudes enter linearly, so for
// given parameters they are solved in closed form by least squares against the data (Householder QR): only the physical
// parameters are left to the optimizer, and the sensor's position and quantity (displacement, velocity, acceleration:
// each multiplies a mode by a constant) do not matter. Time is counted from the first sample (t_0 = 0), which keeps the
// columns of order one.
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace beamid::simulation {

struct FreeDecayFit {
  std::vector<double> y;                          // the least-squares synthesis at t_i = i dt
  std::vector<std::complex<double>> poles_rad_s;  // the modes used (Im > 0, below Nyquist), ascending frequency
  std::vector<double> amplitudes;                 // c0, c1 (with a trend), then a_k, b_k per mode
  std::string status = "ok";                      // or why not (no mode below Nyquist, rank-deficient basis)
};

// The poles a free decay is synthesised from, as indices into `poles_rad_s`: Im > 0, finite, below the Nyquist
// frequency pi / dt, in ascending frequency (fit_free_decay's poles_rad_s, without its least squares).
std::vector<std::size_t> free_decay_pole_indices(const std::vector<std::complex<double>>& poles_rad_s, double dt_s);
// "free decay: the model has no underdamped mode below the Nyquist frequency", the status when that list is empty.
extern const char* const kNoFreeDecayMode;

// InputError for dt <= 0 or empty data.
FreeDecayFit fit_free_decay(const std::vector<std::complex<double>>& poles_rad_s, double dt_s,
                            const std::vector<double>& data, bool trend = false);

}  // namespace beamid::simulation
