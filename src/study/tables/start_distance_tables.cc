#include "study/tables/start_distance_tables.h"

#include <algorithm>
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

// With several records: each run's fitted modes against the truth's, per mode (reference_modes.csv), and as the
// report's table (start_distance_modes.md: frequency and damping-ratio errors with their MCSE, * beyond 2 MCSE).
Rendered render_modes_csv(const StartDistanceMetrics& m) {
  std::ostringstream os;
  os << "cost,method,mode,truth_frequency_hz,truth_damping_ratio,fits,frequency_bias,frequency_mcse,frequency_rmse,"
        "damping_bias,damping_mcse,damping_rmse,experiment,pulse_width_s,samples,modes_in_data\n";
  for (const auto& run : m.runs)
    for (const auto& e : run.mode_errors)
      os << run.cost << "," << run.method << "," << e.mode << "," << io::round_trip(e.truth_frequency_hz) << ","
         << io::round_trip(e.truth_damping_ratio) << "," << e.frequency.count << "," << io::round_trip(e.frequency.mean)
         << "," << io::round_trip(e.frequency_mcse) << "," << io::round_trip(e.frequency.rmse) << ","
         << io::round_trip(e.damping.mean) << "," << io::round_trip(e.damping_mcse) << ","
         << io::round_trip(e.damping.rmse) << experiment_csv(run) << "\n";
  return {"start_distance/reference_modes.csv", os.str()};
}

Rendered render_modes_md(const StartDistanceMetrics& m) {
  std::size_t modes = 0;
  for (const auto& run : m.runs) modes = std::max(modes, run.mode_errors.size());
  std::ostringstream os;
  const bool several = m.experiments > 1;
  os << (several ? "| modes in data |" : "|") << " cost | method |";
  for (std::size_t k = 1; k <= modes; ++k) os << " f" << k << " | zeta" << k << " |";
  os << "\n|" << (several ? "---|" : "") << "---|---|";
  for (std::size_t k = 0; k < modes; ++k) os << "---|---|";
  os << "\n";
  const auto cell = [](const Stats& s, double mcse) {
    return s.count == 0 ? std::string("-")
                        : pct(s.mean) + " (" + pct(mcse) + ")" + (std::abs(s.mean) > 2 * mcse ? " *" : "");
  };
  for (const auto& run : m.runs) {
    if (several) os << "| " << run.modes_in_data << " ";
    os << "| " << run.cost << " | " << run.method << " |";
    for (std::size_t k = 0; k < modes; ++k) {
      if (k < run.mode_errors.size())
        os << " " << cell(run.mode_errors[k].frequency, run.mode_errors[k].frequency_mcse) << " | "
           << cell(run.mode_errors[k].damping, run.mode_errors[k].damping_mcse) << " |";
      else
        os << " - | - |";
    }
    os << "\n";
  }
  return {"start_distance_modes.md", os.str()};
}

// Compute beside success (issue 35 item 3), per run: its fits, their model evaluations and seconds (median and
// total). Seconds change from run to run, so they live in a timings file of their own (start_distance/timings.csv),
// beside timings.csv, and never in a table or the report block.
Rendered render_run_timings(const StudyResults& results, const StartDistanceMetrics& m) {
  std::ostringstream os;
  os << "cost,method,fits,median_evaluations,total_evaluations,median_seconds,total_seconds,experiment,"
        "pulse_width_s,samples,modes_in_data\n";
  for (const auto& run : m.runs) {
    std::vector<double> evaluations, seconds;
    for (const auto& row : results.starts)
      if (row.unit->truth == run.truth && row.unit->samples == run.samples && row.unit->cost == run.cost &&
          row.unit->method == run.method) {
        evaluations.push_back(row.record.number("evaluations"));
        seconds.push_back(row.record.has("wall_time_s") ? row.record.number("wall_time_s") : std::nan(""));
      }
    const auto total = [](const std::vector<double>& v) {
      double sum = 0;
      for (double x : v) sum += std::isfinite(x) ? x : 0;
      return sum;
    };
    os << run.cost << "," << run.method << "," << evaluations.size() << "," << io::round_trip(median(evaluations))
       << "," << io::round_trip(total(evaluations)) << "," << io::round_trip(median(seconds)) << ","
       << io::round_trip(total(seconds)) << experiment_csv(run) << "\n";
  }
  return {"start_distance/timings.csv", os.str()};
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
    files.push_back(render_modes_csv(m));
    files.push_back(render_modes_md(m));
    files.push_back(render_run_timings(results, m));
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
