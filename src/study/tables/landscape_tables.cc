#include "study/tables/landscape_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "io/text.h"
#include "model/beam_parameters.h"
#include "study/tables/format.h"

namespace beamid::study {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

double true_value(const StudySpec& spec, const std::string& key) {
  return model::parameter_value(spec.truth.parameters, key);
}

// (min, max) of the finite values.
std::pair<double, double> finite_range(const std::vector<double>& c) {
  double mn = INFINITY, mx = -INFINITY;
  for (double y : c)
    if (std::isfinite(y)) mn = std::min(mn, y), mx = std::max(mx, y);
  return {mn, mx};
}

// The folder name of a landscape setting, "N8-noise0.01".
std::string setting_name(const Unit& u) {
  return "N" + std::to_string(u.elements) + "-noise" + io::round_trip(u.noise);
}

// The first setting's slices are landscape/slice_*.csv; the others' landscape/<setting>/slice_*.csv.
Rendered slice_file(const LandscapeRow& l, double v, bool first_setting) {
  const Unit& u = *l.unit;
  const std::vector<double> x = l.record.has("x") ? l.record.numbers("x") : std::vector<double>{};
  const std::vector<double> c = l.record.has("cost") ? l.record.numbers("cost") : std::vector<double>{};
  const auto [mn, mx] = finite_range(c);
  std::ostringstream os;
  os << "ratio,value,cost,normalised_cost\n";
  for (std::size_t j = 0; j < c.size() && j < x.size(); ++j)
    os << io::round_trip(x[j] / v) << "," << io::round_trip(x[j]) << "," << io::round_trip(c[j]) << ","
       << io::round_trip(std::isfinite(c[j]) && mx > mn ? (c[j] - mn) / (mx - mn) : kNaN) << "\n";
  return {"landscape/" + (first_setting ? std::string() : setting_name(u) + "/") + "slice_" + u.cost + "_" +
              u.parameters[0] + ".csv",
          os.str()};
}

// gnuplot pm3d blocks (a blank line after each x row); the height is log10 of the normalised cost, which shows the
// floor of a basin as well as its walls. Wide grids are landscape/grid_*.dat, fine ones landscape/zoom/<setting>/.
Rendered grid_file(const LandscapeRow& l, double va, double vb) {
  const Unit& u = *l.unit;
  const std::vector<double> x = l.record.numbers("x"), y = l.record.numbers("y"), c = l.record.numbers("cost");
  const auto [mn, mx] = finite_range(c);
  std::ostringstream os;
  os << "# ratio_" << u.parameters[0] << " ratio_" << u.parameters[1] << " cost log10_normalised_cost\n";
  const std::size_t ny = y.size();
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = 0; j < ny; ++j) {
      const double z = c[i * ny + j];
      const double norm = std::isfinite(z) && mx > mn ? (z - mn) / (mx - mn) : kNaN;
      os << io::round_trip(x[i] / va) << " " << io::round_trip(y[j] / vb) << " " << io::round_trip(z) << " "
         << io::round_trip(std::isfinite(norm) ? std::log10(std::max(norm, 1e-12)) : kNaN) << "\n";
    }
    os << "\n";
  }
  return {"landscape/" + (u.zoom ? "zoom/" + setting_name(u) + "/" : std::string()) + "grid_" + u.cost + "_" +
              u.parameters[0] + "_" + u.parameters[1] + ".dat",
          os.str()};
}

std::string minima(int n) { return std::to_string(n) + (n == 1 ? " minimum" : " minima"); }

std::string start_label(int index) { return index < 0 ? "truth" : std::to_string(index); }

RenderedFiles multistart_files(const StudySpec& spec, const std::vector<MultistartSummary>& summaries) {
  const auto& keys = spec.fit.estimate;
  std::ostringstream ms, md;
  ms << "cost,start,status,cost_value,cost_gap,evaluations,reached";
  for (const auto& k : keys) ms << ",start_" << k << ",estimate_" << k;
  ms << "\n";
  for (const auto& s : summaries)
    for (const auto& f : s.fits) {
      const Record& rec = f.row->record;
      ms << s.cost << "," << start_label(f.row->unit->index) << "," << io::csv_quoted(rec.text("status")) << ","
         << (rec.has("cost") ? rec.text("cost") : "inf") << "," << io::round_trip(f.cost_gap) << ","
         << (rec.has("evaluations") ? rec.text("evaluations") : "0") << "," << (f.reached ? 1 : 0);
      for (const auto& k : keys)
        ms << "," << (rec.has("start." + k) ? rec.text("start." + k) : "nan") << ","
           << (rec.has("estimate." + k) ? rec.text("estimate." + k) : "nan");
      ms << "\n";
    }
  // Markdown: one row per start, one column per cost: the final cost's gap to the reference minimum, and whether
  // the fit reached it (every estimate within the success tolerance of the reference's).
  md << "| start |";
  for (const auto& s : summaries) md << " " << s.cost << ": cost gap |";
  md << "\n|---|";
  for (std::size_t i = 0; i < summaries.size(); ++i) md << "---|";
  md << "\n";
  std::size_t rows = 0;
  for (const auto& s : summaries) rows = std::max(rows, s.fits.size());
  for (std::size_t r = 0; r < rows; ++r) {
    md << "| " << (summaries.front().fits.size() > r ? start_label(summaries.front().fits[r].row->unit->index) : "-")
       << " |";
    for (const auto& s : summaries) {
      if (r >= s.fits.size()) {
        md << " - |";
        continue;
      }
      const auto& f = s.fits[r];
      const std::string status = f.row->record.text("status");
      md << " " << (status.rfind("failed", 0) == 0 ? "failed" : g3(f.cost_gap) + (f.reached ? " (reached)" : ""))
         << " |";
    }
    md << "\n";
  }
  if (summaries.empty()) return {{"landscape/multistart.csv", ms.str()}};  // no multi-start in this study
  return {{"landscape/multistart.csv", ms.str()}, {"landscape/multistart.md", md.str()}};
}

