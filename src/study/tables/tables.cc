#include "study/tables/tables.h"

#include <filesystem>
#include <set>
#include <sstream>

#include "io/files.h"
#include "io/text.h"
#include "study/analysis/claims.h"
#include "study/analysis/metrics.h"
#include "study/tables/case_tables.h"
#include "study/tables/landscape_tables.h"
#include "study/tables/manifest.h"
#include "study/tables/overlay.h"
#include "study/tables/report_block.h"
#include "study/tables/start_distance_tables.h"

namespace beamid::study {
namespace {

void append(RenderedFiles& to, RenderedFiles from) {
  for (auto& f : from) to.push_back(std::move(f));
}

Manifest study_manifest(const StudyResults& results) {
  const StudySpec& spec = *results.spec;
  const Plan& plan = *results.plan;
  Manifest m{spec.name, spec.question, spec.path, spec.file_hash, {}, {}};
  m.before = {{"seed", std::to_string(spec.seed)}};
  std::string records;
  for (std::size_t i = 0; i < plan.truths.size(); ++i) {
    const Record& t = results.truths[i];
    std::string check;
    if (t.has("cvode_status")) {
      check = ", \"cvode_check\": {\"rtol\": " + io::round_trip(spec.truth.rtol) +
              ", \"status\": " + io::json_string(t.text("cvode_status")) + ", \"steps\": " + t.text("cvode_steps");
      if (t.has("cvode_max_difference_over_max_y"))
        check += ", \"max_abs_difference_over_max_abs_y\": " + t.text("cvode_max_difference_over_max_y");
      check += "}";
    }
    records += std::string(i ? ", " : "") + "{\"id\": \"" + plan.truths[i].id +
               "\", \"pulse_width_s\": " + io::round_trip(plan.truths[i].pulse_width_s) +
               ", \"status\": " + io::json_string(t.text("status")) + check + "}";
  }
  m.after = {
      {"truth", "{\"beam\": " + io::json_string(spec.truth.beam) +
                    ", \"elements\": " + std::to_string(spec.truth.elements) +
                    ", \"integrator\": \"fast (exact modal closed form)\"" + ", \"records\": [" + records + "]}"},
      {"noise", io::json_string("z = y + level rms(y) g, g standard normal by Box-Muller over "
                                "std::mt19937_64 (signal/noise.h)")},
      {"cases", std::to_string(results.cases.size())},
      {"landscape_units", std::to_string(results.landscape.size())}};
  if (!results.starts.empty()) m.after.emplace_back("start_distance_fits", std::to_string(results.starts.size()));
  return m;
}

}  // namespace

RenderedFiles render_tables(const StudyResults& results) {
  const StudySpec& spec = *results.spec;
  RenderedFiles files;
  files.push_back({"manifest.json", manifest_json(study_manifest(results))});
  files.push_back({"provenance.csv", provenance_csv(spec.name, static_cast<int>(results.cases.size()))});
  const Groups groups = group_cases(results.cases);
  append(files, render_cases(results));
  append(files, render_summary(results, groups));
  append(files, render_bias(results, groups));
  append(files, render_convergence(results, groups));
  append(files, render_spread(results, groups));
  const std::vector<EfficiencyRow> efficiency = efficiency_rows(results, groups);
  append(files, render_efficiency(efficiency));
  append(files, render_bias_decomposition(bias_rows(results, groups), spec.truth.control));
  append(files, render_modes(results));
  const LandscapeMetrics landscape = landscape_metrics(results);
  append(files, render_landscape(results, landscape));
  const StartDistanceMetrics start_distance = start_distance_metrics(results);
  append(files, render_start_distance(results, start_distance));
  std::vector<std::pair<std::string, Overlay>> overlays;
  for (const auto& cost : spec.sweep.cost)
    for (const CaseRow& r : results.cases)
      if (r.unit->overlay && r.unit->cost == cost) {
        if (auto o = stored_overlay(r.record)) overlays.emplace_back(cost, std::move(*o));
        break;
      }
  append(files, render_overlay_files(overlays));
  const Findings findings = study_findings(results, groups, landscape, start_distance);
  files.push_back({"report.md", render_report_block(results, findings, files)});
  return files;
}

void write_tables(const StudySpec& spec, const Plan& plan, const Store& store, const std::string& output_dir,
                  std::ostream& log) {
  namespace fs = std::filesystem;
  const StudyResults results = load_results(spec, plan, store);
  const RenderedFiles files = render_tables(results);
  for (const Rendered& f : files) io::write_file_atomic(fs::path(output_dir) / f.path, f.text);
  // The tables an earlier run wrote that this one does not (a section removed from the study file) are removed, so
  // that the folder holds this run's tables only; the list of what was written is kept beside the store, with a check
  // line over its content as a record has. Only relative paths inside the folder and outside the store are ever
  // removed, and only from a list whose check holds: a line added to the list deleted a store record and a user's
  // file (the eleventh pass's TT3).
  const fs::path list = fs::path(store.directory()) / "tables.txt";
  std::set<std::string> now;
  for (const Rendered& f : files) now.insert(f.path);
  if (io::is_existing_file(list)) {
    std::string why;
    const std::optional<std::string> body =
        checked_body(io::read_file(list, "cannot read the list of written tables"), why);
    if (!body) {
      log << "beamid study: " << list.string() << ": fails its check (" << why
          << "; edited, or from an older beamid): no earlier table is removed\n";
    } else {
      std::istringstream earlier(*body);
      for (std::string path; std::getline(earlier, path);) {
        std::error_code ec;
        const bool in_store = fs::path(path).begin() != fs::path(path).end() && *fs::path(path).begin() == "store";
        if (io::stays_inside(path) && !in_store && !now.count(path) &&
            fs::is_regular_file(fs::path(output_dir) / path, ec))
          fs::remove(fs::path(output_dir) / path, ec);
      }
    }
  }
  std::string text;
  for (const std::string& path : now) text += path + "\n";
  io::write_file_atomic(list, with_check_line(text));
}

}  // namespace beamid::study
