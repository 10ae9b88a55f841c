#include "model/beam_toml.h"

#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "model/errors.h"
#include "model/geometry.h"
#include "model/toml_reader.h"

namespace beamid::model {
namespace {

std::string where(const std::string& source_name, const toml::source_region& region) {
  return source_name + ":" + std::to_string(region.begin.line);
}

// [geometry]: see model/geometry.h. Every key is checked where it is read, so an error names its line.
BeamParameters parse_geometry_table(const toml::table& root, const std::string& source) {
  const toml::node* node = root.get("geometry");
  if (!node->is_table()) throw InputError(where(source, node->source()) + ": geometry must be a table ([geometry])");
  TableReader r(*node->as_table(), "geometry.", source);
  const auto positive = [](double v) { return v > 0; };
  const auto non_negative = [](double v) { return v >= 0; };
  Geometry g;
  g.length_m = r.number("length_m", std::nullopt, positive, "must be > 0");
  g.width_m = r.number("width_m", std::nullopt, positive, "must be > 0");
  g.thickness_m = r.number("thickness_m", std::nullopt, positive, "must be > 0");
  g.youngs_modulus_Pa = r.number("youngs_modulus_Pa", std::nullopt, positive, "must be > 0");
  g.density_kg_m3 = r.number("density_kg_m3", std::nullopt, positive, "must be > 0");
  if (r.has("poisson_ratio"))
    g.poisson_ratio = r.number("poisson_ratio", std::nullopt, [](double v) { return v > -1 && v < 0.5; }, "must be in (-1, 0.5)");
  if (r.has("shear_modulus_Pa")) g.shear_modulus_Pa = r.number("shear_modulus_Pa", std::nullopt, positive, "must be > 0");
  if (g.poisson_ratio.has_value() == g.shear_modulus_Pa.has_value())
    throw InputError(r.where(nullptr) + ": [geometry] needs exactly one of poisson_ratio and shear_modulus_Pa");
  if (const toml::node* k = r.get("shear_coefficient")) {
    if (k->is_string()) {
      if (*k->value<std::string>() != "cowper")
        r.fail("shear_coefficient", TableReader::text(*k), "must be 'cowper' or a number in (0, 1]");
    } else {
      g.shear_coefficient = r.number("shear_coefficient", std::nullopt, [](double v) { return v > 0 && v <= 1; },
                                     "must be 'cowper' or a number in (0, 1]");
    }
  }
  g.tip_mass_kg = r.number("tip_mass_kg", 0.0, non_negative, "must be >= 0");
  g.tip_offset_m = r.number("tip_offset_m", 0.0, non_negative, "must be >= 0");
  g.tip_inertia_kg_m2 = r.number("tip_inertia_kg_m2", 0.0, non_negative, "must be >= 0");
  if (r.has("tip_block_m")) {
    std::vector<double> a;
    const toml::array* arr = r.array("tip_block_m", true);
    for (const toml::node& item : *arr) a.push_back(item.value<double>().value_or(-1));
    if (a.size() != 3 || !(a[0] > 0 && a[1] > 0 && a[2] > 0))
      r.fail("tip_block_m", "[...]", "must be three sizes > 0 in m: [along the beam, across, in the plane of vibration]");
    if (g.tip_mass_kg != 0 || g.tip_offset_m != 0 || g.tip_inertia_kg_m2 != 0)
      r.fail("tip_block_m", "[...]", "give the tip body either as tip_block_m or as tip_mass_kg, tip_offset_m, tip_inertia_kg_m2");
    g.tip_block_m = a;
    g.tip_block_density_kg_m3 = r.number("tip_block_density_kg_m3", std::nullopt, positive, "must be > 0");
  }
  g.cDI = r.number("cDI", std::nullopt, non_negative, "must be >= 0 (N m^2 s, a nominal value: damping has no geometry)");
  g.kAcs = r.number("kAcs", std::nullopt, non_negative, "must be >= 0 (N s)");
  g.gamma = r.number("gamma", std::nullopt, non_negative, "must be >= 0 (N s/m^2)");
  r.finish({"length_m", "width_m", "thickness_m", "youngs_modulus_Pa", "density_kg_m3", "poisson_ratio",
            "shear_modulus_Pa", "shear_coefficient", "tip_mass_kg", "tip_offset_m", "tip_inertia_kg_m2", "tip_block_m",
            "tip_block_density_kg_m3", "cDI", "kAcs", "gamma"});
  try {
    return lumped_parameters(g);
  } catch (const InputError& e) {
    throw InputError(r.where(nullptr) + ": " + e.what());
  }
}

}  // namespace

BeamParameters parse_beam_toml(std::string_view text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& error) {
    throw InputError(where(source_name, error.source()) + ": TOML syntax error: " + std::string(error.description()));
  }

