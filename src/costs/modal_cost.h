// The modal cost "modal" (modal updating, the practitioners' two-step route; ../shared/docs/comparison.md section 5):
// the data's modes are identified once by the matrix pencil (signal/matrix_pencil.h) from the free decay that follows
// the excitation, and the physical parameters are fitted to them:
//   J_M = sum_l [((|lambda^u_l| - |lambda^z_l|) / |lambda^z_l|)^2 + ((Re lambda^u_l - Re lambda^z_l) /
//   |lambda^z_l|)^2],
// with lambda^z_l an identified pole and lambda^u_l the model's underdamped eigenvalue nearest to it in natural
// frequency (pairing by frequency, not by rank). Frequency errors are relative, so that every mode counts alike
// whatever its frequency; decay-rate errors are divided by the same |lambda^z_l|, because for a damped sinusoid in
// white noise the Cramér-Rao bounds of the decay rate and of the angular frequency are equal, so both residuals of a
// mode carry the same uncertainty. The modes: the `spikes.count` strongest in [min_frequency, max_frequency], or the
// strongest near each of `spikes.frequencies_hz`.
//
// mode_weight "measured" divides instead each mode's frequency error by 2 pi u_l and its decay-rate error by u_d,l,
// the measured uncertainties of its frequency and decay rate (signal/measured_modes.h: the noise's Cramér-Rao bound,
// the drift between the record's segments, the close poles that fit it):
//   J_M = sum_l [((|lambda^u_l| - |lambda^z_l|) / (2 pi u_l))^2 + ((Re lambda^u_l - Re lambda^z_l) / u_d,l)^2],
// the maximum-likelihood weighting of independent modal estimates, and a chi-square of 2 L terms at a model that
// fits. "relative" weighs a mode whose frequency is known to 3e-6 (a steady first mode) as loosely as one known to
// 2.5e-4 (a high mode near the noise): on the synthetic strip's two records the relative fit left the first mode
// 7.5 of its u off to fit the third within 0.25 of its own.
// A divisor is at least kUncertaintyFloor |lambda^z_l| (below).
#pragma once

#include <memory>
#include <vector>

#include "costs/cost.h"

namespace beamid::costs {

// The least divisor of the "measured" weighting, relative to |lambda|: a noise-free record's u is round-off, and the
// pencil is exact to ~1e-9 there (tests/signal/matrix_pencil_test.cc).
inline constexpr double kUncertaintyFloor = 1e-9;

// InputError when the record shows fewer modes than asked for.
std::unique_ptr<Cost> make_modal_cost(const CostOptions& options, std::vector<double> data, double dt_s);

}  // namespace beamid::costs
