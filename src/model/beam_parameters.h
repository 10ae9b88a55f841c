// Lumped physical parameters of the cantilevered Timoshenko beam with a rigid tip body (model.md section 1).
//
//   rho u_tt - S_x + gamma u_t = f,   rho_r2 alpha_tt - M_x - S = 0,
//   M = EI alpha_x + cDI alpha_xt (Kelvin-Voigt),  S = kAG beta + kAcs beta_t,  beta = u_x - alpha,
//   clamped at x = 0; at x = l a tip body of mass m, offset c and inertia J_o about its centre of mass.
//
// Members carry the symbols of the equations (and the TOML keys); the unit of each is in parameter_table().
//
// Attachments (sensor boards, accelerometers, clamps of a shaker rod) are further rigid bodies fixed anywhere on the
// span. One at x with mass m, offset c of its centre of mass along the axis and inertia J about its centre moves with
// the section at x: its centre translates by u(x) + c alpha(x) and it rotates by alpha(x), so its kinetic energy is
//   (1/2) [u_t(x), alpha_t(x)] Lambda [u_t(x), alpha_t(x)]^T,   Lambda = [[m, m c], [m c, J + m c^2]],
// exactly the tip body's form with the tip trace replaced by the section at x.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace beamid::model {

struct Attachment {
  double x = 0;  // m       position on the span, measured from the clamp, 0 < x <= l
  double m = 0;  // kg      mass
  double J = 0;  // kg m^2  rotary inertia about its own centre of mass
  double c = 0;  // m       offset of its centre of mass along the beam axis from x (either sign), |c| <= l
  bool operator==(const Attachment&) const = default;
};

// The clamp at x = 0. Rigid by default (u(0) = alpha(0) = 0); a finite spring lets the root rotate or deflect and
// stores (1/2) k_theta alpha(0)^2 + (1/2) k_w u(0)^2, giving the natural conditions M(0) = k_theta alpha(0),
// S(0) = k_w u(0) (M = EI alpha_x the bending moment, S = kAG beta the shear force).
struct Support {
  double k_theta = std::numeric_limits<double>::infinity();  // N m/rad  rotational spring; infinite: rigid
  double k_w = std::numeric_limits<double>::infinity();      // N/m      translational spring; infinite: rigid
  bool rotation_free() const { return k_theta < std::numeric_limits<double>::infinity(); }
  bool deflection_free() const { return k_w < std::numeric_limits<double>::infinity(); }
  bool rigid() const { return !rotation_free() && !deflection_free(); }
  bool operator==(const Support&) const = default;
};

struct BeamParameters {
  double l = 0;                         // m        length
  double rho = 0;                       // kg/m    linear mass density
  double rho_r2 = 0;                    // kg m    rotary inertia per length, rho I / A
  double kAG = 0;                       // N       shear stiffness kappa A G
  double EI = 0;                        // N m^2   bending stiffness
  double gamma = 0;                     // N s/m^2 viscous (air) damping
  double cDI = 0;                       // N m^2 s Kelvin-Voigt bending damping c_D I
  double kAcs = 0;                      // N s     Kelvin-Voigt shear damping kappa A c_s
  double m = 0;                         // kg      tip body mass
  double c = 0;                         // m       tip body centre of mass beyond the tip, on the axis
  double J_o = 0;                       // kg m^2  tip body inertia about its centre of mass
  std::vector<Attachment> attachments;  // rigid bodies on the span, in the order the beam file gives them
  Support support;                      // the clamp (rigid unless a [support] table says otherwise)
};

// One row per parameter, in the canonical order l, rho, rho_r2, kAG, EI, gamma, cDI, kAcs, m, c, J_o.
// The single place where names, units and admissibility live (the TOML loader and the fit's parameter map use it).
struct ParameterInfo {
  std::string_view key;
  std::string_view unit;
  std::string_view meaning;
  double BeamParameters::*member;
  bool strictly_positive;  // true: must be > 0; false: must be >= 0
  // "geometry" (l, c), "inertia" (rho, rho_r2, m, J_o), "stiffness" (kAG, EI) or "damping" (gamma, cDI, kAcs):
  // the paper's staged fit estimates stiffness and inertia first, damping second, then all.
  std::string_view role;
};
inline constexpr std::size_t kParameterCount = 11;
const std::array<ParameterInfo, kParameterCount>& parameter_table();

// The row for `key`, or nullptr when no parameter has that name.
const ParameterInfo* find_parameter(std::string_view key);
// Comma-separated list of all keys, for "valid names are ..." messages.
std::string parameter_keys();

// Every quantity of a beam a fit may estimate: the lumped parameters of parameter_table() (l too: the Galerkin forms
// scale with it in closed form, galerkin::combine), the clamp's springs
// "support.k_theta" and "support.k_w" (when the beam's clamp has them: a rigid direction has no finite value to start
// from), and attachment K's mass, inertia and position "attachmentK.m", "attachmentK.J", "attachmentK.x" (K from 1).
struct ParameterDescription {
  std::string key;
  std::string_view unit, meaning, role;  // role as in ParameterInfo
  bool strictly_positive = true;
};
// The description of `key` for this beam, or nothing when the beam has no such quantity.
std::optional<ParameterDescription> describe_parameter(const BeamParameters& beam, std::string_view key);
// The role of a key (as in ParameterInfo) without a beam: support springs are "stiffness", attachment masses and
// inertias "inertia", positions "geometry"; empty for an unknown key.
std::string_view parameter_role(std::string_view key);
// The value of `key` in `beam`, and setting it: InputError naming the key and this beam's keys when it has no such
// quantity.
double parameter_value(const BeamParameters& beam, std::string_view key);
void set_parameter_value(BeamParameters& beam, std::string_view key, double value);
// The same for a nominal value of a candidate model: a clamp spring (support.k_theta, support.k_w) may also be given
// to a clamp that is rigid in that direction, which makes it compliant. InputError for any other key the beam lacks.
void set_nominal_value(BeamParameters& beam, std::string_view key, double value);
// "attachmentK.field" -> (K - 1, field), or nothing when the key has another form (K from 1, no leading zero).
std::optional<std::pair<std::size_t, std::string>> attachment_field(std::string_view key);
// This beam's estimable keys, comma-separated, for messages.
std::string estimable_keys(const BeamParameters& beam);