  for (auto&& [key, node] : root) {
    if (key.str() != "beam" && key.str() != "geometry")
      throw InputError(where(source_name, key.source()) + ": unknown top-level key '" + std::string(key.str()) +
                       "': a beam file holds one table, [beam] (lumped parameters) or [geometry]");
  }
  if (root.contains("geometry")) {
    if (root.contains("beam"))
      throw InputError(where(source_name, root.get("geometry")->source()) +
                       ": give either [beam] (lumped parameters) or [geometry], not both");
    return parse_geometry_table(root, source_name);
  }
  const toml::table* table = root["beam"].as_table();
  if (table == nullptr) {
    if (root.contains("beam"))
      throw InputError(where(source_name, root["beam"].node()->source()) + ": beam must be a table ([beam])");
    throw InputError(source_name + ":1: missing table [beam] with keys " + parameter_keys());
  }

  BeamParameters beam;
  std::array<bool, kParameterCount> seen{};
  for (auto&& [key, node] : *table) {
    const std::string name(key.str());
    const ParameterInfo* info = find_parameter(name);
    if (info == nullptr)
      throw InputError(where(source_name, key.source()) + ": unknown key beam." + name + ": valid keys are " +
                       parameter_keys());
    const std::optional<double> value = node.value<double>();  // integers convert exactly
    if (!node.is_number() || !value)
      throw InputError(where(source_name, node.source()) + ": beam." + name + " must be a number in " +
                       std::string(info->unit));
    if (auto violation = constraint_violation(*info, *value))
      throw InputError(where(source_name, node.source()) + ": beam." + name + " = " + format_value(*value) + ": " +
                       *violation);
    beam.*info->member = *value;
    seen[static_cast<std::size_t>(info - parameter_table().data())] = true;
  }
  for (std::size_t i = 0; i < kParameterCount; ++i) {
    if (!seen[i])
      throw InputError(where(source_name, table->source()) + ": [beam] is missing key '" +
                       std::string(parameter_table()[i].key) + "' (" + std::string(parameter_table()[i].meaning) +
                       ", " + std::string(parameter_table()[i].unit) + ")");
  }
  return beam;
}

BeamParameters load_beam_toml(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open beam file (give a preset name: " + [] {
                              std::string names;
                              for (const auto& n : preset_names()) names += (names.empty() ? "" : ", ") + n;
                              return names;
                            }() + ", or a readable .toml file)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_beam_toml(text.str(), path);
}

BeamParameters resolve_beam(const std::string& preset_or_file) {
  if (is_preset(preset_or_file)) return preset(preset_or_file);
  // A bare word that is no file is a mistyped preset name, and is reported as one.
  const bool looks_like_path = preset_or_file.find('/') != std::string::npos ||
                               preset_or_file.find('.') != std::string::npos;
  if (!looks_like_path && !std::ifstream(preset_or_file)) preset(preset_or_file);  // throws, listing the presets
  return load_beam_toml(preset_or_file);
}

}  // namespace beamid::model
