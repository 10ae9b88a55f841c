// The noise model a fit estimates for the costs that weigh by it (time prewhitened, freq-ml: costs/least_squares.h),
// issue 33 item 1. fit::fit (fit/identification.h) runs these when CostOptions::noise_model names one:
//   "estimated" (costs::kEstimatedNoise): from the residuals of the fit's own white-noise fit, record by record;
//   "repeated"  (costs::kRepeatedNoise): from M >= 2 repeats of one experiment (the records of a joint fit, M taps of
//               one beam with a repeatable exciter), by their deviations from their mean, before any fit.
// Either way the time cost takes an AR model (Yule-Walker, order <= 20 by Akaike's criterion: signal/noise_spectrum.h)
// and freq-ml each bin's variance (the local polynomial method on a residual's DFT, or the repeats' sample variance),
// scaled to unit process variance: the colour, not the level, which the records' weights set.
//
// Which to use: the repeated estimate holds nothing of the model, so no model error is taken for noise and no
// resonance leaks in, but it needs repeats; the residual estimate needs one record, and takes for noise whatever the
// model does not explain.
#pragma once

#include <vector>

#include "fit/identification.h"

namespace beamid::fit {

// The highest AR order an estimated time-domain noise model may take.
inline constexpr int kEstimatedArOrder = 20;
// The bins a repeated-record variance is averaged over on each side (signal::repeated_record_variance): 2 x 10 + 1 = 21
// bins, as the local polynomial estimate's smoothing, so that two repeats give about 21 complex degrees of freedom.
inline constexpr int kRepeatedSmoothingBins = 10;

// The white fit, the noise from its residuals, the fit again from the white estimate (o.cost.noise_model
// "estimated"). A white fit that fails or leaves no residual is returned with its stages saying so.
FitResult fit_with_estimated_noise(const FitOptions& o, const std::vector<Record>& records);

// The noise from the records' deviations from their mean, then the fit with it (o.cost.noise_model "repeated").
// InputError, naming the record and what differs, for fewer than 2 records, records whose experiments differ (not
// repeats: another sensor, excitation, force, length or rate); records that do not differ are refused by fit::fit.
FitResult fit_with_repeated_noise(const FitOptions& o, const std::vector<Record>& records);

}  // namespace beamid::fit
