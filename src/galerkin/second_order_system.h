// The Galerkin second-order system  M w'' + C w' + K w = F(t),  w = (a; b) in R^{2(N+2)},
// u^N = sum a_j beta_j (displacement), alpha^N = sum b_j beta_j (section rotation), model.md section 2:
//
//   M = [ rho G0 + m nu nu^T      m c nu nu^T                       ]   (rigid clamp; see BeamForms for a compliant
//   one)
//       [ m c nu nu^T             rho_r2 G0 + (J_o + m c^2) nu nu^T ]
//   K = kAG S + EI B,   C = kAcs S + cDI B + gamma T,   M = rho T + rho_r2 R + tip terms, with the parameter-free
//   S = [ G11  -G10 ; -G10^T  G0 ]  (shear form of <u_x - alpha, phi1_x - phi2>),
//   B = [ 0 0 ; 0 G11 ] (bending),  T = [ G0 0 ; 0 0 ] (translation),  R = [ 0 0 ; 0 G0 ] (rotation),
// where G0, G11, G10 are the Gram matrices on [0, l] (l G0_ref, G11_ref / l, G10_ref).
// The matrices are linear in the parameters: BeamForms holds S, B, T, R and the tip blocks once per (N, l), and
// combine() forms M, C, K for any parameter values with a few scaled additions.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "galerkin/spline_space.h"
#include "model/beam_parameters.h"

namespace beamid::galerkin {

struct SecondOrderSystem {
  Eigen::MatrixXd M, C, K;  // all symmetric, size 2(N+2)
};

struct BeamForms {
  // Parameter-free forms of `space` mapped to [0, length_m] (InputError unless length_m is finite and > 0), for a
  // clamp of the given kind: a block whose root spring is finite (support.rotation_free() for alpha,
  // deflection_free() for u) takes the unclamped space B_{-1..N+1} (N + 3 functions), a rigid one the clamped space
  // (N + 2). The springs' values enter in combine(); only which roots are free is fixed here.
  BeamForms(const SplineSpace& space, double length_m, const model::Support& support = {});

  SplineSpace space;
  double length_m;
  bool deflection_free = false, rotation_free = false;
  Eigen::MatrixXd u_basis, alpha_basis;  // the blocks' bases in B_{-1..N+1}: clamping() or the identity
  Eigen::MatrixXd shear, bending, translation, rotation;  // S, B, T, R above
  Eigen::MatrixXd tip_uu, tip_ua, tip_aa;  // [nu nu^T 0; 0 0], [0 nu nu_a^T; nu_a nu^T 0], [0 0; 0 nu_a nu_a^T]
  Eigen::MatrixXd root_uu, root_aa;        // e e^T of the root values in the u and alpha blocks (zero when clamped)
  // The shear form's parts by their scaling with the length: S = S_uu + S_ua + S_aa at length_m, and at another
  // length l, S(l) = (length_m / l) S_uu + S_ua + (l / length_m) S_aa (G11 scales as 1/l, G10 not at all, G0 as l).
  Eigen::MatrixXd shear_uu, shear_ua, shear_aa;

  int u_dimension() const { return static_cast<int>(u_basis.rows()); }
  int alpha_dimension() const { return static_cast<int>(alpha_basis.rows()); }
  int dimension() const { return u_dimension() + alpha_dimension(); }
  // The u block's (alpha_block false) or alpha block's basis values beta(xi) and d beta / d xi at the fraction
  // xi = x / l of the span (InputError unless 0 <= xi <= 1): loads, sensors and bodies on a beam of any length.
  Eigen::VectorXd block_values(double xi, bool alpha_block) const;
  Eigen::VectorXd block_slopes(double xi, bool alpha_block) const;
};

// M, C, K for the given parameters; the support's free roots must be those of the forms (InputError otherwise).
// A beam length other than forms.length_m scales the forms in closed form (the spline space lives on [0, 1]):
// T, R and G0 blocks by l / l_0, bending by l_0 / l, the shear form by parts (BeamForms::shear_uu ...), and bodies
// on the span are placed at x / l; at l = l_0 the result is the unscaled one exactly. Each attachment adds [m v v^T, m
// c v w^T; m c w v^T, (J + m c^2) w w^T] to M, v and w the u- and alpha-block values at x (model/beam_parameters.h); a
// compliant clamp adds k_theta e_a e_a^T and k_w e_u e_u^T to K (the springs' energy (1/2) k_theta alpha(0)^2 + (1/2)
// k_w u(0)^2).
SecondOrderSystem combine(const BeamForms& forms, const model::BeamParameters& beam);

// dM/dq, dC/dq, dK/dq for the beam parameter `key` at `beam` (exact: M, C, K are linear in every parameter but the
// tip offset c, which enters M as m c and m c^2, and an attachment's position x, which enters through beta(x/l)),
// for the lumped keys, "support.k_theta", "support.k_w" (when the forms' root is free) and "attachmentK.m", ".J",
// ".x", and "l" (the derivative of the closed-form scaling, bodies held at their distance from the clamp).
// InputError for a key the beam does not have.
SecondOrderSystem parameter_derivative(const BeamForms& forms, const model::BeamParameters& beam,
                                       const std::string& key);

// Convenience: BeamForms(space, beam.l) then combine.
SecondOrderSystem assemble(const SplineSpace& space, const model::BeamParameters& beam);

// Generalised load of a unit transverse point force at x_m: F = [beta(x_m); 0] (also the displacement sensor row).
Eigen::VectorXd point_load(const BeamForms& forms, double x_m);
// The same on a beam of length length_m (the forms' own length or another, see combine): beta(x_m / length_m).
Eigen::VectorXd point_load(const BeamForms& forms, double x_m, double length_m);

}  // namespace beamid::galerkin
