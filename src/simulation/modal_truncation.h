// Modal truncation of the Galerkin system, as structural dynamics usually reduces a model: why the forward run keeps
// every mode (results/verification/model_reduction.md, make verify).
//
// In the undamped modal basis w = Phi q (galerkin::undamped_modes: Phi^T M Phi = I, Phi^T K Phi = Omega^2) the system
// is q'' + C~ q' + Omega^2 q = Phi^T f P with C~ = Phi^T C Phi, coupled only by the damping. Truncating at a gap of
// the undamped spectrum keeps the m lowest modes L and discards the stiff rest H (the thin beam's shear modes near
// sqrt(kAG / rho_r2)). Two reductions of that kind:
//   truncated:  the retained block alone, q_L'' + C~_LL q_L' + Omega_L^2 q_L = Phi_L^T f P, output c^T Phi_L q_L
//               (for acceleration with the retained part of the direct term, c^T Phi_L Phi_L^T f P);
//   decoupled:  the retained block and every discarded mode as its own oscillator, M~_jj q_j'' + C~_jj q_j' +
//               K~_jj q_j = phi_j^T f P (M~_jj = 1, K~_jj = omega_j^2 up to round-off): the exact response of the
//               block-diagonal system [X_LL 0; 0 diag X_HH] for X = M~, C~, K~, so the discarded modes keep their
//               static and dynamic response and only the damping's coupling through C~_LH and within H is dropped. This
//               contains the static (mode-acceleration) correction and more.
// The damped spectrum need not have the undamped one's gap: Kelvin-Voigt shear damping turns each stiff shear mode
// into two real roots, a fast one near -kAcs omega_j^2 / kAG and a slow one near -kAG / kAcs whatever omega_j is,
// and the slow one falls among the retained roots. Both reductions are computed exactly (galerkin::StateSpaceModes of
// the reduced matrices and the modal propagator); they do not make a forward run cheaper here, they measure what
// dropping the coupling costs.
#pragma once

#include <Eigen/Dense>
#include <complex>

#include "galerkin/second_order_system.h"
#include "simulation/experiment.h"
#include "simulation/simulator.h"

namespace beamid::simulation {

// The split of the undamped spectrum at its widest gap above the measured band: the retained modes are those below
// the largest ratio omega_{k+1} / omega_k among the k with omega_k >= band_rad_s (a mode inside the band the record
// resolves cannot be discarded, and the first mode above it is kept too). retained = size (nothing discarded) when
// no gap lies above the band; InputError for an empty spectrum.
struct TruncationSplit {
  int retained = 0;
  double gap_ratio = 1;  // omega_retained / omega_{retained - 1} (1 when nothing is discarded)
};
TruncationSplit widest_gap(const Eigen::VectorXd& omega_rad_s, double band_rad_s);

enum class Truncation { truncated, decoupled };

// The response of `problem` (pulse from rest; InputError for an initial displacement) under the reduction, keeping
// the `retained` lowest undamped modes (InputError unless 1 <= retained <= size; `decoupled` keeps the others as
// uncoupled oscillators, `truncated` drops them). A failed decomposition is reported in Trace::status.
Trace truncated_response(const galerkin::SecondOrderSystem& system, const ResponseProblem& problem, int retained,
                         Truncation kind);

// What decides a truncation's error, for the table: the size of the damping's coupling between the blocks,
// max |C~_ij| / sqrt(C~_ii C~_jj) over retained i and discarded j (0 for damping the undamped modes diagonalise, such
// as Rayleigh damping a M + b K, and near 0 for the thin beam at its preset, whose bending and shear relaxation times
// agree), and whether the damped spectrum keeps the undamped one's gap: the discarded modes' slowest root (the smaller
// root in magnitude of lambda^2 + C~_jj lambda + omega_j^2 = 0 over the discarded j, taken with Im >= 0), the largest
// |lambda| among the retained block's damped eigenvalues, and the distance from that slowest root to the nearest
// retained eigenvalue relative to its magnitude. With nothing discarded (retained = size) coupling_relative is 0,
// slowest_discarded_rad_s 0 and nearest_retained_relative infinity. Throws NumericalError when a decomposition fails,
// InputError unless 1 <= retained <= size.
struct TruncationDiagnostics {
  double coupling_relative = 0;
  std::complex<double> slowest_discarded_rad_s = 0;
  double fastest_retained_rad_s = 0;
  double nearest_retained_relative = 0;
};
TruncationDiagnostics truncation_diagnostics(const galerkin::SecondOrderSystem& system, int retained);

}  // namespace beamid::simulation