// The constraint `value` violates for this parameter ("must be finite", "must be > 0", "must be >= 0"), or nothing.
std::optional<std::string> constraint_violation(const ParameterInfo& info, double value);

// The first violated constraint as "EI = -1: must be > 0", or nothing when all values are admissible:
// all finite; l, rho, rho_r2, kAG, EI > 0; gamma, cDI, kAcs, m, c, J_o >= 0; c <= l; and for attachment k (counted
// from 1, named "attachmentK.x" etc.) 0 < x <= l, m >= 0, J >= 0, |c| <= l; support.k_theta, support.k_w > 0 (+inf
// is the rigid clamp).
std::optional<std::string> validation_error(const BeamParameters& beam);
// "attachment1", "attachment2", ...: the name of attachment `index` (from 0) in messages and parameter keys.
std::string attachment_key(std::size_t index);
// The constraint attachment `a` of a beam of length l violates, as "x = 0: must be in (0, l = 0.3] m ...", or nothing.
std::optional<std::string> attachment_violation(const Attachment& a, double l);

// validation_error, then what no real beam has although the mathematics allows it (the exact determinant is tested
// at l/r = 1e6): a section thinner than 1e-4 or thicker than 1 beam length (l/r outside [2 sqrt 3, 2 sqrt 3 1e4],
// r = sqrt(rho_r2/rho)), kAG r^2/EI = kappa G/E outside [1e-4, 10], or a tip body beyond max_body_mass_kg and
// max_body_inertia_kg_m2 (below). For parameters a user gives (beam files).
std::optional<std::string> implausibility(const BeamParameters& beam);

// Scales between a body or a clamp and the beam it sits on that no real rig has, and beyond which the Galerkin
// matrices lose their digits (an adversarial pass found a 1e6 kg body, a 1e6 kg m^2 inertia on a 1 g body and 1e-10 or
// 1e20 clamp springs ending in "K is not positive definite" with no key named). For parameters a user gives.
// A body (tip or attachment) of mass m: at most 1e4 times the beam's own mass rho l.
inline constexpr double kMaxBodyMassRatio = 1e4;
double max_body_mass_kg(const BeamParameters& beam);
// Its rotary inertia about its centre, J = m k^2: a radius of gyration k up to a beam length, counting the beam's mass
// with the body's so that a small body may carry a flywheel: J <= (m + rho l) l^2.
double max_body_inertia_kg_m2(double m_kg, const BeamParameters& beam);
// A clamp spring against the beam's own stiffness, k_theta l/EI and k_w l^3/EI, in [1e-2, 1e10]. Softer, the clamp is
// a hinge, and the near-rigid mode it makes loses digits to the rounding of K's entries, whose energy it is a small
// part of: on the thin beam with both springs at ratio r, the Galerkin mode 1 falls below the exact one (which
// Rayleigh-Ritz forbids) by about 1.5e-7/r at N = 64 and 1e-8/r at N = 16 (measured at r = 1e-3, 1e-2, 1e-1; the
// shifted eigensolver gives the same, so the eigensolver is not the cause); stiffer, the clamp is rigid to 1e-10 and
// only spoils K's conditioning (k = 1e15 on the thin beam moved mode 1 by 2e-4): omit the spring.
inline constexpr double kMinSpringRatio = 1e-2, kMaxSpringRatio = 1e10;
// The admissible range of support.k_theta ("k_theta", N m/rad) or support.k_w ("k_w", N/m) for this beam, and the
// ratio's formula for messages ("k_theta l/EI").
struct SpringRange {
  double lower = 0, upper = 0;
  std::string ratio;
};
SpringRange spring_range(std::string_view spring, const BeamParameters& beam);

// implausibility, then every bound a beam file's [[attachment]] and [support] tables meet (each attachment's m and J,
// the clamp springs' spring_range, all bodies together at most kMaxBodyMassRatio rho l), as "support.k_theta = 1e-12:
// must be in [...]". For a beam whose values were set after its file was read (a real study's candidate `values`,
// which bypassed them: the second adversarial pass's N506-N509).
std::optional<std::string> rig_implausibility(const BeamParameters& beam);

// Built-in parameter sets of model.md section 5: "banks-aluminium" and "thick-steel".
std::vector<std::string> preset_names();
bool is_preset(std::string_view name);
// Throws InputError listing the valid names when `name` is not a preset.
BeamParameters preset(std::string_view name);

// Shear cut-off angular frequency sqrt(kAG / rho_r2), rad/s: the exact Timoshenko reference is valid below it.
double shear_cutoff_rad_s(const BeamParameters& beam);

}  // namespace beamid::model
