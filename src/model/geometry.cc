#include "model/geometry.h"

#include "core/errors.h"

namespace beamid::model {

BeamParameters lumped_parameters(const Geometry& g) {
  const auto positive = [](const char* key, double v) {
    if (!(v > 0)) throw InputError(std::string("geometry.") + key + " = " + format_value(v) + ": must be > 0");
  };
  positive("length_m", g.length_m);
  positive("width_m", g.width_m);
  positive("thickness_m", g.thickness_m);
  positive("youngs_modulus_Pa", g.youngs_modulus_Pa);
  positive("density_kg_m3", g.density_kg_m3);
  if (g.poisson_ratio.has_value() == g.shear_modulus_Pa.has_value())
    throw InputError("geometry: give exactly one of poisson_ratio and shear_modulus_Pa");
  if (g.poisson_ratio && !(*g.poisson_ratio > -1 && *g.poisson_ratio < 0.5))
    throw InputError("geometry.poisson_ratio = " + format_value(*g.poisson_ratio) + ": must be in (-1, 0.5)");
  if (g.shear_modulus_Pa) positive("shear_modulus_Pa", *g.shear_modulus_Pa);
  // With G given, nu = E/(2G) - 1 for Cowper's formula.
  const double nu = g.poisson_ratio ? *g.poisson_ratio : g.youngs_modulus_Pa / (2 * *g.shear_modulus_Pa) - 1;
  const double G = g.shear_modulus_Pa ? *g.shear_modulus_Pa : g.youngs_modulus_Pa / (2 * (1 + nu));
  const double kappa = g.shear_coefficient ? *g.shear_coefficient : 10 * (1 + nu) / (12 + 11 * nu);
  if (!(kappa > 0 && kappa <= 1))
    throw InputError("geometry.shear_coefficient = " + format_value(kappa) + ": must be in (0, 1]");
  const double area = g.width_m * g.thickness_m;
  const double inertia = g.width_m * g.thickness_m * g.thickness_m * g.thickness_m / 12;
  BeamParameters p;
  p.l = g.length_m;
  p.rho = g.density_kg_m3 * area;
  p.rho_r2 = g.density_kg_m3 * inertia;
  p.EI = g.youngs_modulus_Pa * inertia;
  p.kAG = kappa * area * G;
  if (g.tip_block_m) {
    const auto& a = *g.tip_block_m;
    if (a.size() != 3 || !(a[0] > 0 && a[1] > 0 && a[2] > 0))
      throw InputError(
          "geometry.tip_block_m: must be three sizes > 0, [along the beam, across, in the plane of vibration]");
    positive("tip_block_density_kg_m3", g.tip_block_density_kg_m3);
    if (g.tip_mass_kg != 0 || g.tip_offset_m != 0 || g.tip_inertia_kg_m2 != 0)
      throw InputError(
          "geometry: give the tip body either as tip_block_m or as tip_mass_kg, tip_offset_m, tip_inertia_kg_m2");
    p.m = g.tip_block_density_kg_m3 * a[0] * a[1] * a[2];
    p.c = a[0] / 2;
    p.J_o = p.m * (a[0] * a[0] + a[2] * a[2]) / 12;
  } else {
    p.m = g.tip_mass_kg;
    p.c = g.tip_offset_m;
    p.J_o = g.tip_inertia_kg_m2;
  }
  p.cDI = g.cDI;
  p.kAcs = g.kAcs;
  p.gamma = g.gamma;
  if (auto e = validation_error(p)) throw InputError("geometry gives inadmissible lumped parameters: " + *e);
  return p;
}

}  // namespace beamid::model