std::string resolution_csv(const Resolution& r) {
  return io::round_trip(r.frequency_step) + "," + io::round_trip(r.predicted_basin) + "," + (r.resolved() ? "1" : "0");
}

// The step beside the predicted least-squares basin; "(coarse)" when it exceeds a third of it.
std::string step_md(const Resolution& r) {
  if (!std::isfinite(r.frequency_step) || !std::isfinite(r.predicted_basin)) return std::string("unknown");
  return pct(r.frequency_step) + (r.resolved() ? "" : " (coarse: basin " + pct(r.predicted_basin) + ")");
}

std::string setting_csv(const Unit& u) { return std::to_string(u.elements) + "," + io::round_trip(u.noise); }

std::string basin_md(const SliceRow& s) {
  return s.resolution.resolved() ? signed_pct(s.shape.basin_lower) + " .. " + signed_pct(s.shape.basin_upper)
                                 : std::string("unresolved");
}

std::string grid_label(const StudySpec& spec, const GridRow& g) {
  return g.a + " x " + g.b +
         (g.zoom ? " (+-" + pct(spec.landscape.zoom_range_factor - 1) + ", " +
                       std::to_string(spec.landscape.zoom_points) + " points per axis)"
                 : std::string());
}

// Every slice's basin against the predicted least-squares basin, for every experiment.
Rendered basin_file(const LandscapeMetrics& metrics) {
  std::ostringstream basin;
  basin << "modes_in_data,pulse_width_s,samples,N,noise,cost,parameter,local_minima,basin_lower,basin_upper,"
           "basin_width,frequency_step,predicted_basin,resolved\n";
  for (const auto& s : metrics.slices) {
    const Record& rec = s.row->record;
    basin << (rec.has("modes_in_data") ? rec.text("modes_in_data") : "nan") << ","
          << io::round_trip(s.row->unit->pulse_width_s) << "," << s.row->unit->samples << "," << s.row->unit->elements
          << "," << io::round_trip(s.row->unit->noise) << "," << s.cost << "," << s.parameter << ","
          << s.shape.local_minima << "," << io::round_trip(s.shape.basin_lower) << ","
          << io::round_trip(s.shape.basin_upper) << "," << io::round_trip(s.shape.basin_upper - s.shape.basin_lower)
          << "," << io::round_trip(s.resolution.frequency_step) << "," << io::round_trip(s.resolution.predicted_basin)
          << "," << (s.resolution.resolved() ? 1 : 0) << "\n";
  }
  return {"landscape/basin.csv", basin.str()};
}

