#include "study/tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>


#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "io/provenance.h"
#include "model/errors.h"
#include "model/exact_frequencies.h"
#include "study/execute.h"
#include "study/outputs.h"

namespace beamid::study {
namespace fs = std::filesystem;
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string g3(double v) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
std::string pct(double fraction) {  // relative value as a percentage with 3 significant digits
  if (!std::isfinite(fraction)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g %%", 100 * fraction);
  return buf;
}
std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
std::string signed_pct(double fraction) {  // "+1.5 %" / "-3 %"
  if (!std::isfinite(fraction)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.3g %%", 100 * fraction);
  return buf;
}
std::string noise_label(double level) { return level == 0 ? "0" : g3(100 * level) + "%"; }

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Stats {
  int count = 0;
  double mean = kNaN, std = kNaN, rmse = kNaN, median = kNaN;
};
Stats stats(const std::vector<double>& values) {
  Stats s;
  std::vector<double> v;
  for (double x : values)
    if (std::isfinite(x)) v.push_back(x);
  s.count = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0, sq = 0;
  for (double x : v) sum += x, sq += x * x;
  s.mean = sum / s.count;
  s.rmse = std::sqrt(sq / s.count);
  if (s.count > 1) {
    double d = 0;
    for (double x : v) d += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(d / (s.count - 1));
  }
  s.median = median(v);
  return s;
}

// One finished case with its settings.
struct Row {
  const Unit* unit;
  Record record;
  bool ok = false;  // not failed, and every estimate within its tolerance (set once the rows are read)
  bool success() const { return ok; }
  bool failed() const { return record.text("status") == "failed"; }
  double error(const std::string& key) const { return record.number("relative_error." + key); }
  int modes() const { return record.has("modes_in_data") ? static_cast<int>(record.number("modes_in_data")) : 0; }
  double max_abs_error(const std::vector<std::string>& keys) const {
    double m = 0;
    for (const auto& k : keys) {
      const double e = error(k);
      if (!std::isfinite(e)) return kNaN;
      m = std::max(m, std::abs(e));
    }
    return m;
  }
};

struct GroupKey {
  double pulse_width_s;
  int samples;
  std::string cost, method, start;
  int elements;
  double noise;
  auto tie() const { return std::tie(pulse_width_s, samples, cost, method, start, elements, noise); }
  bool operator<(const GroupKey& o) const { return tie() < o.tie(); }
  bool operator==(const GroupKey& o) const { return tie() == o.tie(); }
};
GroupKey key_of(const Unit& u) { return {u.pulse_width_s, u.samples, u.cost, u.method, u.start, u.elements, u.noise}; }

// Groups in plan order of first appearance.
std::vector<std::pair<GroupKey, std::vector<const Row*>>> group_rows(const std::vector<Row>& rows) {
  std::vector<std::pair<GroupKey, std::vector<const Row*>>> groups;
  std::map<GroupKey, std::size_t> index;
  for (const Row& r : rows) {
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

void write_tables(const StudySpec& spec, const Plan& plan, const Store& store, const std::vector<Record>& truths,
                  const std::string& output_dir) {
  const fs::path dir(output_dir);
  const auto& keys = spec.fit.estimate;
  std::vector<Row> rows;
  std::vector<std::pair<const Unit*, Record>> landscape;
  for (const Unit& u : plan.units) {
    Record r = *store.load(u.id);
    if (u.kind == "case") {
      Row row{&u, std::move(r)};
      row.ok = !row.failed();
      for (const auto& k : keys) row.ok = row.ok && std::abs(row.error(k)) <= tolerance(spec, k);  // NaN: false
      rows.push_back(std::move(row));
    }
    else landscape.emplace_back(&u, std::move(r));
  }
  const std::string commit = io::commit_label();

  // ---- manifest.json and provenance.csv
  {
    std::ostringstream os;
    os << "{\n  \"study\": " << json_string(spec.name) << ",\n  \"question\": " << json_string(spec.question)
       << ",\n  \"study_file\": " << json_string(spec.path) << ",\n  \"study_file_fnv1a64\": \"" << spec.file_hash
       << "\",\n  \"seed\": " << spec.seed << ",\n  \"commit\": \"" << io::commit()
       << "\",\n  \"dirty\": " << (io::dirty() ? "true" : "false") << ",\n  \"beamid_version\": \"" << io::version()
       << "\",\n  \"compiler\": " << json_string(compiler()) << ",\n  \"libraries\": " << library_versions_json()
       << ",\n  \"truth\": {\"beam\": " << json_string(spec.truth.beam) << ", \"elements\": " << spec.truth.elements
       << ", \"integrator\": \"cvode\", \"rtol\": " << full(spec.truth.rtol) << ", \"records\": [";
    for (std::size_t i = 0; i < plan.truths.size(); ++i)
      os << (i ? ", " : "") << "{\"id\": \"" << plan.truths[i].id << "\", \"pulse_width_s\": "
         << full(plan.truths[i].pulse_width_s) << ", \"status\": " << json_string(truths[i].text("status")) << "}";
    os << "]},\n  \"noise\": \"z = y + level rms(y) g, g standard normal by Box-Muller over std::mt19937_64 "
          "(signal/noise.h)\",\n  \"cases\": " << rows.size() << ",\n  \"landscape_units\": " << landscape.size()
       << "\n}\n";
    write_file(dir / "manifest.json", os.str());
    write_file(dir / "provenance.csv", "key,value\nstudy," + spec.name + "\ncases," + std::to_string(rows.size()) +
                                           "\ncommit," + commit + "\n");
  }

  // ---- cases.csv and timings.csv
  {
    std::ostringstream os, tm;
    os << "case_id,seed,pulse_width_s,samples,modes_in_data,elements,cost,spikes,noise,replicate,method,start,status,"
          "success,cost_value,evaluations,a4,termination";
    for (const auto& k : keys) os << ",estimate_" << k << ",standard_error_" << k << ",relative_error_" << k;
    os << "\n";
    tm << "unit_id,kind,cost,elements,noise,wall_time_s\n";
    for (std::size_t i = 0; i < plan.truths.size(); ++i)
      tm << plan.truths[i].id << ",truth,,," << "," << full(truths[i].number("wall_time_s")) << "\n";
    for (const Row& r : rows) {
      const Unit& u = *r.unit;
      const Record& c = r.record;
      os << u.id << "," << u.seed << "," << full(u.pulse_width_s) << "," << u.samples << "," << r.modes() << ","
         << u.elements << "," << u.cost << "," << (c.has("spikes") ? c.text("spikes") : "0") << "," << full(u.noise)
         << "," << u.replicate << "," << u.method << "," << u.start << "," << c.text("status") << ","
         << (r.success() ? 1 : 0) << "," << c.text("cost") << "," << c.text("evaluations") << "," << quoted(c.text("a4"))
         << "," << quoted(c.text("termination"));
      for (const auto& k : keys)
        os << "," << c.text("estimate." + k) << "," << c.text("standard_error." + k) << ","
           << c.text("relative_error." + k);
      os << "\n";
    }
    for (const Row& r : rows)
      tm << r.unit->id << ",case," << r.unit->cost << "," << r.unit->elements << "," << full(r.unit->noise) << ","
         << r.record.text("wall_time_s") << "\n";
    for (const auto& [u, rec] : landscape)
      tm << u->id << "," << u->kind << "," << u->cost << "," << u->elements << ",0," << rec.text("wall_time_s") << "\n";
    write_file(dir / "cases.csv", os.str());
    write_file(dir / "timings.csv", tm.str());
  }

  const auto groups = group_rows(rows);
  const bool several_experiments = spec.sweep.pulse_width_s.size() > 1 || spec.sweep.samples.size() > 1;
  std::ostringstream report;  // the generated block

  // ---- summary.csv / summary.md
  {
    std::ostringstream csv, md;
    csv << "pulse_width_s,samples,modes_in_data,cost,method,start,elements,noise,parameter,cases,failed,mean_bias,"
           "std,rmse,median,success_rate,median_evaluations\n";
    md << "| ";
    if (several_experiments) md << "pulse (ms) | Nbar | modes | ";
    md << "cost | method | start | N | noise | success |";
    for (const auto& k : keys) md << " " << k << " bias ± sd |";
    md << " median evals |\n|";
    for (int i = 0; i < (several_experiments ? 3 : 0) + 7 + static_cast<int>(keys.size()); ++i) md << "---|";
    md << "\n";
    for (const auto& [k, members] : groups) {
      int successes = 0, failed = 0;
      std::vector<double> evals;
      for (const Row* r : members) {
        successes += r->success() ? 1 : 0;
        failed += r->failed() ? 1 : 0;
        evals.push_back(r->record.number("evaluations"));
      }
      const double rate = static_cast<double>(successes) / members.size();
      md << "| ";
      if (several_experiments)
        md << g3(1e3 * k.pulse_width_s) << " | " << k.samples << " | " << members.front()->modes() << " | ";
      md << k.cost << " | " << k.method << " | " << k.start << " | " << k.elements << " | " << noise_label(k.noise)
         << " | " << successes << "/" << members.size() << " |";
      for (const auto& key : keys) {
        std::vector<double> e;
        for (const Row* r : members) e.push_back(r->error(key));
        const Stats s = stats(e);
        csv << full(k.pulse_width_s) << "," << k.samples << "," << members.front()->modes() << "," << k.cost << ","
            << k.method << "," << k.start << "," << k.elements << "," << full(k.noise) << "," << key << ","
            << members.size() << "," << failed << "," << full(s.mean) << "," << full(s.std) << "," << full(s.rmse)
            << "," << full(s.median) << "," << full(rate) << "," << full(median(evals)) << "\n";
        md << " " << pct(s.mean) << (std::isfinite(s.std) ? " ± " + pct(s.std) : "") << " |";
      }
      md << " " << g3(median(evals)) << " |\n";
    }
    write_file(dir / "summary.csv", csv.str());
    write_file(dir / "summary.md", md.str());
  }

  // ---- bias_<key>.csv: RMSE and mean bias against N, a column pair per (cost, method, start, noise) series
  std::vector<std::string> series;
  if (spec.sweep.elements.size() > 1) {
    std::map<std::string, std::map<int, std::pair<double, double>>> data;  // series -> N -> (rmse, std)
    for (const auto& key : keys) {
      data.clear();
      std::vector<std::string> order;
      for (const auto& [k, members] : groups) {
        if (k.pulse_width_s != spec.sweep.pulse_width_s.front() || k.samples != spec.sweep.samples.front()) continue;
        std::string name = k.cost + " " + k.method + (spec.sweep.start.size() > 1 ? " " + k.start : "") + " noise " +
                           noise_label(k.noise);
        if (!data.count(name)) order.push_back(name);
        std::vector<double> e;
        for (const Row* r : members) e.push_back(r->error(key));
        const Stats s = stats(e);
        data[name][k.elements] = {s.rmse, s.std};
      }
      std::ostringstream os;
      os << "elements";
      for (const auto& name : order) os << "," << quoted(name + " rmse") << "," << quoted(name + " sd");
      os << "\n";
      for (int n : spec.sweep.elements) {
        os << n;
        for (const auto& name : order) {
          auto it = data[name].find(n);
          os << "," << (it == data[name].end() ? "nan" : full(it->second.first)) << ","
             << (it == data[name].end() ? "nan" : full(it->second.second));
        }
        os << "\n";
      }
      write_file(dir / ("bias_" + key + ".csv"), os.str());
      series = order;
    }
  }

  // ---- convergence in N (noise-free cases) beside the Galerkin frequency errors
  const model::BeamParameters beam = truth_beam(spec);
  std::vector<double> exact;
  try {
    const auto w = model::timoshenko_frequencies_rad_s(beam, 4);
    for (double x : w) exact.push_back(x / (2 * M_PI));
  } catch (const std::exception&) {
  }
  std::map<int, std::vector<double>> galerkin_hz;
  {
    std::ostringstream os;
    os << "elements,mode,galerkin_hz,exact_hz,relative_error\n";
    for (int n : spec.sweep.elements) {
      try {
        const galerkin::SplineSpace space(n);
        const auto modes = galerkin::undamped_modes(galerkin::assemble(space, beam));
        for (std::size_t m = 0; m < exact.size() && static_cast<int>(m) < modes.omega_rad_s.size(); ++m) {
          const double f = modes.omega_rad_s[static_cast<int>(m)] / (2 * M_PI);
          galerkin_hz[n].push_back(f);
          os << n << "," << m + 1 << "," << full(f) << "," << full(exact[m]) << "," << full(f / exact[m] - 1) << "\n";
        }
      } catch (const std::exception&) {
      }
    }
    write_file(dir / "galerkin_frequencies.csv", os.str());
  }
  {
    std::ostringstream csv, md;
    csv << "cost,method,start,elements,status";
    for (const auto& k : keys) csv << ",relative_error_" << k;
    csv << "\n";
    md << "| N |";
    for (std::size_t m = 0; m < exact.size(); ++m) md << " f" << m + 1 << " error |";
    std::vector<std::string> names;
    for (const auto& [k, members] : groups)
      if (k.noise == 0 && k.pulse_width_s == spec.sweep.pulse_width_s.front() && k.samples == spec.sweep.samples.front()) {
        const std::string name = k.cost + " " + k.method + (spec.sweep.start.size() > 1 ? " " + k.start : "");
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      }
    for (const auto& name : names) md << " " << name << " |";
    md << "\n|";
    for (std::size_t i = 0; i < 1 + exact.size() + names.size(); ++i) md << "---|";
    md << "\n";
    for (int n : spec.sweep.elements) {
      md << "| " << n << " |";
      for (std::size_t m = 0; m < exact.size(); ++m)
        md << " " << (m < galerkin_hz[n].size() ? pct(galerkin_hz[n][m] / exact[m] - 1) : "-") << " |";
      for (const auto& name : names) {
        std::string cell = "-";
        for (const auto& [k, members] : groups) {
          const std::string kn = k.cost + " " + k.method + (spec.sweep.start.size() > 1 ? " " + k.start : "");
          if (k.noise != 0 || k.elements != n || kn != name || k.pulse_width_s != spec.sweep.pulse_width_s.front() ||
              k.samples != spec.sweep.samples.front())
            continue;
          const Row& r = *members.front();
          cell = r.failed() ? "failed" : "max " + pct(r.max_abs_error(keys));
          csv << k.cost << "," << k.method << "," << k.start << "," << n << "," << r.record.text("status");
          for (const auto& key : keys) csv << "," << full(r.error(key));
          csv << "\n";
        }
        md << " " << cell << " |";
      }
      md << "\n";
    }
    write_file(dir / "convergence.csv", csv.str());
    write_file(dir / "convergence.md", md.str());
  }

  // ---- Monte-Carlo spread against reported standard errors
  {
    std::ostringstream csv, md;
    csv << "pulse_width_s,samples,cost,method,start,elements,noise,parameter,cases,monte_carlo_sd,median_standard_error,ratio\n";
    md << "| cost | method | N | noise |";
    for (const auto& k : keys) md << " " << k << " MC sd / median SE |";
    md << "\n|";
    for (std::size_t i = 0; i < 4 + keys.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& [k, members] : groups) {
      if (k.noise == 0 || members.size() < 3) continue;
      md << "| " << k.cost << " | " << k.method << " | " << k.elements << " | " << noise_label(k.noise) << " |";
      for (const auto& key : keys) {
        std::vector<double> est, se;
        for (const Row* r : members)
          if (!r->failed()) {
            est.push_back(r->record.number("estimate." + key));
            se.push_back(r->record.number("standard_error." + key));
          }
        const Stats s = stats(est);
        const double mse = median(se);
        csv << full(k.pulse_width_s) << "," << k.samples << "," << k.cost << "," << k.method << "," << k.start << ","
            << k.elements << "," << full(k.noise) << "," << key << "," << s.count << "," << full(s.std) << ","
            << full(mse) << "," << full(s.std / mse) << "\n";
        md << " " << g3(s.std) << " / " << g3(mse) << " = " << g3(s.std / mse) << " |";
      }
      md << "\n";
    }
    write_file(dir / "spread.csv", csv.str());
    write_file(dir / "spread.md", md.str());
  }

  // ---- success against the number of modes in the data
  struct ModeCell {
    int successes = 0, cases = 0;
    std::vector<double> errors;
  };
  std::map<std::tuple<int, double, int, std::string, std::string>, ModeCell> mode_cells;  // modes, tau, Nbar, cost, method
  for (const Row& r : rows) {
    auto& cell = mode_cells[{r.modes(), r.unit->pulse_width_s, r.unit->samples, r.unit->cost, r.unit->method}];
    cell.cases++;
    cell.successes += r.success() ? 1 : 0;
    cell.errors.push_back(r.max_abs_error(keys));
  }
  {
    std::ostringstream csv;
    csv << "modes_in_data,pulse_width_s,samples,cost,method,cases,successes,success_rate,median_max_abs_error\n";
    for (const auto& [key, cell] : mode_cells)
      csv << std::get<0>(key) << "," << full(std::get<1>(key)) << "," << std::get<2>(key) << "," << std::get<3>(key)
          << "," << std::get<4>(key) << "," << cell.cases << "," << cell.successes << ","
          << full(static_cast<double>(cell.successes) / cell.cases) << "," << full(median(cell.errors)) << "\n";
    write_file(dir / "modes.csv", csv.str());
  }

  // ---- landscape
  struct SliceRow { std::string cost, parameter; SliceShape shape; };
  struct GridRow { std::string cost, a, b; GridShape shape; };
  std::vector<SliceRow> slice_rows;
  std::vector<GridRow> grid_rows;
  std::map<std::string, std::pair<int, int>> multistart_reach;  // cost -> (reached, started)
  struct BasinRow { int modes; std::string cost, parameter; SliceShape shape; };
  std::vector<BasinRow> basin_rows;  // slices of every experiment
  if (spec.landscape.enabled) {
    std::map<std::string, Record> reference;  // cost -> multistart from the truth... (index -1 is not planned)
    std::ostringstream ms;
    ms << "cost,start,status,cost_value,evaluations,reached";
    for (const auto& k : keys) ms << ",start_" << k << ",estimate_" << k;
    ms << "\n";
    // The reference minimum of each cost: the lowest final cost over its multistarts and the truth's own value.
    std::ostringstream basin;
    basin << "modes_in_data,pulse_width_s,samples,cost,parameter,local_minima,basin_lower,basin_upper,basin_width\n";
    std::map<std::string, const Record*> best;
    for (const auto& [u, rec] : landscape)
      if (u->kind == "multistart" && rec.text("status") != "failed" && rec.text("status").rfind("failed", 0) != 0) {
        const Record*& b = best[u->cost];
        if (b == nullptr || rec.number("cost") < b->number("cost")) b = &rec;
      }
    for (const auto& [u, rec] : landscape) {
      const std::string& status = rec.text("status");
      if (u->kind == "slice") {
        const std::vector<double> x = rec.has("x") ? rec.numbers("x") : std::vector<double>{};
        const std::vector<double> c = rec.has("cost") ? rec.numbers("cost") : std::vector<double>{};
        const double v = beam.*(model::find_parameter(u->parameters[0])->member);
        if (!c.empty()) {
          const SliceShape shape = slice_shape(x, c, v);
          basin << (rec.has("modes_in_data") ? rec.text("modes_in_data") : "nan") << "," << full(u->pulse_width_s)
                << "," << u->samples << "," << u->cost << "," << u->parameters[0] << "," << shape.local_minima << ","
                << full(shape.basin_lower) << "," << full(shape.basin_upper) << ","
                << full(shape.basin_upper - shape.basin_lower) << "\n";
          basin_rows.push_back({rec.has("modes_in_data") ? static_cast<int>(rec.number("modes_in_data")) : 0, u->cost,
                                u->parameters[0], shape});
        }
        if (u->pulse_width_s != spec.sweep.pulse_width_s.front() || u->samples != spec.sweep.samples.front()) continue;
        std::ostringstream os;
        os << "ratio,value,cost,normalised_cost\n";
        double mn = INFINITY, mx = -INFINITY;
        for (double y : c)
          if (std::isfinite(y)) mn = std::min(mn, y), mx = std::max(mx, y);
        for (std::size_t j = 0; j < c.size(); ++j)
          os << full(x[j] / v) << "," << full(x[j]) << "," << full(c[j]) << ","
             << full(std::isfinite(c[j]) && mx > mn ? (c[j] - mn) / (mx - mn) : kNaN) << "\n";
        write_file(dir / "landscape" / ("slice_" + u->cost + "_" + u->parameters[0] + ".csv"), os.str());
        if (!c.empty()) slice_rows.push_back({u->cost, u->parameters[0], slice_shape(x, c, v)});
      } else if (u->kind == "grid") {
        const std::vector<double> x = rec.has("x") ? rec.numbers("x") : std::vector<double>{};
        const std::vector<double> y = rec.has("y") ? rec.numbers("y") : std::vector<double>{};
        const std::vector<double> c = rec.has("cost") ? rec.numbers("cost") : std::vector<double>{};
        if (c.empty()) continue;
        const double va = beam.*(model::find_parameter(u->parameters[0])->member);
        const double vb = beam.*(model::find_parameter(u->parameters[1])->member);
        double mn = INFINITY, mx = -INFINITY;
        for (double z : c)
          if (std::isfinite(z)) mn = std::min(mn, z), mx = std::max(mx, z);
        // gnuplot pm3d blocks (a blank line after each x row); the height is log10 of the normalised cost, which
        // shows the floor of a basin as well as its walls.
        std::ostringstream os;
        os << "# ratio_" << u->parameters[0] << " ratio_" << u->parameters[1] << " cost log10_normalised_cost\n";
        const int ny = static_cast<int>(y.size());
        for (std::size_t i = 0; i < x.size(); ++i) {
          for (int j = 0; j < ny; ++j) {
            const double z = c[i * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j)];
            const double norm = std::isfinite(z) && mx > mn ? (z - mn) / (mx - mn) : kNaN;
            os << full(x[i] / va) << " " << full(y[static_cast<std::size_t>(j)] / vb) << " " << full(z) << " "
               << full(std::isfinite(norm) ? std::log10(std::max(norm, 1e-12)) : kNaN) << "\n";
          }
          os << "\n";
        }
        write_file(dir / "landscape" /
                       ("grid_" + u->cost + "_" + u->parameters[0] + "_" + u->parameters[1] + ".dat"),
                   os.str());
        grid_rows.push_back({u->cost, u->parameters[0], u->parameters[1],
                             grid_shape(c, static_cast<int>(x.size()), ny)});
      } else {  // multistart
        bool reached = false;
        const Record* b = best.count(u->cost) ? best[u->cost] : nullptr;
        if (b != nullptr && status.rfind("failed", 0) != 0) {
          reached = true;
          for (const auto& k : keys) {
            const double e = rec.number("estimate." + k), r = b->number("estimate." + k);
            reached = reached && std::abs(e - r) <= tolerance(spec, k) * std::abs(r);
          }
        }
        auto& mr = multistart_reach[u->cost];
        mr.first += reached ? 1 : 0;
        mr.second += 1;
        ms << u->cost << "," << u->index << "," << quoted(status) << "," << (rec.has("cost") ? rec.text("cost") : "inf")
           << "," << (rec.has("evaluations") ? rec.text("evaluations") : "0") << "," << (reached ? 1 : 0);
        for (const auto& k : keys)
          ms << "," << (rec.has("start." + k) ? rec.text("start." + k) : "nan") << ","
             << (rec.has("estimate." + k) ? rec.text("estimate." + k) : "nan");
        ms << "\n";
      }
    }
    write_file(dir / "landscape" / "multistart.csv", ms.str());
    write_file(dir / "landscape" / "basin.csv", basin.str());
    std::ostringstream csv, md;
    csv << "cost,kind,parameters,local_minima,basin_lower,basin_upper,total_variation_ratio,flat_share,descent_share\n";
    md << "| cost | slice or grid | local minima | basin around the minimum | TV / range | flat steps | "
          "grid points descending to the minimum |\n|---|---|---|---|---|---|---|\n";
    for (const auto& s : slice_rows) {
      csv << s.cost << ",slice," << s.parameter << "," << s.shape.local_minima << "," << full(s.shape.basin_lower) << ","
          << full(s.shape.basin_upper) << "," << full(s.shape.total_variation_ratio) << "," << full(s.shape.flat_share)
          << ",nan\n";
      md << "| " << s.cost << " | " << s.parameter << " | " << s.shape.local_minima << " | " << signed_pct(s.shape.basin_lower)
         << " .. " << signed_pct(s.shape.basin_upper) << " | " << g3(s.shape.total_variation_ratio) << " | "
         << pct(s.shape.flat_share) << " | - |\n";
    }
    for (const auto& g : grid_rows) {
      csv << g.cost << ",grid," << g.a << "+" << g.b << "," << g.shape.local_minima << ",nan,nan,nan,"
          << full(g.shape.flat_share) << "," << full(g.shape.descent_share) << "\n";
      md << "| " << g.cost << " | " << g.a << " x " << g.b << " | " << g.shape.local_minima << " | - | - | "
         << pct(g.shape.flat_share) << " | " << pct(g.shape.descent_share) << " |\n";
    }
    if (!multistart_reach.empty()) {
      md << "\nLocal fits from " << spec.landscape.multistarts
         << " Latin-hypercube starts in the bounds that reach the lowest minimum found (every parameter within the "
            "success tolerance of it):";
      for (const auto& cost : spec.landscape.cost)
        if (multistart_reach.count(cost))
          md << " " << cost << " " << multistart_reach[cost].first << "/" << multistart_reach[cost].second << ";";
      md << "\n";
    }
    write_file(dir / "landscape" / "smoothness.csv", csv.str());
    write_file(dir / "smoothness.md", md.str());
  }

  // ---- overlay and spectrum of one case per cost (noise outputs.overlay_noise, N outputs.overlay_elements)
  {
    std::vector<std::pair<std::string, Overlay>> overlays;
    for (const auto& cost : spec.sweep.cost)
      for (const Row& r : rows) {
        const Unit& u = *r.unit;
        if (u.cost != cost || u.elements != spec.outputs.overlay_elements || u.noise != spec.outputs.overlay_noise ||
            u.replicate != 0 || u.method != spec.sweep.method.front() || u.start != spec.sweep.start.front() ||
            u.pulse_width_s != spec.sweep.pulse_width_s.front() || u.samples != spec.sweep.samples.front())
          continue;
        try {
          overlays.emplace_back(cost, overlay(spec, u, truths[static_cast<std::size_t>(u.truth)], r.record));
        } catch (const std::exception&) {
        }
        break;
      }
    write_overlay_files(dir, overlays);
  }

  // ---- report.md: the generated block
  std::map<std::string, std::pair<int, int>> by_cost;  // success/cases with noise <= 1 %
  for (const Row& r : rows)
    if (r.unit->noise <= 0.01 + 1e-12) {
      by_cost[r.unit->cost].first += r.success() ? 1 : 0;
      by_cost[r.unit->cost].second += 1;
    }
  report << "*Study `" << spec.name << "` (`" << spec.path << "`), " << rows.size() << " fits";
  if (!landscape.empty()) report << " and " << landscape.size() << " landscape units";
  report << ", seed " << spec.seed << ", commit " << commit << "; truth: `" << spec.truth.beam << "` by CVODE at N = "
         << spec.truth.elements << ", rtol " << g3(spec.truth.rtol) << "; success = every one of " ;
  for (std::size_t i = 0; i < keys.size(); ++i) report << (i ? ", " : "") << keys[i];
  report << " within " << pct(spec.fit.success_tolerance) << " of the truth";
  if (spec.fit.damping_tolerance != spec.fit.success_tolerance)
    report << " (damping parameters within " << pct(spec.fit.damping_tolerance) << ")";
  report << ".*\n\n";
  report << "Computed claims:\n\n";
  const auto claim = [&](bool holds, const std::string& text) {
    report << "- `[" << (holds ? "true" : "false") << "]` " << text << "\n";
  };
  for (const auto& cost : spec.sweep.cost)
    if (by_cost.count(cost))
      claim(true, cost + " succeeds in " + std::to_string(by_cost[cost].first) + "/" +
                      std::to_string(by_cost[cost].second) + " fits with noise <= 1 %");
  const auto rate = [&](const std::string& c) {
    return by_cost.count(c) && by_cost[c].second ? static_cast<double>(by_cost[c].first) / by_cost[c].second : -1.0;
  };
  if (by_cost.count("time") && (by_cost.count("spike") || by_cost.count("spike-smooth"))) {
    const double best_freq = std::max(rate("spike"), rate("spike-smooth"));
    claim(best_freq > rate("time"), "a frequency-domain cost succeeds more often than the time-domain cost "
                                    "(noise <= 1 %: best spike cost " + pct(best_freq) + " against time " +
                                    pct(rate("time")) + ")");
    // Paired per group: where spike-smooth >= time.
    int holds = 0, total = 0;
    std::map<std::tuple<double, int, std::string, std::string, int, double>, std::map<std::string, double>> cmp;
    for (const auto& [k, members] : groups) {
      int s = 0;
      for (const Row* r : members) s += r->success() ? 1 : 0;
      cmp[{k.pulse_width_s, k.samples, k.method, k.start, k.elements, k.noise}][k.cost] =
          static_cast<double>(s) / members.size();
    }
    for (const auto& [k, m] : cmp)
      if (m.count("time") && m.count("spike-smooth")) {
        ++total;
        holds += m.at("spike-smooth") >= m.at("time") ? 1 : 0;
      }
    if (total > 0)
      claim(holds == total, "spike-smooth succeeds at least as often as time in every setting (" +
                                std::to_string(holds) + "/" + std::to_string(total) + " settings)");
  }
  if (several_experiments) {
    for (const auto& cost : spec.sweep.cost) {
      std::map<int, std::pair<int, int>> by_modes;
      for (const Row& r : rows)
        if (r.unit->cost == cost) {
          by_modes[r.modes()].first += r.success() ? 1 : 0;
          by_modes[r.modes()].second += 1;
        }
      if (by_modes.size() < 2) continue;
      const auto& lo = by_modes.begin()->second;
      const auto& hi = by_modes.rbegin()->second;
      const double rlo = static_cast<double>(lo.first) / lo.second, rhi = static_cast<double>(hi.first) / hi.second;
      claim(rhi < rlo, cost + "'s success rate falls from " + std::to_string(lo.first) + "/" + std::to_string(lo.second) +
                           " with " + std::to_string(by_modes.begin()->first) + " mode(s) in the data to " +
                           std::to_string(hi.first) + "/" + std::to_string(hi.second) + " with " +
                           std::to_string(by_modes.rbegin()->first));
    }
  }
  if (several_experiments && !basin_rows.empty()) {
    // Median basin width (over the estimated parameters) at the fewest and the most modes, per cost.
    for (const auto& cost : spec.landscape.cost) {
      std::map<int, std::vector<double>> widths;
      for (const auto& b : basin_rows)
        if (b.cost == cost) widths[b.modes].push_back(b.shape.basin_upper - b.shape.basin_lower);
      if (widths.size() < 2) continue;
      const double lo = median(widths.begin()->second), hi = median(widths.rbegin()->second);
      claim(hi < lo, cost + "'s median basin width narrows from " + pct(lo) + " with " +
                         std::to_string(widths.begin()->first) + " mode(s) in the data to " + pct(hi) + " with " +
                         std::to_string(widths.rbegin()->first));
    }
  }
  if (!slice_rows.empty()) {
    const auto count = [&](const std::string& a, const std::string& b, auto better) {
      int holds = 0, total = 0;
      for (const auto& s : slice_rows)
        if (s.cost == a)
          for (const auto& t : slice_rows)
            if (t.cost == b && t.parameter == s.parameter) ++total, holds += better(s.shape, t.shape) ? 1 : 0;
      return std::make_pair(holds, total);
    };
    for (const std::string freq : {"spike-smooth", "spike"}) {
      const auto wider = count(freq, "time", [](const SliceShape& f, const SliceShape& t) {
        return f.basin_upper - f.basin_lower > t.basin_upper - t.basin_lower;
      });
      if (wider.second > 0)
        claim(wider.first == wider.second, "the " + freq + " basin is wider than time's along every axis (" +
                                               std::to_string(wider.first) + "/" + std::to_string(wider.second) + ")");
    }
    const auto fewer = count("spike-smooth", "time", [](const SliceShape& f, const SliceShape& t) {
      return f.local_minima <= t.local_minima;
    });
    if (fewer.second > 0)
      claim(fewer.first == fewer.second, "spike-smooth has no more local minima than time along every axis (" +
                                             std::to_string(fewer.first) + "/" + std::to_string(fewer.second) + ")");
    // The staircase of (3.5) lives on the axes that move frequencies (stiffness and inertia); damping moves only
    // magnitudes, which (3.5) compares continuously.
    int flat_holds = 0, flat_total = 0;
    for (const auto& s : slice_rows)
      if (s.cost == "spike" && model::find_parameter(s.parameter)->role != "damping")
        for (const auto& t : slice_rows)
          if (t.cost == "spike-smooth" && t.parameter == s.parameter)
            ++flat_total, flat_holds += s.shape.flat_share > t.shape.flat_share ? 1 : 0;
    if (flat_total > 0)
      claim(flat_holds == flat_total, "the paper's spike cost (3.5) has more flat steps (its staircase) than "
                                      "spike-smooth along every stiffness and mass axis (" +
                                          std::to_string(flat_holds) + "/" + std::to_string(flat_total) + ")");
    for (const auto& [cost, reach] : multistart_reach)
      claim(true, cost + ": " + std::to_string(reach.first) + "/" + std::to_string(reach.second) +
                      " local fits from random starts reach the lowest minimum");
    if (multistart_reach.count("time"))
      for (const std::string freq : {"spike-smooth", "spike"})
        if (multistart_reach.count(freq)) {
          const auto& f = multistart_reach[freq];
          const auto& t = multistart_reach["time"];
          claim(f.first * t.second > t.first * f.second,
                "more random starts reach the minimum with " + freq + " than with time (" + std::to_string(f.first) +
                    "/" + std::to_string(f.second) + " against " + std::to_string(t.first) + "/" +
                    std::to_string(t.second) + ")");
        }
  }
  const auto read = [&](const std::string& name) {
    std::ifstream in(dir / name);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
  };
  report << "\n";
  if (!rows.empty()) {
    report << "Summary (relative bias ± standard deviation over replicates; `summary.csv` has RMSE and medians):\n\n"
           << read("summary.md") << "\n";
    if (spec.sweep.noise.front() == 0 && spec.sweep.elements.size() > 1)
      report << "Noise-free estimates against N (largest relative error over the estimated parameters) beside the "
                "Galerkin error of the first frequencies:\n\n" << read("convergence.md") << "\n";
    if (spec.sweep.replicates >= 3)
      report << "Monte-Carlo spread of the estimates against the median standard error the fits report (1 = the "
                "formal errors are right; they assume independent Gaussian residuals):\n\n" << read("spread.md") << "\n";
  }
  if (spec.landscape.enabled) report << "Landscape smoothness at N = " << spec.landscape.elements << ":\n\n" << read("smoothness.md") << "\n";
  // Plot links: the images plots/make_plots.sh makes from these tables (names fixed there), SVG beside each PNG.
  const std::string p = "plots/" + spec.name + "/";
  std::vector<std::pair<std::string, std::string>> images;
  if (spec.landscape.enabled) {
    images.emplace_back("landscape_slices", "cost slices through the truth, normalised to [0, 1]");
    for (const auto& [a, b] : spec.landscape.pairs)
      images.emplace_back("landscape_grid_" + a + "_" + b, "cost surfaces over (" + a + ", " + b + ")");
  }
  if (several_experiments) images.emplace_back("success_vs_modes", "success rate against the modes in the data");
  if (spec.sweep.elements.size() > 1)
    for (const auto& k : keys) images.emplace_back("bias_" + k, "RMSE of the relative error in " + k + " against N");
  if (fs::exists(dir / "spectrum.csv")) {
    images.emplace_back("spectrum", "data spectrum with the detected spikes and their 20 % supports");
    images.emplace_back("overlay", "fits at N = " + std::to_string(spec.outputs.overlay_elements) +
                                       " in time and in frequency");
  }
  report << "Plots (PNG; SVG beside each):\n\n";
  for (const auto& [name, what] : images)
    report << "- [" << what << "](" << p << name << ".png)\n";
  write_file(dir / "report.md", report.str());
}

}  // namespace beamid::study
