// Lumped beam parameters from geometry and material, so that users need not work out kAG or rho_r2 by hand.
// A rectangular section b x h bending about its weak axis (h in the plane of vibration):
//   A = b h, I = b h^3 / 12, rho = density A, rho_r2 = density I, EI = E I, kAG = kappa A G,
//   G = E / (2 (1 + nu)) unless given, kappa = 10 (1 + nu) / (12 + 11 nu) (Cowper 1966, rectangle) or a number.
// Tip body, either lumped (mass, offset of its centre beyond the tip, inertia about its centre) or a solid block of
// given size and density fixed to the tip face: m = density a_x a_y a_z, c = a_x / 2, J_o = m (a_x^2 + a_z^2) / 12
// (a_x along the beam, a_z in the plane of vibration).
// Damping cannot come from geometry: cDI, kAcs and gamma are given as nominal values (starts for a fit).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "model/beam_parameters.h"

namespace beamid::model {

struct Geometry {
  double length_m = 0, width_m = 0, thickness_m = 0;
  double youngs_modulus_Pa = 0, density_kg_m3 = 0;
  std::optional<double> poisson_ratio, shear_modulus_Pa;  // one of them (nu also sets Cowper's kappa)
  std::optional<double> shear_coefficient;                // kappa; nothing: Cowper's rectangle (needs nu)
  double tip_mass_kg = 0, tip_offset_m = 0, tip_inertia_kg_m2 = 0;
  std::optional<std::vector<double>> tip_block_m;  // a_x, a_y, a_z
  double tip_block_density_kg_m3 = 0;
  double cDI = 0, kAcs = 0, gamma = 0;
};

// The lumped parameters (model.md section 1). InputError naming the field and constraint when inadmissible.
BeamParameters lumped_parameters(const Geometry& geometry);

}  // namespace beamid::model
