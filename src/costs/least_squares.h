// The two least-squares costs on the model output itself: "time" on the samples (cost.h) and, here in detail,
// the frequency-band least-squares cost "freq-band" (the standard frequency-domain estimator: Pintelon and
// Schoukens, System Identification, ch. 2; ../shared/docs/comparison.md section 2):
//   J_B = sum_{k in band} w_k |a U(k) - Z(k)|^2,   w_k = 1 at k = 0 and k = Nbar/2, 2 elsewhere,
// over the DFT bins 0..Nbar/2 whose frequency lies in [min_frequency, max_frequency] (default: all), with U the DFT of
// the model's exact sampled response, so that leakage and the transient are modelled rather than windowed away, and
// the same window on data and model. w_k counts the conjugate bins above Nbar/2, so on the full band with the
// rectangular window J_B = J_T / Nbar (Parseval with the 1/Nbar scaling). a = 1, or with an unknown excitation
// amplitude the closed-form a = Re <U, Z>_w / <U, U>_w. Residuals: sqrt(w_k) (Re, Im) of a U(k) - Z(k).
//
// "freq-ml" is the same sum with each bin over the noise's variance there, w_k / sigma^2(k) (signal::model_bin_variance
// for the cost's noise model, rectangular window): the frequency-domain maximum-likelihood output-error cost for
// Gaussian noise whose DFT bins are uncorrelated (exactly so for circulant noise, asymptotically for AR noise in a long
// record; Pintelon and Schoukens ch. 10). With white noise it is Nbar times freq-band. "time" with a coloured noise
// model compares W y with W z, W the whitening (signal::Whitener): generalised least squares, the exact time-domain
// maximum likelihood for Gaussian noise of that colour.
#pragma once

#include <memory>
#include <vector>

#include "costs/cost.h"

namespace beamid::costs {

std::unique_ptr<Cost> make_time_cost(const CostOptions& options, std::vector<double> data);
// InputError when the band holds no bin.
std::unique_ptr<Cost> make_band_cost(const CostOptions& options, std::vector<double> data, double dt_s);

}  // namespace beamid::costs
