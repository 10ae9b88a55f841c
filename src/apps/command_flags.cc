#include "apps/command_flags.h"

#include <cstdlib>
#include <map>
#include <sstream>

#include "model/errors.h"

namespace beamid::apps {

bool wants_help(const io::Arguments& a, std::ostream& out, const std::string& synopsis) {
  if (!a.has("help")) return false;
  out << "usage: beamid " << a.command() << " " << synopsis << "\n\n" << a.usage();
  return true;
}

std::vector<io::FlagSpec> join_flags(std::vector<io::FlagSpec> a, const std::vector<io::FlagSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<io::FlagSpec> experiment_flag_specs() {
  return {{"dt", true, "sampling interval, s (default 1e-3)"},
          {"samples", true, "number of samples Nbar >= 2 (default 4096)"},
          {"sensor-x", true, "sensor position xbar, m (default: the tip)"},
          {"output", true, "displacement | velocity | acceleration (default displacement)"},
          {"excitation", true, "pulse | pluck | free-decay (fit only: unknown initial state, amplitudes solved) (default pulse)"},
          {"force-x", true, "force position x_f, m (default: the tip)"},
          {"force-amplitude", true, "pulse peak F0, or pluck static load P0, N (default 1)"},
          {"pulse-width", true, "pulse width tau, s (default 0.01; pulse only)"}};
}

simulation::Experiment read_experiment(const io::Arguments& a, double length_m) {
  simulation::Experiment e;
  e.dt_s = a.optional_number("dt").value_or(e.dt_s);
  e.samples = a.optional_integer("samples").value_or(e.samples);
  e.sensor_x_m = a.optional_number("sensor-x");
  e.output = a.text_or("output", e.output);
  e.excitation = a.text_or("excitation", e.excitation);
  e.force_x_m = a.optional_number("force-x");
  e.force_amplitude_N = a.optional_number("force-amplitude").value_or(e.force_amplitude_N);
  e.pulse_width_s = a.optional_number("pulse-width").value_or(e.pulse_width_s);
  if (e.excitation == "pluck" && a.has("pulse-width"))
    throw InputError("beamid " + a.command() + ": --pulse-width applies to --excitation pulse only");
  if (auto error = simulation::validation_error(e, length_m)) throw InputError("beamid " + a.command() + ": " + *error);
  return e;
}

std::vector<fit::EstimatedParameter> parse_estimate(const io::Arguments& a, const model::BeamParameters& nominal,
                                                    double factor) {
  const std::string where = "beamid " + a.command() + ": ";
  std::map<std::string, std::pair<double, double>> explicit_bounds;
  if (a.has("bounds")) {
    std::stringstream list(a.text("bounds"));
    std::string item;
    while (std::getline(list, item, ',')) {
      const auto eq = item.find('='), colon = item.find(':');
      char* end1 = nullptr;
      char* end2 = nullptr;
      if (eq == std::string::npos || colon == std::string::npos || colon < eq)
        throw InputError(where + "--bounds item '" + item + "': must read KEY=LO:HI");
      const std::string lo = item.substr(eq + 1, colon - eq - 1), hi = item.substr(colon + 1);
      const double l = std::strtod(lo.c_str(), &end1), h = std::strtod(hi.c_str(), &end2);
      if (lo.empty() || hi.empty() || *end1 || *end2)
        throw InputError(where + "--bounds item '" + item + "': LO and HI must be numbers");
      explicit_bounds[item.substr(0, eq)] = {l, h};
    }
  }
  std::vector<fit::EstimatedParameter> estimate;
  std::stringstream keys(a.text("estimate"));
  std::string key;
  while (std::getline(keys, key, ',')) {
    const model::ParameterInfo* info = model::find_parameter(key);
    if (!info)
      throw InputError(where + "--estimate = '" + a.text("estimate") + "': '" + key +
                       "' is not a beam parameter (valid: " + model::parameter_keys() + ")");
    fit::EstimatedParameter p{key, 0, 0};
    if (auto b = explicit_bounds.find(key); b != explicit_bounds.end()) {
      std::tie(p.lower, p.upper) = b->second;
      explicit_bounds.erase(b);
    } else {
      const double v = nominal.*(info->member);
      if (!(v > 0))
        throw InputError(where + "--estimate " + key + ": the --beam value is " + format_value(v) +
                         ", so --bound-factor gives no range: give --bounds " + key + "=LO:HI");
      p.lower = v / factor;
      p.upper = v * factor;
    }
    estimate.push_back(p);
  }
  if (!explicit_bounds.empty())
    throw InputError(where + "--bounds names '" + explicit_bounds.begin()->first + "', which is not in --estimate");
  return estimate;
}

}  // namespace beamid::apps
