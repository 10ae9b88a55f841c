// Exact sensitivities d y_i / d q of the sampled output of a pulse experiment, from the same modal closed form as
// the "fast" simulator (simulation/modal_simulator.h), for the least-squares Jacobian and the Cramér-Rao bound.
//
// With the eigenpairs (lambda_k, x_k) of T(lambda) = lambda^2 M + lambda C + K (all 2n, in physical coordinates),
// s_k = 1 / x_k^T (2 lambda_k M + C) x_k (the normalisation u_k^T E v_k = 1 of the first-order pencil, whose left
// eigenvector is s_k [(lambda_k M + C) x_k; x_k] because M, C, K are symmetric), the output of a sin^2 pulse is
//   y(t) = sum_k R_k rho_k(t) (+ c^T M^-1 f P(t) for acceleration),  R_k = lambda_k^d (c^T x_k) s_k (x_k^T f) F0,
// rho_k(t) = int_0^t e^{lambda_k (t-s)} sin^2(pi s / tau) ds, d = 0, 1, 2 for displacement, velocity, acceleration.
// For a parameter q with derivatives dM, dC, dK (galerkin::parameter_derivative), first-order perturbation of the
// pencil gives, with Q_jk = -s_j x_j^T (dK + lambda_k dC + lambda_k^2 dM) x_k and N_kj = s_k lambda_j x_k^T dM x_j:
//   d lambda_k = Q_kk,
//   d(h_k g_k) = g_k sum_{j != k} h_j Q_jk / (lambda_k - lambda_j) - h_k sum_{j != k} Q_kj g_j / (lambda_j - lambda_k)
//                - h_k sum_j N_kj g_j                       (h_k = c^T x_k, g_k = s_k x_k^T f F0),
// (the eigenvector derivative dV = V C with C_jk = Q_jk / (lambda_k - lambda_j) and dU^T = -(C + N) U^T), and
//   dy(t) = sum_k [dR_k rho_k(t) + R_k d lambda_k d rho_k/d lambda (t)]
// with d rho / d lambda in closed form (pulse_response_derivative), and after the pulse rho_k(t) = rho_k(tau)
// e^{lambda_k (t - tau)}, d rho_k/d lambda (t) = [d rho_k/d lambda (tau) + (t - tau) rho_k(tau)] e^{lambda_k (t-tau)}.
// There is no differencing: the result is exact up to the round-off of the eigen-decomposition, and costs about one
// model evaluation plus, per parameter and per matrix among M, C, K that it moves, one real (2n x n) (n x 2n) product
// (galerkin::ConjugatePairs::congruence).
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "simulation/experiment.h"
#include "simulation/simulator.h"

namespace beamid::simulation {

struct SensitivityTrace {
  Trace trace;            // the output y, exactly as ModalSimulator gives it
  Eigen::MatrixXd dy_dq;  // samples x keys: d y_i / d q_k, in the output's units per parameter unit
  std::vector<std::string> keys;
};

// Whether an experiment's sensitivities are available in closed form (a pulse from rest; not a pluck or free decay).
bool has_exact_sensitivities(const Experiment& experiment);
// And for these keys: not for l when the force or sensor position is given in metres (its place on the span then
// moves with l, and the modal derivatives hold the load and sensor vectors fixed); absent positions (the tip) are
// fractions 1 whatever l.
bool has_exact_sensitivities(const Experiment& experiment, const std::vector<std::string>& keys);

// y and d y / d q for the parameters `keys` (estimable beam keys). InputError for an experiment without closed
// form sensitivities or a bad key; a failed decomposition is a trace with that status (dy_dq then empty). With an
// output filter (output_filter.h), both as it delivers them: the filter is linear and starts from rest, so the
// sensitivities of the filtered output are the filtered sensitivities.
SensitivityTrace simulate_with_sensitivities(const galerkin::BeamForms& forms, const model::BeamParameters& beam,
                                             const Experiment& experiment, const std::vector<std::string>& keys,
                                             std::shared_ptr<const OutputFilter> filter = nullptr);

}  // namespace beamid::simulation
