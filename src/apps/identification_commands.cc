// beamid spikes, cost and fit: the identification commands (see commands.h for their forms).
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/fit_report.h"
#include "apps/flag_requests.h"
#include "apps/flags.h"
#include "config/beam_file.h"
#include "core/errors.h"
#include "core/limits.h"
#include "costs/cost.h"
#include "fit/identification.h"
#include "fit/window_spread.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/text.h"
#include "io/time_series.h"
#include "signal/spikes.h"

namespace beamid::apps {

std::vector<FlagSpec> spike_flags() {
  return {
      integer_flag("spikes", "number of spikes NM (default 4)", 1, core::kMaxSpikes),
      text_flag("window", "rectangular | hann | exponential (default rectangular)"),
      number_flag("exponential-end", "exponential window's last weight, in [1e-6, 1) (default 0.01)"),
      text_flag("spike-rule", "largest | prominence (default largest: the NM highest local maxima)"),
      number_flag("min-frequency", "lowest spike frequency considered (freq-band: the band's low end), Hz (default 0)"),
      number_flag("max-frequency",
                  "highest spike frequency considered (freq-band: the band's high end), Hz (default Nyquist)"),
      text_flag("spike-frequencies",
                "choose the spikes: F1,F2,... Hz, the largest peak within +-5 % of each "
                "(pairs model and data by frequency)"),
      text_flag("artefacts",
                "reject | keep: skip peaks at harmonics or sidebands of stronger ones and the offset's leakage, "
                "listed with the reason (default reject: a record read from a file is a measured one)"),
      integer_flag("welch",
                   "pick the spikes on Welch's average of K half-overlapping Hann segments (default: the "
                   "whole record's DFT)",
                   2, 1000)};
}

// Reading the --data record: CSV, LabVIEW .lvm, text table (.txt, .dat), .npy, .mat or UFF 58, a channel, units, a time
// window, a rate (io/time_series.h).
std::vector<FlagSpec> import_flags() {
  return {text_flag("channel", "signal column by name or 1-based index (default: the only one)"),
          text_flag("units",
                    "auto | g | as-is (default auto: records in g, mm, mm/s or mm/s^2 are converted to SI; as-is: the "
                    "values as SI, for a record that states no unit or one beamid does not convert)"),
          number_flag("start", "keep samples from this time, s (default: the first)"),
          number_flag("duration", "keep this many seconds from --start (default: to the end)"),
          switch_flag("resample", "interpolate a non-uniform time base onto a uniform one instead of refusing it"),
          number_flag("sample-rate", "the sampling rate of a record without a time base (.npy, .mat), Hz"),
          text_flag("variable", ".mat: the record's variable, a dotted path into structs (default: the only one)"),
          text_flag("time-variable", ".mat: a time vector of the record's length, instead of --sample-rate"),
          integer_flag("time-channel",
                       ".npy, .mat: the channel (1-based, as --channel counts) that holds the time in s, instead of "
                       "--sample-rate",
                       1, 1 << 20),
          number_flag("resample-rate",
                      "resample the record onto this rate, Hz (windowed sinc; a low-pass first when it falls)")};
}

std::vector<FlagSpec> cost_flags(bool required) {
  auto flags = spike_flags();
  flags.push_back(text_flag("cost", costs::cost_names().alternatives(), required));
  flags.push_back(number_flag("eps1", "weight of squared frequency errors, 1/Hz^2 (default 1/df^2)"));
  flags.push_back(number_flag("eps2", "weight of squared magnitude errors (default 1 / sum of |Z|^2 on the supports)"));
  flags.push_back(number_flag("eps3", "spike-smooth: weight of squared decay-rate errors, s^2 (default (T/2pi)^2)"));
  flags.push_back(switch_flag("unknown-amplitude",
                              "excitation amplitude unknown: solved in closed form (time, freq-band), scale-free "
                              "magnitudes (spike costs)"));
  flags.push_back(
      text_flag("model-poles", "spike-smooth: " + costs::model_pole_names().alternatives() + " (default dft)"));
  flags.push_back(
      text_flag("mode-weight", "modal: " + costs::mode_weight_names().alternatives() +
                                   " (default relative; measured: maximum likelihood for a measured record's modes)"));
  flags.push_back(
      text_flag("frequency-weight", "spike costs: " + costs::frequency_weight_names().alternatives() +
                                        " (default relative: a record read from a file is a measured one)"));
  flags.push_back(text_flag("noise-model",
                            "time, freq-ml: the noise assumed, white | ar:a1,... | power:alpha (time: least squares "
                            "on the prewhitened record; freq-ml: each bin over its variance; default white); fit: "
                            "estimated, from the residuals of a white fit first (time an AR model, freq-ml each "
                            "bin's variance), or repeated, from several --channel's that repeat one test (at one "
                            "--sensor-x), by their deviations from their mean"));
  flags.push_back(number_flag("force-noise-sd",
                              "freq-ml with fit --force-channel: the force channel's white noise sd, N: the "
                              "errors-in-variables form, each bin over its response noise plus |G|^2 its force noise"));
  flags.push_back(number_flag("noise-sd",
                              "with --force-noise-sd: the response's noise sd (its process sd, --noise-model's "
                              "colour), in the record's units"));
  return flags;
}

int run_spikes(const Flags& a, std::ostream& out) {
  const io::TimeSeries data = read_data(a);  // the record first, then the flags' request (their errors in that order)
  const api::SpikesResult r = api::compute_spikes(spikes_request_of(a), data);
  const auto& picks = r.picks;
  const auto& peaks = r.peaks;
  if (static_cast<int>(picks.size()) < r.requested)
    std::cerr << "beamid spikes: --spikes " << r.requested << ": the record shows only " << picks.size()
              << " spike(s) (local maxima of |Z| in the band, artefacts skipped): " << picks.size() << " printed\n";
  // The picks in order of frequency, then the peaks passed over on the way, with the reason.
  // The bin's frequency, then the sub-bin (three-bin) estimate of the peak's frequency and decay rate, then the
  // measured frequency and its uncertainty as modal-id, fit and real report them (picks only).
  out << "spike,bin,frequency_hz,magnitude,n_left,n_right,skipped,subbin_frequency_hz,decay_rate_1_s,"
         "measured_frequency_hz,measured_uncertainty_hz\n";
  const double nan = std::nan("");
  const auto row = [&](const std::string& label, const signal::Spike& p, const std::string& skipped,
                       const signal::MeasuredMode* measured) {
    const signal::PoleEstimate e = r.subbin(p.bin);
    out << label << "," << p.bin << "," << io::full_precision(p.frequency_hz) << "," << io::full_precision(p.magnitude)
        << "," << p.n_left << "," << p.n_right << "," << skipped << "," << io::full_precision(e.frequency_hz) << ","
        << io::full_precision(e.decay_rate_1_s) << ","
        << io::full_precision(measured ? measured->mode.frequency_hz : nan) << ","
        << io::full_precision(measured ? measured->uncertainty_hz : nan) << "\n";
  };
  for (std::size_t l = 0; l < picks.size(); ++l) row(std::to_string(l + 1), picks[l], "", &r.measured[l]);
  for (const auto& p : peaks)
    if (!p.skipped.empty()) row("", p.spike, "\"" + p.skipped + "\"", nullptr);
  if (!r.measured_note.empty()) std::cerr << "beamid spikes: " << r.measured_note << "\n";
  for (const std::string& note : r.notes) std::cerr << "beamid spikes: " << note << "\n";
  if (a.has("welch"))
    std::cerr << "beamid spikes: picked on Welch's average of " << a.integer("welch") << " segments of "
              << r.spectrum.samples << " samples (df = " << r.spectrum.df_hz() << " Hz; bins are of that spectrum)\n";
  return 0;
}

int run_cost(const Flags& a, std::ostream& out) {
  // The record and the prediction first, then the flags' request (their errors in that order, as before).
  const io::TimeSeries data = read_data(a);
  const io::TimeSeries prediction = read_prediction(a, data);
  const costs::Evaluation e = api::compute_cost(cost_evaluation_request_of(a), data, prediction);
  out << "cost,value\n" << a.text("cost") << "," << io::full_precision(e.value) << "\n";
  if (e.a4 != "ok") std::cerr << "beamid cost: " << e.a4 << "\n";
  return 0;
}

int run_fit(const Flags& a, std::ostream& out) {
  check_report_outputs(a);
  const std::vector<io::TimeSeries> channels = read_channels(a);
  const io::TimeSeries& data = channels.front();
  const std::string beam_name = a.text("beam");
  const api::FitComputation c = api::compute_fit(fit_request_of(a, read_force_channel(a)), channels, std::cerr);
  const fit::FitOptions& o = c.options;
  const fit::FitResult& result = c.result;
  const std::vector<double>& sensors = c.sensors_m;
  const std::optional<fit::WindowSpread>& spread = c.spread;
  if (c.welch_picked) {
    std::cerr << "beamid fit: spikes picked on Welch's average (" << a.integer("welch") << " segments):";
    for (double f : o.cost.spikes.frequencies_hz) std::cerr << " " << f;
    std::cerr << " Hz\n";
  }
  out << "parameter,estimate,standard_error,start,lower,upper,status,robust_standard_error,window_sd,"
         "window_standard_error\n";
  for (std::size_t i = 0; i < result.parameters.size(); ++i) {
    const fit::ParameterEstimate& p = result.parameters[i];
    out << p.key << "," << io::full_precision(p.estimate) << "," << io::full_precision(p.standard_error) << ","
        << io::full_precision(p.start) << "," << io::full_precision(p.lower) << "," << io::full_precision(p.upper)
        << "," << p.status << "," << io::full_precision(p.robust_standard_error) << ","
        << io::full_precision(spread ? spread->sd[i] : std::nan("")) << ","
        << io::full_precision(spread ? spread->standard_error[i] : std::nan("")) << "\n";
  }
  const api::FitNotes notes = api::fit_notes(result, o.cost);
  if (!notes.budget.empty()) std::cerr << "beamid fit: " << notes.budget << "\n";
  if (!notes.rough.empty()) std::cerr << "beamid fit: " << notes.rough << "\n";
  if (!notes.other_minimum.empty()) std::cerr << "beamid fit: " << notes.other_minimum << "\n";
  if (!notes.few_degrees.empty()) std::cerr << "beamid fit: " << notes.few_degrees << "\n";
  if (!notes.weighting.empty()) std::cerr << "beamid fit: " << notes.weighting << "\n";
  if (!notes.transient.empty()) std::cerr << "beamid fit: " << notes.transient << "\n";
  if (!notes.on_bound.empty()) std::cerr << "beamid fit: " << notes.on_bound << "\n";
  if (!notes.explains_nothing.empty()) std::cerr << "beamid fit: " << notes.explains_nothing << "\n";
  if (!notes.no_errors.empty()) std::cerr << "beamid fit: " << notes.no_errors << "\n";
  if (!notes.no_sandwich.empty()) std::cerr << "beamid fit: " << notes.no_sandwich << "\n";
  if (!notes.correlated_bins.empty()) std::cerr << "beamid fit: " << notes.correlated_bins << "\n";
  if (!notes.correlated_residuals.empty()) std::cerr << "beamid fit: " << notes.correlated_residuals << "\n";
  if (!notes.failed.empty()) std::cerr << "beamid fit: " << notes.failed << "\n";
  std::cerr << "beamid fit (commit " << io::commit_label() << "): " << data.path << ", beam " << beam_name
            << ", N = " << o.elements << ", cost " << o.cost.name << ", optimizer " << o.optimizer.method
            << ", strategy " << o.strategy << (o.strategy == fit::kHybrid ? " (refined by " + o.refine + ")" : "")
            << ": " << result.status << " (" << result.termination << "), cost " << result.cost << ", "
            << result.evaluations << " evaluations, " << result.wall_time_s << " s"
            << (result.final_evaluation.a4 != "ok" ? ", " + result.final_evaluation.a4 : "") << "\n";
  if (!notes.pairing.empty()) std::cerr << "beamid fit: " << notes.pairing << "\n";
  for (const fit::Profile& p : c.profiles) std::cerr << "beamid fit: " << api::profile_line(p, notes) << "\n";
  if (c.posterior)
    for (const std::string& line : api::posterior_lines(*c.posterior)) std::cerr << "beamid fit: " << line << "\n";
  if (!notes.identifiability.empty()) std::cerr << "beamid fit: " << notes.identifiability << "\n";
  if (result.records.size() > 1)
    for (std::size_t k = 0; k < result.records.size(); ++k) {
      const fit::RecordResult& part = result.records[k];
      std::cerr << "beamid fit: record " << k + 1 << " '" << part.name << "' (sensor at " << sensors[k]
                << " m): " << part.evaluation.status << ", cost " << part.evaluation.value << " x weight^2 "
                << part.weight * part.weight
                << (o.cost.unknown_amplitude ? ", amplitude scale " + format_value(part.evaluation.amplitude_scale)
                                             : std::string())
                << (part.evaluation.a4 != "ok" ? ", " + part.evaluation.a4 : std::string()) << "\n";
    }
  if (spread) std::cerr << "beamid fit: " << api::window_spread_line(*spread, result) << "\n";
  const FitReportInput input{o, result, data, beam_name, a.arguments(), channels, spread ? &*spread : nullptr};
  const ModeComparison modes = compare_modes(input);
  std::cerr << "beamid fit: " << modes_line(modes) << "\n";
  for (const ModePair& pair : modes.pairs)
    if (!pair.data_note.empty()) std::cerr << "beamid fit: the record: " << pair.data_note << "\n";
  for (const std::string& note : modes.notes) std::cerr << "beamid fit: " << note << "\n";
  if (const std::string note = modes_mismatch_note(modes); !note.empty()) std::cerr << "beamid fit: " << note << "\n";
  if (const std::string note = damping_mismatch_note(modes); !note.empty()) std::cerr << "beamid fit: " << note << "\n";
  if (a.has("report")) {
    FitReportInput with_modes = input;
    with_modes.modes = &modes;
    write_fit_report(a.text("report"), with_modes);
    std::cerr << "beamid fit: report written to " << a.text("report") << " and its full spectra to " << a.text("report")
              << ".spectra.csv\n";
  }
  return result.status == "failed" ? 3 : 0;
}

std::vector<FlagSpec> fit_flags() {
  std::vector<FlagSpec> flags = {
      text_flag("data",
                "record to fit, CSV, LabVIEW .lvm, text table (.txt, .dat), .npy, .mat or UFF 58; its time step and "
                "length fix dt and Nbar; "
                "with a --channel "
                "list, every channel is a record of one joint fit (one --sensor-x each)",
                true),
      text_flag("beam", "preset or TOML file: the known parameters and the start of the estimated ones", true),
      integer_flag("elements", "Galerkin order N of the fitted model", core::kMinElements, core::kMaxElements, true),
      text_flag("estimate", "comma-separated keys to estimate, e.g. EI,rho,cDI,gamma", true),
      text_flag("of-interest",
                "comma-separated estimated keys the identifiability verdict is about, the rest marginalised "
                "(default: the non-damping ones)"),
      text_flag("profile",
                "comma-separated estimated keys: their profile-likelihood intervals (68 and 95 %), the others "
                "refitted with each fixed on a grid"),
      switch_flag("posterior",
                  "sample the estimated parameters' posterior (least-squares costs: time, freq-band, freq-ml; "
                  "uniform prior on the bounds, the noise level integrated out): means, sds, 95 % intervals, "
                  "R-hat, effective sample sizes and the evidence"),
      integer_flag(
          "posterior-steps",
          "with --posterior, the steps per walker after the warm-up (default 2000: 50 autocorrelation times of a "
          "4-parameter posterior)",
          20, 1000000),
      text_flag("optimizer", fit::optimizer_names().alternatives() + " (default: lm, nelder-mead for spike)"),
      text_flag("strategy", fit::strategy_names().alternatives() + " (default direct)"),
      text_flag("refine",
                "hybrid: the cost of the second fit, time | freq-band | freq-ml | spike-smooth (default time)"),
      number_flag("start-scale", "start of every estimated parameter = S x its --beam value (default 1)"),
      number_flag("bound-factor", "bounds [v/F, v F] around each --beam value v (default 2)"),
      text_flag("bounds", "explicit bounds KEY=LO:HI,... (override --bound-factor)"),
      text_flag("scaling", "linear | log optimizer coordinates (default linear)"),
      integer_flag("starts", "number of starts: the given one plus space-filling starts in the bounds (default 1)", 1,
                   core::kMaxStarts),
      integer_flag("seed", "seed of the extra starts and of stochastic optimizers (default 1)", 0,
                   std::numeric_limits<int>::max()),
      integer_flag("max-evaluations", "model evaluations per optimizer run (default 3000)", 1, core::kMaxEvaluations),
      text_flag("integrator", "fast | cvode model integrator (default fast)"),
      text_flag("report", "write a Markdown fit report to this file"),
      text_flag("record-weights",
                "several channels: rms (each channel's residuals relative to its RMS; default) | noise (each "
                "channel weighted by its own residual noise, maximum likelihood)"),
      text_flag("detrend",
                "none | mean | linear: removed from the record where the spikes are picked (default linear for a "
                "free decay, none otherwise); for a free decay fitted by the time or freq-band cost, mean (the "
                "default) or linear: what its amplitudes fit beside the modes, a sensor offset or an offset and a "
                "drift"),
      text_flag("force-channel",
                "the record's measured force, N (a column of --data, e.g. force_N): it drives the model (linear "
                "between samples, at --force-x, from rest) instead of a modelled pulse"),
      integer_flag("windows",
                   "also fit K disjoint windows of the record(s) and report the estimates' spread over them, an "
                   "uncertainty that admits model error (default: not done)",
                   2, 64),
      number_flag("sensor-bandwidth",
                  "the record's anti-alias filter in the model: a Butterworth low-pass of this cut-off, Hz, applied "
                  "to the model's output simulated --sensor-oversampling times finer (default: none)"),
      integer_flag("sensor-filter-order", "that filter's order (default 4)", 1, 8),
      integer_flag("sensor-oversampling", "the model simulated this many times finer for the filter (default 16)", 2,
                   64)};
  for (const auto& more : {experiment_flag_specs(), cost_flags(true), import_flags()})
    flags.insert(flags.end(), more.begin(), more.end());
  for (FlagSpec& f : flags) {  // lists: one record per channel, each at its own sensor position
    if (f.name == "sensor-x")
      f = text_flag("sensor-x",
                    "sensor position(s) xbar, m: one per --channel, e.g. 0.15,0.3, or one for all with "
                    "--noise-model repeated (default: the tip)");
    if (f.name == "channel")
      f = text_flag("channel",
                    "signal column(s) by name or 1-based index: a comma-separated list fits the channels jointly, "
                    "with shared parameters and each channel's residuals relative to its RMS (default: the only one)");
  }
  return flags;
}

}  // namespace beamid::apps
