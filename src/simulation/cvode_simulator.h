// Reference integrator: SUNDIALS CVODE, BDF (orders 1-5) with Newton iteration, a dense direct linear solver and the
// constant analytic Jacobian of the first-order form
//   d/dt [w; v] = [[0, I], [-M^-1 K, -M^-1 C]] [w; v] + [0; M^-1 f P(t)].
// The integration stops at the end of the pulse and restarts there (P is only C^1 at tau), and returns values at the
// sample times from CVODE's interpolant. Acceleration is c^T (M^-1 (f P - C v - K w)) at each sample.
// No SUNDIALS type appears in this header.
#pragma once

#include "simulation/simulator.h"

namespace beamid::simulation {

class CvodeSimulator final : public Simulator {
 public:
  explicit CvodeSimulator(CvodeOptions options) : options_(options) {}
  Trace run(const galerkin::SecondOrderSystem& system, const ResponseProblem& problem) const override;

 private:
  CvodeOptions options_;
};

// "6.4.1": the SUNDIALS version, for provenance.
std::string sundials_library_version();

}  // namespace beamid::simulation
