// Beams from geometry: the thick-steel preset (model.md set B) is itself defined by its geometry, so a [geometry]
// file with its dimensions must give its lumps exactly; the tip block's lumps follow from the solid's formulas.
#include <gtest/gtest.h>

#include "config/beam_file.h"
#include "core/errors.h"

namespace beamid::model {
namespace {

const char* kThick = R"([geometry]
length_m = 0.30
width_m = 0.025
thickness_m = 0.015
youngs_modulus_Pa = 200e9
poisson_ratio = 0.3
density_kg_m3 = 7850
shear_coefficient = "cowper"
tip_mass_kg = 0.314
tip_offset_m = 0.02
tip_inertia_kg_m2 = 8.373333333333333e-5
cDI = 2.81e-3
kAcs = 490
gamma = 2
)";

std::string error_of(const std::string& text) {
  try {
    config::parse_beam_toml(text, "g.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

TEST(Geometry, ThickSteelFromItsGeometryIsThePreset) {
  const BeamParameters g = config::parse_beam_toml(kThick, "g.toml");
  const BeamParameters p = preset("thick-steel");
  // Same formulas and inputs: equal to round-off (a few ulp from the order of operations).
  for (const auto& info : parameter_table())
    EXPECT_NEAR(g.*info.member, p.*info.member, 1e-14 * std::abs(p.*info.member)) << info.key;
}

TEST(Geometry, TipBlockGivesMassOffsetAndInertia) {
  // A 40 mm cube whose density makes m = 0.314 kg: c = 20 mm, J_o = m (a^2 + a^2)/12, as in the preset.
  const std::string block =
      replaced(replaced(replaced(kThick, "tip_mass_kg = 0.314\n", ""), "tip_offset_m = 0.02\n", ""),
               "tip_inertia_kg_m2 = 8.373333333333333e-5\n",
               "tip_block_m = [0.04, 0.04, 0.04]\ntip_block_density_kg_m3 = 4906.25\n");
  const BeamParameters g = config::parse_beam_toml(block, "g.toml");
  EXPECT_NEAR(g.m, 0.314, 1e-15);
  EXPECT_NEAR(g.c, 0.02, 1e-16);
  EXPECT_NEAR(g.J_o, 0.314 * 2 * 0.04 * 0.04 / 12, 1e-18);
  // Shear modulus instead of Poisson's ratio: G = E / (2 (1 + nu)) gives the same kAG (kappa from nu = E/2G - 1).
  const std::string with_g = replaced(kThick, "poisson_ratio = 0.3", "shear_modulus_Pa = 76923076923.07692");
  EXPECT_NEAR(config::parse_beam_toml(with_g, "g.toml").kAG, preset("thick-steel").kAG,
              1e-9 * preset("thick-steel").kAG);
}

TEST(Geometry, ErrorsNameLineKeyAndConstraint) {
  EXPECT_EQ(
      error_of(replaced(kThick, "thickness_m = 0.015", "thickness_m = -0.015")),
      "g.toml:4: geometry.thickness_m = -0.015: must be in (0, length_m / 2]: a beam is at least twice as long as it "
      "is thick (length_m = 0.3)");
  EXPECT_EQ(error_of(replaced(kThick, "density_kg_m3 = 7850", "density_kg_m3 = 7850\ncolour = 'grey'")),
            "g.toml:8: unknown key geometry.colour: valid keys are length_m, width_m, thickness_m, youngs_modulus_Pa, "
            "density_kg_m3, poisson_ratio, shear_modulus_Pa, shear_coefficient, tip_mass_kg, tip_offset_m, "
            "tip_inertia_kg_m2, tip_block_m, tip_block_density_kg_m3, cDI, kAcs, gamma");
  EXPECT_EQ(error_of(replaced(kThick, "poisson_ratio = 0.3", "poisson_ratio = 0.3\nshear_modulus_Pa = 8e10")),
            "g.toml:1: [geometry] needs exactly one of poisson_ratio and shear_modulus_Pa");
  EXPECT_EQ(error_of(replaced(kThick, "shear_coefficient = \"cowper\"", "shear_coefficient = 1.2")),
            "g.toml:8: geometry.shear_coefficient = 1.2: must be 'cowper' or a number in (0, 1]");
  EXPECT_EQ(error_of(replaced(kThick, "gamma = 2\n", "")), "g.toml:1: [geometry] is missing key 'gamma'");
  EXPECT_EQ(error_of(std::string(kThick) + "[beam]\nl = 1\n").substr(0, 60),
            "g.toml:1: give either [beam] (lumped parameters) or [geometr");
}

}  // namespace
}  // namespace beamid::model
