// What a model run says about its own accuracy, beside its values: notes (one line each, "" when there is nothing to
// say) that beamid modes, simulate, system, crb and fit print on stderr and the Python package raises as warnings.
// Each names the measured size of the error and what removes it; none changes a value.
#pragma once

#include <string>

#include "model/beam_parameters.h"

namespace beamid::api {

// A body with rotary inertia on the span (an attachment at x < l with J > 0 or offset c != 0) makes the bending
// moment jump there, a kink in the rotation that the C2 cubic splines cannot follow, so that the Galerkin model
// converges only roughly as 1/N (the thirteenth adversarial pass's problem 3: x = 0.2 m, m = 0.01 kg,
// J = 1e-4 kg m^2 on the thin beam put mode 4 8 % high at N = 16 and 1.6 % high at N = 48, where a point mass converges
// to 1e-7 by N = 80). Compares the model's first six undamped frequencies at `elements` with the exact ones
// (model/exact_frequencies.h), and the same for the beam with its bodies as point masses, and says so when the rotary
// inertia adds more than kAttachmentExcessGap to a mode's relative error.
std::string attachment_convergence_note(const model::BeamParameters& beam, int elements);

// The damped modes' eigenvalue condition (galerkin::StateSpaceModes::eigenvector_rcond) below
// kNearlyDefectiveRcond: a mode damped almost exactly critically, where the modal closed form (the fast integrator,
// and the exact sensitivities built on it) loses accuracy. Measured against CVODE (rtol 1e-12) on the thin beam at
// N = 8 and 16, gamma swept towards mode 1's critical value: the response's largest error was 1e-8 to 1.4e-7 of its
// peak at rcond 0.05 to 0.4, 0.5e-6 to 3.7e-6 at rcond 0.008 to 0.02, and 2.7e-4 at rcond 1.3e-3; the presets run at
// rcond 0.15 to 0.7. `elements` names the model.
std::string nearly_defective_note(const model::BeamParameters& beam, int elements);
// The same from a computed condition (a simulation's Trace::stats.eigenvector_rcond).
std::string nearly_defective_note(double eigenvector_rcond);

inline constexpr double kAttachmentExcessGap = 1e-3;  // 0.1 % of a frequency: ~0.2 % of EI (f ~ sqrt(EI))
inline constexpr double kNearlyDefectiveRcond = 0.02;

}  // namespace beamid::api
