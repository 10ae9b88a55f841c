#include "galerkin/second_order_system.h"

#include <cmath>

#include "core/errors.h"

namespace beamid::galerkin {

namespace {
double checked_length(double length_m) {
  if (!(length_m > 0) || !std::isfinite(length_m))
    throw InputError("beam length l = " + format_value(length_m) + ": must be finite and > 0");
  return length_m;
}

// The inertia form of a rigid body, [m v v^T, m c v w^T; m c w v^T, (J + m c^2) w w^T], with v, w the u- and
// alpha-block vectors it acts through; with (v, w) and (v', w') it is the symmetric part needed for d/dx.
void add_body(Eigen::MatrixXd& m, const BeamForms& f, double mass, double mc, double j, const Eigen::VectorXd& v,
              const Eigen::VectorXd& w, const Eigen::VectorXd& v2, const Eigen::VectorXd& w2) {
  const Eigen::Index nu = f.u_dimension(), na = f.alpha_dimension();
  m.topLeftCorner(nu, nu) += mass * (v * v2.transpose());
  m.topRightCorner(nu, na) += mc * (v * w2.transpose());
  m.bottomLeftCorner(na, nu) += mc * (w * v2.transpose());
  m.bottomRightCorner(na, na) += j * (w * w2.transpose());
}

void require_on_beam(double x_m, double length_m) {
  if (!(x_m >= 0 && x_m <= length_m))
    throw InputError("position x = " + format_value(x_m) +
                     " m: must lie on the beam, 0 <= x <= l = " + format_value(length_m));
}

}  // namespace

BeamForms::BeamForms(const SplineSpace& s, double l, const model::Support& support)
    : space(s),
      length_m(checked_length(l)),
      deflection_free(support.deflection_free()),
      rotation_free(support.rotation_free()) {
  const int full = space.elements() + 3;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(full, full);
  u_basis = deflection_free ? identity : space.clamping();
  alpha_basis = rotation_free ? identity : space.clamping();
  const Eigen::MatrixXd& pu = u_basis;
  const Eigen::MatrixXd& pa = alpha_basis;
  const int nu_dim = u_dimension(), na_dim = alpha_dimension();
  // Gram matrices on [0, l] in each block's basis: int beta_i beta_j dx = l G0, int beta_i' beta_j' dx = G11 / l,
  // int beta_i' beta_j dx = G10 (scale-free). A clamped block takes the space's own (symmetrised) clamped matrices,
  // a free one the unclamped ones, and the mixed G10 is T_u G10_full T_a^T.
  const Eigen::MatrixXd g0_uu = length_m * (deflection_free ? space.full_G0() : space.G0());
  const Eigen::MatrixXd g0_aa = length_m * (rotation_free ? space.full_G0() : space.G0());
  const Eigen::MatrixXd g11_uu = (deflection_free ? space.full_G11() : space.G11()) / length_m;
  const Eigen::MatrixXd g11_aa = (rotation_free ? space.full_G11() : space.G11()) / length_m;
  const Eigen::MatrixXd g10_ua =
      (deflection_free || rotation_free) ? Eigen::MatrixXd(pu * space.full_G10() * pa.transpose()) : space.G10();
  const Eigen::VectorXd nu_u = pu * space.full_values(1.0), nu_a = pa * space.full_values(1.0);
  const Eigen::VectorXd e_u = pu * space.full_values(0.0), e_a = pa * space.full_values(0.0);
  const auto blocks = [&](const Eigen::MatrixXd& uu, const Eigen::MatrixXd& ua, const Eigen::MatrixXd& aa) {
    Eigen::MatrixXd m(nu_dim + na_dim, nu_dim + na_dim);
    m << uu, ua, ua.transpose(), aa;
    return m;
  };
  const Eigen::MatrixXd zero_uu = Eigen::MatrixXd::Zero(nu_dim, nu_dim),
                        zero_ua = Eigen::MatrixXd::Zero(nu_dim, na_dim),
                        zero_aa = Eigen::MatrixXd::Zero(na_dim, na_dim);
  // <u_x - alpha, phi1_x - phi2>: rows phi1 = beta_i give [G11, -G10], rows phi2 = beta_i give [-G10^T, G0].
  shear = blocks(g11_uu, -g10_ua, g0_aa);
  shear_uu = blocks(g11_uu, zero_ua, zero_aa);
  shear_ua = blocks(zero_uu, -g10_ua, zero_aa);
  shear_aa = blocks(zero_uu, zero_ua, g0_aa);
  bending = blocks(zero_uu, zero_ua, g11_aa);
  translation = blocks(g0_uu, zero_ua, zero_aa);
  rotation = blocks(zero_uu, zero_ua, g0_aa);
  tip_uu = blocks(nu_u * nu_u.transpose(), zero_ua, zero_aa);
  tip_ua = blocks(zero_uu, nu_u * nu_a.transpose(), zero_aa);
  tip_aa = blocks(zero_uu, zero_ua, nu_a * nu_a.transpose());
  // Clamped blocks have e = 0 (every clamped basis function vanishes at the root), so these are zero there.
  root_uu = blocks(e_u * e_u.transpose(), zero_ua, zero_aa);
  root_aa = blocks(zero_uu, zero_ua, e_a * e_a.transpose());
}

Eigen::VectorXd BeamForms::block_values(double xi, bool alpha_block) const {
  return (alpha_block ? alpha_basis : u_basis) * space.full_values(xi);
}

Eigen::VectorXd BeamForms::block_slopes(double xi, bool alpha_block) const {
  return (alpha_block ? alpha_basis : u_basis) * space.full_slopes(xi);
}

SecondOrderSystem combine(const BeamForms& f, const model::BeamParameters& p) {
  if (!(p.l > 0) || !std::isfinite(p.l)) throw InputError("beam length l = " + format_value(p.l) + ": must be > 0");
  if (p.support.rotation_free() != f.rotation_free || p.support.deflection_free() != f.deflection_free)
    throw InputError(std::string("the beam's clamp (") + (p.support.rigid() ? "rigid" : "compliant") +
                     ") differs from the one the Galerkin forms were made for: build them with BeamForms(space, l, "
                     "beam.support)");
  SecondOrderSystem s;
  // Tip inertia Lambda = [[m, m c], [m c, m c^2 + J_o]] acting on (u(l), alpha(l)). (Each sum is written out in one
  // expression, in the same order in both branches, so that the unscaled one rounds as it always has.)
  const double mc = p.m * p.c, j_tip = p.J_o + p.m * p.c * p.c;
  if (p.l == f.length_m) {
    s.M = p.rho * f.translation + p.rho_r2 * f.rotation + p.m * f.tip_uu + mc * f.tip_ua + j_tip * f.tip_aa;
    s.K = p.kAG * f.shear + p.EI * f.bending;
    s.C = p.kAcs * f.shear + p.cDI * f.bending + p.gamma * f.translation;
  } else {
    const double up = p.l / f.length_m, down = f.length_m / p.l;  // G0 ~ l, G11 ~ 1/l
    const Eigen::MatrixXd shear = down * f.shear_uu + f.shear_ua + up * f.shear_aa;
    s.M =
        (p.rho * up) * f.translation + (p.rho_r2 * up) * f.rotation + p.m * f.tip_uu + mc * f.tip_ua + j_tip * f.tip_aa;
    s.K = p.kAG * shear + (p.EI * down) * f.bending;
    s.C = p.kAcs * shear + (p.cDI * down) * f.bending + (p.gamma * up) * f.translation;
  }
  // Attachments: the same inertia Lambda_k acting on (u(x_k), alpha(x_k)), with the blocks' values at x_k in place of
  // the tip traces.
  for (const model::Attachment& a : p.attachments) {
    require_on_beam(a.x, p.l);
    const double xi = a.x / p.l;
    const Eigen::VectorXd v = f.block_values(xi, false), w = f.block_values(xi, true);
    add_body(s.M, f, a.m, a.m * a.c, a.J + a.m * a.c * a.c, v, w, v, w);
  }
  if (f.rotation_free) s.K += p.support.k_theta * f.root_aa;
  if (f.deflection_free) s.K += p.support.k_w * f.root_uu;
  return s;
}

SecondOrderSystem parameter_derivative(const BeamForms& f, const model::BeamParameters& p, const std::string& key) {
  const Eigen::Index n = f.dimension();
  SecondOrderSystem d{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  // The forms at the beam's length (combine): factors of 1 when it is the forms' own.
  const double up = p.l / f.length_m, down = f.length_m / p.l;
  const auto shear = [&] { return Eigen::MatrixXd(down * f.shear_uu + f.shear_ua + up * f.shear_aa); };
  const auto body_vectors = [&](const model::Attachment& a, Eigen::VectorXd& v, Eigen::VectorXd& w) {
    require_on_beam(a.x, p.l);
    v = f.block_values(a.x / p.l, false);
    w = f.block_values(a.x / p.l, true);
  };
  if (key == "rho") {
    d.M = up * f.translation;
  } else if (key == "rho_r2") {
    d.M = up * f.rotation;
  } else if (key == "m") {
    d.M = f.tip_uu + p.c * f.tip_ua + p.c * p.c * f.tip_aa;
  } else if (key == "c") {
    d.M = p.m * f.tip_ua + 2 * p.m * p.c * f.tip_aa;
  } else if (key == "J_o") {
    d.M = f.tip_aa;
  } else if (key == "kAG") {
    d.K = shear();
  } else if (key == "EI") {
    d.K = down * f.bending;
  } else if (key == "kAcs") {
    d.C = shear();
  } else if (key == "cDI") {
    d.C = down * f.bending;
  } else if (key == "gamma") {
    d.C = up * f.translation;
  } else if (key == "l") {
    // d up / dl = 1 / l_0, d down / dl = -down / l; bodies stay at x from the clamp, so beta(x/l) moves with l:
    // d/dl beta(x/l) = -(x / l^2) beta'(x/l).
    const Eigen::MatrixXd d_shear = (-down / p.l) * f.shear_uu + (1 / f.length_m) * f.shear_aa;
    d.M = (p.rho / f.length_m) * f.translation + (p.rho_r2 / f.length_m) * f.rotation;
    d.K = p.kAG * d_shear - (p.EI * down / p.l) * f.bending;
    d.C = p.kAcs * d_shear - (p.cDI * down / p.l) * f.bending + (p.gamma / f.length_m) * f.translation;
    for (const model::Attachment& a : p.attachments) {
      Eigen::VectorXd v, w;
      body_vectors(a, v, w);
      const double factor = -a.x / (p.l * p.l);
      const Eigen::VectorXd dv = factor * f.block_slopes(a.x / p.l, false);
      const Eigen::VectorXd dw = factor * f.block_slopes(a.x / p.l, true);
      add_body(d.M, f, a.m, a.m * a.c, a.J + a.m * a.c * a.c, dv, dw, v, w);
      add_body(d.M, f, a.m, a.m * a.c, a.J + a.m * a.c * a.c, v, w, dv, dw);
    }
  } else if (key == "support.k_theta" && f.rotation_free) {
    d.K = f.root_aa;
  } else if (key == "support.k_w" && f.deflection_free) {
    d.K = f.root_uu;
  } else if (const auto body = model::attachment_field(key); body && model::describe_parameter(p, key)) {
    // attachmentK.m, .J, .x (describe_parameter checked that the beam has body K and the field is estimable).
    const model::Attachment& a = p.attachments[body->first];
    Eigen::VectorXd v, w;
    body_vectors(a, v, w);
    const std::string& field = body->second;
    if (field == "m") add_body(d.M, f, 1, a.c, a.c * a.c, v, w, v, w);
    if (field == "J") add_body(d.M, f, 0, 0, 1, v, w, v, w);
    if (field == "x") {
      // d/dx of Lambda-weighted outer products: (v' v^T + v v'^T) and likewise, v' = d beta(x/l)/dx = beta'(x/l)/l.
      const Eigen::VectorXd dv = f.block_slopes(a.x / p.l, false) / p.l;
      const Eigen::VectorXd dw = f.block_slopes(a.x / p.l, true) / p.l;
      add_body(d.M, f, a.m, a.m * a.c, a.J + a.m * a.c * a.c, dv, dw, v, w);
      add_body(d.M, f, a.m, a.m * a.c, a.J + a.m * a.c * a.c, v, w, dv, dw);
    }
  } else {
    throw InputError("parameter '" + key + "': the Galerkin matrices have no derivative with respect to it (not a " +
                     "parameter of this beam: " + model::estimable_keys(p) + ")");
  }
  return d;
}

SecondOrderSystem assemble(const SplineSpace& space, const model::BeamParameters& beam) {
  return combine(BeamForms(space, beam.l, beam.support), beam);
}

Eigen::VectorXd point_load(const BeamForms& forms, double x_m) { return point_load(forms, x_m, forms.length_m); }

Eigen::VectorXd point_load(const BeamForms& forms, double x_m, double length_m) {
  require_on_beam(x_m, length_m);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(forms.dimension());
  f.head(forms.u_dimension()) = forms.block_values(x_m / length_m, false);
  return f;
}

}  // namespace beamid::galerkin
