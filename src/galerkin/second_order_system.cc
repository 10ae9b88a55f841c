#include "galerkin/second_order_system.h"

#include <cmath>

#include "model/errors.h"

namespace beamid::galerkin {

namespace {
double checked_length(double length_m) {
  if (!(length_m > 0) || !std::isfinite(length_m))
    throw InputError("beam length l = " + format_value(length_m) + ": must be finite and > 0");
  return length_m;
}
}  // namespace

BeamForms::BeamForms(const SplineSpace& s, double l) : space(s), length_m(checked_length(l)) {
  const int n = space.dimension();
  const Eigen::MatrixXd g0 = length_m * space.G0();    // int_0^l beta_i beta_j dx
  const Eigen::MatrixXd g11 = space.G11() / length_m;  // int_0^l beta_i' beta_j' dx
  const Eigen::MatrixXd& g10 = space.G10();            // int_0^l beta_i' beta_j dx (scale-free)
  const Eigen::VectorXd& nu = space.tip_trace();
  const Eigen::MatrixXd nnt = nu * nu.transpose();
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(n, n);

  const auto blocks = [n](const Eigen::MatrixXd& uu, const Eigen::MatrixXd& ua, const Eigen::MatrixXd& au,
                          const Eigen::MatrixXd& aa) {
    Eigen::MatrixXd m(2 * n, 2 * n);
    m << uu, ua, au, aa;
    return m;
  };
  // <u_x - alpha, phi1_x - phi2>: rows phi1 = beta_i give [G11, -G10], rows phi2 = beta_i give [-G10^T, G0].
  shear = blocks(g11, -g10, -g10.transpose(), g0);
  bending = blocks(zero, zero, zero, g11);
  translation = blocks(g0, zero, zero, zero);
  rotation = blocks(zero, zero, zero, g0);
  tip_uu = blocks(nnt, zero, zero, zero);
  tip_ua = blocks(zero, nnt, nnt, zero);
  tip_aa = blocks(zero, zero, zero, nnt);
}

Eigen::VectorXd BeamForms::values_at(double x_m) const {
  if (!(x_m >= 0 && x_m <= length_m))
    throw InputError("position x = " + format_value(x_m) +
                     " m: must lie on the beam, 0 <= x <= l = " + format_value(length_m));
  return space.values(x_m / length_m);
}

SecondOrderSystem combine(const BeamForms& f, const model::BeamParameters& p) {
  if (p.l != f.length_m)
    throw InputError("beam length l = " + format_value(p.l) +
                     " differs from the length the Galerkin forms were made for (" + format_value(f.length_m) + ")");
  // Tip inertia Lambda = [[m, m c], [m c, m c^2 + J_o]] acting on (u(l), alpha(l)).
  SecondOrderSystem s;
  s.M = p.rho * f.translation + p.rho_r2 * f.rotation + p.m * f.tip_uu + (p.m * p.c) * f.tip_ua +
        (p.J_o + p.m * p.c * p.c) * f.tip_aa;
  // Attachments: the same inertia Lambda_k acting on (u(x_k), alpha(x_k)), with v = beta(x_k / l) in place of nu.
  const Eigen::Index n = f.space.dimension();
  for (const model::Attachment& a : p.attachments) {
    const Eigen::VectorXd v = f.values_at(a.x);
    const Eigen::MatrixXd vvt = v * v.transpose();
    s.M.topLeftCorner(n, n) += a.m * vvt;
    s.M.topRightCorner(n, n) += (a.m * a.c) * vvt;
    s.M.bottomLeftCorner(n, n) += (a.m * a.c) * vvt;
    s.M.bottomRightCorner(n, n) += (a.J + a.m * a.c * a.c) * vvt;
  }
  s.K = p.kAG * f.shear + p.EI * f.bending;
  s.C = p.kAcs * f.shear + p.cDI * f.bending + p.gamma * f.translation;
  return s;
}

SecondOrderSystem parameter_derivative(const BeamForms& f, const model::BeamParameters& p, const std::string& key) {
  const Eigen::Index n = f.dimension();
  SecondOrderSystem d{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  if (key == "rho") {
    d.M = f.translation;
  } else if (key == "rho_r2") {
    d.M = f.rotation;
  } else if (key == "m") {
    d.M = f.tip_uu + p.c * f.tip_ua + p.c * p.c * f.tip_aa;
  } else if (key == "c") {
    d.M = p.m * f.tip_ua + 2 * p.m * p.c * f.tip_aa;
  } else if (key == "J_o") {
    d.M = f.tip_aa;
  } else if (key == "kAG") {
    d.K = f.shear;
  } else if (key == "EI") {
    d.K = f.bending;
  } else if (key == "kAcs") {
    d.C = f.shear;
  } else if (key == "cDI") {
    d.C = f.bending;
  } else if (key == "gamma") {
    d.C = f.translation;
  } else {
    throw InputError("parameter '" + key + "': the Galerkin matrices have no derivative with respect to it (" +
                     (key == "l" ? std::string("the forms are built for one length") : "not a beam parameter") + ")");
  }
  return d;
}

SecondOrderSystem assemble(const SplineSpace& space, const model::BeamParameters& beam) {
  return combine(BeamForms(space, beam.l), beam);
}

Eigen::VectorXd point_load(const BeamForms& forms, double x_m) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(forms.dimension());
  f.head(forms.space.dimension()) = forms.values_at(x_m);
  return f;
}

}  // namespace beamid::galerkin
