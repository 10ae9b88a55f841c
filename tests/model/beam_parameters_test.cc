// Beam parameters: presets, validation, and strict TOML loading with located errors.
#include "model/beam_parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "config/beam_file.h"
#include "core/errors.h"

namespace beamid::model {
namespace {

// The shipped example beam file (the banks-aluminium preset), read once.
const std::string kValid = [] {
  std::ifstream in(std::string(BEAMID_SOURCE_DIR) + "/tests/data/banks-aluminium.toml");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}();

std::string error_of(const std::string& text) {
  try {
    config::parse_beam_toml(text, "beam.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(BeamParameters, PresetsAreAdmissibleAndDistinct) {
  for (const auto& name : preset_names()) EXPECT_FALSE(validation_error(preset(name))) << name;
  EXPECT_DOUBLE_EQ(preset("banks-aluminium").EI, 0.491);
  EXPECT_DOUBLE_EQ(preset("thick-steel").kAcs, 490.0);
  EXPECT_THROW(preset("steel"), InputError);
}

TEST(BeamParameters, TableCoversEveryMemberOnce) {
  BeamParameters p;
  double value = 1;
  for (const auto& info : parameter_table()) p.*info.member = value++;
  EXPECT_EQ(p.l, 1);
  EXPECT_EQ(p.J_o, 11);
  EXPECT_EQ(parameter_keys(), "l, rho, rho_r2, kAG, EI, gamma, cDI, kAcs, m, c, J_o");
}

TEST(BeamParameters, ValidationNamesKeyValueAndConstraint) {
  BeamParameters p = preset("thick-steel");
  p.EI = -1;
  EXPECT_EQ(validation_error(p).value_or(""), "EI = -1: must be > 0");
  p = preset("thick-steel");
  p.gamma = -0.5;
  EXPECT_EQ(validation_error(p).value_or(""), "gamma = -0.5: must be >= 0");
  p = preset("thick-steel");
  p.m = std::nan("");
  EXPECT_EQ(validation_error(p).value_or(""), "m = nan: must be finite");
  p = preset("thick-steel");
  p.cDI = 0;  // zero damping is admissible
  EXPECT_FALSE(validation_error(p));
}

TEST(BeamParameters, EstimableKeysIncludeSpringsAndAttachmentsTheBeamHas) {
  BeamParameters beam = preset("thick-steel");
  EXPECT_EQ(estimable_keys(beam), "l, rho, rho_r2, kAG, EI, gamma, cDI, kAcs, m, c, J_o");
  EXPECT_FALSE(describe_parameter(beam, "support.k_theta"));  // rigid: no finite value to start from
  EXPECT_THROW(parameter_value(beam, "support.k_theta"), InputError);
  beam.support.k_theta = 2e4;
  beam.attachments = {{0.2, 0.1, 1e-6, 0.0}};
  EXPECT_EQ(estimable_keys(beam),
            "l, rho, rho_r2, kAG, EI, gamma, cDI, kAcs, m, c, J_o, support.k_theta, attachment1.m, attachment1.J, "
            "attachment1.x");
  EXPECT_EQ(parameter_value(beam, "support.k_theta"), 2e4);
  EXPECT_EQ(parameter_value(beam, "attachment1.x"), 0.2);
  set_parameter_value(beam, "attachment1.m", 0.25);
  EXPECT_EQ(beam.attachments[0].m, 0.25);
  set_parameter_value(beam, "EI", 1000);
  EXPECT_EQ(beam.EI, 1000);
  EXPECT_EQ(parameter_role("attachment7.x"), "geometry");
  EXPECT_EQ(parameter_role("attachment1.J"), "inertia");
  EXPECT_EQ(parameter_role("support.k_w"), "stiffness");
  EXPECT_EQ(parameter_role("EI"), "stiffness");
  EXPECT_EQ(parameter_role("attachment0.m"), "");  // attachments count from 1
  EXPECT_EQ(parameter_role("attachment1.c"), "");  // the offset is not estimable
  for (const char* bad : {"attachment2.m", "attachment01.m", "attachment.m", "attachment1", "support.k_w", "EJ"})
    EXPECT_FALSE(describe_parameter(beam, bad)) << bad;
  set_parameter_value(beam, "l", 0.31);
  EXPECT_EQ(beam.l, 0.31);
}

TEST(BeamToml, ReadsAllKeysMatchingThePreset) {
  const BeamParameters p = config::parse_beam_toml(kValid, "beam.toml");
  const BeamParameters q = preset("banks-aluminium");
  for (const auto& info : parameter_table()) EXPECT_DOUBLE_EQ(p.*info.member, q.*info.member) << info.key;
  // Integers are accepted as numbers.
  EXPECT_DOUBLE_EQ(config::parse_beam_toml(replace(kValid, "kAcs = 9.73", "kAcs = 10"), "b").kAcs, 10.0);
}

TEST(BeamToml, AttachmentsAreReadInFileOrderWithDefaults) {
  const std::string text = std::string(kValid) +
                           "\n[[attachment]]   # a sensor board 6 cm from the tip\nx = 0.3973\nm = 0.012\nJ = 1e-6\n"
                           "\n[[attachment]]\nx = 0.2\nm = 0.004\nc = -0.01\n";
  const BeamParameters p = config::parse_beam_toml(text, "beam.toml");
  ASSERT_EQ(p.attachments.size(), 2u);
  EXPECT_EQ(p.attachments[0], (Attachment{0.3973, 0.012, 1e-6, 0.0}));
  EXPECT_EQ(p.attachments[1], (Attachment{0.2, 0.004, 0.0, -0.01}));
  EXPECT_FALSE(validation_error(p));
  EXPECT_TRUE(config::parse_beam_toml(kValid, "beam.toml").attachments.empty());
}

TEST(BeamToml, SupportSpringsAreReadAndAbsentMeansRigid) {
  const BeamParameters rigid = config::parse_beam_toml(kValid, "beam.toml");
  EXPECT_TRUE(rigid.support.rigid());
  const BeamParameters both = config::parse_beam_toml(kValid + "[support]\nk_theta = 350\nk_w = 2e6\n", "beam.toml");
  EXPECT_EQ(both.support.k_theta, 350.0);
  EXPECT_EQ(both.support.k_w, 2e6);
  const BeamParameters rotation = config::parse_beam_toml(kValid + "[support]\nk_theta = 350\n", "beam.toml");
  EXPECT_TRUE(rotation.support.rotation_free());
  EXPECT_FALSE(rotation.support.deflection_free());
  // The springs' range is the beam's own stiffness times [1e-2, 1e10] (model::spring_range): EI/l = 1.0737 N m for
  // k_theta, EI/l^3 = 5.134 N/m for k_w on this beam.
  EXPECT_EQ(error_of(kValid + "[support]\nk_theta = 0\n"),
            "beam.toml:16: support.k_theta = 0: must be in [0.01074, 1.074e+10] N m/rad (k_theta l/EI in "
            "[0.01, 1e+10] with EI = 0.491, l = 0.4573; softer is a hinge, stiffer is rigid: omit it)");
  EXPECT_EQ(error_of(kValid + "[support]\nk_w = -3\n"),
            "beam.toml:16: support.k_w = -3: must be in [0.05134, 5.134e+10] N/m (k_w l^3/EI in [0.01, "
            "1e+10] with EI = 0.491, l = 0.4573; softer is a hinge, stiffer is rigid: omit it)");
  // The adversarial pass's springs, which ended in "K is not positive definite" with no key named.
  for (const char* spring : {"k_theta = 1e-10", "k_theta = 1e20", "k_w = 1e-12", "k_w = 1e15"})
    EXPECT_NE(error_of(kValid + "[support]\n" + spring + "\n").find("beam.toml:16: support.k_"), std::string::npos)
        << spring;
  EXPECT_EQ(error_of(kValid + "[support]\nk_x = 3\n"),
            "beam.toml:16: unknown key support.k_x: valid keys are k_theta, k_w");
  BeamParameters beam = preset("thick-steel");
  beam.support.k_w = 0;
  EXPECT_EQ(*validation_error(beam), "support.k_w = 0: must be > 0 (omit it for a rigid clamp)");
}

TEST(BeamToml, ATipBodyNoRigHasIsRefusedOnItsLine) {
  // The adversarial pass's tip bodies: 1e6 kg (a failed eigenproblem with no key named) and J_o = 1e3 kg m^2 on a
  // 50 g body (accepted; modes at 0.06 Hz). The bounds: 1e4 rho l, and (m + rho l) l^2.
  EXPECT_EQ(error_of(replace(kValid, "m = 0.050", "m = 1e6")),
            "beam.toml:12: beam.m = 1e+06: the tip body must be at most 1e+04 times the beam's mass (rho l = "
            "0.04253 kg): at most 425.3 kg");
  EXPECT_EQ(error_of(replace(kValid, "J_o = 5.208e-6", "J_o = 1e3")),
            "beam.toml:14: beam.J_o = 1000: the tip body's inertia about its centre must be at most (m + rho l) l^2 = "
            "0.01935 kg m^2 (the body's and the beam's mass at a radius of gyration of a beam length)");
  // A body of no mass has no inertia (the thirty-first pass's adv71 P6: m = 0, J_o = 0.008 moved mode 1 to 1.79 Hz).
  EXPECT_EQ(error_of(replace(replace(kValid, "m = 0.050", "m = 0"), "J_o = 5.208e-6", "J_o = 0.008")),
            "beam.toml:14: beam.J_o = 0.008: the tip body has no mass (m = 0), so no inertia; give its mass m");
  // The largest admissible body is admissible.
  EXPECT_NO_THROW(config::parse_beam_toml(replace(kValid, "m = 0.050", "m = 425"), "beam.toml"));
}

TEST(BeamToml, AttachmentErrorsNameLineKeyValueAndConstraint) {
  const std::string base = std::string(kValid) + "[[attachment]]\n";  // the table opens on line 15
  EXPECT_EQ(error_of(base + "x = 0.5\nm = 0.01\n"),
            "beam.toml:16: attachment1.x = 0.5: must be in (0, l] m, measured from the clamp (l = 0.4573 m)");
  EXPECT_EQ(error_of(base + "x = 0.1\nm = -1\n"),
            "beam.toml:17: attachment1.m = -1: must be in [0, 425.3] kg (at most 1e+04 times the beam's mass rho l "
            "= 0.04253 kg)");
  // A body 1e4 times the beam's mass, or whose radius of gyration exceeds a beam length, is no rig (and ended in a
  // failed eigenproblem with no key named): refused with the line, the key and the bound.
  EXPECT_EQ(error_of(base + "x = 0.1\nm = 1e6\n"),
            "beam.toml:17: attachment1.m = 1e+06: must be in [0, 425.3] kg (at most 1e+04 times the beam's mass rho "
            "l = 0.04253 kg)");
  EXPECT_EQ(error_of(base + "x = 0.1\nm = 0.001\nJ = 1e6\n"),
            "beam.toml:18: attachment1.J = 1e+06: must be in [0, (m + rho l) l^2 = 0.009103] kg m^2 (about the "
            "body's centre; the body's and the beam's mass at a radius of gyration of a beam length)");
  EXPECT_EQ(error_of(base + "x = 0.1\nm = 1\nc = 0.5\n"),
            "beam.toml:18: attachment1.c = 0.5: must be in [-l, l] m: the body's centre lies within a beam length of "
            "its fixing point (l = 0.4573 m)");
  EXPECT_EQ(error_of(base + "x = 0.1\n"), "beam.toml:15: [attachment1] is missing key 'm'");
  EXPECT_EQ(error_of(base + "x = 0.1\nm = 1\nmass = 2\n"),
            "beam.toml:18: unknown key attachment1.mass: valid keys are x, m, J, c");
  EXPECT_EQ(error_of("attachment = 3\n" + kValid), "beam.toml:1: attachment = 3: must be an array");
  // The second table is named attachment2.
  EXPECT_EQ(error_of(base + "x = 0.1\nm = 1\n[[attachment]]\nx = 0\nm = 1\n"),
            "beam.toml:19: attachment2.x = 0: must be in (0, l] m, measured from the clamp (l = 0.4573 m)");
  // At most kMaxAttachments = 100 bodies (core/limits.h).
  std::string many = kValid;
  for (int k = 0; k < 101; ++k) many += "[[attachment]]\nx = 0.1\nm = 0.001\n";
  EXPECT_EQ(error_of(many), "beam.toml:15: attachment = [101 tables]: must hold at most 100 attachments");
  // The model's own check names the same constraint for beams built in code.
  BeamParameters beam = preset("thick-steel");
  beam.attachments.push_back({0.1, 1.0, -1.0, 0.0});
  EXPECT_EQ(*validation_error(beam), "attachment1.J = -1: must be finite and >= 0 (kg m^2)");
}

TEST(BeamToml, ErrorsNameFileLineKeyValueAndConstraint) {
  EXPECT_EQ(error_of(replace(kValid, "EI = 0.491", "EI = -0.491")), "beam.toml:8: beam.EI = -0.491: must be > 0");
  EXPECT_EQ(error_of(replace(kValid, "gamma = 0.013", "gamma = -1")), "beam.toml:9: beam.gamma = -1: must be >= 0");
  EXPECT_EQ(error_of(replace(kValid, "rho = 0.093", "rho = nan")), "beam.toml:5: beam.rho = nan: must be finite");
  EXPECT_EQ(error_of(replace(kValid, "m = 0.050", "m = \"heavy\"")), "beam.toml:12: beam.m must be a number in kg");
  EXPECT_EQ(error_of(replace(kValid, "c = 0.0125         # m        tip body offset beyond the tip\n", "")),
            "beam.toml:3: [beam] is missing key 'c' (tip body offset beyond the tip, m)");
  EXPECT_EQ(error_of(replace(kValid, "J_o = 5.208e-6     # kg m^2   tip body inertia about its centre of mass",
                             "J_o = 5.208e-6\nEA = 1")),
            "beam.toml:15: unknown key beam.EA: valid keys are l, rho, rho_r2, kAG, EI, gamma, cDI, kAcs, m, c, J_o");
  EXPECT_EQ(error_of(std::string(kValid) + "[fit]\nx = 1\n"),
            "beam.toml:15: unknown top-level key 'fit': a beam file holds one table, [beam] (lumped parameters) or "
            "[geometry], any number of [[attachment]] tables and an optional [support]");
  EXPECT_NE(error_of("[beam\nl = 1").find("beam.toml:1: TOML syntax error"), std::string::npos);
  EXPECT_EQ(
      error_of("l = 1\n"),
      "beam.toml:1: unknown top-level key 'l': a beam file holds one table, [beam] (lumped parameters) or [geometry], "
      "any number of [[attachment]] tables and an optional [support]");
  EXPECT_EQ(error_of(""),
            "beam.toml:1: missing table [beam] with keys l, rho, rho_r2, kAG, EI, gamma, cDI, kAcs, m, c, J_o");
}

TEST(BeamToml, ResolvesPresetsAndFiles) {
  EXPECT_DOUBLE_EQ(config::resolve_beam("thick-steel").EI, 1406.25);
  try {
    config::resolve_beam("/nonexistent/beam.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/beam.toml: cannot open beam file"), std::string::npos);
  }
}

}  // namespace
}  // namespace beamid::model
