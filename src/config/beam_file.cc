#include "config/beam_file.h"

#include <array>
#include <cmath>
#include <fstream>
#include <tuple>

#include "config/document.h"
#include "core/errors.h"
#include "core/limits.h"
#include "io/files.h"
#include "model/geometry.h"

namespace beamid::config {
namespace {

using model::BeamParameters;

// [geometry]: see model/geometry.h. Every key is checked where it is read, so an error names its line.
BeamParameters parse_geometry_table(Table r) {
  const auto non_negative = [](double v) { return v >= 0; };
  model::Geometry g;
  // Ranges of real beams and materials: a beam is at least twice as long as it is thick (below that no beam theory
  // holds), no wider than long; moduli from soft rubber (1e5 Pa) to diamond (1.2e12 Pa); densities from aerogels
  // (1 kg/m^3) to osmium (22 590 kg/m^3), with margin.
  g.length_m = r.number(
      "length_m", std::nullopt, [](double v) { return v > 0 && v <= 1e3; }, "must be in (0, 1000] m");
  const double l = g.length_m;
  const std::string of_length = " (length_m = " + format_value(l) + ")";
  g.width_m = r.number(
      "width_m", std::nullopt, [&](double v) { return v > 0 && v <= l; }, "must be in (0, length_m]" + of_length);
  g.thickness_m = r.number(
      "thickness_m", std::nullopt, [&](double v) { return v > 0 && v <= l / 2; },
      "must be in (0, length_m / 2]: a beam is at least twice as long as it is thick" + of_length);
  g.youngs_modulus_Pa = r.number(
      "youngs_modulus_Pa", std::nullopt, [](double v) { return v >= 1e5 && v <= 2e12; },
      "must be in [1e5, 2e12] Pa (soft rubber to diamond)");
  g.density_kg_m3 = r.number(
      "density_kg_m3", std::nullopt, [](double v) { return v >= 1 && v <= 1e5; },
      "must be in [1, 1e5] kg/m^3 (aerogels to osmium, 22 590 kg/m^3)");
  if (r.has("poisson_ratio"))
    g.poisson_ratio = r.number(
        "poisson_ratio", std::nullopt, [](double v) { return v > -1 && v < 0.5; }, "must be in (-1, 0.5)");
  // G against E: 2.6 for metals (E/G = 2(1 + nu)), up to about 50 for fibre composites; beyond [E/1e4, 10 E] the
  // derived Poisson ratio overflows Cowper's shear coefficient (G = 1e-300 or 1e300 was reported as
  // "geometry.shear_coefficient = nan", a key the file did not hold).
  if (r.has("shear_modulus_Pa")) {
    const double E = g.youngs_modulus_Pa;
    g.shear_modulus_Pa = r.number(
        "shear_modulus_Pa", std::nullopt, [&](double v) { return v >= E / 1e4 && v <= 10 * E; },
        "must be in [E/1e4, 10 E] = [" + format_rounded(E / 1e4) + ", " + format_rounded(10 * E) +
            "] Pa with E = youngs_modulus_Pa (E/G is 2.6 for metals, up to about 50 for fibre composites)");
  }
  if (g.poisson_ratio.has_value() == g.shear_modulus_Pa.has_value())
    throw InputError(r.where() + ": [geometry] needs exactly one of poisson_ratio and shear_modulus_Pa");
  if (const auto k = r.get("shear_coefficient")) {
    if (k->is_string()) {
      if (*k->string() != "cowper") r.fail("shear_coefficient", k->text(), "must be 'cowper' or a number in (0, 1]");
    } else {
      g.shear_coefficient = r.number(
          "shear_coefficient", std::nullopt, [](double v) { return v > 0 && v <= 1; },
          "must be 'cowper' or a number in (0, 1]");
    }
  }
  g.tip_mass_kg = r.number("tip_mass_kg", 0.0, non_negative, "must be >= 0");
  g.tip_offset_m = r.number(
      "tip_offset_m", 0.0, [&](double v) { return v >= 0 && v <= l; },
      "must be in [0, length_m]: the tip body's centre lies within a beam length of the tip" + of_length);
  g.tip_inertia_kg_m2 = r.number("tip_inertia_kg_m2", 0.0, non_negative, "must be >= 0");
  if (r.has("tip_block_m")) {
    std::vector<double> a;
    const std::vector<Node> items = *r.array("tip_block_m", true);
    for (const Node& item : items) a.push_back(item.number().value_or(-1));
    if (a.size() != 3 || !(a[0] > 0 && a[1] > 0 && a[2] > 0) || a[0] > 2 * l || a[1] > 2 * l || a[2] > 2 * l)
      r.fail("tip_block_m", "[...]",
             "must be three sizes in (0, 2 length_m] m: [along the beam, across, in the plane of vibration]");
    if (g.tip_mass_kg != 0 || g.tip_offset_m != 0 || g.tip_inertia_kg_m2 != 0)
      r.fail("tip_block_m", "[...]",
             "give the tip body either as tip_block_m or as tip_mass_kg, tip_offset_m, tip_inertia_kg_m2");
    g.tip_block_m = a;
    g.tip_block_density_kg_m3 = r.number(
        "tip_block_density_kg_m3", std::nullopt, [](double v) { return v >= 1 && v <= 1e5; },
        "must be in [1, 1e5] kg/m^3 (aerogels to osmium)");
  }
  g.cDI =
      r.number("cDI", std::nullopt, non_negative, "must be >= 0 (N m^2 s, a nominal value: damping has no geometry)");
  g.kAcs = r.number("kAcs", std::nullopt, non_negative, "must be >= 0 (N s)");
  g.gamma = r.number("gamma", std::nullopt, non_negative, "must be >= 0 (N s/m^2)");
  r.finish({"length_m", "width_m", "thickness_m", "youngs_modulus_Pa", "density_kg_m3", "poisson_ratio",
            "shear_modulus_Pa", "shear_coefficient", "tip_mass_kg", "tip_offset_m", "tip_inertia_kg_m2", "tip_block_m",
            "tip_block_density_kg_m3", "cDI", "kAcs", "gamma"});
  try {
    return model::lumped_parameters(g);
  } catch (const InputError& e) {
    throw InputError(r.where() + ": " + e.what());
  }
}

// [[attachment]] tables (model/beam_parameters.h): x (m from the clamp, required), m (kg, required), J (kg m^2 about
// the body's centre, default 0), c (m, offset of its centre along the axis, default 0). Appended to beam.attachments
// in file order; each key is checked where it is read, against the beam's length.
void parse_attachments(Table root, BeamParameters& beam) {
  const std::optional<std::vector<Node>> items = root.array("attachment", false);
  if (!items) return;
  const double l = beam.l;
  // The cap (core/limits.h) keeps a generated file from sizing the exact reference's matrices.
  if (items->size() > static_cast<std::size_t>(core::kMaxAttachments))
    root.fail("attachment", "[" + std::to_string(items->size()) + " tables]",
              "must hold at most " + std::to_string(core::kMaxAttachments) + " attachments");
  for (std::size_t k = 0; k < items->size(); ++k) {
    const std::string name = model::attachment_key(k);
    Table t = (*items)[k].table(name + ".", "attachment");
    const std::string of_length = " (l = " + format_value(l) + " m)";
    model::Attachment a;
    a.x = t.number(
        "x", std::nullopt, [&](double v) { return v > 0 && v <= l; },
        "must be in (0, l] m, measured from the clamp" + of_length);
    // A body and the beam it sits on (model::max_body_mass_kg, max_body_inertia_kg_m2): beyond, no rig, and the
    // Galerkin matrices lose their digits.
    const double most_m = model::max_body_mass_kg(beam);
    a.m = t.number(
        "m", std::nullopt, [&](double v) { return v >= 0 && v <= most_m; },
        "must be in [0, " + format_rounded(most_m) + "] kg (at most " + format_rounded(model::kMaxBodyMassRatio) +
            " times the beam's mass rho l = " + format_rounded(beam.rho * l) + " kg)");
    const double most_J = model::max_body_inertia_kg_m2(a.m, beam);
    a.J = t.number(
        "J", 0.0, [&](double v) { return v >= 0 && v <= most_J && (a.m > 0 || v == 0); },
        a.m > 0 ? "must be in [0, (m + rho l) l^2 = " + format_rounded(most_J) +
                      "] kg m^2 (about the body's centre; the body's and the beam's mass at a radius of gyration of "
                      "a beam length)"
                : std::string("must be 0: the attachment has no mass (m = 0), so no inertia"));
    a.c = t.number(
        "c", 0.0, [&](double v) { return std::abs(v) <= l; },
        "must be in [-l, l] m: the body's centre lies within a beam length of its fixing point" + of_length);
    t.finish({"x", "m", "J", "c"});
    beam.attachments.push_back(a);
  }
}

// [support]: the clamp's springs (model/beam_parameters.h), k_theta in N m/rad and k_w in N/m, each optional (absent:
// rigid in that direction). The range (model::spring_range) is relative to the beam's own stiffness: from a clamp
// that is nearly a hinge to one that is rigid to 1e-10; beyond it the eigensolvers lose their digits.
void parse_support(Table root, BeamParameters& beam) {
  std::optional<Table> t = root.table("support");
  if (!t) return;
  for (const auto& [key, unit, slot] :
       {std::tuple{"k_theta", "N m/rad", &beam.support.k_theta}, std::tuple{"k_w", "N/m", &beam.support.k_w}}) {
    if (!t->has(key)) continue;
    const model::SpringRange range = model::spring_range(key, beam);
    *slot = t->number(
        key, std::nullopt, [&](double v) { return v >= range.lower && v <= range.upper; },
        "must be in [" + format_rounded(range.lower) + ", " + format_rounded(range.upper) + "] " + unit + " (" +
            range.ratio + " in [" + format_rounded(model::kMinSpringRatio) + ", " +
            format_rounded(model::kMaxSpringRatio) + "] with EI = " + format_value(beam.EI) +
            ", l = " + format_value(beam.l) + "; softer is a hinge, stiffer is rigid: omit it)");
  }
  t->finish({"k_theta", "k_w"});
}

// All bodies together, the tip's and the attachments', at most 1e4 times the beam's mass, the bound each meets alone
// (64 bodies of 425 kg stacked at the tip of the thin beam brought the eigensolver's jargon back).
void check_bodies(const BeamParameters& beam, const std::string& where) {
  double total = beam.m;
  for (const model::Attachment& a : beam.attachments) total += a.m;
  if (total > model::max_body_mass_kg(beam))
    throw InputError(where + ": the bodies on the beam weigh " + format_rounded(total) + " kg together (tip and " +
                     std::to_string(beam.attachments.size()) + " attachment(s)): at most " +
                     format_rounded(model::max_body_mass_kg(beam)) + " kg, " +
                     format_rounded(model::kMaxBodyMassRatio) +
                     " times the beam's mass rho l = " + format_rounded(beam.rho * beam.l) + " kg");
}

}  // namespace

BeamParameters parse_beam_toml(const std::string& text, const std::string& source_name) {
  const Document document = Document::parse(text, source_name);
  const Table root = document.root();
  const auto at = [&](int line) { return source_name + ":" + std::to_string(line); };
  for (const auto& [key, node] : root.entries())
    if (key != "beam" && key != "geometry" && key != "attachment" && key != "support")
      throw InputError(at(root.key_line(key)) + ": unknown top-level key '" + key +
                       "': a beam file holds one table, [beam] (lumped parameters) or [geometry], any number of "
                       "[[attachment]] tables and an optional [support]");
  if (root.has("geometry")) {
    if (root.has("beam"))
      throw InputError(at(root.key_line("geometry")) +
                       ": give either [beam] (lumped parameters) or [geometry], not both");
    BeamParameters beam = parse_geometry_table(document.required("geometry"));
    // The lumped parameters a geometry gives meet the same bounds as a [beam] table's (a 1e6 kg tip, a 1 nm thick
    // strip or a 1000 m long one were accepted and ended in solver jargon or 5e-9 Hz): named as derived values.
    if (auto e = model::implausibility(beam))
      throw InputError(at(root.key_line("geometry")) + ": [geometry] gives beam." + *e +
                       " (derived from the geometry: check its dimensions, material and tip)");
    parse_attachments(root, beam);
    parse_support(root, beam);
    check_bodies(beam, at(root.key_line("geometry")));
    return beam;
  }
  if (!root.has("beam"))
    throw InputError(source_name + ":1: missing table [beam] with keys " + model::parameter_keys());
  const Table table = document.required("beam");

  BeamParameters beam;
  std::array<bool, model::kParameterCount> seen{};
  for (const auto& [name, node] : table.entries()) {
    const model::ParameterInfo* info = model::find_parameter(name);
    if (info == nullptr)
      throw InputError(at(table.key_line(name)) + ": unknown key beam." + name + ": valid keys are " +
                       model::parameter_keys());
    const std::optional<double> value = node.number();  // integers convert exactly
    if (!value)
      throw InputError(at(node.line()) + ": beam." + name + " must be a number in " + std::string(info->unit));
    if (auto violation = model::constraint_violation(*info, *value))
      throw InputError(at(node.line()) + ": beam." + name + " = " + format_value(*value) + ": " + *violation);
    beam.*info->member = *value;
    seen[static_cast<std::size_t>(info - model::parameter_table().data())] = true;
  }
  for (std::size_t i = 0; i < model::kParameterCount; ++i) {
    const model::ParameterInfo& info = model::parameter_table()[i];
    if (!seen[i])
      throw InputError(table.where() + ": [beam] is missing key '" + std::string(info.key) + "' (" +
                       std::string(info.meaning) + ", " + std::string(info.unit) + ")");
  }
  // Constraints between parameters (each one alone was checked where it was read).
  // The message opens with the key it is about ("c = ...", "kAG = ..."): the error names that key's line.
  // A ratio's other terms are named with their lines too: the term that is wrong may be any of them (a changed rho_r2
  // was blamed on the kAG line alone).
  if (auto e = model::implausibility(beam)) {
    const std::string first = e->substr(0, e->find(' '));
    std::string others;
    for (const auto& info : model::parameter_table()) {
      const std::string key(info.key);
      // named as a term ("with EI = ", ", rho_r2 = ", "and rho = "), not inside a product ("rho l = ")
      bool named = false;
      for (const char* lead : {", ", "with ", "and "})
        named = named || e->find(lead + key + " = ") != std::string::npos;
      if (key != first && named)
        others += (others.empty() ? "" : ", ") + key + " on line " + std::to_string(table.key_line(key));
    }
    throw InputError(at(table.key_line(first)) + ": beam." + *e + (others.empty() ? "" : " (" + others + ")"));
  }
  parse_attachments(root, beam);
  parse_support(root, beam);
  check_bodies(beam, table.where());
  return beam;
}

BeamParameters load_beam_toml(const std::string& path) {
  return parse_beam_toml(io::read_file(path,
                                       "cannot open beam file (give a preset name: " +
                                           Table::join(model::preset_names()) + ", or a readable .toml file)",
                                       kMaxFileBytes),
                         path);
}

BeamParameters resolve_beam(const std::string& preset_or_file) {
  if (model::is_preset(preset_or_file)) return model::preset(preset_or_file);
  // A bare word that is no file is a mistyped preset name, and is reported as one.
  const bool looks_like_path =
      preset_or_file.find('/') != std::string::npos || preset_or_file.find('.') != std::string::npos;
  if (!looks_like_path && !std::ifstream(preset_or_file)) model::preset(preset_or_file);  // throws, listing presets
  return load_beam_toml(preset_or_file);
}

}  // namespace beamid::config