// The first experiment's slices and grids: one CSV row per setting, one Markdown row for the first setting; and the
// multi-starts' reach.
RenderedFiles smoothness_files(const StudySpec& spec, const LandscapeMetrics& metrics) {
  std::ostringstream csv, md;
  csv << "N,noise,cost,kind,parameters,local_minima,basin_lower,basin_upper,total_variation_ratio,flat_share,"
         "descent_share,frequency_step,predicted_basin,resolved\n";
  md << "| cost | slice or grid | step in frequency | local minima | basin around the minimum | TV / range | flat "
        "steps "
        "| grid points descending to the minimum |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : metrics.slices) {
    if (!s.first_experiment) continue;
    csv << setting_csv(*s.row->unit) << "," << s.cost << ",slice," << s.parameter << "," << s.shape.local_minima << ","
        << io::round_trip(s.shape.basin_lower) << "," << io::round_trip(s.shape.basin_upper) << ","
        << io::round_trip(s.shape.total_variation_ratio) << "," << io::round_trip(s.shape.flat_share) << ",nan,"
        << resolution_csv(s.resolution) << "\n";
    if (!s.first_setting) continue;
    md << "| " << s.cost << " | " << s.parameter << " | " << step_md(s.resolution) << " | " << s.shape.local_minima
       << " | " << basin_md(s) << " | " << g3(s.shape.total_variation_ratio) << " | " << pct(s.shape.flat_share)
       << " | - |\n";
  }
  for (const auto& g : metrics.grids) {
    csv << setting_csv(*g.row->unit) << "," << g.cost << "," << (g.zoom ? "zoom-grid," : "grid,") << g.a << "+" << g.b
        << "," << g.shape.local_minima << ",nan,nan,nan," << io::round_trip(g.shape.flat_share) << ","
        << io::round_trip(g.shape.descent_share) << "," << resolution_csv(g.resolution) << "\n";
    if (!g.first_setting) continue;
    md << "| " << g.cost << " | " << grid_label(spec, g) << " | " << step_md(g.resolution) << " | "
       << g.shape.local_minima << " | - | - | " << pct(g.shape.flat_share) << " | " << pct(g.shape.descent_share)
       << " |\n";
  }
  if (!metrics.multistarts.empty()) {
    md << "\nLocal fits from " << spec.landscape.multistarts
       << " Latin-hypercube starts in the bounds that reach the reference minimum (the lowest final cost of all the "
          "cost's fits, the fit started at the truth included; every parameter within the success tolerance of "
          "it):";
    for (const auto& s : metrics.multistarts) md << " " << s.cost << " " << s.reached << "/" << s.started << ";";
    md << "\n";
  }
  return {{"landscape/smoothness.csv", csv.str()}, {"smoothness.md", md.str()}};
}

// Across N and noise (the first experiment): one column per setting, one row per slice or fine grid.
Rendered across_file(const StudySpec& spec, const LandscapeMetrics& metrics) {
  std::ostringstream across;
  across << "| cost | slice or grid |";
  for (int n : spec.landscape.elements)
    for (double noise : spec.landscape.noise) across << " N = " << n << ", noise " << pct(noise) << " |";
  across << "\n|---|---|";
  for (std::size_t i = 0; i < spec.landscape.elements.size() * spec.landscape.noise.size(); ++i) across << "---|";
  across << "\n";
  // Cells in plan order: the settings of one (cost, axis) follow the order N, then noise.
  std::map<std::pair<std::string, std::string>, std::vector<std::string>> rows;
  std::vector<std::pair<std::string, std::string>> order;
  const auto cell = [&](const std::string& cost, const std::string& what, const std::string& text) {
    const auto key = std::make_pair(cost, what);
    if (!rows.count(key)) order.push_back(key);
    rows[key].push_back(text);
  };
  for (const auto& s : metrics.slices)
    if (s.first_experiment)
      cell(s.cost, s.parameter,
           basin_md(s) + ", " + minima(s.shape.local_minima) + (s.resolution.resolved() ? std::string() : " (coarse)"));
  for (const auto& g : metrics.grids)
    if (g.zoom)
      cell(g.cost, grid_label(spec, g),
           minima(g.shape.local_minima) + ", " + pct(g.shape.descent_share) + " descend" +
               (g.resolution.resolved() ? std::string() : " (coarse)"));
  std::stable_sort(order.begin(), order.end(), [&](const auto& x, const auto& y) {
    const auto rank = [&](const std::string& c) {
      return std::find(spec.landscape.cost.begin(), spec.landscape.cost.end(), c) - spec.landscape.cost.begin();
    };
    return rank(x.first) < rank(y.first);
  });
  for (const auto& key : order) {
    across << "| " << key.first << " | " << key.second << " |";
    for (const auto& text : rows[key]) across << " " << text << " |";
    across << "\n";
  }
  return {"landscape_across.md", across.str()};
}

}  // namespace

RenderedFiles render_landscape(const StudyResults& results, const LandscapeMetrics& metrics) {
  const StudySpec& spec = *results.spec;
  RenderedFiles files;
  if (!spec.landscape.enabled) return files;
  for (const LandscapeRow& l : results.landscape) {
    const Unit& u = *l.unit;
    const bool first = u.pulse_width_s == spec.sweep.pulse_width_s.front() && u.samples == spec.sweep.samples.front();
    if (u.kind == UnitKind::Slice && first)
      files.push_back(slice_file(l, true_value(spec, u.parameters[0]), first_setting(spec, u)));
  }
  for (const GridRow& g : metrics.grids)  // the grids whose lists agree in size (metrics.h)
    files.push_back(grid_file(*g.row, true_value(spec, g.a), true_value(spec, g.b)));
  const RenderedFiles ms = multistart_files(spec, metrics.multistarts);
  files.insert(files.end(), ms.begin(), ms.end());
  files.push_back(basin_file(metrics));
  const bool across = spec.landscape.elements.size() * spec.landscape.noise.size() > 1;
  const RenderedFiles smoothness = smoothness_files(spec, metrics);
  if (across) files.push_back(across_file(spec, metrics));
  files.insert(files.end(), smoothness.begin(), smoothness.end());
  return files;
}

}  // namespace beamid::study
