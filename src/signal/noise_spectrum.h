// The noise's variance at each DFT bin, E|N(k)|^2 with the paper's scaling N(k) = (1/Nbar) sum_i n_i e^{-j 2 pi k i
// / Nbar} (signal/spectrum.h), rectangular window: the weights of the frequency-domain maximum-likelihood cost
// "freq-ml" (costs/least_squares.h; Pintelon and Schoukens, System Identification, 2nd ed., ch. 7 and 10), either
// given as a model of the noise or estimated from the record itself (issue 33).
//
// From a model: signal::model_bin_variance (signal/noise.h).
//
// From one record by the local polynomial method (LPM; Pintelon, Schoukens, Vandersteen and Barbé, "Estimation of
// nonparametric noise and FRF models for multivariable systems", MSSP 24 (2010) 573-595), output only: around bin k
// the record's DFT over the 2n + 1 bins k + r, |r| <= n, is fitted by a complex polynomial of degree R in r, which
// takes up the response and the transient where they are smooth on the scale of 2n + 1 bins; the residual e gives
//   sigma^2(k) = |e|^2 / q,   q = 2n + 1 - (R + 1) complex degrees of freedom,
// unbiased for noise whose variance is constant over the window and whose bins are uncorrelated (white or smooth
// coloured noise in a long record): q sigma^2(k) / E|N(k)|^2 is then chi-square with 2q real degrees of freedom over 2,
// so its relative sd is 1/sqrt(q). Windows stay inside bins 1..Nbar/2 - 1 (the offset and Nyquist bins are real, and
// bins beyond them are conjugates of bins inside), shifted at the edges. The estimates are then averaged over the
// 2m + 1 estimates centred on k (m = smoothing_half_width), because a weight estimated with few degrees of freedom
// costs a weighted fit efficiency: the noise spectrum is smooth where the response need not be. The resonance peaks
// are where the response is least polynomial: a mode whose half-power band spans fewer bins than the window leaves
// part of itself in e, so the LPM overestimates the noise there (say why, and how much, where it is used).
//
// From M >= 2 repeated records of one experiment (the same excitation, sensor, length and rate: M taps of one beam
// with a repeatable exciter, or M periods of a steady state): the records differ by their noise alone, so around the
// mean Zbar(k) = (1/M) sum_m Z_m(k)
//   sigma^2(k) = sum_m |Z_m(k) - Zbar(k)|^2 / (M - 1),   M - 1 complex degrees of freedom,
// unbiased whatever the response and the transient (Pintelon and Schoukens, ch. 2.4 and 7.2), with nothing of the
// model in it: no resonance leaks in and no model error is taken for noise, unlike an estimate from a fit's
// residuals. (M - 1) sigma^2(k) / E|N(k)|^2 is chi-square with 2 (M - 1) real degrees of freedom over 2, so with few
// records each bin's estimate is rough (relative sd 1/sqrt(M - 1)); it is averaged over 2m + 1 neighbouring bins as
// the LPM's is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "signal/noise.h"
#include "signal/spectrum.h"

namespace beamid::signal {

struct LocalPolynomialOptions {
  int degree = 2;                 // R
  int half_width = 6;             // n: 2n + 1 bins per local fit
  int smoothing_half_width = 10;  // m: the estimates averaged over 2m + 1 neighbouring bins (0: none)
};
// First violated constraint, or nothing: degree >= 0, 2n + 1 > R + 1 (at least one degree of freedom), m >= 0.
std::optional<std::string> validation_error(const LocalPolynomialOptions& options);

struct BinVariance {
  std::vector<double> variance;  // E|N(k)|^2 estimated, k = 0..Nbar/2
  int dof = 0;                   // q, complex degrees of freedom of each local fit (before smoothing)
};
// InputError when the options are invalid or the record has fewer bins inside 1..Nbar/2 - 1 than one local fit needs.
// The offset and Nyquist bins take their nearest neighbour's estimate.
BinVariance local_polynomial_variance(const Spectrum& record, const LocalPolynomialOptions& options);

// The repeated-record estimate above, averaged over 2 smoothing_half_width + 1 bins (0: none; the offset and Nyquist
// bins are averaged like the others). dof: M - 1 (before smoothing). InputError for fewer than 2 records, records of
// different lengths or time steps, or a negative smoothing half width.
BinVariance repeated_record_variance(const std::vector<Spectrum>& records, int smoothing_half_width);

// The autoregressive model of a noise record e (a fit's residuals): Yule-Walker by the Levinson-Durbin recursion on
// the biased sample autocorrelation (so the model is stationary), of the order p <= max_order that minimises Akaike's
// criterion n ln(sigma_p^2) + 2 p, sigma_p^2 the order-p prediction-error variance (Brockwell and Davis, Introduction
// to Time Series and Forecasting, 5.1 and 5.5). Order 0 is "white". InputError for fewer than 8 samples or a
// max_order outside 0..32; a record of zeros is white.
NoiseModel fit_autoregressive(const std::vector<double>& e, int max_order);
// The model's power in each DFT bin k = 0..samples/2 over its average: samples E|N(k)|^2 of model_bin_variance for
// unit process variance (1 in every bin for white noise). Where it exceeds 1, the noise is stronger than white noise
// of its variance; the standard errors and detection thresholds that take it as white understate it there.
std::vector<double> power_excess(const NoiseModel& model, int samples);
// Beyond this excess in some bin a fit's residual is called coloured (fit notes, the record's modes in fit reports):
// the standard error of what the record holds there is then about sqrt(1.5) = 1.22 times what white noise gives.
inline constexpr double kColouredExcess = 1.5;
// The excess an AR(p) model of m samples of white noise stays under: its log spectrum's sd is about sqrt(4 p / m) at
// 0 Hz and Nyquist (sqrt(2 p / m) between; Berk 1974), so three of those, or kColouredExcess where that is more. (At
// 64-256 samples Akaike's order 1-4 of white residuals put 1.5 times the power somewhere on 14 in 40 to 4 in 40
// records: the thirtieth pass's adv69 P3.)
double coloured_excess_threshold(int order, int samples);
// power_excess of `model` for `samples` samples, its largest bin above the offset, and whether that exceeds
// coloured_excess_threshold at the model's order (never for white noise): the one test of colour the fit notes and
// the fit reports share.
struct ColourExcess {
  std::vector<double> by_bin;  // power_excess
  std::size_t peak_bin = 0;
  bool coloured = false;
};
ColourExcess colour_excess(const NoiseModel& model, int samples);
// The same from several records of one process (the deviations of repeated records from their mean): one mean over
// all samples removed, the lag products summed over the records (none across a record's ends) over the total count, n
// in Akaike's criterion the total count, the order at most the shortest record's length / 4. InputError for no records
// or a record of fewer than 8 samples.
NoiseModel fit_autoregressive(const std::vector<std::vector<double>>& records, int max_order);

}  // namespace beamid::signal
