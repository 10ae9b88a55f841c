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
#pragma once

#include <memory>
#include <vector>

#include "costs/cost.h"

namespace beamid::costs {

// InputError when the record shows fewer modes than asked for.
std::unique_ptr<Cost> make_modal_cost(const CostOptions& options, std::vector<double> data, double dt_s);

}  // namespace beamid::costs
