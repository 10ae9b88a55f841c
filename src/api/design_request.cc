#include "api/design_request.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "api/cost_request.h"
#include "core/errors.h"
#include "core/limits.h"

namespace beamid::api {

std::vector<double> design_choices(const Caller& caller, const std::string& flag,
                                   const std::vector<std::string>& items) {
  std::vector<double> out;
  const auto number = [&](const std::string& item, const std::string& text) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || !std::isfinite(v))
      refuse(caller, flag, item, "each item must be a finite number or a range START:STOP:COUNT");
    return v;
  };
  for (const std::string& item : items) {
    const std::size_t first = item.find(':');
    if (first == std::string::npos) {
      out.push_back(number(item, item));
      continue;
    }
    const std::size_t second = item.find(':', first + 1);
    if (second == std::string::npos || item.find(':', second + 1) != std::string::npos)
      refuse(caller, flag, item, "a range is START:STOP:COUNT");
    const double start = number(item, item.substr(0, first)),
                 stop = number(item, item.substr(first + 1, second - first - 1));
    const double count = number(item, item.substr(second + 1));
    if (!(count >= 2 && count <= 1000 && count == std::floor(count)))
      refuse(caller, flag, item, "a range's COUNT must be an integer in 2..1000");
    // (1 - t) START + t STOP: both ends exact (START + (STOP - START) t put 0.15:0.4573's end 4e-17 off the beam).
    for (int i = 0; i < static_cast<int>(count); ++i) {
      const double t = static_cast<double>(i) / (count - 1);
      out.push_back(i + 1 == static_cast<int>(count) ? stop : (1 - t) * start + t * stop);
    }
  }
  return out;
}

DesignResult compute_design(const DesignRequest& request, std::ostream& warnings) {
  const Caller& caller = request.run.caller;
  if (request.run.experiment.excitation && *request.run.experiment.excitation != simulation::kPulse)
    refuse(caller, "excitation", *request.run.experiment.excitation,
           "a design ranks pulse experiments (their sensitivities are exact); the pulse width is one of its choices");
  DesignResult r;
  r.run = model_run(request.run, 0, warnings);  // validated below per candidate, each run's size guarded
  fit::DesignOptions& o = r.options;
  o.beam = r.run.beam;
  o.elements = r.run.elements;
  o.keys = request.estimate;
  o.base = r.run.experiment;
  const double l = o.beam.l;
  o.sensor_positions_m =
      request.sensor_x.empty() ? std::vector<double>{l} : design_choices(caller, "sensor-x", request.sensor_x);
  o.force_positions_m =
      request.force_x.empty() ? std::vector<double>{l} : design_choices(caller, "force-x", request.force_x);
  o.pulse_widths_s = request.pulse_width.empty() ? std::vector<double>{o.base.pulse_width_s}
                                                 : design_choices(caller, "pulse-width", request.pulse_width);
  o.dts_s = request.dt.empty() ? std::vector<double>{o.base.dt_s} : design_choices(caller, "dt", request.dt);
  for (const double n : request.samples.empty() ? std::vector<double>{static_cast<double>(o.base.samples)}
                                                : design_choices(caller, "samples", request.samples)) {
    if (!(n >= 2 && n <= core::kMaxSamples && n == std::floor(n)))
      refuse(caller, "samples", format_value(n), "each must be an integer in 2.." + std::to_string(core::kMaxSamples));
    o.samples.push_back(static_cast<int>(n));
  }
  // Each choice as an experiment would take it (positions on the span, widths and steps > 0), named by its flag.
  for (const auto& [flag, values] :
       {std::pair{"sensor-x", &o.sensor_positions_m}, std::pair{"force-x", &o.force_positions_m}})
    for (const double x : *values)
      if (!(x >= 0 && x <= l))
        refuse(caller, flag, format_value(x), "must lie on the beam, in [0, " + format_value(l) + "] m");
  for (const double tau : o.pulse_widths_s)
    if (!(tau > 0)) refuse(caller, "pulse-width", format_value(tau), "must be > 0");
  for (const double dt : o.dts_s)
    if (!(dt >= 1e-9)) refuse(caller, "dt", format_value(dt), "must be >= 1e-9 s");
  double largest = 0;
  for (const int n : o.samples) largest = std::max(largest, static_cast<double>(n));
  guard_run_size(caller, o.elements, largest, core::kSimulateBytesPerSample, warnings);
  o.sensor_count = request.sensors.value_or(1);
  o.criterion = request.criterion.value_or(fit::kDOptimal);
  if (request.noise_sd && request.noise_level)
    refuse(caller,
           "give one of --noise-sd S (absolute, the same on every channel) and --noise-level L (a fraction of "
           "each channel's RMS), not both");
  if (!request.noise_sd && !request.noise_level)
    refuse(caller, "give one of --noise-sd S (absolute, the same on every channel) and --noise-level L");
  o.noise_sd = request.noise_sd.value_or(0);
  o.noise_level = request.noise_level.value_or(0);
  if (request.noise_sd && !(o.noise_sd >= 1e-150 && o.noise_sd <= 1e150))
    refuse(caller, "noise-sd", format_value(o.noise_sd), "must lie in [1e-150, 1e150] (in the output's unit)");
  if (request.noise_level && !(o.noise_level > 0 && std::isfinite(o.noise_level)))
    refuse(caller, "noise-level", format_value(o.noise_level), "must be > 0");
  if (request.noise_model) o.noise_model = parsed_noise_model(caller, *request.noise_model).text();
  std::string listed;
  for (const std::string& key : o.keys) listed += (listed.empty() ? "" : ",") + key;
  if (o.keys.empty()) refuse(caller, "estimate", listed, "must name at least one parameter");
  for (const std::string& key : o.keys)
    if (!model::describe_parameter(o.beam, key))
      refuse(caller, "estimate", listed,
             "'" + key + "' is not a parameter of this beam (valid: " + model::estimable_keys(o.beam) + ")");
  if (o.criterion != fit::kDOptimal && o.criterion != fit::kAOptimal &&
      std::find(o.keys.begin(), o.keys.end(), o.criterion) == o.keys.end())
    refuse(caller, "criterion", o.criterion, "must be D, A or one of --estimate's parameters (" + listed + ")");
  if (o.sensor_count < 1 || o.sensor_count > static_cast<int>(o.sensor_positions_m.size()))
    refuse(caller, "sensors", std::to_string(o.sensor_count),
           "must be in 1.." + std::to_string(o.sensor_positions_m.size()) + " (the --sensor-x positions given)");
  if (fit::candidate_count(o) > fit::kMaxDesignCandidates)
    refuse(caller, "sensors", std::to_string(o.sensor_count),
           "the positions' subsets times the other choices make more than " +
               std::to_string(fit::kMaxDesignCandidates) + " candidates: fewer positions or sensors");
  if (auto error = fit::validation_error(o)) refuse(caller, *error);
  r.rows = fit::rank_designs(o);
  return r;
}

}  // namespace beamid::api
