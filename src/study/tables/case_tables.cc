#include "study/tables/case_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "io/text.h"
#include "study/tables/format.h"

namespace beamid::study {
namespace {

bool several_experiments(const StudySpec& spec) {
  return spec.sweep.pulse_width_s.size() > 1 || spec.sweep.samples.size() > 1;
}

}  // namespace

// cases.csv and timings.csv
RenderedFiles render_cases(const StudyResults& results) {
  const StudySpec& spec = *results.spec;
  const auto& keys = spec.fit.estimate;
  std::ostringstream os, tm;
  os << "case_id,seed,pulse_width_s,samples,modes_in_data,elements,cost,spikes,noise,replicate,method,start,status,"
        "success,cost_value,evaluations,a4,termination";
  for (const auto& k : keys) os << ",estimate_" << k << ",standard_error_" << k << ",relative_error_" << k;
  os << "\n";
  tm << "unit_id,kind,cost,elements,noise,wall_time_s\n";
  for (std::size_t i = 0; i < results.plan->truths.size(); ++i)
    tm << results.plan->truths[i].id << ",truth,,,"
       << "," << io::round_trip(results.truths[i].number("wall_time_s")) << "\n";
  for (const CaseRow& r : results.cases) {
    const Unit& u = *r.unit;
    const Record& c = r.record;
    os << u.id << "," << u.seed << "," << io::round_trip(u.pulse_width_s) << "," << u.samples << "," << r.modes() << ","
       << u.elements << "," << u.cost << "," << (c.has("spikes") ? c.text("spikes") : "0") << ","
       << io::round_trip(u.noise) << "," << u.replicate << "," << u.method << "," << u.start << "," << c.text("status")
       << "," << (r.success ? 1 : 0) << "," << c.text("cost") << "," << c.text("evaluations") << ","
       << io::csv_quoted(c.text("a4")) << "," << io::csv_quoted(c.text("termination"));
    for (const auto& k : keys)
      os << "," << c.text("estimate." + k) << "," << c.text("standard_error." + k) << ","
         << c.text("relative_error." + k);
    os << "\n";
  }
  for (const CaseRow& r : results.cases)
    tm << r.unit->id << ",case," << r.unit->cost << "," << r.unit->elements << "," << io::round_trip(r.unit->noise)
       << "," << r.record.text("wall_time_s") << "\n";
  for (const LandscapeRow& l : results.bounds)
    tm << l.unit->id << ",bound,," << l.unit->elements << "," << io::round_trip(l.unit->noise) << ","
       << l.record.text("wall_time_s") << "\n";
  for (const LandscapeRow& l : results.starts)
    tm << l.unit->id << ",start," << l.unit->cost << "," << l.unit->elements << "," << io::round_trip(l.unit->noise)
       << "," << l.record.text("wall_time_s") << "\n";
  for (const LandscapeRow& l : results.landscape)
    tm << l.unit->id << "," << unit_kind_name(l.unit->kind) << "," << l.unit->cost << "," << l.unit->elements << ",0,"
       << l.record.text("wall_time_s") << "\n";
  for (const Unit& u : results.plan->units)
    if (u.kind == UnitKind::Frequencies)
      tm << u.id << ",frequencies,," << u.elements << ",0," << results.frequencies.at(u.elements).text("wall_time_s")
         << "\n";
  return {{"cases.csv", os.str()}, {"timings.csv", tm.str()}};
}

// summary.csv and summary.md
RenderedFiles render_summary(const StudyResults& results, const Groups& groups) {
  const StudySpec& spec = *results.spec;
  const auto& keys = spec.fit.estimate;
  std::ostringstream csv, md;
  csv << "pulse_width_s,samples,modes_in_data,cost,method,start,elements,noise,parameter,cases,failed,mean_bias,"
         "std,rmse,median,success_rate,median_evaluations\n";
  md << "| ";
  if (several_experiments(spec)) md << "pulse (ms) | Nbar | modes | ";
  md << "cost | method | start | N | noise | success |";
  for (const auto& k : keys) md << " " << k << " bias ± sd |";
  md << " median evals |\n|";
  for (int i = 0; i < (several_experiments(spec) ? 3 : 0) + 7 + static_cast<int>(keys.size()); ++i) md << "---|";
  md << "\n";
  for (const auto& [k, members] : groups) {
    int successes = 0, failed = 0;
    std::vector<double> evals;
    for (const CaseRow* r : members) {
      successes += r->success ? 1 : 0;
      failed += r->failed() ? 1 : 0;
      evals.push_back(r->record.number("evaluations"));
    }
    const double rate = static_cast<double>(successes) / members.size();
    md << "| ";
    if (several_experiments(spec))
      md << g3(1e3 * k.pulse_width_s) << " | " << k.samples << " | " << members.front()->modes() << " | ";
    md << k.cost << " | " << k.method << " | " << k.start << " | " << k.elements << " | " << noise_label(k.noise)
       << " | " << successes << "/" << members.size() << " |";
    for (const auto& key : keys) {
      std::vector<double> e;
      for (const CaseRow* r : members) e.push_back(r->error(key));
      const Stats s = stats(e);
      csv << io::round_trip(k.pulse_width_s) << "," << k.samples << "," << members.front()->modes() << "," << k.cost
          << "," << k.method << "," << k.start << "," << k.elements << "," << io::round_trip(k.noise) << "," << key
          << "," << members.size() << "," << failed << "," << io::round_trip(s.mean) << "," << io::round_trip(s.std)
          << "," << io::round_trip(s.rmse) << "," << io::round_trip(s.median) << "," << io::round_trip(rate) << ","
          << io::round_trip(median(evals)) << "\n";
      md << " " << pct(s.mean) << (std::isfinite(s.std) ? " ± " + pct(s.std) : "") << " |";
    }
    md << " " << g3(median(evals)) << " |\n";
  }
  return {{"summary.csv", csv.str()}, {"summary.md", md.str()}};
}

// bias_<key>.csv
RenderedFiles render_bias(const StudyResults& results, const Groups& groups) {
  const StudySpec& spec = *results.spec;
  const auto& keys = spec.fit.estimate;
  RenderedFiles files;
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
        for (const CaseRow* r : members) e.push_back(r->error(key));
        const Stats s = stats(e);
        data[name][k.elements] = {s.rmse, s.std};
      }
      std::ostringstream os;
      os << "elements";
      for (const auto& name : order) os << "," << io::csv_quoted(name + " rmse") << "," << io::csv_quoted(name + " sd");
      os << "\n";
      for (int n : spec.sweep.elements) {
        os << n;
        for (const auto& name : order) {
          auto it = data[name].find(n);
          os << "," << (it == data[name].end() ? "nan" : io::round_trip(it->second.first)) << ","
             << (it == data[name].end() ? "nan" : io::round_trip(it->second.second));
        }
        os << "\n";
      }
      files.push_back({"bias_" + key + ".csv", os.str()});
    }
  }

  return files;
}

