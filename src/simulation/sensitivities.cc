#include "simulation/sensitivities.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "core/errors.h"
#include "galerkin/complex_products.h"
#include "galerkin/modes.h"
#include "simulation/modal_simulator.h"
#include "simulation/output_filter.h"

namespace beamid::simulation {
namespace {

using complex = std::complex<double>;
using galerkin::real_times;

// Per mode k (one of each conjugate pair) and parameter p: the residue R_k, its derivative and d lambda_k.
struct ModalDerivatives {
  Eigen::VectorXcd lambda, residue;      // 2n
  Eigen::MatrixXcd d_lambda, d_residue;  // 2n x keys
};

ModalDerivatives modal_derivatives(const galerkin::SecondOrderSystem& system, const ResponseProblem& p,
                                   const galerkin::StateSpaceModes& modes,
                                   const std::vector<galerkin::SecondOrderSystem>& derivatives) {
  ModalDerivatives d;
  d.lambda = modes.eigenvalues();
  const Eigen::Index m = d.lambda.size();
  // Each conjugate pair's vectors held once as real vectors: a congruence X^T D X is then one real product.
  const galerkin::ConjugatePairs pairs(modes.physical_vectors(), d.lambda);
  const Eigen::MatrixXcd& x = pairs.vectors();  // n x 2n
  const Eigen::MatrixXcd mx = real_times(system.M, x), cx = real_times(system.C, x);
  // s_k = 1 / x_k^T (2 lambda_k M + C) x_k, h_k = c^T x_k, g_k = s_k x_k^T f F0.
  Eigen::VectorXcd s(m), h = x.transpose() * p.sensor.cast<complex>(), g = x.transpose() * p.load.cast<complex>();
  for (Eigen::Index k = 0; k < m; ++k)  // transpose, not adjoint: the pencil is complex symmetric
    s(k) = 1.0 / (x.col(k).transpose() * (2.0 * d.lambda(k) * mx.col(k) + cx.col(k))).value();
  g = p.amplitude_N * s.cwiseProduct(g);
  const int power = p.derivative;
  Eigen::VectorXcd lambda_power = d.lambda.array().pow(power);
  d.residue = lambda_power.cwiseProduct(h).cwiseProduct(g);

  d.d_lambda.resize(m, static_cast<Eigen::Index>(derivatives.size()));
  d.d_residue.resize(m, static_cast<Eigen::Index>(derivatives.size()));
  const Eigen::VectorXcd lambda2 = d.lambda.cwiseProduct(d.lambda);
  // W_jk = 1 / (lambda_k - lambda_j) off the diagonal, 0 on it: the same for every parameter.
  Eigen::MatrixXcd w(m, m);
  for (Eigen::Index k = 0; k < m; ++k)
    for (Eigen::Index j = 0; j < m; ++j) w(j, k) = j == k ? complex(0.0) : 1.0 / (d.lambda(k) - d.lambda(j));
  for (std::size_t q = 0; q < derivatives.size(); ++q) {
    const galerkin::SecondOrderSystem& ds = derivatives[q];
    // X^T Y = X^T dK X + (X^T dC X) Lambda + (X^T dM X) Lambda^2 for Y = dK X + dC X Lambda + dM X Lambda^2;
    // Q = -diag(s) X^T Y;  N = diag(s) (X^T dM X) Lambda. A parameter moves one or two of M, C, K (EI: K; rho: M;
    // cDI, gamma: C), and a matrix it leaves alone costs nothing.
    Eigen::MatrixXcd xty = Eigen::MatrixXcd::Zero(m, m), xmx;
    if (!ds.K.isZero(0.0)) xty += pairs.congruence(ds.K);
    if (!ds.C.isZero(0.0)) xty += pairs.congruence(ds.C) * d.lambda.asDiagonal();
    if (!ds.M.isZero(0.0)) {
      xmx = pairs.congruence(ds.M);
      xty += xmx * lambda2.asDiagonal();
    }
    const Eigen::MatrixXcd q_matrix = -(s.asDiagonal() * xty);
    // into_k = sum_{j != k} h_j Q_jk / (lambda_k - lambda_j),
    // out_k = sum_j N_kj g_j + sum_{j != k} Q_kj g_j / (lambda_j - lambda_k).
    const Eigen::MatrixXcd qw = q_matrix.cwiseProduct(w);  // (Q o W)_kj = Q_kj / (lambda_j - lambda_k)
    const Eigen::VectorXcd into_all = qw.transpose() * h;
    Eigen::VectorXcd out_all = qw * g;
    if (xmx.size() > 0) out_all += s.cwiseProduct(xmx * d.lambda.cwiseProduct(g));
    const auto col = static_cast<Eigen::Index>(q);
    for (Eigen::Index k = 0; k < m; ++k) {
      const complex into = into_all(k), out = out_all(k);
      const complex dl = q_matrix(k, k);
      const complex d_hg = g(k) * into - h(k) * out;
      d.d_lambda(k, col) = dl;
      d.d_residue(k, col) =
          lambda_power(k) * d_hg +
          (power > 0 ? static_cast<double>(power) * std::pow(d.lambda(k), power - 1) * dl : complex(0.0)) * h(k) * g(k);
    }
  }
  return d;
}

// Adds d y / d q inside the pulse to the rows 1 <= i < first_free of dy (grid p.dt_s; t = 0 is exactly 0: the pulse
// starts at rest with P(0) = 0), with the acceleration's direct term. rho and d rho / d lambda are the closed forms
// every `anchor_every` samples and between them the exact one-sample step (the sensed model's fine grid, R times the
// samples), from rho(t + h) = e^{lambda h} rho(t) + h [D(lambda h, 0)/2 - (e^{iwt} D(lambda h, iwh) + e^{-iwt}
// D(lambda h, -iwh))/4] and its derivative in lambda, d rho(t + h) = e^{lambda h} (d rho(t) + h rho(t)) + h^2
// [D_a(lambda h, 0)/2 - (e^{iwt} D_a(lambda h, iwh) + e^{-iwt} D_a(lambda h, -iwh))/4]; anchor_every = 1: the closed
// forms at every sample.
void add_in_pulse(Eigen::MatrixXd& dy, const ModalDerivatives& d, const ResponseProblem& p, int first_free,
                  const std::vector<galerkin::SecondOrderSystem>& derivatives,
                  const galerkin::SecondOrderSystem& system, int anchor_every) {
  const double tau = p.pulse_width_s, h = p.dt_s, w = 2 * std::numbers::pi / tau;
  const Eigen::Index np = dy.cols();
  for (Eigen::Index k = 0; k < d.lambda.size(); ++k) {
    const complex l = d.lambda(k);
    if (l.imag() < 0) continue;  // its conjugate partner carries it (2 Re below)
    const double weight = l.imag() > 0 ? 2.0 : 1.0;
    const Eigen::VectorXcd dr = weight * d.d_residue.row(k).transpose();
    const Eigen::VectorXcd rdl = weight * d.residue(k) * d.d_lambda.row(k).transpose();
    const complex step = std::exp(l * h), turn = std::polar(1.0, w * h), iwh(0.0, w * h);
    const complex d0 = h * pulse_divided_exp(l * h, 0.0), dp = h * pulse_divided_exp(l * h, iwh),
                  dm = h * pulse_divided_exp(l * h, -iwh);
    const complex e0 = h * h * pulse_divided_exp_da(l * h, 0.0), ep = h * h * pulse_divided_exp_da(l * h, iwh),
                  em = h * h * pulse_divided_exp_da(l * h, -iwh);
    complex rho, drho, rotation;
    for (int i = 1; i < first_free; ++i) {
      if ((i - 1) % anchor_every == 0) {
        rho = pulse_response(l, i * h, tau);
        drho = pulse_response_derivative(l, i * h, tau);
        rotation = std::polar(1.0, w * i * h);
      }
      for (Eigen::Index q = 0; q < np; ++q) dy(i, q) += (dr(q) * rho + rdl(q) * drho).real();
      drho = step * (drho + h * rho) + 0.5 * e0 - 0.25 * (rotation * ep + std::conj(rotation) * em);
      rho = step * rho + 0.5 * d0 - 0.25 * (rotation * dp + std::conj(rotation) * dm);
      rotation *= turn;
    }
  }
  if (p.derivative == 2) {
    // The acceleration's direct term c^T M^-1 f P(t): d/dq = -c^T M^-1 dM M^-1 f P(t).
    const Eigen::LLT<Eigen::MatrixXd> mass(system.M);
    const Eigen::VectorXd mf = mass.solve(p.load), mc = mass.solve(p.sensor);
    for (Eigen::Index q = 0; q < np; ++q) {
      const double direct = -mc.dot(derivatives[static_cast<std::size_t>(q)].M * mf);
      for (int i = 1; i < first_free; ++i) dy(i, q) += direct * p.force_N(i * h);
    }
  }
}

// After the pulse, mode by mode: Re[(a_q + (t - tau) b_q) e^{lambda (t - tau)}] with a_q = dR_q rho(tau) + R dlambda_q
// d rho / d lambda (tau), b_q = R dlambda_q rho(tau) (the weights of a pair included), at the samples i >= begin of
// the grid dt_s, until e^{lambda (t - tau)} is below 1e-18 (the mode's contribution has then fallen by 18 orders of
// magnitude from its size at tau).
struct FreeSensitivity {
  complex lambda;
  Eigen::VectorXcd a, b;
};
std::vector<FreeSensitivity> free_sensitivities(const ModalDerivatives& d, double tau) {
  std::vector<FreeSensitivity> out;
  for (Eigen::Index k = 0; k < d.lambda.size(); ++k) {
    const complex l = d.lambda(k);
    if (l.imag() < 0) continue;
    const double weight = l.imag() > 0 ? 2.0 : 1.0;
    const Eigen::VectorXcd dr = weight * d.d_residue.row(k).transpose();
    const Eigen::VectorXcd rdl = weight * d.residue(k) * d.d_lambda.row(k).transpose();
    const complex rho_tau = pulse_response(l, tau, tau), drho_tau = pulse_response_derivative(l, tau, tau);
    out.push_back({l, dr * rho_tau + rdl * drho_tau, rdl * rho_tau});
  }
  return out;
}
void add_free(Eigen::MatrixXd& dy, const FreeSensitivity& mode, double tau, double dt, int begin) {
  constexpr int kAnchorEvery = 256;
  const complex l = mode.lambda;
  const int samples = static_cast<int>(dy.rows());
  int last = samples - 1;
  if (l.real() < 0) {
    const double c = std::ceil((tau + std::log(1e-18) / l.real()) / dt);
    if (std::isfinite(c)) last = static_cast<int>(std::clamp<double>(c, begin - 1.0, samples - 1.0));
  }
  const complex step = std::exp(l * dt);
  complex factor;
  for (int i = begin; i <= last; ++i) {
    const double since = i * dt - tau;
    if ((i - begin) % kAnchorEvery == 0) factor = std::exp(l * since);
    for (Eigen::Index q = 0; q < dy.cols(); ++q) dy(i, q) += (factor * (mode.a(q) + since * mode.b(q))).real();
    factor *= step;
  }
}

// The sensitivities as the output filter delivers them (output_filter.h): inside the pulse on the fine grid, filtered
// sample by sample from rest; after it, each mode's a, b through the filter (a' = H a + dt_f mu H' b, b' = H b) on the
// record's grid, and the filter's decay from its state at the pulse's end less the modes' particular states there,
// Re[(v a + b ((t - tau) v + dt_f mu v')) e^{lambda (t - tau)}].
Eigen::MatrixXd filtered_sensitivities(const ModalDerivatives& d, const ResponseProblem& p,
                                       const std::vector<galerkin::SecondOrderSystem>& derivatives,
                                       const galerkin::SecondOrderSystem& system, Eigen::Index np) {
  const OutputFilter& filter = *p.output_filter;
  const int decimation = filter.decimation();
  ResponseProblem fine = p;
  fine.dt_s = p.dt_s / decimation;
  const double tau = p.pulse_width_s;
  const int n1 =
      static_cast<int>(std::min(static_cast<double>(p.samples) * decimation, std::floor(tau / fine.dt_s) + 1));
  Eigen::MatrixXd head = Eigen::MatrixXd::Zero(n1, np);
  add_in_pulse(head, d, fine, n1, derivatives, system, 256);
  Eigen::MatrixXd dy = Eigen::MatrixXd::Zero(p.samples, np);
  Eigen::MatrixXd state = Eigen::MatrixXd::Zero(filter.order(), np);  // at rest: every derivative 0 before t = 0
  filter.run(head, state, dy);
  const int begin = (n1 + decimation - 1) / decimation;
  if (begin >= p.samples) return dy;
  const double since = n1 * fine.dt_s - tau;
  for (FreeSensitivity mode : free_sensitivities(d, tau)) {
    const complex mu = std::exp(mode.lambda * fine.dt_s);
    const OutputFilter::Response at = filter.at(mu);
    if (filter.order() > 0) {
      const complex e = std::exp(mode.lambda * since);
      const Eigen::VectorXcd tail = since * at.v + fine.dt_s * mu * at.dv;
      state -= ((at.v * mode.a.transpose() + tail * mode.b.transpose()) * e).real();
    }
    mode.a = at.h * mode.a + fine.dt_s * mu * at.dh * mode.b;
    mode.b *= at.h;
    add_free(dy, mode, tau, p.dt_s, begin);
  }
  filter.add_transient(dy, n1, std::move(state));
  return dy;
}

}  // namespace

bool has_exact_sensitivities(const Experiment& e) { return e.excitation == kPulse; }

bool has_exact_sensitivities(const Experiment& e, const std::vector<std::string>& keys) {
  const bool length = std::find(keys.begin(), keys.end(), "l") != keys.end();
  return has_exact_sensitivities(e) && !(length && (e.force_x_m || e.sensor_x_m));
}

SensitivityTrace simulate_with_sensitivities(const galerkin::BeamForms& forms, const model::BeamParameters& beam,
                                             const Experiment& experiment, const std::vector<std::string>& keys,
                                             std::shared_ptr<const OutputFilter> filter) {
  if (!has_exact_sensitivities(experiment))
    throw InputError("excitation = '" + experiment.excitation +
                     "': exact sensitivities are available for a pulse from rest only");
  if (!has_exact_sensitivities(experiment, keys))
    throw InputError(
        "sensitivities with respect to l: the force or sensor is given in metres, so its place on the "
        "span moves with l, which the modal derivatives do not include (use differences)");
  std::vector<galerkin::SecondOrderSystem> derivatives;  // dM, dC, dK per key (InputError for a bad key, first)
  for (const auto& key : keys) derivatives.push_back(galerkin::parameter_derivative(forms, beam, key));
  SensitivityTrace out;
  out.keys = keys;
  const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
  ResponseProblem p = make_problem(forms, system, experiment, beam.l);
  p.output_filter = std::move(filter);
  std::optional<galerkin::StateSpaceModes> modes;  // decomposed once, for the output and its derivatives
  try {
    modes.emplace(system);
  } catch (const NumericalError&) {
    out.trace = ModalSimulator().run(system, p);  // the simulator's own failure trace and status
    return out;
  }
  out.trace = ModalSimulator().run(*modes, system, p);
  if (!out.trace.ok()) return out;
  try {
    const ModalDerivatives d = modal_derivatives(system, p, *modes, derivatives);
    const auto np = static_cast<Eigen::Index>(keys.size());
    if (p.output_filter) {
      out.dy_dq = filtered_sensitivities(d, p, derivatives, system, np);
      return out;
    }
    out.dy_dq = Eigen::MatrixXd::Zero(p.samples, np);
    const double tau = p.pulse_width_s;
    const int first_free = static_cast<int>(std::min<double>(p.samples, std::floor(tau / p.dt_s) + 1));
    add_in_pulse(out.dy_dq, d, p, first_free, derivatives, system, 1);
    if (first_free < p.samples)
      for (const FreeSensitivity& mode : free_sensitivities(d, tau)) add_free(out.dy_dq, mode, tau, p.dt_s, first_free);
  } catch (const NumericalError& error) {
    out.trace.status = std::string("sensitivities: ") + error.what();
    out.dy_dq.resize(0, 0);
  }
  return out;
}

}  // namespace beamid::simulation
