// Exact propagator for the linear time-invariant Galerkin system ("fast").
//
// The balanced state-space modes of galerkin::StateSpaceModes decouple the system: eta_k' = lambda_k eta_k + g_k P(t).
// For the sin^2 pulse, sin^2(pi s/tau) = 1/2 - (e^{i w s} + e^{-i w s})/4 with w = 2 pi/tau, and
//   int_0^t e^{lambda (t-s)} e^{mu s} ds = t D(lambda t, mu t),  D(a, b) = (e^a - e^b)/(a - b),
// evaluated as e^a phi1(b - a) with Re(a) >= Re(b) and phi1(z) = (e^z - 1)/z by a cancellation-free expm1, so that
// neither resonance (lambda ~ mu) nor stiff, overdamped modes (Re lambda tau ~ -1e5) lose accuracy or overflow.
// After the pulse every mode decays freely: eta_k(t + dt) = e^{lambda_k dt} eta_k(t), re-anchored on the exact
// exponential every 256 samples; a mode is dropped once its amplitude is below 1e-18 of the output's bound.
// The output y = sum_k h_k eta_k (+ c^T M^-1 f P for acceleration) sums conjugate pairs as 2 Re.
// There is no time-stepping error: the result is exact up to round-off in the eigen-decomposition.
// A sampled force F_i, linear between samples, steps each mode exactly:
//   eta_{i+1} = e eta_i + (a - b) F_i + b F_{i+1},  e = e^{lambda dt},  a = g dt phi1(lambda dt),  b = g dt phi2(lambda
//   dt),
// so that in steady state the sampled system's transfer function is G(z) = sum_k h_k ((a_k - b_k) + b_k z)/(z - e_k)
// (+ the feedthrough for acceleration), over every mode (conjugates included), which Trace::frf gives at the DFT bins.
// Over a record from rest the output's DFT is then exactly Y(k) = G(z_k) F(k) + sum_k t_k / (1 - e_k z_k^-1): the
// transient terms, one per mode, carry the modal states at the record's two ends (with xi = eta - b F, which steps as
// xi_{i+1} = e xi_i + (e b + a - b) F_i), the form freq-ml's errors-in-variables cost takes them in
// (costs/least_squares.h).
#pragma once

#include "galerkin/modes.h"
#include "simulation/simulator.h"

namespace beamid::simulation {

class ModalSimulator final : public Simulator {
 public:
  Trace run(const galerkin::SecondOrderSystem& system, const ResponseProblem& problem) const override;
  // The same with the state-space modes of `system` already decomposed (so that a caller who needs them too, such as
  // the sensitivities, decomposes once).
  Trace run(const galerkin::StateSpaceModes& modes, const galerkin::SecondOrderSystem& system,
            const ResponseProblem& problem) const;
};

// The unit-amplitude pulse response of one mode, int_0^t e^{lambda (t-s)} sin^2(pi s / tau) ds, 0 <= t <= tau.
std::complex<double> pulse_response(std::complex<double> lambda, double t_s, double tau_s);
// Its derivative with respect to lambda, int_0^t (t-s) e^{lambda (t-s)} sin^2(pi s / tau) ds, 0 <= t <= tau, from
// dD/da (a, b) = e^a phi2(b - a), phi2(z) = (e^z - 1 - z)/z^2 (the second divided exponential).
std::complex<double> pulse_response_derivative(std::complex<double> lambda, double t_s, double tau_s);

// The divided exponential D(a, b) = (e^a - e^b)/(a - b) and its derivative in a, dD/da (a, b), without cancellation
// or overflow (the one-sample steps of the pulse response and its derivative, simulation/sensitivities.cc).
std::complex<double> pulse_divided_exp(std::complex<double> a, std::complex<double> b);
std::complex<double> pulse_divided_exp_da(std::complex<double> a, std::complex<double> b);

}  // namespace beamid::simulation