// galerkin_frequencies.csv, convergence.csv and convergence.md
RenderedFiles render_convergence(const StudyResults& results, const Groups& groups) {
  const StudySpec& spec = *results.spec;
  const auto& keys = spec.fit.estimate;
  RenderedFiles files;
  // The noise-free estimates against N beside the Galerkin frequency errors (the "frequencies" unit).
  const std::vector<double> exact =
      results.frequencies.empty() ? std::vector<double>{} : results.frequencies.begin()->second.numbers("exact_hz");
  std::map<int, std::vector<double>> galerkin_hz;
  std::ostringstream os;
  os << "elements,mode,galerkin_hz,exact_hz,relative_error\n";
  for (int n : spec.sweep.elements) {
    galerkin_hz[n] = results.frequencies.at(n).numbers("galerkin_hz");
    for (std::size_t m = 0; m < galerkin_hz[n].size(); ++m) {
      const double f = galerkin_hz[n][m];
      os << n << "," << m + 1 << "," << io::round_trip(f) << "," << io::round_trip(exact[m]) << ","
         << io::round_trip(f / exact[m] - 1) << "\n";
    }
  }
  files.push_back({"galerkin_frequencies.csv", os.str()});
  std::ostringstream csv, md;
  csv << "cost,method,start,elements,status";
  for (const auto& k : keys) csv << ",relative_error_" << k;
  csv << "\n";
  md << "| N |";
  for (std::size_t m = 0; m < exact.size(); ++m) md << " f" << m + 1 << " error |";
  std::vector<std::string> names;
  for (const auto& [k, members] : groups)
    if (k.noise == 0 && k.pulse_width_s == spec.sweep.pulse_width_s.front() &&
        k.samples == spec.sweep.samples.front()) {
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
        const CaseRow& r = *members.front();
        cell = r.failed() ? "failed" : "max " + pct(r.max_abs_error(keys));
        csv << k.cost << "," << k.method << "," << k.start << "," << n << "," << r.record.text("status");
        for (const auto& key : keys) csv << "," << io::round_trip(r.error(key));
        csv << "\n";
      }
      md << " " << cell << " |";
    }
    md << "\n";
  }
  files.push_back({"convergence.csv", csv.str()});
  files.push_back({"convergence.md", md.str()});
  return files;
}

