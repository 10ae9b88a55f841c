// A sensor's finite bandwidth (issue 35: a truth measured as a real channel is, through an anti-alias filter before
// sampling): an order-n Butterworth low-pass of cut-off f_c, whose analog magnitude is
//   |H(j 2 pi f)|^2 = 1 / (1 + (f / f_c)^(2n)),
// with the analog filter's phase lag (n = 4: pi rad at f_c, about 2.61 f / f_c rad well below it, a delay of
// 0.42 / f_c s that a model without the filter reads as a stiffness and damping error). It is realised on a record
// sampled R times faster than the one it delivers, by the bilinear transform with the frequency prewarped at f_c (exact
// there; below f_c the digital response follows the analog one to about (pi f / (R f_s))^2 / 3 in frequency), in
// second-order sections with their zeros at Nyquist, started in the steady state of what the sensor measured before
// t = 0 (the beam at rest, or a displacement held at a pluck's static deflection); then every R-th sample is kept.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <vector>

namespace beamid::signal {

struct SensorFilter {
  double cutoff_hz = 0;   // f_c; 0: no filter
  int order = 4;          // n, 1..8
  int oversampling = 16;  // R: the filter runs at R times the record's rate
};
// First violated constraint, or nothing: f_c >= 0, order 1..8, oversampling 2..64, and f_c below a quarter of the
// fine rate's Nyquist frequency (R f_s / 8), where the bilinear transform follows the analog filter.
std::optional<std::string> validation_error(const SensorFilter& filter, double dt_s);

// The filtered record of `fine` (sampled at dt_s / R), every R-th sample kept: fine.size() / R samples. The filter
// starts in the steady state of a constant input `level_before`, what the sensor saw before t = 0 (the first sample
// when not given: a displacement held at a pluck's static deflection, or a beam at rest; a velocity or an
// acceleration is 0 before a release or a force, whatever its first sample). InputError for an invalid filter or a
// fine record whose length is not a multiple of R.
std::vector<double> sense(const SensorFilter& filter, const std::vector<double>& fine, double dt_s,
                          std::optional<double> level_before = std::nullopt);

// The filter on its fine grid (dt_s / oversampling) as one linear system of order `order`, the sections in cascade
// (each in direct form II transposed, a first-order one with one state):
//   s_{i+1} = A s_i + B x_i,  y_i = C s_i + D x_i,
// with unit gain at DC, C (I - A)^-1 B + D = 1. sense() runs the same recursion section by section; this form lets a
// closed-form response carry the filter through a sum of exponentials (simulation/output_filter.h). An identity (order
// 0, D = 1) for a cut-off of 0. InputError for an invalid filter.
struct FilterStateSpace {
  Eigen::MatrixXd a;
  Eigen::VectorXd b, c;
  double d = 1;
};
FilterStateSpace state_space(const SensorFilter& filter, double dt_s);

// The digital filter's response at f (Hz) on the fine grid (for checks against the analog magnitude).
std::complex<double> sensor_response(const SensorFilter& filter, double dt_s, double frequency_hz);

}  // namespace beamid::signal
