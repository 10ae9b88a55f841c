// The fit setup the cost tests share: the thin beam at N = 8, a 4 ms pulse at 0.7 l, tip velocity, 4096 samples at
// 1 ms, the band below 120 Hz (modes 1-3), the cost's default optimizer; nothing estimated yet.
#pragma once

#include "fit/identification.h"

namespace beamid::costs {

inline fit::FitOptions thin_beam_fit(const std::string& cost) {
  const auto truth = model::preset("banks-aluminium");
  fit::FitOptions o;
  o.start = truth;
  o.elements = 8;
  o.experiment.dt_s = 1e-3;
  o.experiment.samples = 4096;
  o.experiment.pulse_width_s = 4e-3;
  o.experiment.force_x_m = 0.7 * truth.l;
  o.experiment.output = "velocity";
  o.cost.name = cost;
  o.cost.spikes.max_frequency_hz = 120;
  o.optimizer.method = fit::default_optimizer(cost);
  return o;
}

// Noise-free data of that experiment from the same model (fast, exact).
inline std::vector<double> thin_beam_data(const fit::FitOptions& o) {
  const galerkin::SplineSpace space(o.elements);
  return simulation::simulate(galerkin::BeamForms(space, o.start.l, o.start.support), o.start, o.experiment, {}).y;
}

}  // namespace beamid::costs
