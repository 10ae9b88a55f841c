// The two spike costs' factories (their formulas: costs/cost.h): "spike", the paper's (3.5) as written, and
// "spike-smooth", sub-bin frequencies, decay rates and magnitudes of the spikes.
#pragma once

#include <memory>
#include <vector>

#include "costs/cost.h"

namespace beamid::costs {

std::unique_ptr<Cost> make_spike_cost(const CostOptions& options, std::vector<double> data, double dt_s);
std::unique_ptr<Cost> make_smooth_spike_cost(const CostOptions& options, std::vector<double> data, double dt_s);

}  // namespace beamid::costs