// spread.csv and spread.md
RenderedFiles render_spread(const StudyResults& results, const Groups& groups) {
  const StudySpec& spec = *results.spec;
  const auto& keys = spec.fit.estimate;
  std::ostringstream csv, md;
  csv << "pulse_width_s,samples,cost,method,start,elements,noise,parameter,cases,monte_carlo_sd,median_standard_"
         "error,ratio\n";
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
      for (const CaseRow* r : members)
        if (!r->failed()) {
          est.push_back(r->record.number("estimate." + key));
          se.push_back(r->record.number("standard_error." + key));
        }
      const Stats s = stats(est);
      const double mse = median(se);
      csv << io::round_trip(k.pulse_width_s) << "," << k.samples << "," << k.cost << "," << k.method << "," << k.start
          << "," << k.elements << "," << io::round_trip(k.noise) << "," << key << "," << s.count << ","
          << io::round_trip(s.std) << "," << io::round_trip(mse) << "," << io::round_trip(s.std / mse) << "\n";
      md << " " << g3(s.std) << " / " << g3(mse) << " = " << g3(s.std / mse) << " |";
    }
    md << "\n";
  }
  return {{"spread.csv", csv.str()}, {"spread.md", md.str()}};
}

RenderedFiles render_efficiency(const std::vector<EfficiencyRow>& rows) {
  if (rows.empty()) return {};
  std::ostringstream csv, md;
  csv << "pulse_width_s,samples,cost,method,start,elements,noise,parameter,fits,stayed,bias,bias_mcse,"
         "bias_significant,sd,rmse,crb_relative_sd,rmse_over_crb,sd_over_crb,modes_in_data\n";
  // With several experiments (pulse widths or record lengths), each row opens with its modes in the data.
  bool several = false;
  for (const EfficiencyRow& r : rows)
    several =
        several || r.key.pulse_width_s != rows.front().key.pulse_width_s || r.key.samples != rows.front().key.samples;
  md << (several ? "| modes in data " : "")
     << "| cost | method | N | noise | parameter | stayed at the minimum | bias ± MCSE | RMSE | bound | RMSE / bound "
        "|\n"
     << (several ? "|---" : "") << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const EfficiencyRow& r : rows) {
    const GroupKey& k = r.key;
    csv << io::round_trip(k.pulse_width_s) << "," << k.samples << "," << k.cost << "," << k.method << "," << k.start
        << "," << k.elements << "," << io::round_trip(k.noise) << "," << r.parameter << "," << r.fits << "," << r.stayed
        << "," << io::round_trip(r.errors.mean) << "," << io::round_trip(r.mcse) << ","
        << (r.significant_bias() ? 1 : 0) << "," << io::round_trip(r.errors.std) << "," << io::round_trip(r.errors.rmse)
        << "," << io::round_trip(r.bound) << "," << io::round_trip(r.efficiency()) << ","
        << io::round_trip(r.errors.std / r.bound) << "," << r.modes << "\n";
    if (several) md << "| " << r.modes << " ";
    md << "| " << k.cost << " | " << k.method << " | " << k.elements << " | " << noise_label(k.noise) << " | "
       << r.parameter << " | " << count_with_interval(r.stayed, r.fits) << " | " << g3(r.errors.mean) << " ± "
       << g3(r.mcse) << (r.significant_bias() ? " (significant)" : "") << " | " << g3(r.errors.rmse) << " | "
       << g3(r.bound) << " | " << g3(r.efficiency()) << " |\n";
  }
  return {{"efficiency.csv", csv.str()}, {"efficiency.md", md.str()}};
}

