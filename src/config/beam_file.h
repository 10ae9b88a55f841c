// Beam parameters from the [beam] table of a TOML file, strictly: every key of parameter_table() must be present,
// no other key may be, and each value must be an admissible number. Or from a [geometry] table (model/geometry.h:
// length, section, material, shear coefficient, tip body, nominal damping), which gives the lumps. Errors are one
// line naming file:line, key, value and constraint, e.g. "my_beam.toml:4: beam.EI = -1: must be > 0".
// Either may be followed by [[attachment]] tables, rigid bodies on the span (x, m required; J, c default 0):
//   [[attachment]]
//   x = 0.397   # m from the clamp
//   m = 0.012   # kg
//   J = 2e-6    # kg m^2 about its centre (optional)
//   c = 0.0     # m, its centre's offset along the axis (optional)
// and by one [support] table, the clamp's springs (each optional; absent: rigid):
//   [support]
//   k_theta = 350   # N m/rad
//   k_w = 2e6       # N/m
#pragma once

#include <string>

#include "model/beam_parameters.h"

namespace beamid::config {

// Parses a TOML file; throws InputError on any problem (unreadable file, TOML syntax, missing, unknown or bad key).
model::BeamParameters load_beam_toml(const std::string& path);

// Same, from text already in memory; `source_name` stands for the file name in messages.
model::BeamParameters parse_beam_toml(const std::string& text, const std::string& source_name);

// "banks-aluminium" or "thick-steel" give the preset; anything else is read as a TOML file path.
model::BeamParameters resolve_beam(const std::string& preset_or_file);

}  // namespace beamid::config
