#include "study/analysis/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "study/analysis/start_distance.h"

namespace beamid::study {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Discrete steepest descent on a grid (8 neighbours) from every point: share of points ending at the lowest point.
double descent_share(const std::vector<double>& c, int nx, int ny) {
  const auto at = [&](int i, int j) { return c[static_cast<std::size_t>(i * ny + j)]; };
  int best = 0;
  for (int p = 1; p < nx * ny; ++p)
    if (c[static_cast<std::size_t>(p)] < c[static_cast<std::size_t>(best)]) best = p;
  int reach = 0;
  for (int p = 0; p < nx * ny; ++p) {
    int i = p / ny, j = p % ny;
    for (;;) {
      int bi = i, bj = j;
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          const int a = i + di, b = j + dj;
          if ((di || dj) && a >= 0 && a < nx && b >= 0 && b < ny && at(a, b) < at(bi, bj)) bi = a, bj = b;
        }
      if (bi == i && bj == j) break;
      i = bi, j = bj;
    }
    reach += (i * ny + j == best) ? 1 : 0;
  }
  return static_cast<double>(reach) / (nx * ny);
}

double flat_share_of(const std::vector<double>& steps) {
  double total = 0;
  int n = 0;
  for (double s : steps)
    if (std::isfinite(s)) total += std::abs(s), ++n;
  if (n == 0 || total == 0) return n == 0 ? kNaN : 1.0;
  const double threshold = 0.01 * total / n;
  int flat = 0;
  for (double s : steps)
    if (std::isfinite(s) && std::abs(s) < threshold) ++flat;
  return static_cast<double>(flat) / n;
}

}  // namespace

GroupKey key_of(const Unit& u) { return {u.pulse_width_s, u.samples, u.cost, u.method, u.start, u.elements, u.noise}; }

Groups group_cases(const std::vector<CaseRow>& rows) {
  Groups groups;
  std::map<GroupKey, std::size_t> index;
  for (const CaseRow& r : rows) {
    const GroupKey k = key_of(*r.unit);
    auto it = index.find(k);
    if (it == index.end()) {
      index[k] = groups.size();
      groups.push_back({k, {&r}});
    } else {
      groups[it->second].second.push_back(&r);
    }
  }
  return groups;
}

std::map<std::string, SuccessCount> success_by_cost(const std::vector<CaseRow>& cases, double max_noise) {
  std::map<std::string, SuccessCount> by_cost;
  for (const CaseRow& r : cases)
    if (r.unit->noise <= max_noise + 1e-12) {
      by_cost[r.unit->cost].successes += r.success ? 1 : 0;
      by_cost[r.unit->cost].cases += 1;
    }
  return by_cost;
}

SliceShape slice_shape(const std::vector<double>& x, const std::vector<double>& c, double truth) {
  SliceShape s;
  const int n = static_cast<int>(c.size());
  // Runs of equal values, so a plateau is one point.
  std::vector<double> runs;
  for (double v : c)
    if (runs.empty() || v != runs.back()) runs.push_back(v);
  for (std::size_t j = 1; j + 1 < runs.size(); ++j)
    if (runs[j] < runs[j - 1] && runs[j] < runs[j + 1]) ++s.local_minima;
  int best = 0;
  for (int j = 1; j < n; ++j)
    if (c[static_cast<std::size_t>(j)] < c[static_cast<std::size_t>(best)]) best = j;
  int lo = best, hi = best;
  while (lo > 0 && c[static_cast<std::size_t>(lo - 1)] >= c[static_cast<std::size_t>(lo)]) --lo;
  while (hi + 1 < n && c[static_cast<std::size_t>(hi + 1)] >= c[static_cast<std::size_t>(hi)]) ++hi;
  s.basin_lower = x[static_cast<std::size_t>(lo)] / truth - 1;
  s.basin_upper = x[static_cast<std::size_t>(hi)] / truth - 1;
  double mn = INFINITY, mx = -INFINITY, tv = 0;
  std::vector<double> steps;
  for (int j = 0; j < n; ++j) {
    const double v = c[static_cast<std::size_t>(j)];
    if (std::isfinite(v)) mn = std::min(mn, v), mx = std::max(mx, v);
    if (j > 0) {
      const double d = v - c[static_cast<std::size_t>(j - 1)];
      steps.push_back(d);
      if (std::isfinite(d)) tv += std::abs(d);
    }
  }
  s.total_variation_ratio = mx > mn ? tv / (mx - mn) : kNaN;
  s.flat_share = flat_share_of(steps);
  return s;
}