RenderedFiles render_bias_decomposition(const std::vector<BiasRow>& rows, bool control) {
  if (rows.empty()) return {};
  std::ostringstream csv, md;
  csv << "pulse_width_s,samples,cost,method,start,elements,noise,parameter,fits,stayed,noise_free_bias,mean_bias,"
         "mean_bias_mcse,mean_bias_significant,noise_induced_bias,noise_induced_significant,sd\n";
  const std::string minimum =
      control ? "estimator's own bias (noise-free, N = N_truth)" : "bias of the minimum (noise-free)";
  md << "| cost | method | N | noise | parameter | stayed at the minimum | " << minimum
     << " | mean bias ± MCSE | noise-induced bias ± MCSE |\n|---|---|---|---|---|---|---|---|---|\n";
  const auto flag = [](bool significant) { return significant ? std::string(" (significant)") : std::string(); };
  for (const BiasRow& r : rows) {
    const GroupKey& k = r.key;
    csv << io::round_trip(k.pulse_width_s) << "," << k.samples << "," << k.cost << "," << k.method << "," << k.start
        << "," << k.elements << "," << io::round_trip(k.noise) << "," << r.parameter << "," << r.fits << "," << r.stayed
        << "," << io::round_trip(r.noise_free) << "," << io::round_trip(r.errors.mean) << "," << io::round_trip(r.mcse)
        << "," << (r.significant_total() ? 1 : 0) << "," << io::round_trip(r.noise_induced()) << ","
        << (r.significant_noise_induced() ? 1 : 0) << "," << io::round_trip(r.errors.std) << "\n";
    md << "| " << k.cost << " | " << k.method << " | " << k.elements << " | " << noise_label(k.noise) << " | "
       << r.parameter << " | " << count_with_interval(r.stayed, r.fits) << " | " << g3(r.noise_free) << " | "
       << g3(r.errors.mean) << " ± " << g3(r.mcse) << flag(r.significant_total()) << " | " << g3(r.noise_induced())
       << " ± " << g3(r.mcse) << flag(r.significant_noise_induced()) << " |\n";
  }
  return {{"bias_decomposition.csv", csv.str()}, {"bias_decomposition.md", md.str()}};
}

// modes.csv
RenderedFiles render_modes(const StudyResults& results) {
  const auto mode_cells_ = mode_cells(results);
  std::ostringstream csv;
  csv << "modes_in_data,pulse_width_s,samples,cost,method,cases,successes,success_rate,median_max_abs_error\n";
  for (const auto& [key, cell] : mode_cells_)
    csv << std::get<0>(key) << "," << io::round_trip(std::get<1>(key)) << "," << std::get<2>(key) << ","
        << std::get<3>(key) << "," << std::get<4>(key) << "," << cell.cases << "," << cell.successes << ","
        << io::round_trip(static_cast<double>(cell.successes) / cell.cases) << ","
        << io::round_trip(median(cell.errors)) << "\n";
  return {{"modes.csv", csv.str()}};
}

}  // namespace beamid::study
