// An uncertainty that admits model error: the spread of the estimates over K disjoint windows of the record(s).
//
// The formal standard error assumes that the residuals are white noise; with model error they are systematic, and
// the formal error can be 40-600x smaller than the scatter between repeated records (issue 11). Fitting K disjoint,
// consecutive windows of the same record (each 1/K of it, every record of a joint fit cut alike) gives K estimates
// whose scatter contains whatever the model gets wrong in a way that changes along the record (amplitude-dependent
// damping, a drifting clamp, a mode the model lacks beating with one it has), as well as the noise. Reported:
//   sd   = the sample standard deviation of the K window estimates: the uncertainty of one window's estimate;
//   standard_error = sd / sqrt(K): that of the full record's estimate, if the windows carried equal, independent
//        information. A free decay's later windows carry less (the signal decays), so this is a lower estimate of
//        the window-based error; sd is the conservative one.
// Each window after the first starts from an unknown state, so it is fitted as a free decay (simulation/
// experiment.h: mode amplitudes solved in closed form), from the full record's estimate, by the direct strategy with
// the fit's cost and optimizer. A pulse record's first window keeps its pulse; its later windows cannot separate EI
// from rho (the force is not in them), which the spread then shows. A window whose fit fails or stops at the
// evaluation budget is listed with its status and estimate and left out of the statistics: only converged windows
// count.
#pragma once

#include <string>
#include <vector>

#include "fit/identification.h"

namespace beamid::fit {

struct WindowSpread {
  int windows = 0;                               // K
  std::vector<std::string> keys;                 // the estimated parameters, in the fit's order
  std::vector<std::vector<double>> estimates;    // [window][parameter] (NaN for a failed window)
  std::vector<std::string> statuses;             // per window: the fit's status
  std::vector<double> mean, sd, standard_error;  // per parameter, over the converged windows
  // Per parameter, the RMS over the converged windows of each window's own formal standard error: the spread that
  // noise alone would give. Later windows are free decays that carry less information than the full record, so sd
  // is compared with this, not with the full fit's formal error (on a model-exact noisy record the sd was 37 times
  // the full fit's formal error and the report said to quote it as model error: the third pass's P317).
  std::vector<double> window_formal;
  std::vector<bool> counted;  // per window: its fit converged, so it counts in the statistics
  int used = 0;               // windows whose fit converged (status converged...)
  // Per parameter, the converged windows where it is not on a bound: its statistics are over these only (a window's
  // cDI on its bound was counted in cDI's sd, the bound's value rather than the data's: the fifth pass's R284).
  std::vector<int> used_per_parameter;
  // Some counted window has a parameter on its bound: the bound biases that window's other estimates as well, so the
  // spread of the parameters off their bound holds that bias beside noise and model error (the verdict says so).
  bool bound_bias = false;
};

// The smallest window, in samples: shorter windows resolve no mode below a few hundred bins.
inline constexpr int kMinWindowSamples = 256;

// InputError when K < 2 or a window would have fewer than kMinWindowSamples samples (naming both), or when the
// options are not admissible (as fit()).
WindowSpread window_spread(const FitOptions& options, const std::vector<Record>& records, const FitResult& full,
                           int windows);
WindowSpread window_spread(const FitOptions& options, const std::vector<double>& data, const FitResult& full,
                           int windows);

}  // namespace beamid::fit
