#include "model/beam_parameters.h"

#include <charconv>
#include <cmath>

#include "core/errors.h"
#include "core/limits.h"

namespace beamid::model {

const std::array<ParameterInfo, kParameterCount>& parameter_table() {
  static const std::array<ParameterInfo, kParameterCount> table = {{
      {"l", "m", "length", &BeamParameters::l, true, "geometry"},
      {"rho", "kg/m", "linear mass density", &BeamParameters::rho, true, "inertia"},
      {"rho_r2", "kg m", "rotary inertia per length (rho I/A)", &BeamParameters::rho_r2, true, "inertia"},
      {"kAG", "N", "shear stiffness (kappa A G)", &BeamParameters::kAG, true, "stiffness"},
      {"EI", "N m^2", "bending stiffness", &BeamParameters::EI, true, "stiffness"},
      {"gamma", "N s/m^2", "viscous air damping", &BeamParameters::gamma, false, "damping"},
      {"cDI", "N m^2 s", "Kelvin-Voigt bending damping", &BeamParameters::cDI, false, "damping"},
      {"kAcs", "N s", "Kelvin-Voigt shear damping", &BeamParameters::kAcs, false, "damping"},
      {"m", "kg", "tip body mass", &BeamParameters::m, false, "inertia"},
      {"c", "m", "tip body offset beyond the tip", &BeamParameters::c, false, "geometry"},
      {"J_o", "kg m^2", "tip body inertia about its centre of mass", &BeamParameters::J_o, false, "inertia"},
  }};
  return table;
}

const ParameterInfo* find_parameter(std::string_view key) {
  for (const auto& info : parameter_table())
    if (info.key == key) return &info;
  return nullptr;
}

std::string parameter_keys() {
  std::string keys;
  for (const auto& info : parameter_table()) {
    if (!keys.empty()) keys += ", ";
    keys += info.key;
  }
  return keys;
}

std::optional<std::pair<std::size_t, std::string>> attachment_field(std::string_view key) {
  constexpr std::string_view prefix = "attachment";
  if (key.substr(0, prefix.size()) != prefix) return std::nullopt;
  const std::size_t dot = key.find('.');
  if (dot == std::string_view::npos || dot == prefix.size()) return std::nullopt;
  std::size_t index = 0;
  for (std::size_t i = prefix.size(); i < dot; ++i) {
    if (key[i] < '0' || key[i] > '9' || index > 1000000) return std::nullopt;
    index = 10 * index + static_cast<std::size_t>(key[i] - '0');
  }
  if (index == 0 || key[prefix.size()] == '0') return std::nullopt;
  return std::pair{index - 1, std::string(key.substr(dot + 1))};
}

std::string_view parameter_role(std::string_view key) {
  if (const ParameterInfo* info = find_parameter(key)) return info->role;
  if (key == "support.k_theta" || key == "support.k_w") return "stiffness";
  if (const auto a = attachment_field(key)) {
    if (a->second == "m" || a->second == "J") return "inertia";
    if (a->second == "x") return "geometry";
  }
  return {};
}

std::optional<ParameterDescription> describe_parameter(const BeamParameters& beam, std::string_view key) {
  if (const ParameterInfo* info = find_parameter(key))
    return ParameterDescription{std::string(key), info->unit, info->meaning, info->role, info->strictly_positive};
  if (key == "support.k_theta" && beam.support.rotation_free())
    return ParameterDescription{std::string(key), "N m/rad", "rotational spring of the clamp", "stiffness", true};
  if (key == "support.k_w" && beam.support.deflection_free())
    return ParameterDescription{std::string(key), "N/m", "translational spring of the clamp", "stiffness", true};
  if (const auto a = attachment_field(key); a && a->first < beam.attachments.size()) {
    if (a->second == "m") return ParameterDescription{std::string(key), "kg", "attachment mass", "inertia", false};
    if (a->second == "J")
      return ParameterDescription{std::string(key), "kg m^2", "attachment inertia about its centre", "inertia", false};
    if (a->second == "x")
      return ParameterDescription{std::string(key), "m", "attachment position from the clamp", "geometry", true};
  }
  return std::nullopt;
}

std::string estimable_keys(const BeamParameters& beam) {
  std::string keys;
  const auto add = [&](const std::string& key) { keys += (keys.empty() ? "" : ", ") + key; };
  for (const auto& info : parameter_table()) add(std::string(info.key));
  if (beam.support.rotation_free()) add("support.k_theta");
  if (beam.support.deflection_free()) add("support.k_w");
  for (std::size_t k = 0; k < beam.attachments.size(); ++k)
    for (const char* field : {".m", ".J", ".x"}) add(attachment_key(k) + field);
  return keys;
}

namespace {

// The member holding `key` (const or not with the beam), or nullptr when the beam has no such quantity.
template <class Beam>
auto parameter_slot(Beam& beam, std::string_view key) -> decltype(&beam.l) {
  if (const ParameterInfo* info = find_parameter(key)) return &(beam.*info->member);
  if (!describe_parameter(beam, key)) return nullptr;
  if (key == "support.k_theta") return &beam.support.k_theta;
  if (key == "support.k_w") return &beam.support.k_w;
  const auto a = attachment_field(key);
  auto& body = beam.attachments[a->first];
  return a->second == "m" ? &body.m : a->second == "J" ? &body.J : &body.x;
}

[[noreturn]] void no_such_parameter(const BeamParameters& beam, std::string_view key) {
  throw InputError("parameter '" + std::string(key) +
                   "': this beam has no such quantity (estimable: " + estimable_keys(beam) +
                   (beam.support.rigid() ? "; a clamp spring needs a [support] value" : "") + ")");
}

}  // namespace

double parameter_value(const BeamParameters& beam, std::string_view key) {
  const double* slot = parameter_slot(beam, key);
  if (slot == nullptr) no_such_parameter(beam, key);
  return *slot;
}

void set_parameter_value(BeamParameters& beam, std::string_view key, double value) {
  double* slot = parameter_slot(beam, key);
  if (slot == nullptr) no_such_parameter(beam, key);
  *slot = value;
}

void set_nominal_value(BeamParameters& beam, std::string_view key, double value) {
  if (key == "support.k_theta")
    beam.support.k_theta = value;
  else if (key == "support.k_w")
    beam.support.k_w = value;
  else
    set_parameter_value(beam, key, value);
}

std::optional<std::string> constraint_violation(const ParameterInfo& info, double value) {
  if (!std::isfinite(value)) return "must be finite";
  if (info.strictly_positive && !(value > 0)) return "must be > 0";
  if (!info.strictly_positive && !(value >= 0)) return "must be >= 0";
  // No real beam comes near it (a steel I-beam has EI ~ 1e8 N m^2 and kAG ~ 1e10 N), and beyond it the Galerkin
  // matrices lose every digit or overflow.
  if (value > 1e20) return "must be <= 1e20 (far beyond any real beam, in " + std::string(info.unit) + ")";
  return std::nullopt;
}

std::string attachment_key(std::size_t index) { return "attachment" + std::to_string(index + 1); }

std::optional<std::string> attachment_violation(const Attachment& a, double l) {
  // Same magnitude cap as the beam's own parameters (constraint_violation).
  const auto bad = [](double v) { return !std::isfinite(v) || std::abs(v) > 1e20; };
  if (bad(a.x) || !(a.x > 0 && a.x <= l))
    return "x = " + format_value(a.x) + ": must be in (0, l = " + format_value(l) +
           "] m (measured from the clamp; a body at the clamp does not move)";
  if (bad(a.m) || !(a.m >= 0)) return "m = " + format_value(a.m) + ": must be finite and >= 0 (kg)";
  if (bad(a.J) || !(a.J >= 0)) return "J = " + format_value(a.J) + ": must be finite and >= 0 (kg m^2)";
  if (bad(a.c) || !(std::abs(a.c) <= l))
    return "c = " + format_value(a.c) + ": must be in [-l, l] = [-" + format_value(l) + ", " + format_value(l) +
           "] m (the body's centre lies within a beam length of its fixing point)";
  return std::nullopt;
}

std::optional<std::string> validation_error(const BeamParameters& beam) {
  for (const auto& info : parameter_table()) {
    const double value = beam.*info.member;
    if (auto violation = constraint_violation(info, value))
      return std::string(info.key) + " = " + format_value(value) + ": " + *violation;
  }
  if (beam.c > beam.l)
    return "c = " + format_value(beam.c) + ": must be <= l = " + format_value(beam.l) +
           ": the tip body's centre lies within a beam length of the tip";
  for (const auto& [key, value] :
       {std::pair{"support.k_theta", beam.support.k_theta}, std::pair{"support.k_w", beam.support.k_w}})
    if (!(value > 0))
      return std::string(key) + " = " + format_value(value) + ": must be > 0 (omit it for a rigid clamp)";
  if (beam.attachments.size() > static_cast<std::size_t>(core::kMaxAttachments))
    return "attachments: " + std::to_string(beam.attachments.size()) + " bodies on the span: must be at most " +
           std::to_string(core::kMaxAttachments);
  for (std::size_t k = 0; k < beam.attachments.size(); ++k) {
    if (auto e = attachment_violation(beam.attachments[k], beam.l)) return attachment_key(k) + "." + *e;
  }
  return std::nullopt;
}

std::optional<std::string> implausibility(const BeamParameters& beam) {
  if (auto error = validation_error(beam)) return error;
  // Two ratios that no real beam breaks, and beyond which the Galerkin matrices lose their digits (an absurd density
  // or stiffness read from a file otherwise ends in a failed eigenproblem with no key named):
  // the radius of gyration r = sqrt(rho_r2 / rho) of a section between 1e-4 and 1 beam length thick (r = h/sqrt(12)
  // for a rectangle) gives l/r in [2 sqrt(3), 2 sqrt(3) 1e4] (the thin Banks beam: 990);
  const double r = std::sqrt(beam.rho_r2 / beam.rho), slenderness = beam.l / r;
  const double least = 2 * std::sqrt(3.0), most = least * 1e4;
  if (!(slenderness >= least && slenderness <= most))
    return "rho_r2 = " + format_value(beam.rho_r2) + ": with rho = " + format_value(beam.rho) +
           ", the radius of gyration sqrt(rho_r2/rho) = " + format_rounded(r) + " m is l/" +
           format_rounded(slenderness) + ": must lie between l/" + format_rounded(most) + " and l/" +
           format_rounded(least) + " (a section between 1e-4 and 1 beam length thick)";
  // shear against bending, kAG r^2 / EI = kappa G / E: 0.26-0.33 for metals (kappa ~ 5/6, G/E = 1/(2(1 + nu))), about
  // 0.01 for fibre composites; [1e-4, 10] leaves room for fits that move kAG and EI to their bounds.
  const double shear_ratio = beam.kAG * r * r / beam.EI;
  if (!(shear_ratio >= 1e-4 && shear_ratio <= 10))
    return "kAG = " + format_value(beam.kAG) + ": with EI = " + format_value(beam.EI) +
           ", rho_r2 = " + format_value(beam.rho_r2) + " and rho = " + format_value(beam.rho) +
           ", kAG r^2/EI (= kappa G/E, r = sqrt(rho_r2/rho) = " + format_rounded(r) + " m) is " +
           format_rounded(shear_ratio) +
           ": must lie in [1e-4, 10] (0.26-0.33 for metals, about 0.01 for fibre composites)";
  if (!(beam.m <= max_body_mass_kg(beam)))
    return "m = " + format_value(beam.m) + ": the tip body must be at most " + format_rounded(kMaxBodyMassRatio) +
           " times the beam's mass (rho l = " + format_rounded(beam.rho * beam.l) + " kg): at most " +
           format_rounded(max_body_mass_kg(beam)) + " kg";
  // A body of no mass has no inertia (m = 0 with J_o = 0.008 moved mode 1 from 6.14 to 1.79 Hz: the thirty-first
  // pass's adv71 P6). The bound (m + rho l) l^2 lets a light body's inertia be estimated with its mass held.
  if (beam.m == 0 && beam.J_o > 0)
    return "J_o = " + format_value(beam.J_o) + ": the tip body has no mass (m = 0), so no inertia; give its mass m";
  if (!(beam.J_o <= max_body_inertia_kg_m2(beam.m, beam)))
    return "J_o = " + format_value(beam.J_o) +
           ": the tip body's inertia about its centre must be at most (m + rho l) l^2 = " +
           format_rounded(max_body_inertia_kg_m2(beam.m, beam)) +
           " kg m^2 (the body's and the beam's mass at a radius of gyration of a beam length)";
  return std::nullopt;
}

std::optional<std::string> rig_implausibility(const BeamParameters& beam) {
  if (auto e = implausibility(beam)) return e;
  double total_kg = beam.m;
  for (std::size_t k = 0; k < beam.attachments.size(); ++k) {
    const Attachment& a = beam.attachments[k];
    if (!(a.m <= max_body_mass_kg(beam)))
      return attachment_key(k) + ".m = " + format_value(a.m) + ": must be at most " +
             format_rounded(max_body_mass_kg(beam)) + " kg (" + format_rounded(kMaxBodyMassRatio) +
             " times the beam's mass rho l = " + format_rounded(beam.rho * beam.l) + " kg)";
    if (a.m == 0 && a.J > 0)
      return attachment_key(k) + ".J = " + format_value(a.J) + ": the attachment has no mass (m = 0), so no inertia";
    if (!(a.J <= max_body_inertia_kg_m2(a.m, beam)))
      return attachment_key(k) + ".J = " + format_value(a.J) +
             ": must be at most (m + rho l) l^2 = " + format_rounded(max_body_inertia_kg_m2(a.m, beam)) +
             " kg m^2 (the body's and the beam's mass at a radius of gyration of a beam length)";
    total_kg += a.m;
  }
  if (!(total_kg <= max_body_mass_kg(beam)))
    return "m = " + format_value(beam.m) + ": the bodies on the beam weigh " + format_rounded(total_kg) +
           " kg together (tip and " + std::to_string(beam.attachments.size()) + " attachment(s)): at most " +
           format_rounded(max_body_mass_kg(beam)) + " kg, " + format_rounded(kMaxBodyMassRatio) +
           " times the beam's mass rho l = " + format_rounded(beam.rho * beam.l) + " kg";
  for (const auto& [spring, value] : {std::pair{"k_theta", beam.support.k_theta}, std::pair{"k_w", beam.support.k_w}}) {
    if (std::isinf(value)) continue;  // rigid
    const SpringRange range = spring_range(spring, beam);
    if (!(value >= range.lower && value <= range.upper))
      return std::string("support.") + spring + " = " + format_value(value) + ": must be in [" +
             format_rounded(range.lower) + ", " + format_rounded(range.upper) + "] (" + range.ratio + " in [" +
             format_rounded(kMinSpringRatio) + ", " + format_rounded(kMaxSpringRatio) +
             "]; softer is a hinge, stiffer is rigid: omit it)";
  }
  return std::nullopt;
}

double max_body_mass_kg(const BeamParameters& beam) { return kMaxBodyMassRatio * beam.rho * beam.l; }

double max_body_inertia_kg_m2(double m_kg, const BeamParameters& beam) {
  return (m_kg + beam.rho * beam.l) * beam.l * beam.l;
}

SpringRange spring_range(std::string_view spring, const BeamParameters& beam) {
  // The spring's stiffness in units of the beam's: EI/l for a rotation, EI/l^3 for a deflection.
  const bool rotation = spring == "k_theta";
  const double unit = rotation ? beam.EI / beam.l : beam.EI / (beam.l * beam.l * beam.l);
  return {kMinSpringRatio * unit, kMaxSpringRatio * unit, rotation ? "k_theta l/EI" : "k_w l^3/EI"};
}

namespace {

// model.md section 5, set A: the Banks-group thin aluminium beam B1TAPIH with a tip body added.
// b = 0.0203 m, h = 0.0016 m; rho_r2 = rho h^2/12; kAG with nu = 0.33 and Cowper's kappa = 0.8509.
BeamParameters banks_aluminium() {
  BeamParameters p;
  p.l = 0.4573;
  p.rho = 0.093;
  p.rho_r2 = 1.984e-8;
  p.kAG = 7.363e5;
  p.EI = 0.491;
  p.gamma = 0.013;
  p.cDI = 0.649e-5;
  p.kAcs = 9.73;
  p.m = 0.050;
  p.c = 0.0125;
  p.J_o = 5.208e-6;
  return p;
}

// model.md section 5, set B: a thick steel beam (l/h = 20) where shear, rotary inertia and shear damping matter.
// Derived from its geometry and material, unrounded: model.md prints the lumps rounded (rho = 2.944, rho_r2 = 5.52e-5,
// kAG = 2.451e7, J_o = 8.373e-5), but its exact frequencies (81.740, 579.236, 1665.412, 3260.857 Hz) belong to these
// unrounded values; the rounded ones shift every frequency by about 4e-5.
BeamParameters thick_steel() {
  const double b = 0.025, h = 0.015, E = 200e9, nu = 0.3, density = 7850;
  const double area = b * h, inertia = b * h * h * h / 12;
  const double kappa = 10 * (1 + nu) / (12 + 11 * nu);  // Cowper's rectangular-section shear coefficient
  const double block = 0.04;                            // tip body: a 40 mm cube of mass m (J_o = m (a^2 + a^2)/12)
  BeamParameters p;
  p.l = 0.30;
  p.rho = density * area;                     // 2.94375 kg/m
  p.rho_r2 = density * inertia;               // 5.5195e-5 kg m
  p.EI = E * inertia;                         // 1406.25 N m^2
  p.kAG = kappa * area * E / (2 * (1 + nu));  // 2.45098e7 N
  p.m = 0.314;
  p.c = 0.02;
  p.J_o = p.m * (block * block + block * block) / 12;  // 8.3733e-5 kg m^2
  p.cDI = 2.81e-3;                                     // shear retardation time kAcs/kAG = 10 x cDI/EI
  p.kAcs = 490.0;
  p.gamma = 2.0;
  return p;
}

}  // namespace

std::vector<std::string> preset_names() { return {"banks-aluminium", "thick-steel"}; }

bool is_preset(std::string_view name) { return name == "banks-aluminium" || name == "thick-steel"; }

BeamParameters preset(std::string_view name) {
  if (name == "banks-aluminium") return banks_aluminium();
  if (name == "thick-steel") return thick_steel();
  throw InputError("unknown beam preset '" + std::string(name) +
                   "': valid presets are banks-aluminium, thick-steel (or give a .toml file)");
}

double shear_cutoff_rad_s(const BeamParameters& beam) { return std::sqrt(beam.kAG / beam.rho_r2); }

}  // namespace beamid::model
