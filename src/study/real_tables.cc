// The rendering half of a real-data study (real_study.h): fits.csv, modes.csv, timings.csv, the overlay files, the
// manifest and the report block, from its results alone.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "io/provenance.h"
#include "io/text.h"
#include "study/format.h"
#include "study/manifest.h"
#include "study/real_study.h"

namespace beamid::study {

RenderedFiles render_real_study(const RealStudySpec& spec, const RealResults& results) {
  const io::TimeSeries& record = results.record;
  const model::BeamParameters& nominal = results.nominal;
  const std::vector<double>& measured = results.measured_hz;
  const std::vector<double>& measured_zeta = results.measured_zeta;
  std::ostringstream fits, modes, timings, md;
  fits << "cost,status,cost_value,evaluations,parameter,estimate,standard_error,nominal,ratio_to_nominal,"
          "parameter_status\n";
  modes << "cost,mode,measured_frequency_hz,identified_frequency_hz,identified_damping_ratio\n";
  timings << "cost,wall_time_s\n";
  std::vector<std::pair<std::string, Overlay>> overlays;
  for (const RealFit& f : results.fits) {
    timings << f.cost << "," << io::round_trip(f.wall_time_s) << "\n";
    if (f.status.rfind("failed", 0) == 0) {
      fits << f.cost << "," << io::json_string(f.status) << ",inf,0,,,,,,\n";
      continue;
    }
    for (const auto& p : f.parameters) {
      const double v = model::parameter_value(nominal, p.key);
      fits << f.cost << "," << f.status << "," << io::round_trip(f.cost_value) << "," << f.evaluations << "," << p.key
           << "," << io::round_trip(p.estimate) << "," << io::round_trip(p.standard_error) << "," << io::round_trip(v)
           << "," << io::round_trip(p.estimate / v) << "," << p.status << "\n";
    }
    for (std::size_t m = 0; m < measured.size(); ++m)
      modes << f.cost << "," << m + 1 << "," << io::round_trip(measured[m]) << "," << io::round_trip(f.identified_hz[m])
            << "," << io::round_trip(f.zeta[m]) << "\n";
    if (f.overlay) overlays.emplace_back(f.cost, *f.overlay);
  }
  // report.md: the generated block.
  md << "*Study `" << spec.name << "` (`" << spec.path << "`), commit " << io::commit_label() << ": "
     << record.values.size() << " samples at " << g4(1 / record.dt_s) << " Hz of `" << record.value_column << "` ("
     << record.notes.substr(0, record.notes.size() >= 2 ? record.notes.size() - 2 : 0)
     << "), free decay with unknown initial state (mode amplitudes solved in closed form), "
     << "Galerkin N = " << spec.elements << "; estimated ";
  for (std::size_t i = 0; i < spec.estimate.size(); ++i) md << (i ? ", " : "") << spec.estimate[i];
  md << "; the other parameters at their nominal values (`" << std::filesystem::path(spec.beam_file).filename().string()
     << "`).*\n\n";
  md << "Computed claims:\n\n";
  for (const RealFit& o : results.fits) {
    if (o.identified_hz.empty()) {
      md << "- `[false]` " << o.cost << " fits the record (" << o.status << ")\n";
      continue;
    }
    int within = 0;
    double worst = 0;
    for (std::size_t m = 0; m < measured.size(); ++m) {
      const double e = std::abs(o.identified_hz[m] / measured[m] - 1);
      worst = std::max(worst, e);
      within += e <= 0.015 ? 1 : 0;
    }
    md << "- `[" << (within == static_cast<int>(measured.size()) ? "true" : "false") << "]` " << o.cost
       << ": every identified frequency within 1.5 % of its measured peak (" << within << "/" << measured.size()
       << "; worst " << g4(100 * worst) << " %)\n";
  }
  md << "\n| cost | status |";
  for (const auto& k : spec.estimate) md << " " << k << " (x nominal) |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < spec.estimate.size(); ++i) md << "---|";
  md << "\n";
  for (const RealFit& o : results.fits) {
    md << "| " << o.cost << " | " << o.status << " |";
    for (std::size_t i = 0; i < spec.estimate.size(); ++i) {
      if (i >= o.parameters.size()) {
        md << " - |";
        continue;
      }
      const double v = model::parameter_value(nominal, spec.estimate[i]);
      md << " " << g4(o.parameters[i].estimate) << " (" << g4(o.parameters[i].estimate / v) << ") |";
    }
    md << "\n";
  }
  md << "\n| mode | measured f (Hz) | measured zeta |";
  for (const RealFit& o : results.fits) md << " " << o.cost << " f (Hz) | " << o.cost << " zeta |";
  md << "\n|---|---|---|";
  for (std::size_t i = 0; i < results.fits.size(); ++i) md << "---|---|";
  md << "\n";
  for (std::size_t m = 0; m < measured.size(); ++m) {
    md << "| " << m + 1 << " | " << g4(measured[m]) << " | " << g4(measured_zeta[m]) << " |";
    for (const RealFit& o : results.fits)
      md << " " << (m < o.identified_hz.size() ? g4(o.identified_hz[m]) : "-") << " | "
         << (m < o.zeta.size() ? g4(o.zeta[m]) : "-") << " |";
    md << "\n";
  }
  md << "\nPlots: [residuals in time and frequency](plots/" << spec.name << "/overlay.png), [the record's spectrum "
     << "with the chosen spikes](plots/" << spec.name << "/spectrum.png).\n";

  Manifest manifest{spec.name, spec.question, spec.path, spec.file_hash, {}, {}};
  manifest.before = {{"record", io::json_string(spec.record_file)}, {"record_notes", io::json_string(record.notes)}};
  RenderedFiles files = {{"manifest.json", manifest_json(manifest)},
                         {"provenance.csv", provenance_csv(spec.name, static_cast<int>(spec.costs.size()))},
                         {"fits.csv", fits.str()},
                         {"modes.csv", modes.str()},
                         {"timings.csv", timings.str()},
                         {"report.md", md.str()}};
  for (auto& f : render_overlay_files(overlays)) files.push_back(std::move(f));
  return files;
}

}  // namespace beamid::study
