#include "study/tables/report_block.h"

#include <algorithm>
#include <sstream>

#include "io/provenance.h"
#include "io/text.h"
#include "simulation/experiment.h"
#include "study/tables/format.h"

namespace beamid::study {
namespace {

bool has(const RenderedFiles& files, const std::string& path) {
  for (const auto& f : files)
    if (f.path == path) return true;
  return false;
}
std::string read(const RenderedFiles& files, const std::string& path) {
  for (const auto& f : files)
    if (f.path == path) return f.text;
  return "";
}

// The plots plots/make_plots.sh makes from these tables (names fixed there): (file stem, what it shows).
std::vector<std::pair<std::string, std::string>> plot_links(const StudySpec& spec, const RenderedFiles& tables) {
  const auto& keys = spec.fit.estimate;
  std::vector<std::pair<std::string, std::string>> images;
  if (spec.landscape.enabled) {
    images.emplace_back("landscape_slices", "cost slices through the truth, normalised to [0, 1]");
    for (const auto& [a, b] : spec.landscape.pairs)
      images.emplace_back("landscape_grid_" + a + "_" + b, "cost surfaces over (" + a + ", " + b + ")");
    if (spec.landscape.zoom_range_factor > 1)
      for (int n : spec.landscape.elements)
        for (double noise : spec.landscape.noise)
          for (const auto& [a, b] : spec.landscape.pairs)
            images.emplace_back(
                "landscape_zoom_N" + std::to_string(n) + "-noise" + io::round_trip(noise) + "_" + a + "_" + b,
                "fine cost surfaces over (" + a + ", " + b + ") at N = " + std::to_string(n) + ", noise " + pct(noise));
  }
  if (spec.start_distance.enabled)
    images.emplace_back("start_distance",
                        "share of starts that reach the minimum against the start's frequency offset");
  if (spec.sweep.pulse_width_s.size() > 1 || spec.sweep.samples.size() > 1)
    images.emplace_back("success_vs_modes", "success rate against the modes in the data");
  if (spec.sweep.elements.size() > 1)
    for (const auto& k : keys) images.emplace_back("bias_" + k, "RMSE of the relative error in " + k + " against N");
  if (has(tables, "spectrum.csv")) {
    images.emplace_back("spectrum", "data spectrum with the detected spikes and their 20 % supports");
    images.emplace_back("overlay",
                        "fits at N = " + std::to_string(spec.outputs.overlay_elements) + " in time and in frequency");
  }
  return images;
}

// The start-distance paragraphs: the curves, and with several records the fits from the truth.
void report_start_distance(const StudySpec& spec, const RenderedFiles& tables, std::ostringstream& report) {
  const auto& d = spec.start_distance;
  report << "Start-distance curves at N = " << d.elements << " (noise " << pct(d.noise) << "; " << d.directions
         << " random directions per offset in the log space of the estimated parameters; a start \"reaches\" when "
            "every estimate is within "
         << pct(d.agreement) << " (damping " << pct(d.damping_agreement) << ") of the same run's fit from the truth"
         << (d.records > 1 ? " on the same record; " + std::to_string(d.records) + " independent noise records" : "")
         << "). Columns: the share of starts that reach it at each frequency offset of the fitted modes; "
         << (d.records > 1 ? "the 50 % radius of a logistic reach curve in log offset (Firth's fit), with a 95 % "
                             "bootstrap interval across records, "
                           : "the offset where that share falls through one half, with the interval from the 95 % "
                             "Wilson bounds, ")
         << "and its ratio to the predicted 1/(2 f T):\n\n"
         << read(tables, "start_distance.md") << "\n";
  if (has(tables, "start_distance_reference.md"))
    report << "The fits from the truth, one per record (every fit counted: none is set aside for where it "
              "ended): bias of the relative error with its Monte-Carlo standard error (* beyond 2 MCSE), and RMSE "
              "over the Cramér-Rao bound of the fitted model for the records' noise (under model error the bound "
              "is the fitted model's, so RMSE / bound above 1 includes the bias the model error causes); the last "
              "column counts the run's fits (from the truth and every offset) that ran out of their evaluation "
              "budget:\n\n"
           << read(tables, "start_distance_reference.md") << "\n";
  if (has(tables, "start_distance_modes.md"))
    report << "The same fits judged per mode of the data: the fitted model's natural frequency f_k and damping ratio "
              "zeta_k against the truth beam's own (before the sensor), bias of the relative error with its "
              "Monte-Carlo standard error (* beyond 2 MCSE). Under a damping law the model lacks, cDI and gamma have "
              "no true value, but every mode's damping ratio has:\n\n"
           << read(tables, "start_distance_modes.md") << "\n";
}

}  // namespace

std::string render_report_block(const StudyResults& results, const Findings& findings, const RenderedFiles& tables) {
  const StudySpec& spec = *results.spec;
  const auto& keys = spec.fit.estimate;
  std::ostringstream report;
  report << "*Study `" << spec.name << "` (`" << spec.path << "`), " << results.cases.size() << " fits";
  if (!results.landscape.empty()) report << " and " << results.landscape.size() << " landscape units";
  report << ", seed " << spec.seed << ", commit " << io::commit_label() << "; truth: `" << spec.truth.beam
         << "` by the exact modal closed form at N = " << spec.truth.elements;
  if (spec.truth.control)
    report
        << " (a control: the fits use the truth's own model, so no discretisation error separates them from the data)";
  if (spec.truth.modal_damping_ratio > 0)
    report << ", with constant modal damping of ratio " << g3(spec.truth.modal_damping_ratio)
           << " added to every mode (a damping law the fitted model lacks)";
  if (spec.truth.sensor.cutoff_hz > 0)
    report << ", measured through an order-" << spec.truth.sensor.order << " Butterworth anti-alias filter of cut-off "
           << g3(spec.truth.sensor.cutoff_hz) << " Hz ("
           << (std::any_of(spec.methods.begin(), spec.methods.end(),
                           [](const MethodSpec& m) { return m.sensor_in_model; })
                   ? "in the fitted model only for the methods with sensor_in_model"
                   : "a sensor the fitted model lacks")
           << ")";
  if (spec.truth.experiment.excitation == simulation::kSampledForce)
    report << ", driven by its force channel's samples"
           << (spec.truth.force_noise > 0 ? " (white noise of " + pct(spec.truth.force_noise) +
                                                " of the force's RMS on the channel of every "
                                                "noisy record, which drives the fits)"
                                          : std::string());
  if (!results.truths.empty() && results.truths.front().has("cvode_max_difference_over_max_y")) {
    const Record& first = results.truths.front();
    report << " (CVODE at rtol " << g3(spec.truth.rtol) << " agrees to "
           << g3(first.number("cvode_max_difference_over_max_y")) << " of max |y|";
    if (first.text("cvode_status") != "ok") report << "; " << first.text("cvode_status");
    report << ")";
  }
  report << "; success = every one of ";
  for (std::size_t i = 0; i < keys.size(); ++i) report << (i ? ", " : "") << keys[i];
  report << " within " << pct(spec.fit.success_tolerance) << " of the truth";
  if (spec.fit.damping_tolerance != spec.fit.success_tolerance)
    report << " (damping parameters within " << pct(spec.fit.damping_tolerance) << ")";
  report << ".*\n\n";
  if (!findings.counts.empty()) {
    report << "Counts:\n\n";
    for (const auto& c : findings.counts) report << "- " << c.text << "\n";
    report << "\n";
  }
  report << "Computed claims:\n\n";
  for (const auto& c : findings.claims) report << "- `[" << (c.holds ? "true" : "false") << "]` " << c.text << "\n";
  report << "\n";
  if (!results.cases.empty()) {
    report << "Summary (relative bias ± standard deviation over replicates; `summary.csv` has RMSE and medians):\n\n"
           << read(tables, "summary.md") << "\n";
    if (spec.sweep.noise.front() == 0 && spec.sweep.elements.size() > 1)
      report << "Noise-free estimates against N (largest relative error over the estimated parameters) beside the "
                "Galerkin error of the first frequencies:\n\n"
             << read(tables, "convergence.md") << "\n";
    if (spec.sweep.replicates >= 3)
      report << "Monte-Carlo spread of the estimates against the median standard error the fits report (1 = the "
                "formal errors are right; they assume independent Gaussian residuals):\n\n"
             << read(tables, "spread.md") << "\n";
  }
  if (has(tables, "efficiency.md"))
    report << "Efficiency: the fits that stayed at the minimum (every estimate within the success tolerances; the "
              "others are counted apart), their bias with its Monte-Carlo standard error (\"significant\" beyond 2 "
              "MCSE), RMSE, and the Cramér-Rao bound of the fitted model for the same noise (relative sd; RMSE / "
              "bound = 1 is the best any unbiased estimator can do):\n\n"
           << read(tables, "efficiency.md") << "\n";
  if (spec.landscape.enabled)
    report << "Landscape smoothness at N = " << spec.landscape.elements.front() << ", noise "
           << pct(spec.landscape.noise.front()) << ":\n\n"
           << read(tables, "smoothness.md") << "\n";
  if (has(tables, "landscape_across.md"))
    report << "Across N and noise (the noisy records are the sweep's first draw at each level): each slice's basin "
              "around its minimum and its local minima, and each fine grid's local minima and the share of its "
              "points from which steepest descent on the grid reaches the minimum:\n\n"
           << read(tables, "landscape_across.md") << "\n";
  if (has(tables, "landscape/multistart.md"))
    report << "Each local fit's final cost minus the reference minimum (the lowest over the cost's fits; \"reached\": "
              "every estimate within the success tolerance of the reference's):\n\n"
           << read(tables, "landscape/multistart.md") << "\n";
  if (has(tables, "start_distance.md")) report_start_distance(spec, tables, report);
  // Plot links, SVG beside each PNG.
  const std::string p = "plots/" + spec.name + "/";
  const std::vector<std::pair<std::string, std::string>> images = plot_links(spec, tables);
  report << "Plots (PNG; SVG beside each):\n\n";
  for (const auto& [name, what] : images) report << "- [" << what << "](" << p << name << ".png)\n";
  return report.str();
}

}  // namespace beamid::study
