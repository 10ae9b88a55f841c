#include "fit/profile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/errors.h"
#include "fit/joint_objective.h"

namespace beamid::fit {

namespace {

// The minimum sum of squares with `key` fixed at `value`: the other estimated parameters refitted from `from` (a
// neighbouring point's estimates, one beam per record), or with none left, the cost there.
struct Refit {
  double cost = std::numeric_limits<double>::quiet_NaN();
  std::string status;
  std::vector<model::BeamParameters> beams;
};
Refit refit(const FitOptions& options, const std::vector<Record>& records, const std::string& key, double value,
            const std::vector<model::BeamParameters>& from) {
  FitOptions o = options;
  o.estimate.erase(
      std::remove_if(o.estimate.begin(), o.estimate.end(), [&](const EstimatedParameter& e) { return e.key == key; }),
      o.estimate.end());
  o.of_interest.erase(std::remove(o.of_interest.begin(), o.of_interest.end(), key), o.of_interest.end());
  std::vector<Record> fixed = records;
  for (std::size_t r = 0; r < fixed.size(); ++r) {
    fixed[r].start = from[r];
    model::set_parameter_value(fixed[r].start, key, value);
  }
  o.start = fixed.front().start;
  Refit out;
  try {
    if (o.estimate.empty()) {
      // Nothing to refit: the cost at the value, as the fit's objective computes it.
      std::vector<model::BeamParameters> beams;
      for (const Record& r : fixed) beams.push_back(r.start);
      const ParameterMap map(beams, options.estimate, options.scaling);  // every record's beam, as fit's map has
      JointObjective objective(options, fixed, map);
      const costs::Evaluation e = objective.evaluate(beams).evaluation;
      out.cost = e.ok() ? e.value : std::numeric_limits<double>::infinity();
      out.status = e.ok() ? "evaluated" : e.status;
      out.beams = beams;
      return out;
    }
    const FitResult r = fit(o, fixed);
    out.status = r.status;
    out.cost = r.status == "failed" ? std::numeric_limits<double>::quiet_NaN() : r.cost;
    for (const auto& record : r.records) out.beams.push_back(record.beam);
    if (out.beams.size() != records.size()) out.beams = from;
  } catch (const std::exception& e) {
    out.status = std::string("failed: ") + e.what();
    out.beams = from;
  }
  return out;
}

// The value where the signed root sqrt(D) reaches sqrt(level) between two points (D rising from a to b), linearly in
// ln q: the root is linear in q where the cost is quadratic.
double crossing(const ProfilePoint& a, const ProfilePoint& b, double level) {
  const double ra = std::sqrt(std::max(0.0, a.statistic)), rb = std::sqrt(std::max(0.0, b.statistic));
  const double t = rb > ra ? (std::sqrt(level) - ra) / (rb - ra) : 1.0;
  return std::exp(std::log(a.value) + std::clamp(t, 0.0, 1.0) * (std::log(b.value) - std::log(a.value)));
}

}  // namespace

double profile_level(double probability, int dof) {
  const double z = probability > 0.9 ? 1.959963984540054 : 1.0;  // the standard normal quantile of 0.975 or 0.8413
  if (dof <= 0) return std::numeric_limits<double>::infinity();
  double t = 0;
  if (dof == 1) {
    t = std::tan(std::numbers::pi * (probability - 0.5));
  } else if (dof == 2) {
    t = (2 * probability - 1) / std::sqrt(2 * probability * (1 - probability));
  } else {
    const double n = dof, z2 = z * z;
    t = z + (z2 * z + z) / (4 * n) + (5 * std::pow(z, 5) + 16 * z2 * z + 3 * z) / (96 * n * n) +
        (3 * std::pow(z, 7) + 19 * std::pow(z, 5) + 17 * z2 * z - 15 * z) / (384 * n * n * n) +
        (79 * std::pow(z, 9) + 776 * std::pow(z, 7) + 1482 * std::pow(z, 5) - 1920 * z2 * z - 945 * z) /
            (92160 * n * n * n * n);
  }
  return t * t;
}

Profile profile(const FitOptions& options, const std::vector<Record>& records, const FitResult& best,
                const std::string& key) {
  Profile p;
  p.key = key;
  const auto it = std::find_if(best.parameters.begin(), best.parameters.end(),
                               [&](const ParameterEstimate& e) { return e.key == key; });
  if (it == best.parameters.end())
    throw InputError("profile = '" + key + "': not an estimated parameter (the profile fixes one of them)");
  if (record_key(key))
    throw InputError("profile = '" + key + "': a record's own parameter; profiles are of shared keys");
  if (best.status == "failed") throw InputError("profile = '" + key + "': the fit failed, so there is no minimum");
  const auto m = static_cast<double>(best.final_evaluation.residuals.size());
  const auto n = static_cast<double>(best.parameters.size());
  if (!(m > n) || !(best.cost > 0))
    throw InputError("profile = '" + key + "': the fit leaves no degrees of freedom (" + format_value(m) +
                     " residuals, " + format_value(n) +
                     " parameters) or no residual, so no noise level to scale "
                     "the cost's rise by");
  if (options.record_weights == kNoiseWeights && records.size() > 1)
    throw InputError("profile = '" + key +
                     "': the records are weighted by their noise (--record-weights noise), which "
                     "every refit would estimate again, flattening the profile; profile with the default weights");
  if (best.parameters.size() == 1 && costs::is_estimated_noise(options.cost.noise_model))
    throw InputError("profile = '" + key +
                     "': with one estimated parameter and the noise estimated from the fit, "
                     "the profile would evaluate the cost under another noise model; estimate another parameter too");
  p.estimate = it->estimate, p.standard_error = it->standard_error;
  const int dof = static_cast<int>(m - n);
  p.level68 = profile_level(0.8413447460685429, dof), p.level95 = profile_level(0.975, dof);
  const double variance = best.cost / (m - n);
  const double log_range = std::log(it->upper) - std::log(it->lower);
  const double step = std::isfinite(it->standard_error) && it->standard_error > 0
                          ? std::min(0.5 * it->standard_error / std::abs(it->estimate), log_range / 4)
                          : log_range / 50;
  std::vector<model::BeamParameters> start;
  for (const auto& r : best.records) start.push_back(r.beam);
  p.points.push_back({it->estimate, best.cost, 0.0, best.status});
  for (const int side : {-1, 1}) {
    std::vector<model::BeamParameters> from = start;
    bool closed = false;
    double offset = 0, stride = step, previous = 0;  // ln(value / estimate) of the last point, and its D
    int halvings = 0;
    for (int k = 1; k <= kMaxProfileSteps;) {
      double value = it->estimate * std::exp(side * (offset + stride));
      const bool at_bound = side < 0 ? value <= it->lower : value >= it->upper;
      if (at_bound) value = side < 0 ? it->lower : it->upper;
      const Refit r = refit(options, records, key, value, from);
      ProfilePoint point{value, r.cost, (r.cost - best.cost) / variance, r.status};
      if (point.statistic - previous > 2 && halvings < kMaxProfileHalvings) {  // too coarse a step: halve it
        stride /= 2, ++halvings;
        continue;
      }
      if (std::isfinite(point.statistic) && point.statistic < -kLowerMinimumD && p.lower_minimum.empty())
        p.lower_minimum = key + " = " + format_value(value) + " gives a lower cost (" + format_value(r.cost) + " < " +
                          format_value(best.cost) + "): the fit's estimate is no global minimum";
      p.points.push_back(point);
      ++k, offset = std::abs(std::log(value / it->estimate));
      if (std::isfinite(r.cost)) from = r.beams, previous = point.statistic;
      if (point.statistic > p.level95) {
        closed = true;
        break;
      }
      if (at_bound) break;
    }
    (side < 0 ? p.open_below : p.open_above) = !closed;
  }
  std::sort(p.points.begin(), p.points.end(),
            [](const ProfilePoint& a, const ProfilePoint& b) { return a.value < b.value; });
  const auto centre = static_cast<std::size_t>(
      std::find_if(p.points.begin(), p.points.end(), [&](const ProfilePoint& q) { return q.value == p.estimate; }) -
      p.points.begin());
  // Outwards from the estimate, the first point at or beyond each level.
  for (const bool wide : {false, true}) {
    const double level = wide ? p.level95 : p.level68;
    for (std::size_t i = centre; i + 1 < p.points.size(); ++i)
      if (p.points[i + 1].statistic >= level) {
        (wide ? p.upper95 : p.upper68) = crossing(p.points[i], p.points[i + 1], level);
        break;
      }
    for (std::size_t i = centre; i > 0; --i)
      if (p.points[i - 1].statistic >= level) {
        (wide ? p.lower95 : p.lower68) = crossing(p.points[i], p.points[i - 1], level);
        break;
      }
  }
  return p;
}

std::string Profile::line() const {
  if (status != "ok") return key + ": no profile (" + status + ")";
  const auto end = [](double v, const char* open) { return std::isnan(v) ? std::string(open) : format_value(v); };
  std::ostringstream s;
  s << key << " profile: 68 % [" << end(lower68, "open") << ", " << end(upper68, "open") << "], 95 % ["
    << end(lower95, "open") << ", " << end(upper95, "open") << "]";
  if (std::isfinite(standard_error))
    s << " (formal: " << format_value(estimate - 1.96 * standard_error) << ", "
      << format_value(estimate + 1.96 * standard_error) << " at 95 %)";
  if (open_below || open_above)
    s << "; not bounded "
      << (open_below && open_above ? "below or above"
          : open_below             ? "below"
                                   : "above")
      << " by the data within its bounds";
  if (!lower_minimum.empty()) s << "; " << lower_minimum;
  return s.str();
}

}  // namespace beamid::fit
