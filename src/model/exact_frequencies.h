// Exact (analytic) undamped natural frequencies used to verify the Galerkin model (model.md section 6).
//
// Timoshenko cantilever with a rigid tip body: for a trial omega the clamped shapes
//   U   = C1 (cosh ax - cos bx) + C2 (sinh ax - (d_a/d_b) sin bx)
//   Psi = C1 (d_a sinh ax + d_b sin bx) + C2 d_a (cosh ax - cos bx)
// satisfy U(0) = Psi(0) = 0; the tip conditions
//   R1 = kAG (U' - Psi) - omega^2 (m U + m c Psi),   R2 = EI Psi' - omega^2 (m c U + (J_o + m c^2) Psi)
// give a 2x2 system whose determinant R1_1 R2_2 - R1_2 R2_1 vanishes at the natural frequencies.
// Valid below the shear cut-off omega_c = sqrt(kAG / rho_r2); damping is ignored.
//
// Euler-Bernoulli checks: 1 + cos L cosh L = 0 (plain cantilever) and, with a tip mass M_t and rotary inertia J about
// the tip (c = 0), mu = M_t/(rho l), eta = J/(rho l^3):
//   1 + cos L cosh L + mu L (cos L sinh L - sin L cosh L) - eta L^3 (cosh L sin L + sinh L cos L)
//     + mu eta L^4 (1 - cos L cosh L) = 0,    omega_n = L_n^2 sqrt(EI / (rho l^4)).
#pragma once

#include <vector>

#include "model/beam_parameters.h"

namespace beamid::model {

// The frequency determinant above divided by cosh^2(a l), so that it stays O(1) as omega grows. For the rigid clamp
// and the tip body only: InputError when the beam has attachments or a compliant support.
// Requires 0 < omega_rad_s < shear_cutoff_rad_s(beam).
double timoshenko_determinant(const BeamParameters& beam, double omega_rad_s);

// With attachments on the span (BeamParameters::attachments) or a compliant clamp (BeamParameters::support: the root
// rows become S(0) = k_w U(0) and M(0) = k_theta Psi(0)) the beam is cut into segments at them and the
// determinant is that of the global 4S x 4S system (S segments): four free solutions per segment, the clamp, U and
// Psi continuous at each cut, the shear force and moment jumping by the inertia forces of the bodies there, and the
// tip conditions above with the tip body and any attachment at x = l. Zero at the natural frequencies and
// continuous (no poles) in (0, shear cut-off); equals the 2x2 form's roots when there are no attachments.
// Requires 0 < omega_rad_s < shear_cutoff_rad_s(beam).
double segmented_determinant(const BeamParameters& beam, double omega_rad_s);

// The first `count` roots of timoshenko_determinant (segmented_determinant when the beam has attachments) in
// increasing order, rad/s, found by marching in steps small
// against the spacing of the roots (a fixed fraction of pi in b*l) and refining each sign change to full precision.
// Returns fewer than `count` values when fewer roots lie below the shear cut-off. count >= 1.
std::vector<double> timoshenko_frequencies_rad_s(const BeamParameters& beam, int count);

// First `count` positive roots L_n of 1 + cos L cosh L = 0.
std::vector<double> euler_bernoulli_cantilever_roots(int count);

// First `count` positive roots L_n of the tip-mass equation above (mu, eta >= 0).
std::vector<double> euler_bernoulli_tip_body_roots(double mu, double eta, int count);

// Euler-Bernoulli frequencies of the beam (rho, EI, l), rad/s, with its tip body taken as a point mass m and
// rotary inertia J_o + m c^2 about the tip (exact for c = 0; shear, rotary inertia of the beam and damping ignored).
// InputError when the beam has attachments on the span.
std::vector<double> euler_bernoulli_frequencies_rad_s(const BeamParameters& beam, int count);

}  // namespace beamid::model
