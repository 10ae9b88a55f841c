#include "model/beam_toml.h"

#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "model/errors.h"

namespace beamid::model {
namespace {

std::string where(const std::string& source_name, const toml::source_region& region) {
  return source_name + ":" + std::to_string(region.begin.line);
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
    if (key.str() != "beam")
      throw InputError(where(source_name, key.source()) + ": unknown top-level key '" + std::string(key.str()) +
                       "': a beam file holds only a [beam] table");
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
