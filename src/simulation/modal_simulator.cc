#include "simulation/modal_simulator.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "galerkin/modes.h"
#include "model/errors.h"

namespace beamid::simulation {
namespace {

using complex = std::complex<double>;

// e^z - 1 without cancellation: Re = expm1(x) cos y - 2 sin^2(y/2), Im = e^x sin y.
complex expm1(complex z) {
  const double x = z.real(), y = z.imag();
  const double s = std::sin(0.5 * y);
  return {std::expm1(x) * std::cos(y) - 2 * s * s, std::exp(x) * std::sin(y)};
}

// phi1(z) = (e^z - 1)/z, with phi1(0) = 1.
complex phi1(complex z) {
  if (std::abs(z) < 1e-8) return 1.0 + 0.5 * z;  // next term z^2/6 is below round-off
  return expm1(z) / z;
}

// D(a, b) = (e^a - e^b)/(a - b) = e^a phi1(b - a), taking a as the argument with the larger real part so that
// |e^{b-a}| <= 1 and nothing overflows.
complex divided_exp(complex a, complex b) {
  if (a.real() < b.real()) std::swap(a, b);
  return std::exp(a) * phi1(b - a);
}

// phi2(z) = (e^z - 1 - z)/z^2 = sum_k z^k/(k+2)!, with phi2(0) = 1/2: by its series for |z| < 1/2 (18 terms: the
// remainder is below 2^-18/20! ~ 1e-24), else as (phi1(z) - 1)/z, which loses at most a factor 3 to cancellation.
complex phi2(complex z) {
  if (std::abs(z) >= 0.5) return (phi1(z) - 1.0) / z;
  complex sum = 0, term = 0.5;  // z^0 / 2!
  for (int k = 0; k < 18; ++k) {
    sum += term;
    term *= z / static_cast<double>(k + 3);
  }
  return sum;
}

// dD/da (a, b) for D(a, b) = (e^a - e^b)/(a - b): e^a phi2(b - a), or, with b the argument of larger real part (so
// that nothing overflows), e^b phi1'(a - b) = e^b (phi1(a - b) - phi2(a - b)).
complex divided_exp_da(complex a, complex b) {
  if (a.real() >= b.real()) return std::exp(a) * phi2(b - a);
  return std::exp(b) * (phi1(a - b) - phi2(a - b));
}

}  // namespace

complex pulse_response_derivative(complex lambda, double t, double tau) {
  // d/dlambda of t D(lambda t, mu t) is t^2 dD/da (lambda t, mu t), for mu = 0 and +-i w.
  const double w = 2 * std::numbers::pi / tau;
  const complex a = lambda * t;
  const complex i_wt(0.0, w * t);
  return t * t * (0.5 * divided_exp_da(a, 0.0) - 0.25 * (divided_exp_da(a, i_wt) + divided_exp_da(a, -i_wt)));
}

complex pulse_response(complex lambda, double t, double tau) {
  const double w = 2 * std::numbers::pi / tau;
  const complex a = lambda * t;
  const complex i_wt(0.0, w * t);
  return t * (0.5 * divided_exp(a, 0.0) - 0.25 * (divided_exp(a, i_wt) + divided_exp(a, -i_wt)));
}

Trace ModalSimulator::run(const galerkin::SecondOrderSystem& system, const ResponseProblem& p) const {
  std::optional<galerkin::StateSpaceModes> modes;
  try {
    modes.emplace(system);
  } catch (const NumericalError& error) {
    Trace trace;
    trace.stats.integrator = "fast";
    trace.y.assign(static_cast<std::size_t>(p.samples), 0.0);
    trace.status = std::string("fast: ") + error.what();
    return trace;
  }
  return run(*modes, system, p);
}

Trace ModalSimulator::run(const galerkin::StateSpaceModes& modes, const galerkin::SecondOrderSystem& system,
                          const ResponseProblem& p) const {
  Trace trace;
  trace.stats.integrator = "fast";
  trace.y.assign(static_cast<std::size_t>(p.samples), 0.0);
  try {
    const Eigen::VectorXcd& lambda = modes.eigenvalues();
    const Eigen::VectorXcd h = modes.output_coefficients(p.sensor, p.derivative);
    const bool pulse = p.pulse_width_s > 0 && p.amplitude_N != 0;
    const Eigen::VectorXcd g = pulse ? Eigen::VectorXcd(p.amplitude_N * modes.input_coefficients(p.load))
                                     : Eigen::VectorXcd::Zero(lambda.size());
    // Modal initial state: only a pluck has one (a pulse starts at rest), so the pulse path skips the solve.
    const Eigen::VectorXcd e0 = p.w0.isZero(0.0) ? Eigen::VectorXcd::Zero(lambda.size())
                                                 : modes.state_coefficients(p.w0, Eigen::VectorXd::Zero(p.w0.size()));
    const double direct = (p.derivative == 2 && pulse) ? modes.feedthrough(p.sensor, p.load) : 0.0;
    trace.stats.eigenvector_rcond = modes.eigenvector_rcond();
    for (int k = 0; k < lambda.size(); ++k)
      if (lambda(k).imag() > 0) trace.poles_rad_s.push_back(lambda(k));

    const double tau = pulse ? p.pulse_width_s : 0.0;
    // Samples inside the pulse, t_i <= tau, are evaluated in closed form; the rest propagate freely from tau.
    // (In double before the cast: tau / dt may exceed the int range, e.g. dt = 1e-12 s against a 4 ms pulse.)
    const int first_free = static_cast<int>(std::min<double>(p.samples, pulse ? std::floor(tau / p.dt_s) + 1 : 0));
    constexpr int kAnchorEvery = 256;  // samples between exact re-evaluations of a recurrence
    double bound = 0;                  // sum of |mode amplitudes| at tau: no later output can exceed it
    std::vector<int> kept;
    std::vector<complex> at_tau;
    for (int k = 0; k < lambda.size(); ++k) {
      if (lambda(k).imag() < 0) continue;  // its conjugate partner carries it (2 Re below)
      const double weight = lambda(k).imag() > 0 ? 2.0 : 1.0;
      const complex hk = weight * h(k);
      if (first_free > 0) {
        // Inside the pulse (e0 = 0 there: a pulse starts at rest), one exact step at a time instead of the closed form
        // at every sample: with rho(t) = int_0^t e^{lambda (t-s)} sin^2(pi s/tau) ds and sin^2 = 1/2 - (e^{iws} +
        // e^{-iws})/4,  rho(t + h) = e^{lambda h} rho(t) + h [D(lambda h, 0)/2 - (e^{iwt} D(lambda h, iwh) + e^{-iwt}
        // D(lambda h, -iwh))/4]: three divided exponentials per mode and a few products per sample, re-anchored on
        // the closed form every kAnchorEvery samples so that round-off cannot accumulate.
        const complex l = lambda(k);
        const double h = p.dt_s, w = 2 * std::numbers::pi / tau;
        const complex step = std::exp(l * h), turn = std::polar(1.0, w * h);
        const complex d0 = h * divided_exp(l * h, 0.0), d_plus = h * divided_exp(l * h, complex(0.0, w * h)),
                      d_minus = h * divided_exp(l * h, complex(0.0, -w * h));
        const complex hg = hk * g(k);
        complex rho, rotation;
        for (int i = 0; i < first_free; ++i) {
          if (i % kAnchorEvery == 0) {
            rho = pulse_response(l, i * h, tau);
            rotation = std::polar(1.0, w * i * h);
          }
          trace.y[i] += (hg * rho).real();
          if (e0(k) != 0.0) trace.y[i] += (hk * e0(k) * std::exp(l * (i * h))).real();  // a pulse on a plucked beam
          rho = step * rho + 0.5 * d0 - 0.25 * (rotation * d_plus + std::conj(rotation) * d_minus);
          rotation *= turn;
        }
      }
      const complex amplitude =
          hk * ((pulse ? g(k) * pulse_response(lambda(k), tau, tau) : complex(0)) + e0(k) * std::exp(lambda(k) * tau));
      bound += std::abs(amplitude);
      kept.push_back(k);
      at_tau.push_back(amplitude);
    }
    for (int i = 0; i < first_free; ++i) trace.y[i] += direct * p.force_N(i * p.dt_s);

    // Free decay: y_i = Re sum_k A_k e^{lambda_k (t_i - tau)}.
    const double negligible = 1e-18 * bound;
    int modes_used = 0;
    for (std::size_t j = 0; j < kept.size(); ++j) {
      const complex l = lambda(kept[j]);
      const complex amplitude = at_tau[j];
      if (std::abs(amplitude) <= negligible || first_free >= p.samples) continue;
      ++modes_used;
      const complex step = std::exp(l * p.dt_s);
      // Last sample at which |A| e^{Re(l) (t - tau)} can still exceed `negligible`.
      int last = p.samples - 1;
      if (l.real() < 0) {
        const double t_end = tau + std::log(negligible / std::abs(amplitude)) / l.real();
        const double c = std::ceil(t_end / p.dt_s);
        if (std::isfinite(c)) last = static_cast<int>(std::clamp<double>(c, first_free - 1.0, p.samples - 1.0));
      }
      complex value;
      for (int i = first_free; i <= last; ++i) {
        if ((i - first_free) % kAnchorEvery == 0) value = amplitude * std::exp(l * (i * p.dt_s - tau));
        trace.y[i] += value.real();
        value *= step;
      }
    }
    trace.stats.modes = modes_used;
    // t = 0 is the initial condition itself: evaluate it from the state, not as a sum over modes (for a pluck's
    // acceleration that sum runs over every stiff mode, clustered shear relaxation rates included, and loses ~1e-5).
    // w(0) = w0, w'(0) = 0, w''(0) = M^-1 (f P(0) - K w0).
    if (p.derivative == 0) trace.y[0] = p.sensor.dot(p.w0);
    if (p.derivative == 1) trace.y[0] = 0.0;
    if (p.derivative == 2) trace.y[0] = p.sensor.dot(system.M.llt().solve(p.force_N(0.0) * p.load - system.K * p.w0));
  } catch (const NumericalError& error) {
    trace.status = std::string("fast: ") + error.what();
  }
  return trace;
}

}  // namespace beamid::simulation