GridShape grid_shape(const std::vector<double>& c, int nx, int ny) {
  GridShape g;
  const auto at = [&](int i, int j) { return c[static_cast<std::size_t>(i * ny + j)]; };
  std::vector<double> steps;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      bool minimum = std::isfinite(at(i, j));
      for (int di = -1; di <= 1 && minimum; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          const int a = i + di, b = j + dj;
          if ((di || dj) && a >= 0 && a < nx && b >= 0 && b < ny && !(at(i, j) < at(a, b))) minimum = false;
        }
      g.local_minima += minimum ? 1 : 0;
      if (i + 1 < nx) steps.push_back(at(i + 1, j) - at(i, j));
      if (j + 1 < ny) steps.push_back(at(i, j + 1) - at(i, j));
    }
  g.descent_share = descent_share(c, nx, ny);
  g.flat_share = flat_share_of(steps);
  return g;
}

namespace {

// The resolution of a landscape unit whose axes are `keys` with log steps `log_steps` (see Resolution).
Resolution landscape_resolution(const StudyResults& results, const Unit& u, const std::vector<std::string>& keys,
                                const std::vector<double>& log_steps) {
  const StudySpec& spec = *results.spec;
  Resolution r;
  StartDistanceMetrics prediction;
  prediction.fitted_modes = spec.fit.spikes;
  if (!predict_basins(results, u.truth, u.samples, prediction) || prediction.limiting_mode == 0) return r;
  try {
    const galerkin::BeamForms forms(galerkin::SplineSpace(u.elements), spec.truth.parameters.l,
                                    spec.truth.parameters.support);
    const Eigen::MatrixXd g = galerkin::frequency_sensitivities(forms, spec.truth.parameters, keys, spec.fit.spikes);
    double step = 0;
    for (std::size_t i = 0; i < keys.size(); ++i)
      step = std::max(step, g.col(static_cast<Eigen::Index>(i)).cwiseAbs().maxCoeff() * std::abs(log_steps[i]));
    r.frequency_step = step;
    r.predicted_basin = prediction.predicted_basin_decay;
  } catch (const std::exception&) {  // a model without enough modes: resolution unknown
  }
  return r;
}

}  // namespace

bool first_setting(const StudySpec& spec, const Unit& u) {
  return u.elements == spec.landscape.elements.front() && u.noise == spec.landscape.noise.front();
}

LandscapeMetrics landscape_metrics(const StudyResults& results) {
  const StudySpec& spec = *results.spec;
  const model::BeamParameters& beam = spec.truth.parameters;
  LandscapeMetrics m;
  for (const LandscapeRow& l : results.landscape) {
    const Unit& u = *l.unit;
    const Record& rec = l.record;
    if (u.kind != UnitKind::Slice && u.kind != UnitKind::Grid) continue;
    // Each list parsed once; a record whose lists disagree in size (or are absent) has no shape.
    const auto list = [&](const char* key) { return rec.has(key) ? rec.numbers(key) : std::vector<double>{}; };
    const std::vector<double> x = list("x"), c = list("cost");
    if (u.kind == UnitKind::Slice) {
      if (c.empty() || x.size() != c.size()) continue;
      const double v = model::parameter_value(beam, u.parameters[0]);
      const bool first = u.pulse_width_s == spec.sweep.pulse_width_s.front() && u.samples == spec.sweep.samples.front();
      m.slices.push_back(
          {&l, rec.has("modes_in_data") ? static_cast<int>(rec.number("modes_in_data")) : 0, u.cost, u.parameters[0],
           slice_shape(x, c, v), first, first_setting(spec, u),
           x.size() > 1 ? landscape_resolution(results, u, {u.parameters[0]}, {std::log(x[1] / x[0])}) : Resolution{}});
    } else {
      const std::vector<double> y = list("y");
      if (c.empty() || x.size() * y.size() != c.size()) continue;
      m.grids.push_back({&l, u.cost, u.parameters[0], u.parameters[1],
                         grid_shape(c, static_cast<int>(x.size()), static_cast<int>(y.size())),
                         x.size() > 1 && y.size() > 1
                             ? landscape_resolution(results, u, {u.parameters[0], u.parameters[1]},
                                                    {std::log(x[1] / x[0]), std::log(y[1] / y[0])})
                             : Resolution{},
                         u.zoom, first_setting(spec, u)});
    }
  }
  for (const auto& cost : spec.landscape.cost) {
    MultistartSummary s;
    s.cost = cost;
    s.reference_cost = kNaN;
    const Record* reference = nullptr;
    for (const LandscapeRow& l : results.landscape)
      if (l.unit->kind == UnitKind::Multistart && l.unit->cost == cost &&
          l.record.text("status").rfind("failed", 0) != 0 &&
          (reference == nullptr || l.record.number("cost") < reference->number("cost"))) {
        reference = &l.record;
        s.reference_start = l.unit->index;
      }
    if (reference != nullptr) s.reference_cost = reference->number("cost");
    for (const LandscapeRow& l : results.landscape) {
      if (l.unit->kind != UnitKind::Multistart || l.unit->cost != cost) continue;
      const Record& rec = l.record;
      bool reached = false;
      if (reference != nullptr && rec.text("status").rfind("failed", 0) != 0) {
        reached = true;
        for (const auto& k : spec.fit.estimate) {
          const double e = rec.number("estimate." + k), r = reference->number("estimate." + k);
          reached = reached && std::abs(e - r) <= tolerance(spec, k) * std::abs(r);
        }
      }
      const double gap = rec.has("cost") ? rec.number("cost") - s.reference_cost : kNaN;
      s.fits.push_back({&l, gap, reached});
      if (l.unit->index >= 0) {
        s.started += 1;
        s.reached += reached ? 1 : 0;
      }
    }
    if (!s.fits.empty()) m.multistarts.push_back(s);
  }
  return m;
}

