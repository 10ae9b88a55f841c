#include "study/tables/start_distance_tables.h"

#include <cmath>
#include <sstream>

#include "io/text.h"
#include "study/analysis/metrics.h"
#include "study/tables/format.h"

namespace beamid::study {
namespace {

// A radius with its interval: "0.31 % (0.22-0.40 %)", the ends marked "<" or ">" where the curve leaves the range.
std::string radius_with_interval(const StartRun& run) {
  if (!run.reference_ok) return "- (the fit from the truth failed)";
  return radius_text(run.radius) + " (" + radius_text(run.radius_low) + " to " + radius_text(run.radius_high) + ")";
}

std::string flag(const HalfRadius& r) { return r.below ? "below" : r.above ? "above" : "inside"; }

// The experiment of a run, as the last columns of the CSV files: experiment,pulse_width_s,samples,modes_in_data.
std::string experiment_csv(const StartRun& run) {
  return "," + std::to_string(run.experiment) + "," + io::round_trip(run.pulse_width_s) + "," +
         std::to_string(run.samples) + "," + std::to_string(run.modes_in_data);
}

// With several records: the fitted reach curves (reach.csv) and the runs compared in pairs on the same starts
// (pairs.csv), one file each.
Rendered render_reach_curves(const StartDistanceMetrics& m) {
  std::ostringstream os;
  os << "cost,method,records,references_failed,starts,reached,half_radius,half_radius_low,half_radius_high,position,"
        "experiment,pulse_width_s,samples,modes_in_data\n";
  for (const auto& run : m.runs) {
    int reached = 0;
    for (const auto& o : run.outcomes) reached += o.reached ? 1 : 0;
    const auto value = [&](const HalfRadius& h) { return io::round_trip(run.reference_ok ? h.value : std::nan("")); };
    os << run.cost << "," << run.method << "," << run.records << "," << run.references_failed << ","
       << run.outcomes.size() << "," << reached << "," << value(run.radius) << "," << value(run.radius_low) << ","
       << value(run.radius_high) << "," << (run.reference_ok ? flag(run.radius) : "-") << experiment_csv(run) << "\n";
  }
  return {"start_distance/reach.csv", os.str()};
}

Rendered render_pairs(const StartDistanceMetrics& m) {
  std::ostringstream os;
  os << "experiment,first,second,matched_starts,both_reached,first_only,second_only,neither,rate_difference,"
        "mcnemar_p\n";
  for (const auto& p : m.pairs) {
    const StartRun &a = m.runs[p.first], &b = m.runs[p.second];
    os << p.experiment << "," << a.cost << "/" << a.method << "," << b.cost << "/" << b.method << "," << p.matched
       << "," << p.both << "," << p.first_only << "," << p.second_only << "," << p.neither << ","
       << io::round_trip(p.matched > 0 ? static_cast<double>(p.first_only - p.second_only) / p.matched : std::nan(""))
       << "," << io::round_trip(p.p_value) << "\n";
  }
  return {"start_distance/pairs.csv", os.str()};
}

// With several records: each run's fits from the truth, per parameter (reference.csv), and as the report's table
// (start_distance_reference.md: bias +- MCSE and RMSE / bound per parameter, with the budget count).
Rendered render_reference_csv(const StudySpec& spec, const StartDistanceMetrics& m) {
  std::ostringstream os;
  os << "cost,method,parameter,fits,records,bias,mcse,sd,rmse,bound,rmse_over_bound,fits_run,budget_exhausted,"
        "experiment,pulse_width_s,samples,modes_in_data\n";
  for (const auto& run : m.runs)
    for (const auto& e : run.reference_errors)
      os << run.cost << "," << run.method << "," << e.parameter << "," << e.errors.count << ","
         << spec.start_distance.records << "," << io::round_trip(e.errors.mean) << "," << io::round_trip(e.mcse) << ","
         << io::round_trip(e.errors.std) << "," << io::round_trip(e.errors.rmse) << "," << io::round_trip(e.bound)
         << "," << io::round_trip(e.efficiency()) << "," << run.fits_run << "," << run.budget_exhausted
         << experiment_csv(run) << "\n";
  return {"start_distance/reference.csv", os.str()};
}

Rendered render_reference_md(const StudySpec& spec, const StartDistanceMetrics& m) {
  std::ostringstream os;
  const bool several = m.experiments > 1;
  os << (several ? "| modes in data |" : "|") << " cost | method | fits |";
  for (const auto& key : spec.fit.estimate) os << " " << key << " bias (MCSE) | " << key << " RMSE / bound |";
  os << " budget exhausted |\n|" << (several ? "---|" : "") << "---|---|---|";
  for (std::size_t i = 0; i < spec.fit.estimate.size(); ++i) os << "---|---|";
  os << "---|\n";
  for (const auto& run : m.runs) {
    if (several) os << "| " << run.modes_in_data << " ";
    const int fits = run.reference_errors.empty() ? 0 : run.reference_errors.front().errors.count;
    os << "| " << run.cost << " | " << run.method << " | " << fits << "/" << run.records << " |";
    for (const auto& e : run.reference_errors) {
      const bool significant = std::abs(e.errors.mean) > 2 * e.mcse;
      os << " " << pct(e.errors.mean) << " (" << pct(e.mcse) << ")" << (significant ? " *" : "") << " | "
         << g3(e.efficiency()) << " |";
    }
    os << " " << run.budget_exhausted << "/" << run.fits_run << " |\n";
  }
  return {"start_distance_reference.md", os.str()};
}

}  // namespace

RenderedFiles render_start_distance(const StudyResults& results, const StartDistanceMetrics& m) {
  const StudySpec& spec = *results.spec;
  RenderedFiles files;
  if (!spec.start_distance.enabled) return files;
  const auto& keys = spec.fit.estimate;
  {
    std::ostringstream os;
    os << "cost,method,offset,direction,frequency_offset,shrunk,status,reached,evaluations,cost_value";
    for (const auto& k : keys) os << ",start." << k;
    for (const auto& k : keys) os << ",estimate." << k;
    os << ",pulse_width_s,samples,modes_in_data\n";
    for (std::size_t i = 0; i < results.starts.size(); ++i) {
      const LandscapeRow& row = results.starts[i];
      const Unit& u = *row.unit;
      const Record& r = row.record;
      os << u.cost << "," << u.method << "," << io::round_trip(u.offset) << "," << u.index << ","
         << io::round_trip(r.number("frequency_offset")) << "," << r.number("shrunk") << "," << r.text("status") << ","
         << (u.index < 0    ? "reference"
             : m.reached[i] ? "1"
                            : "0")
         << "," << r.number("evaluations") << "," << io::round_trip(r.number("cost"));
      for (const auto& k : keys) os << "," << io::round_trip(r.number("start." + k));
      for (const auto& k : keys) os << "," << io::round_trip(r.number("estimate." + k));
      os << "," << io::round_trip(u.pulse_width_s) << "," << u.samples << ","
         << (r.has("modes_in_data") ? r.text("modes_in_data") : "nan") << "\n";
    }
    files.push_back({"start_distance/fits.csv", os.str()});
  }
  {
    std::ostringstream os;
    os << "cost,method,offset,reached,fits,rate,wilson_low,wilson_high,shrunk,median_evaluations,experiment,"
          "pulse_width_s,samples,modes_in_data\n";
    for (const auto& run : m.runs)
      for (const auto& p : run.points) {
        const auto [low, high] = wilson_interval(p.reached, p.fits);
        os << run.cost << "," << run.method << "," << io::round_trip(p.offset) << "," << p.reached << "," << p.fits
           << "," << io::round_trip(p.rate()) << "," << io::round_trip(low) << "," << io::round_trip(high) << ","
           << p.shrunk << "," << io::round_trip(p.median_evaluations) << experiment_csv(run) << "\n";
      }
    files.push_back({"start_distance/curves.csv", os.str()});
  }
  {
    std::ostringstream os;
    os << "cost,method,reference_status,half_radius,half_radius_low,half_radius_high,position,predicted_basin,"
          "ratio_to_predicted,predicted_basin_decay_limited,ratio_to_decay_limited,limiting_mode,"
          "predicted_basin_highest_mode_decay_limited,experiment,pulse_width_s,samples,modes_in_data,fitted_modes\n";
    for (const auto& run : m.runs)
      os << run.cost << "," << run.method << ","
         << (run.reference ? run.reference->record.text("status") : std::string("missing")) << ","
         << io::round_trip(run.reference_ok ? run.radius.value : std::nan("")) << ","
         << io::round_trip(run.reference_ok ? run.radius_low.value : std::nan("")) << ","
         << io::round_trip(run.reference_ok ? run.radius_high.value : std::nan("")) << ","
         << (run.reference_ok ? flag(run.radius) : "-") << "," << io::round_trip(run.predicted_basin) << ","
         << io::round_trip(run.reference_ok ? run.radius.value / run.predicted_basin : std::nan("")) << ","
         << io::round_trip(run.predicted_basin_decay) << ","
         << io::round_trip(run.reference_ok ? run.radius.value / run.predicted_basin_decay : std::nan("")) << ","
         << run.limiting_mode << "," << io::round_trip(run.predicted_basin_highest_decay) << experiment_csv(run) << ","
         << run.fitted_modes << "\n";
    files.push_back({"start_distance/radius.csv", os.str()});
  }
  if (spec.start_distance.records > 1) {
    files.push_back(render_reach_curves(m));
    files.push_back(render_pairs(m));
    files.push_back(render_reference_csv(spec, m));
    files.push_back(render_reference_md(spec, m));
  }
  {
    std::ostringstream os;
    // With several experiments, each row opens with its own: modes in the data (fitted) and the pulse width.
    const bool several = m.experiments > 1;
    const int records = spec.start_distance.records;
    os << (several ? "| modes in data (fitted) | pulse |" : "|") << " cost | method | 50 % radius (95 % interval"
       << (records > 1 ? " across " + std::to_string(records) + " records" : std::string())
       << ") | x 1/(2 f T) | x min_k 1/(2 f_k T_eff,k) |";
    for (double r : spec.start_distance.offsets) os << " " << pct(r) << " |";
    os << " evaluations (median) |\n|" << (several ? "---|---|" : "") << "---|---|---|---|---|";
    for (std::size_t j = 0; j < spec.start_distance.offsets.size(); ++j) os << "---|";
    os << "---|\n";
    for (const auto& run : m.runs) {
      if (several)
        os << "| " << run.modes_in_data << " (" << run.fitted_modes << ") | " << g3(1e3 * run.pulse_width_s) << " ms ";
      os << "| " << run.cost << " | " << run.method << " | " << radius_with_interval(run) << " | "
         << (run.reference_ok ? g3(run.radius.value / run.predicted_basin) : "-") << " | "
         << (run.reference_ok ? g3(run.radius.value / run.predicted_basin_decay) : "-") << " |";
      std::vector<double> evaluations;
      for (const auto& p : run.points) {
        os << " " << p.reached << "/" << p.fits << " |";
        evaluations.push_back(p.median_evaluations);
      }
      os << " " << g3(median(evaluations)) << " |\n";
    }
    files.push_back({"start_distance.md", os.str()});
  }
  return files;
}

}  // namespace beamid::study
