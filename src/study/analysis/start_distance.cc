#include "study/analysis/start_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "core/errors.h"
#include "core/hash.h"
#include "galerkin/modes.h"
#include "signal/noise.h"
#include "study/analysis/statistics.h"
#include "study/tables/format.h"

namespace beamid::study {
Eigen::VectorXd random_direction(std::uint64_t seed, int dimension) {
  const std::vector<double> g = signal::gaussian_deviates(seed, static_cast<std::size_t>(dimension));
  Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(g.data(), dimension);
  return u / u.norm();
}

OffsetStart offset_start(const galerkin::BeamForms& forms, const model::BeamParameters& truth,
                         const std::vector<std::string>& keys, int modes, const Eigen::VectorXd& direction,
                         double offset, double bound_factor) {
  const Eigen::MatrixXd g = galerkin::frequency_sensitivities(forms, truth, keys, modes);
  const double slope = (g * direction).cwiseAbs().maxCoeff();  // max_k |d log f_k / ds| along u
  OffsetStart out;
  const double limit = 0.9 * std::log(bound_factor) / direction.cwiseAbs().maxCoeff();
  out.step = slope > 0 ? std::log1p(offset) / slope : limit;
  if (!(slope > 0) || out.step > limit) out.step = limit, out.shrunk = true;
  out.start = truth;
  for (std::size_t i = 0; i < keys.size(); ++i)
    model::set_parameter_value(
        out.start, keys[i],
        model::parameter_value(out.start, keys[i]) * std::exp(out.step * direction(static_cast<Eigen::Index>(i))));
  const Eigen::VectorXd f0 = galerkin::lowest_undamped_modes(forms, truth, modes).omega_rad_s,
                        f1 = galerkin::lowest_undamped_modes(forms, out.start, modes).omega_rad_s;
  out.frequency_offset = (f1.array() / f0.array() - 1).abs().maxCoeff();
  return out;
}

HalfRadius half_radius(const std::vector<double>& offsets, const std::vector<double>& rates) {
  HalfRadius r;
  if (offsets.empty() || offsets.size() != rates.size()) throw InputError("half_radius: no curve");
  if (!(rates.front() >= 0.5)) {
    r.below = true;
    r.value = offsets.front();
    return r;
  }
  for (std::size_t j = 1; j < rates.size(); ++j) {
    if (rates[j] >= 0.5) continue;
    const double a = std::log(offsets[j - 1]), b = std::log(offsets[j]);
    r.value = std::exp(a + (rates[j - 1] - 0.5) / (rates[j - 1] - rates[j]) * (b - a));
    return r;
  }
  r.above = true;
  r.value = offsets.back();
  return r;
}

std::string radius_text(const HalfRadius& r) {
  const std::string percent = g3(100 * r.value) + " %";
  return r.below ? "< " + percent : r.above ? "> " + percent : percent;
}

void predict_basins(const std::vector<double>& f, const std::vector<double>& zeta, double record_s,
                    StartDistanceMetrics& m) {
  m.record_s = record_s;
  const auto fitted = static_cast<std::size_t>(m.fitted_modes);
  if (fitted == 0 || f.size() < fitted || zeta.size() < fitted) return;
  // f is the natural frequency |lambda| / (2 pi) and zeta = -Re(lambda) / |lambda|, so sigma = 2 pi f zeta.
  const auto decay_limited = [&](std::size_t k) {
    return 1 / (2 * f[k] * std::min(record_s, 1 / (2 * M_PI * f[k] * zeta[k])));
  };
  m.highest_mode_hz = f[fitted - 1];
  m.predicted_basin = 1 / (2 * m.highest_mode_hz * record_s);
  m.predicted_basin_highest_decay = decay_limited(fitted - 1);
  m.limiting_mode = 0;
  for (std::size_t k = 0; k < fitted; ++k)
    if (m.limiting_mode == 0 || decay_limited(k) < m.predicted_basin_decay) {
      m.limiting_mode = static_cast<int>(k + 1);
      m.limiting_mode_hz = f[k];
      m.decay_rate_1_s = 2 * M_PI * f[k] * zeta[k];
      m.predicted_basin_decay = decay_limited(k);
    }
}

bool predict_basins(const StudyResults& results, int truth, int samples, StartDistanceMetrics& m) {
  const auto t = static_cast<std::size_t>(truth);
  if (t >= results.truths.size() || !results.truths[t].has("mode_frequency_hz") ||
      !results.truths[t].has("mode_damping_ratio"))
    return false;
  predict_basins(results.truths[t].numbers("mode_frequency_hz"), results.truths[t].numbers("mode_damping_ratio"),
                 samples * results.spec->truth.experiment.dt_s, m);
  return true;
}

bool reaches(const StudySpec& spec, const Record& reference, const Record& fit) {
  if (fit.text("status") == "failed" || reference.text("status") == "failed") return false;
  for (const auto& key : spec.fit.estimate) {
    const double a = reference.number("estimate." + key), b = fit.number("estimate." + key);
    const double tolerance =
        model::parameter_role(key) == "damping" ? spec.start_distance.damping_agreement : spec.start_distance.agreement;
    if (!(std::abs(b - a) <= tolerance * std::abs(a))) return false;  // NaN: not reached
  }
  return true;
}

// Bootstrap resamples of the records behind a radius's interval: 1,000 put its 2.5 % quantile within about 0.5 % in
// probability of the true one (Efron and Tibshirani 1993, section 13.6: 1,000 for percentile intervals).
constexpr int kBootstrapResamples = 1000;

HalfRadius reach_radius(const std::vector<double>& offsets, const std::vector<ReachOutcome>& outcomes) {
  if (offsets.empty()) throw InputError("reach_radius: no offsets");
  HalfRadius r;
  std::vector<double> x;
  std::vector<int> y;
  int reached = 0;
  for (const auto& o : outcomes) {
    x.push_back(std::log(o.offset));
    y.push_back(o.reached ? 1 : 0);
    reached += o.reached ? 1 : 0;
  }
  const auto at_end = [&](bool above) {
    r.above = above;
    r.below = !above;
    r.value = above ? offsets.back() : offsets.front();
    return r;
  };
  if (outcomes.empty()) return at_end(false);
  // All of one kind: the curve does not cross 1/2 within the range (Firth's fit would put it just outside).
  if (reached == 0 || reached == static_cast<int>(outcomes.size())) return at_end(reached > 0);
  const LogisticFit fit = firth_logistic(x, y);
  if (!fit.converged) {
    std::vector<double> rates;
    for (double offset : offsets) {
      int k = 0, n = 0;
      for (const auto& o : outcomes)
        if (o.offset == offset) ++n, k += o.reached ? 1 : 0;
      rates.push_back(n > 0 ? static_cast<double>(k) / n : 0.0);
    }
    return half_radius(offsets, rates);
  }
  if (!(fit.slope < 0)) return at_end(2 * reached >= static_cast<int>(outcomes.size()));
  const double log_r50 = -fit.intercept / fit.slope;
  if (log_r50 < std::log(offsets.front())) return at_end(false);
  if (log_r50 > std::log(offsets.back())) return at_end(true);
  r.value = std::exp(log_r50);
  return r;
}

std::pair<HalfRadius, HalfRadius> reach_radius_interval(const std::vector<double>& offsets,
                                                        const std::vector<ReachOutcome>& outcomes, int records,
                                                        std::uint64_t seed, int resamples) {
  std::vector<std::vector<ReachOutcome>> by_record(static_cast<std::size_t>(std::max(records, 0)));
  for (const auto& o : outcomes)
    if (o.record >= 0 && o.record < records) by_record[static_cast<std::size_t>(o.record)].push_back(o);
  // ln r50 per resample, a censored one at -inf or +inf, so that it sorts at its end.
  std::vector<double> logs;
  for (const auto& sample : bootstrap_resamples(seed, records, resamples)) {
    std::vector<ReachOutcome> pooled;
    for (int record : sample) {
      const auto& own = by_record[static_cast<std::size_t>(record)];
      pooled.insert(pooled.end(), own.begin(), own.end());
    }
    const HalfRadius h = reach_radius(offsets, pooled);
    const double inf = std::numeric_limits<double>::infinity();
    logs.push_back(h.below ? -inf : h.above ? inf : std::log(h.value));
  }
  const auto bound = [&](double q) {
    HalfRadius h;
    const double v = quantile(logs, q);
    h.below = v == -std::numeric_limits<double>::infinity();
    h.above = v == std::numeric_limits<double>::infinity();
    h.value = h.below ? offsets.front() : h.above ? offsets.back() : std::exp(v);
    return h;
  };
  return {bound(0.025), bound(0.975)};
}

std::vector<ReferenceErrors> reference_errors(const StudyResults& results, const StartRun& run) {
  const StudySpec& spec = *results.spec;
  const auto& d = spec.start_distance;
  const LandscapeRow* bound = nullptr;
  for (const auto& b : results.bounds)
    if (b.unit->truth == run.truth && b.unit->samples == run.samples && b.unit->elements == d.elements &&
        b.unit->noise == d.noise && b.record.text("status") == "ok")
      bound = &b;
  std::vector<ReferenceErrors> out;
  for (const auto& key : spec.fit.estimate) {
    ReferenceErrors e;
    e.parameter = key;
    const double truth = model::parameter_value(spec.truth.parameters, key);
    std::vector<double> errors;
    for (const LandscapeRow* r : run.references)
      if (r && r->record.text("status") != "failed") errors.push_back(r->record.number("estimate." + key) / truth - 1);
    e.errors = stats(errors);
    e.mcse = e.errors.mcse();
    if (bound) e.bound = bound->record.number("relative_sd." + key);
    out.push_back(e);
  }
  return out;
}

std::vector<ModeErrors> mode_errors(const StudyResults& results, const StartRun& run, int modes) {
  std::vector<ModeErrors> out;
  const auto t = static_cast<std::size_t>(run.truth);
  if (t >= results.truths.size() || !results.truths[t].has("mode_frequency_hz") ||
      !results.truths[t].has("mode_damping_ratio"))
    return out;
  const std::vector<double> f0 = results.truths[t].numbers("mode_frequency_hz"),
                            z0 = results.truths[t].numbers("mode_damping_ratio");
  for (int k = 0; k < modes && static_cast<std::size_t>(k) < std::min(f0.size(), z0.size()); ++k) {
    ModeErrors e;
    e.mode = k + 1;
    e.truth_frequency_hz = f0[static_cast<std::size_t>(k)];
    e.truth_damping_ratio = z0[static_cast<std::size_t>(k)];
    std::vector<double> df, dz;
    for (const LandscapeRow* r : run.references) {
      if (!r || r->record.text("status") == "failed" || !r->record.has("fitted_mode_frequency_hz")) continue;
      const std::vector<double> f = r->record.numbers("fitted_mode_frequency_hz"),
                                z = r->record.numbers("fitted_mode_damping_ratio");
      if (static_cast<std::size_t>(k) >= std::min(f.size(), z.size())) continue;
      df.push_back(f[static_cast<std::size_t>(k)] / e.truth_frequency_hz - 1);
      dz.push_back(z[static_cast<std::size_t>(k)] / e.truth_damping_ratio - 1);
    }
    e.frequency = stats(df);
    e.damping = stats(dz);
    e.frequency_mcse = e.frequency.mcse();
    e.damping_mcse = e.damping.mcse();
    out.push_back(e);
  }
  return out;
}

std::vector<StartPair> paired_comparisons(const std::vector<StartRun>& runs) {
  std::vector<StartPair> pairs;
  // An outcome's key within its experiment: the same record, direction and offset.
  using Key = std::tuple<int, int, double>;
  for (std::size_t a = 0; a < runs.size(); ++a)
    for (std::size_t b = a + 1; b < runs.size(); ++b) {
      if (runs[a].experiment != runs[b].experiment) continue;
      std::map<Key, bool> first;
      for (const auto& o : runs[a].outcomes) first[{o.record, o.direction, o.offset}] = o.reached;
      StartPair p;
      p.experiment = runs[a].experiment;
      p.first = a;
      p.second = b;
      for (const auto& o : runs[b].outcomes) {
        const auto it = first.find({o.record, o.direction, o.offset});
        if (it == first.end()) continue;
        ++p.matched;
        (it->second ? (o.reached ? p.both : p.first_only) : (o.reached ? p.second_only : p.neither)) += 1;
      }
      p.p_value = mcnemar_exact_p(p.first_only, p.second_only);
      pairs.push_back(p);
    }
  return pairs;
}

// A run's 50 % radius and its interval: with several records the reach curve and its bootstrap across records
// (seeded by the study seed, the run and the experiment, so that the tables are byte-identical between runs); with
// one, the crossing of the rates and of their Wilson bounds.
void set_radius(const StudySpec& spec, int experiment, StartRun& run) {
  const auto& d = spec.start_distance;
  if (!run.reference_ok) return;
  if (d.records > 1) {
    run.radius = reach_radius(d.offsets, run.outcomes);
    const std::uint64_t seed = core::derive_seed(
        spec.seed, "reach-bootstrap;" + run.cost + "/" + run.method + ";" + std::to_string(experiment));
    std::tie(run.radius_low, run.radius_high) =
        reach_radius_interval(d.offsets, run.outcomes, d.records, seed, kBootstrapResamples);
    return;
  }
  std::vector<double> offsets, rates, lows, highs;
  for (const auto& p : run.points) {
    const auto [low, high] = wilson_interval(p.reached, p.fits);
    offsets.push_back(p.offset);
    rates.push_back(p.rate());
    lows.push_back(low);
    highs.push_back(high);
  }
  run.radius = half_radius(offsets, rates);
  run.radius_low = half_radius(offsets, lows);
  run.radius_high = half_radius(offsets, highs);
}

StartDistanceMetrics start_distance_metrics(const StudyResults& results) {
  const StudySpec& spec = *results.spec;
  const auto& d = spec.start_distance;
  StartDistanceMetrics m;
  m.reached.assign(results.starts.size(), false);
  if (!d.enabled) return m;
  // The experiments in plan order (the truth index and record length of the start units).
  std::vector<std::pair<int, int>> experiments;
  for (const auto& row : results.starts) {
    const std::pair<int, int> e{row.unit->truth, row.unit->samples};
    if (std::find(experiments.begin(), experiments.end(), e) == experiments.end()) experiments.push_back(e);
  }
  m.experiments = static_cast<int>(experiments.size());
  for (std::size_t ei = 0; ei < experiments.size(); ++ei) {
    // Plain copies, not a structured binding: C++17 lambdas may not capture structured bindings (clang rejects it).
    const int truth = experiments[ei].first;
    const int samples = experiments[ei].second;
    const auto in_experiment = [&](const Unit& u) { return u.truth == truth && u.samples == samples; };
    for (const auto& [cost, method] : d.runs) {
      StartRun run;
      run.cost = cost;
      run.method = method;
      run.experiment = static_cast<int>(ei);
      run.truth = truth;
      run.samples = samples;
      run.pulse_width_s = results.plan->truths[static_cast<std::size_t>(truth)].pulse_width_s;
      run.records = d.records;
      run.references.assign(static_cast<std::size_t>(d.records), nullptr);
      for (const auto& row : results.starts)
        if (in_experiment(*row.unit) && row.unit->cost == cost && row.unit->method == method && row.unit->index < 0 &&
            row.unit->replicate >= 0 && row.unit->replicate < d.records)
          run.references[static_cast<std::size_t>(row.unit->replicate)] = &row;
      run.reference = run.references.front();
      const auto ok = [](const LandscapeRow* r) { return r && r->record.text("status") != "failed"; };
      for (const LandscapeRow* r : run.references) run.references_failed += ok(r) ? 0 : 1;
      run.reference_ok = run.references_failed < d.records;
      for (double offset : d.offsets) {
        StartCurvePoint p;
        p.offset = offset;
        std::vector<double> evaluations;
        for (std::size_t i = 0; i < results.starts.size(); ++i) {
          const LandscapeRow& row = results.starts[i];
          const Unit& u = *row.unit;
          if (!in_experiment(u) || u.cost != cost || u.method != method || u.index < 0 || u.offset != offset) continue;
          const LandscapeRow* reference = run.references[static_cast<std::size_t>(u.replicate)];
          if (!ok(reference)) continue;
          ++p.fits;
          m.reached[i] = reaches(spec, reference->record, row.record);
          p.reached += m.reached[i] ? 1 : 0;
          p.shrunk += row.record.number("shrunk") > 0 ? 1 : 0;
          evaluations.push_back(row.record.number("evaluations"));
          run.outcomes.push_back({u.replicate, u.index, offset, m.reached[i]});
        }
        p.median_evaluations = median(evaluations);
        run.points.push_back(p);
      }
      for (const auto& row : results.starts)
        if (in_experiment(*row.unit) && row.unit->cost == cost && row.unit->method == method) {
          ++run.fits_run;
          run.budget_exhausted += row.record.text("status") == "max-evaluations" ? 1 : 0;
        }
      run.reference_errors = reference_errors(results, run);
      if (run.reference) {
        const Record& r = run.reference->record;
        run.fitted_modes = r.has("fitted_modes") ? static_cast<int>(r.number("fitted_modes")) : 0;
        run.modes_in_data = r.has("modes_in_data") ? static_cast<int>(r.number("modes_in_data")) : 0;
      }
      run.mode_errors = mode_errors(results, run, run.fitted_modes);
      set_radius(spec, static_cast<int>(ei), run);
      run.record_s = samples * spec.truth.experiment.dt_s;
      StartDistanceMetrics prediction;
      prediction.fitted_modes = run.fitted_modes;
      if (run.fitted_modes > 0 && predict_basins(results, truth, samples, prediction)) {
        run.predicted_basin = prediction.predicted_basin;
        run.predicted_basin_decay = prediction.predicted_basin_decay;
        run.predicted_basin_highest_decay = prediction.predicted_basin_highest_decay;
        run.limiting_mode = prediction.limiting_mode;
        // The study-wide predictions are the first experiment's (from its first run with a known mode count).
        if (ei == 0 && m.fitted_modes == 0) {
          m.fitted_modes = run.fitted_modes;
          predict_basins(results, truth, samples, m);
        }
      }
      m.runs.push_back(run);
    }
  }
  m.pairs = paired_comparisons(m.runs);
  return m;
}

}  // namespace beamid::study