std::map<ModeKey, ModeCell> mode_cells(const StudyResults& results) {
  std::map<ModeKey, ModeCell> cells;
  for (const CaseRow& r : results.cases) {
    auto& cell = cells[{r.modes(), r.unit->pulse_width_s, r.unit->samples, r.unit->cost, r.unit->method}];
    cell.cases++;
    cell.successes += r.success ? 1 : 0;
    cell.errors.push_back(r.max_abs_error(results.spec->fit.estimate));
  }
  return cells;
}

namespace {

// The relative errors in `key` of the replicates that stayed at the minimum (succeeded), their statistics and the
// Monte-Carlo standard error of their mean, sd / sqrt(stayed), as the efficiency and bias tables state them.
void stayed_errors(const std::vector<const CaseRow*>& members, const std::string& key, int& fits, int& stayed,
                   Stats& errors, double& mcse) {
  std::vector<double> values;
  for (const CaseRow* r : members)
    if (r->success) values.push_back(r->error(key));
  fits = static_cast<int>(members.size());
  stayed = static_cast<int>(values.size());
  errors = stats(values);
  mcse = errors.mcse();
}

}  // namespace

std::vector<BiasRow> bias_rows(const StudyResults& results, const Groups& groups) {
  std::vector<BiasRow> rows;
  if (!results.spec->outputs.bias_decomposition) return rows;
  for (const auto& [k, members] : groups) {
    if (k.noise == 0) continue;
    GroupKey twin = k;
    twin.noise = 0;
    const CaseRow* noise_free = nullptr;
    for (const auto& [other, other_members] : groups)
      if (other == twin && !other_members.empty()) noise_free = other_members.front();
    if (!noise_free) continue;
    for (const auto& key : results.spec->fit.estimate) {
      BiasRow row;
      row.key = k;
      row.parameter = key;
      if (noise_free->success) row.noise_free = noise_free->error(key);
      stayed_errors(members, key, row.fits, row.stayed, row.errors, row.mcse);
      rows.push_back(row);
    }
  }
  return rows;
}

std::vector<EfficiencyRow> efficiency_rows(const StudyResults& results, const Groups& groups) {
  std::vector<EfficiencyRow> rows;
  for (const auto& [k, members] : groups) {
    if (k.noise == 0) continue;
    const LandscapeRow* bound = nullptr;
    for (const auto& b : results.bounds)
      if (b.unit->pulse_width_s == k.pulse_width_s && b.unit->samples == k.samples && b.unit->elements == k.elements &&
          b.unit->noise == k.noise)
        bound = &b;
    if (!bound) continue;
    for (const auto& key : results.spec->fit.estimate) {
      EfficiencyRow row;
      row.key = k;
      row.modes = members.empty() ? 0 : members.front()->modes();
      row.parameter = key;
      stayed_errors(members, key, row.fits, row.stayed, row.errors, row.mcse);
      if (bound->record.text("status") == "ok") row.bound = bound->record.number("relative_sd." + key);
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace beamid::study
