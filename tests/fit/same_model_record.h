// Test helper: the record of `truth` in `experiment` by the fast exact propagator at `elements`, i.e. data from the
// same model a fit at that N uses, whose cost minimum is then the truth itself (no discretisation error, no noise).
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "simulation/simulator.h"

namespace beamid::fit {

inline std::vector<double> same_model_record(const model::BeamParameters& truth,
                                             const simulation::Experiment& experiment, int elements) {
  const galerkin::SplineSpace space(elements);
  const auto trace = simulation::simulate(galerkin::BeamForms(space, truth.l, truth.support), truth, experiment, {});
  EXPECT_TRUE(trace.ok()) << trace.status;
  return trace.y;
}

}  // namespace beamid::fit
