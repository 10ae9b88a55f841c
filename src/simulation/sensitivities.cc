#include "simulation/sensitivities.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>

#include "core/errors.h"
#include "galerkin/complex_products.h"
#include "galerkin/modes.h"
#include "simulation/modal_simulator.h"

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

}  // namespace

bool has_exact_sensitivities(const Experiment& e) { return e.excitation == kPulse; }

bool has_exact_sensitivities(const Experiment& e, const std::vector<std::string>& keys) {
  const bool length = std::find(keys.begin(), keys.end(), "l") != keys.end();
  return has_exact_sensitivities(e) && !(length && (e.force_x_m || e.sensor_x_m));
}

SensitivityTrace simulate_with_sensitivities(const galerkin::BeamForms& forms, const model::BeamParameters& beam,
                                             const Experiment& experiment, const std::vector<std::string>& keys) {
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
  const ResponseProblem p = make_problem(forms, system, experiment, beam.l);
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
    out.dy_dq = Eigen::MatrixXd::Zero(p.samples, np);
    const double tau = p.pulse_width_s, dt = p.dt_s;
    const int first_free = static_cast<int>(std::min<double>(p.samples, std::floor(tau / dt) + 1));
    constexpr int kAnchorEvery = 256;
    for (Eigen::Index k = 0; k < d.lambda.size(); ++k) {
      const complex l = d.lambda(k);
      if (l.imag() < 0) continue;  // its conjugate partner carries it (2 Re below)
      const double weight = l.imag() > 0 ? 2.0 : 1.0;
      const Eigen::VectorXcd dr = weight * d.d_residue.row(k).transpose();
      const Eigen::VectorXcd rdl = weight * d.residue(k) * d.d_lambda.row(k).transpose();
      // Inside the pulse: closed forms at every sample (t = 0 is exactly 0: the pulse starts at rest with P(0) = 0).
      for (int i = 1; i < first_free; ++i) {
        const double t = i * dt;
        const complex rho = pulse_response(l, t, tau), drho = pulse_response_derivative(l, t, tau);
        for (Eigen::Index q = 0; q < np; ++q) out.dy_dq(i, q) += (dr(q) * rho + rdl(q) * drho).real();
      }
      if (first_free >= p.samples) continue;
      // After it: A_q + (t - tau) B_q times e^{lambda (t - tau)}, until that factor is below 1e-18 (the mode's
      // contribution has then fallen by 18 orders of magnitude from its size at tau).
      const complex rho_tau = pulse_response(l, tau, tau), drho_tau = pulse_response_derivative(l, tau, tau);
      const Eigen::VectorXcd a = dr * rho_tau + rdl * drho_tau, b = rdl * rho_tau;
      int last = p.samples - 1;
      if (l.real() < 0) {
        const double c = std::ceil((tau + std::log(1e-18) / l.real()) / dt);
        if (std::isfinite(c)) last = static_cast<int>(std::clamp<double>(c, first_free - 1.0, p.samples - 1.0));
      }
      const complex step = std::exp(l * dt);
      complex factor;
      for (int i = first_free; i <= last; ++i) {
        const double since = i * dt - tau;
        if ((i - first_free) % kAnchorEvery == 0) factor = std::exp(l * since);
        for (Eigen::Index q = 0; q < np; ++q) out.dy_dq(i, q) += (factor * (a(q) + since * b(q))).real();
        factor *= step;
      }
    }
    if (p.derivative == 2) {
      // The acceleration's direct term c^T M^-1 f P(t): d/dq = -c^T M^-1 dM M^-1 f P(t).
      const Eigen::LLT<Eigen::MatrixXd> mass(system.M);
      const Eigen::VectorXd mf = mass.solve(p.load), mc = mass.solve(p.sensor);
      for (Eigen::Index q = 0; q < np; ++q) {
        const double direct = -mc.dot(derivatives[static_cast<std::size_t>(q)].M * mf);
        for (int i = 1; i < first_free; ++i) out.dy_dq(i, q) += direct * p.force_N(i * dt);
      }
    }
  } catch (const NumericalError& error) {
    out.trace.status = std::string("sensitivities: ") + error.what();
    out.dy_dq.resize(0, 0);
  }
  return out;
}

}  // namespace beamid::simulation
