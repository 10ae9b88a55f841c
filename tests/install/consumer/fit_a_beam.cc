// Fits the thin aluminium beam's EI and rho to a record of its own model, through the installed headers and
// libraries only: what a C++ user of find_package(beamid) writes. Prints "EI <estimate> rho <estimate>" and exits 0
// when the fit converged.
#include <beamid/api/fit_request.h>
#include <beamid/galerkin/second_order_system.h>
#include <beamid/simulation/simulator.h>

#include <cstdio>
#include <iostream>

int main() {
  using namespace beamid;
  const model::BeamParameters truth = model::preset("banks-aluminium");
  simulation::Experiment experiment;  // 4096 samples at 1 ms of the tip after a 4 ms pulse
  experiment.pulse_width_s = 0.004;
  const galerkin::SplineSpace space(6);
  const simulation::Trace trace =
      simulation::simulate(galerkin::BeamForms(space, truth.l, truth.support), truth, experiment, {});
  io::TimeSeries record;
  record.path = "<simulated>";
  record.dt_s = experiment.dt_s;
  record.values = trace.y;

  api::FitRequest request;
  request.caller.label = "fit_a_beam";
  request.beam = truth;
  request.elements = 6;
  request.experiment.pulse_width_s = 0.004;
  request.estimate = {"EI", "rho"};
  request.start_scale = 1.02;
  request.cost.name = "time";
  const api::FitComputation c = api::compute_fit(request, {record}, std::cerr);
  std::printf("EI %.17g rho %.17g %s\n", c.result.parameters[0].estimate, c.result.parameters[1].estimate,
              c.result.status.c_str());
  return c.result.status == "converged" ? 0 : 1;
}
