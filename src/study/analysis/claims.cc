#include "study/analysis/claims.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "costs/cost.h"
#include "model/beam_parameters.h"
#include "study/tables/format.h"

namespace beamid::study {
namespace {

// The costs the claims compare (their names from the cost registry).
const std::string& kTime = costs::kTimeCost;
const std::string& kSpike = costs::kSpikeCost;
const std::string& kSmooth = costs::kSpikeSmoothCost;

}  // namespace

namespace {

// Start-distance counts and claims: each run's 50 % radius with its interval; least squares (direct) against the
// predicted 1/(2 f T); every other run against the first (the study lists time/direct first).
void start_distance_findings(const StartDistanceMetrics& m, Findings& f) {
  if (m.runs.empty()) return;
  // With several experiments, a run is named with its experiment's modes in the data and pulse width.
  const auto name = [&](const StartRun& r) {
    return r.cost + "/" + r.method +
           (m.experiments > 1 ? " (" + std::to_string(r.modes_in_data) + " modes in the data, pulse " +
                                    g3(1e3 * r.pulse_width_s) + " ms)"
                              : std::string());
  };
  for (const auto& r : m.runs) {
    if (!r.reference_ok) {
      f.counts.push_back({name(r) + ": the fit from the truth failed, so no start can be judged", 0, 0});
      continue;
    }
    int reached = 0, fits = 0;
    for (const auto& p : r.points) reached += p.reached, fits += p.fits;
    f.counts.push_back({name(r) + ": half of the starts reach the minimum out to a frequency offset of " +
                            radius_text(r.radius) + " (95 % interval " + radius_text(r.radius_low) + " to " +
                            radius_text(r.radius_high) + "; " + std::to_string(reached) + "/" + std::to_string(fits) +
                            " starts reach it over all offsets)",
                        reached, fits});
  }
  for (const auto& r : m.runs)
    if (r.reference_ok && (r.cost == "time" || r.cost == "freq-band") && r.method == "direct" && !r.radius.below &&
        !r.radius.above && r.predicted_basin > 0) {
      const auto within = [&](double predicted) {
        return r.radius.value <= 3 * predicted && r.radius.value >= predicted / 3;
      };
      f.claims.push_back({within(r.predicted_basin),
                          name(r) + "'s 50 % radius, " + radius_text(r.radius) +
                              ", is within a factor 3 of the least-squares basin 1/(2 f T) = " +
                              pct(r.predicted_basin) + " predicted from the record length (f of mode " +
                              std::to_string(r.fitted_modes) + ", T = " + g3(r.record_s) + " s)",
                          -1, -1});
      f.claims.push_back(
          {within(r.predicted_basin_decay),
           name(r) + "'s 50 % radius, " + radius_text(r.radius) +
               ", is within a factor 3 of min_k 1/(2 f_k T_eff,k) = " + pct(r.predicted_basin_decay) +
               ", predicted from the time each fitted mode is visible, T_eff = min(T, 1/sigma), and " +
               "reached at mode " + std::to_string(r.limiting_mode) +
               (r.experiment == 0 ? " (f = " + g3(m.limiting_mode_hz) + " Hz, sigma = " + g3(m.decay_rate_1_s) +
                                        " 1/s, T_eff = " + g3(std::min(m.record_s, 1 / m.decay_rate_1_s)) + " s)"
                                  : std::string()),
           -1, -1});
    }
  // Paired on the same starts (several records): every run against the first of its experiment, by McNemar's test
  // at the 5 % level on the starts one of the two reaches and the other does not.
  for (const StartPair& p : m.pairs) {
    const StartRun &a = m.runs[p.first], &b = m.runs[p.second];
    if (m.runs.front().records < 2 || a.cost != m.runs.front().cost || a.method != m.runs.front().method) continue;
    f.claims.push_back({p.second_only > p.first_only && p.p_value < 0.05,
                        name(b) + " reaches the minimum from more of the same starts than " + name(a) + " (of " +
                            std::to_string(p.matched) + " starts, it alone reaches from " +
                            std::to_string(p.second_only) + ", the other alone from " + std::to_string(p.first_only) +
                            "; McNemar p = " + g3(p.p_value) + ")",
                        -1, -1});
  }
  // Every run against the first of its experiment (the study lists time/direct first).
  for (const StartRun& first : m.runs) {
    if (first.cost != m.runs.front().cost || first.method != m.runs.front().method || !first.reference_ok) continue;
    for (const StartRun& r : m.runs) {
      if (r.experiment != first.experiment || &r == &first || !r.reference_ok) continue;
      f.claims.push_back(
          {r.radius_low.value > first.radius_high.value && !r.radius_low.below && !first.radius_high.above,
           name(r) + "'s 50 % radius is larger than " + name(first) + "'s, their 95 % intervals apart (" +
               radius_text(r.radius_low) + " to " + radius_text(r.radius_high) + " against " +
               radius_text(first.radius_low) + " to " + radius_text(first.radius_high) + ")",
           -1, -1});
    }
  }
}

// Efficiency counts and claims at the largest N of the sweep: each cost's RMSE / bound per noise level, whether it is
// efficient (within 0.8-1.25 x the bound: the relative Monte-Carlo standard error of an RMSE from n fits is about
// 1/sqrt(2 (n - 1)), 10 % at n = 50 and 7 % at 100, so the claim is made only where every setting kept 50 fits or
// more at the minimum), and its significant biases.
void efficiency_findings(const StudySpec& spec, const std::vector<EfficiencyRow>& rows, Findings& f) {
  if (rows.empty()) return;
  const int largest = *std::max_element(spec.sweep.elements.begin(), spec.sweep.elements.end());
  std::map<std::tuple<std::string, std::string, double>, std::vector<const EfficiencyRow*>> by_setting;
  for (const auto& r : rows)
    if (r.key.elements == largest) by_setting[{r.key.cost, r.key.method, r.key.noise}].push_back(&r);
  for (const auto& [setting, members] : by_setting) {
    const auto& [cost, method, noise] = setting;
    std::string text =
        cost + " (" + method + ", N = " + std::to_string(largest) + ", noise " + pct(noise) + "): RMSE / bound";
    for (const EfficiencyRow* r : members) text += " " + r->parameter + " " + g3(r->efficiency());
    text += ", over the " + count_with_interval(members.front()->stayed, members.front()->fits) +
            " fits that stayed at the minimum";
    f.counts.push_back({text, members.front()->stayed, members.front()->fits});
  }
  std::map<std::pair<std::string, std::string>, std::vector<const EfficiencyRow*>> by_cost;
  for (const auto& r : rows)
    if (r.key.elements == largest) by_cost[{r.key.cost, r.key.method}].push_back(&r);
  for (const auto& [cost_method, members] : by_cost) {
    int efficient = 0, biased = 0, total = 0;
    bool enough = true;
    for (const EfficiencyRow* r : members) {
      ++total;
      efficient += r->efficiency() >= 0.8 && r->efficiency() <= 1.25 ? 1 : 0;
      biased += r->significant_bias() ? 1 : 0;
      enough = enough && r->stayed >= 50;
    }
    const std::string name = cost_method.first + " (" + cost_method.second + ")";
    if (enough)
      f.claims.push_back({efficient == total,
                          name +
                              " is efficient: RMSE within 0.8-1.25 x the Cramér-Rao bound for every parameter and "
                              "noise level (" +
                              std::to_string(efficient) + "/" + std::to_string(total) + ")",
                          efficient, total});
    f.counts.push_back({name + ": a bias beyond 2 Monte-Carlo standard errors in " + std::to_string(biased) + " of " +
                            std::to_string(total) + " (parameter, noise) settings",
                        biased, total});
  }
}

// Bias decomposition counts, per cost, method and N: the noise-free bias of each parameter (the minimum's), and in how
// many (parameter, noise) settings the noise-induced bias exceeds twice its Monte-Carlo standard error.
void bias_findings(const std::vector<BiasRow>& rows, bool control, Findings& f) {
  std::map<std::tuple<std::string, std::string, int>, std::vector<const BiasRow*>> by_setting;
  for (const auto& r : rows) by_setting[{r.key.cost, r.key.method, r.key.elements}].push_back(&r);
  for (const auto& [setting, members] : by_setting) {
    const auto& [cost, method, elements] = setting;
    std::string text = cost + " (" + method + ", N = " + std::to_string(elements) +
                       "): " + (control ? "the estimator's own bias" : "noise-free bias");
    std::map<std::string, bool> named;
    for (const BiasRow* r : members)
      if (!named[r->parameter]) {
        named[r->parameter] = true;
        text += " " + r->parameter + " " + g3(r->noise_free);
      }
    int significant = 0;
    for (const BiasRow* r : members) significant += r->significant_noise_induced() ? 1 : 0;
    const int total = static_cast<int>(members.size());
    text += "; the noise adds a bias beyond 2 Monte-Carlo standard errors in " + std::to_string(significant) + " of " +
            std::to_string(total) + " (parameter, noise) settings";
    f.counts.push_back({text, significant, total});
  }
}

void claim(Findings& f, bool holds, int count, int total, const std::string& text) {
  f.claims.push_back({holds, text, count, total});
}

// Success rates per cost (noise <= 1 %), and the frequency-domain costs against time, overall and per setting.
void success_findings(const StudyResults& results, const Groups& groups, Findings& f) {
  const StudySpec& spec = *results.spec;
  auto by_cost = success_by_cost(results.cases, 0.01);
  for (const auto& cost : spec.sweep.cost)
    if (by_cost.count(cost))
      f.counts.push_back({cost + " succeeds in " + count_with_interval(by_cost[cost].successes, by_cost[cost].cases) +
                              " of the fits with noise <= 1 %",
                          by_cost[cost].successes, by_cost[cost].cases});
  const auto rate = [&](const std::string& c) { return by_cost.count(c) ? by_cost[c].rate() : -1.0; };
  // Rates are compared only from 10 fits per cost up: below that the intervals span most of [0, 1].
  const auto enough = [&](const std::string& c) { return by_cost.count(c) && by_cost[c].cases >= 10; };
  if (enough(kTime) && (enough(kSpike) || enough(kSmooth))) {
    const std::string best = rate(kSmooth) > rate(kSpike) ? kSmooth : kSpike;
    const double best_freq = rate(best);
    claim(f, best_freq > rate(kTime), -1, -1,
          "a frequency-domain cost succeeds more often than the time-domain cost "
          "(noise <= 1 %: best spike cost, " +
              best + ", " + count_with_interval(by_cost[best].successes, by_cost[best].cases) + " against time " +
              count_with_interval(by_cost[kTime].successes, by_cost[kTime].cases) + ")");
    // Paired per group: where spike-smooth >= time.
    int holds = 0, total = 0;
    std::map<std::tuple<double, int, std::string, std::string, int, double>, std::map<std::string, double>> cmp;
    for (const auto& [k, members] : groups) {
      int s = 0;
      for (const CaseRow* r : members) s += r->success ? 1 : 0;
      cmp[{k.pulse_width_s, k.samples, k.method, k.start, k.elements, k.noise}][k.cost] =
          static_cast<double>(s) / members.size();
    }
    for (const auto& [k, m] : cmp)
      if (m.count(kTime) && m.count(kSmooth)) {
        ++total;
        holds += m.at(kSmooth) >= m.at(kTime) ? 1 : 0;
      }
    if (total > 0)
      claim(f, holds == total, holds, total,
            "spike-smooth succeeds at least as often as time in every setting (" + std::to_string(holds) + "/" +
                std::to_string(total) + " settings)");
  }
}

// Each cost's success rate at the fewest and the most modes in the data (several experiments).
void modes_findings(const StudyResults& results, Findings& f) {
  const StudySpec& spec = *results.spec;
  for (const auto& cost : spec.sweep.cost) {
    std::map<int, std::pair<int, int>> by_modes;
    for (const CaseRow& r : results.cases)
      if (r.unit->cost == cost) {
        by_modes[r.modes()].first += r.success ? 1 : 0;
        by_modes[r.modes()].second += 1;
      }
    if (by_modes.size() < 2) continue;
    const auto& lo = by_modes.begin()->second;
    const auto& hi = by_modes.rbegin()->second;
    const double rlo = static_cast<double>(lo.first) / lo.second, rhi = static_cast<double>(hi.first) / hi.second;
    claim(f, rhi < rlo, -1, -1,
          cost + "'s success rate falls from " + count_with_interval(lo.first, lo.second) + " with " +
              std::to_string(by_modes.begin()->first) + " mode(s) in the data to " +
              count_with_interval(hi.first, hi.second) + " with " + std::to_string(by_modes.rbegin()->first));
  }
}

// Median basin width (over the estimated parameters) at the fewest and the most modes, per cost.
void basin_findings(const StudySpec& spec, const LandscapeMetrics& landscape, Findings& f) {
  for (const auto& cost : spec.landscape.cost) {
    std::map<int, std::vector<double>> widths;
    for (const auto& b : landscape.slices)  // only where the slice resolves the least-squares basin
      if (b.cost == cost && b.first_setting && b.resolution.resolved())
        widths[b.modes].push_back(b.shape.basin_upper - b.shape.basin_lower);
    if (widths.size() < 2) continue;
    const double lo = median(widths.begin()->second), hi = median(widths.rbegin()->second);
    claim(f, hi < lo, -1, -1,
          cost + "'s median basin width narrows from " + pct(lo) + " with " + std::to_string(widths.begin()->first) +
              " mode(s) in the data to " + pct(hi) + " with " + std::to_string(widths.rbegin()->first));
  }
}

// The first experiment's slices: basins, local minima and flat steps of the frequency costs against time's.
void slice_findings(const std::vector<SliceRow>& slice_rows, Findings& out) {
  const auto count = [&](const std::string& a, const std::string& b, auto better) {
    int holds = 0, total = 0;
    for (const auto& s : slice_rows)
      if (s.cost == a)
        for (const auto& t : slice_rows)
          if (t.cost == b && t.parameter == s.parameter && s.resolution.resolved() && t.resolution.resolved())
            ++total, holds += better(s.shape, t.shape) ? 1 : 0;
    return std::make_pair(holds, total);
  };
  for (const std::string& freq : {kSmooth, kSpike}) {
    const auto wider = count(freq, kTime, [](const SliceShape& f, const SliceShape& t) {
      return f.basin_upper - f.basin_lower > t.basin_upper - t.basin_lower;
    });
    if (wider.second > 0)
      claim(out, wider.first == wider.second, wider.first, wider.second,
            "the " + freq + " basin is wider than time's along every axis (" + std::to_string(wider.first) + "/" +
                std::to_string(wider.second) + ")");
  }
  const auto fewer =
      count(kSmooth, kTime, [](const SliceShape& f, const SliceShape& t) { return f.local_minima <= t.local_minima; });
  if (fewer.second > 0)
    claim(out, fewer.first == fewer.second, fewer.first, fewer.second,
          "spike-smooth has no more local minima than time along every axis (" + std::to_string(fewer.first) + "/" +
              std::to_string(fewer.second) + ")");
  // The staircase of (3.5) lives on the axes that move frequencies (stiffness and inertia); damping moves only
  // magnitudes, which (3.5) compares continuously.
  int flat_holds = 0, flat_total = 0;
  for (const auto& s : slice_rows)
    if (s.cost == kSpike && model::parameter_role(s.parameter) != "damping")
      for (const auto& t : slice_rows)
        if (t.cost == kSmooth && t.parameter == s.parameter)
          ++flat_total, flat_holds += s.shape.flat_share > t.shape.flat_share ? 1 : 0;
  if (flat_total > 0)
    claim(out, flat_holds == flat_total, flat_holds, flat_total,
          "the paper's spike cost (3.5) has more flat steps (its staircase) than "
          "spike-smooth along every stiffness and mass axis (" +
              std::to_string(flat_holds) + "/" + std::to_string(flat_total) + ")");
}

// Local fits from random starts that reach the reference minimum, per cost and against time.
void multistart_findings(const LandscapeMetrics& landscape, Findings& f) {
  for (const auto& s : landscape.multistarts)
    f.counts.push_back({s.cost + ": " + count_with_interval(s.reached, s.started) +
                            " local fits from random starts reach the reference minimum (the best of all its fits, "
                            "the truth start's included)",
                        s.reached, s.started});
  const auto reach = [&](const std::string& cost) -> const MultistartSummary* {
    for (const auto& s : landscape.multistarts)
      if (s.cost == cost) return &s;
    return nullptr;
  };
  if (const MultistartSummary* t = reach(kTime))
    for (const std::string& freq : {kSmooth, kSpike})
      if (const MultistartSummary* q = reach(freq))
        claim(f, q->reached * t->started > t->reached * q->started, -1, -1,
              "more random starts reach the minimum with " + freq + " than with time (" +
                  count_with_interval(q->reached, q->started) + " against " +
                  count_with_interval(t->reached, t->started) + ")");
}

}  // namespace

Findings study_findings(const StudyResults& results, const Groups& groups, const LandscapeMetrics& landscape,
                        const StartDistanceMetrics& start_distance) {
  const StudySpec& spec = *results.spec;
  const bool several = spec.sweep.pulse_width_s.size() > 1 || spec.sweep.samples.size() > 1;
  Findings f;
  success_findings(results, groups, f);
  if (several) modes_findings(results, f);
  if (several && !landscape.slices.empty()) basin_findings(spec, landscape, f);
  std::vector<SliceRow> slice_rows;  // the first experiment's
  for (const auto& s : landscape.slices)
    if (s.first_experiment && s.first_setting) slice_rows.push_back(s);
  if (!slice_rows.empty()) slice_findings(slice_rows, f);
  multistart_findings(landscape, f);
  start_distance_findings(start_distance, f);
  efficiency_findings(spec, efficiency_rows(results, groups), f);
  bias_findings(bias_rows(results, groups), spec.truth.control, f);
  return f;
}

}  // namespace beamid::study
