// beamid spikes, cost and fit: the identification commands (see commands.h for their forms).
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/computations.h"
#include "apps/fit_report.h"
#include "apps/flags.h"
#include "config/beam_file.h"
#include "costs/cost.h"
#include "fit/identification.h"
#include "fit/window_spread.h"
#include "io/provenance.h"
#include "io/text.h"
#include "io/time_series.h"
#include "model/errors.h"
#include "model/limits.h"
#include "signal/spikes.h"

namespace beamid::apps {

std::vector<FlagSpec> spike_flags() {
  return {
      integer_flag("spikes", "number of spikes NM (default 4)", 1, model::kMaxSpikes),
      text_flag("window", "rectangular | hann | exponential (default rectangular)"),
      number_flag("exponential-end", "exponential window's last weight, in (0, 1) (default 0.01)"),
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

// Reading the --data record: CSV, LabVIEW .lvm, .npy, .mat or UFF 58, a channel, units, a time window, a rate
// (io/time_series.h).
std::vector<FlagSpec> import_flags() {
  return {text_flag("channel", "signal column by name or 1-based index (default: the only one)"),
          text_flag("units", "auto | g | as-is (default auto: records in g are converted to m/s^2)"),
          number_flag("start", "keep samples from this time, s (default: the first)"),
          number_flag("duration", "keep this many seconds from --start (default: to the end)"),
          switch_flag("resample", "interpolate a non-uniform time base onto a uniform one instead of refusing it"),
          number_flag("sample-rate", "the sampling rate of a record without a time base (.npy, .mat), Hz"),
          text_flag("variable", ".mat: the record's variable, a dotted path into structs (default: the only one)"),
          text_flag("time-variable", ".mat: a time vector of the record's length, instead of --sample-rate"),
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
  flags.push_back(text_flag("model-poles", "spike-smooth: dft | eigenvalues (default dft)"));
  flags.push_back(
      text_flag("frequency-weight", "spike costs: " + costs::frequency_weight_names().alternatives() +
                                        " (default relative: a record read from a file is a measured one)"));
  return flags;
}

namespace {

signal::SpikeOptions read_spike_options(const Flags& a) {
  signal::SpikeOptions o;
  o.count = a.optional_integer("spikes").value_or(o.count);
  o.rule = a.text_or("spike-rule", o.rule);
  o.min_frequency_hz = a.optional_number("min-frequency").value_or(o.min_frequency_hz);
  const std::string artefacts = a.text_or("artefacts", "reject");
  a.require(artefacts == "reject" || artefacts == "keep", "artefacts", "must be one of reject, keep");
  o.reject_artefacts = artefacts == "reject";
  o.max_frequency_hz = a.optional_number("max-frequency").value_or(o.max_frequency_hz);
  if (a.has("spike-frequencies")) {
    o.frequencies_hz = a.numbers("spike-frequencies");
    for (const double f : o.frequencies_hz)
      a.require(f > 0, "spike-frequencies", "must be a comma-separated list of frequencies > 0 in Hz");
    std::sort(o.frequencies_hz.begin(), o.frequencies_hz.end());
    a.require(!a.has("spikes") || a.integer("spikes") == static_cast<int>(o.frequencies_hz.size()), "spikes",
              "must equal the number of --spike-frequencies (or be left out)");
    o.count = static_cast<int>(o.frequencies_hz.size());
  }
  if (auto error = signal::validation_error(o)) throw InputError("beamid " + a.command() + ": " + *error);
  return o;
}

signal::WindowOptions read_window(const Flags& a) {
  signal::WindowOptions w;
  w.name = a.text_or("window", w.name);
  w.exponential_end = a.optional_number("exponential-end").value_or(w.exponential_end);
  if (auto error = signal::validation_error(w)) throw InputError("beamid " + a.command() + ": " + *error);
  return w;
}

costs::CostOptions read_cost_options(const Flags& a) {
  costs::CostOptions o;
  o.name = a.text("cost");
  o.spikes = read_spike_options(a);
  o.window = read_window(a);
  o.eps1 = a.optional_number("eps1");
  o.eps2 = a.optional_number("eps2");
  o.eps3 = a.optional_number("eps3");
  o.unknown_amplitude = a.has("unknown-amplitude");
  o.model_poles = a.text_or("model-poles", o.model_poles);
  // A record read from a file is a measured record as far as beamid knows: errors relative to each mode's frequency,
  // so that the highest fitted mode does not dominate (cost.h); the studies' synthetic records keep the paper's Hz.
  o.frequency_weight = a.text_or("frequency-weight", costs::kRelativeWeight);
  if (auto error = costs::validation_error(o)) throw InputError("beamid " + a.command() + ": " + *error);
  return o;
}

}  // namespace

SpikesResult compute_spikes(const Flags& a, const io::TimeSeries& data) {
  // A record read from a file: its offset and trend removed by default (signal/spikes.h), so that their leakage into
  // the lowest bins is not picked as a mode.
  const std::string mode = a.text_or("detrend", signal::kDetrendLinear);
  a.require(signal::detrend_names().contains(mode), "detrend", "must be one of " + signal::detrend_names().list());
  a.require(!a.has("welch") || !a.has("window"), "window", "Welch's segments are Hann-windowed: leave out --window");
  const std::vector<double> values = signal::detrend(data.values, mode);
  SpikesResult r;
  const signal::SpikeOptions options = read_spike_options(a);
  if (a.has("welch")) {
    r.spectrum = signal::welch_spectrum(values, data.dt_s, a.integer("welch"));
  } else {
    signal::Dft dft(static_cast<int>(values.size()), data.dt_s, read_window(a));
    r.spectrum = dft.transform(values);
  }
  r.requested = options.count;
  r.peaks = signal::label_peaks(r.spectrum, options);
  for (const auto& p : r.peaks)
    if (p.skipped.empty()) r.picks.push_back(p.spike);
  std::sort(r.picks.begin(), r.picks.end(), [](const auto& x, const auto& y) { return x.bin < y.bin; });
  return r;
}

int run_spikes(const Flags& a, std::ostream& out) {
  const SpikesResult r = compute_spikes(a, read_data(a));
  const auto& picks = r.picks;
  const auto& peaks = r.peaks;
  if (static_cast<int>(picks.size()) < r.requested)
    std::cerr << "beamid spikes: --spikes " << r.requested << ": the record shows only " << picks.size()
              << " spike(s) (local maxima of |Z| in the band, artefacts skipped): " << picks.size() << " printed\n";
  // The picks in order of frequency, then the peaks passed over on the way, with the reason.
  out << "spike,bin,frequency_hz,magnitude,n_left,n_right,skipped\n";
  const auto row = [&](const std::string& label, const signal::Spike& p, const std::string& skipped) {
    out << label << "," << p.bin << "," << io::full_precision(p.frequency_hz) << "," << io::full_precision(p.magnitude)
        << "," << p.n_left << "," << p.n_right << "," << skipped << "\n";
  };
  for (std::size_t l = 0; l < picks.size(); ++l) row(std::to_string(l + 1), picks[l], "");
  for (const auto& p : peaks)
    if (!p.skipped.empty()) row("", p.spike, "\"" + p.skipped + "\"");
  if (a.has("welch"))
    std::cerr << "beamid spikes: picked on Welch's average of " << a.integer("welch") << " segments of "
              << r.spectrum.samples << " samples (df = " << r.spectrum.df_hz() << " Hz; bins are of that spectrum)\n";
  return 0;
}

costs::Evaluation compute_cost(const Flags& a, const io::TimeSeries& data, const io::TimeSeries& prediction) {
  if (prediction.values.size() != data.values.size() || std::abs(prediction.dt_s - data.dt_s) > 1e-9 * data.dt_s)
    throw InputError("beamid cost: --prediction = '" + prediction.path +
                     "': " + std::to_string(prediction.values.size()) +
                     " samples at dt = " + format_value(prediction.dt_s) + " s: must match the data's " +
                     std::to_string(data.values.size()) + " at " + format_value(data.dt_s) + " s");
  const costs::CostOptions options = read_cost_options(a);
  if (options.model_poles == "eigenvalues")
    throw InputError("beamid cost: --model-poles = 'eigenvalues': a prediction file carries no eigenvalues");
  auto cost = costs::make_cost(options, data.values, data.dt_s);
  const std::vector<std::complex<double>> none;
  costs::Evaluation e = cost->evaluate(costs::ModelResponse{prediction.values, none});
  if (!e.ok()) throw NumericalError("beamid cost: " + e.status);
  return e;
}

int run_cost(const Flags& a, std::ostream& out) {
  const costs::Evaluation e = compute_cost(a, read_data(a), io::read_time_series(a.text("prediction")));
  out << "cost,value\n" << a.text("cost") << "," << io::full_precision(e.value) << "\n";
  if (e.a4 != "ok") std::cerr << "beamid cost: " << e.a4 << "\n";
  return 0;
}

FitComputation compute_fit(const Flags& a, const std::vector<io::TimeSeries>& channels) {
  const io::TimeSeries& data = channels.front();
  const model::BeamParameters nominal = read_beam(a);

  FitComputation c;
  fit::FitOptions& o = c.options;
  o.elements = a.integer("elements");
  o.experiment = read_experiment(a, nominal.l);
  guard_run_size(a, o.elements, static_cast<double>(data.values.size() * channels.size()),
                 model::kRecordBytesPerSample);
  // A forced experiment starts at t = 0; a free decay is timed from its first sample.
  if (o.experiment.excitation != simulation::kFreeDecay && std::abs(data.t0_s) > 1e-9 * data.dt_s)
    throw InputError("beamid fit: --data = '" + data.path + "': first time " + format_value(data.t0_s) +
                     " s: must be 0 (the experiment starts at t = 0; a record cut from later is a free decay: "
                     "--excitation free-decay)");
  if (a.has("dt") && std::abs(o.experiment.dt_s - data.dt_s) > 1e-9 * data.dt_s)
    a.require(false, "dt", "must equal the data's time step " + format_value(data.dt_s) + " s");
  if (a.has("samples") && o.experiment.samples != static_cast<int>(data.values.size()))
    a.require(false, "samples", "must equal the data's " + std::to_string(data.values.size()));
  o.experiment.dt_s = data.dt_s;
  o.experiment.samples = static_cast<int>(data.values.size());
  o.simulator.integrator = a.text_or("integrator", o.simulator.integrator);
  o.cost = read_cost_options(a);
  o.optimizer.method = a.text_or("optimizer", fit::default_optimizer(o.cost.name));
  o.optimizer.max_evaluations = a.optional_integer("max-evaluations").value_or(o.optimizer.max_evaluations);
  o.strategy = a.text_or("strategy", o.strategy);
  o.refine = a.text_or("refine", o.refine);
  a.require(!a.has("refine") || o.strategy == fit::kHybrid, "refine", "is the second cost of --strategy hybrid only");
  o.scaling = a.text_or("scaling", o.scaling);
  o.record_weights = a.text_or("record-weights", o.record_weights);
  a.require(o.record_weights == fit::kRmsWeights || o.record_weights == fit::kNoiseWeights, "record-weights",
            "must be one of rms, noise");
  o.starts = a.optional_integer("starts").value_or(o.starts);
  const std::optional<int> seed = a.optional_integer("seed");
  a.require(!seed || *seed >= 0, "seed", "must be an integer >= 0");
  o.seed = static_cast<std::uint64_t>(seed.value_or(1));
  const double start_scale = a.optional_number("start-scale").value_or(1.0);
  a.require(start_scale > 0, "start-scale", "must be > 0");
  const double factor = a.optional_number("bound-factor").value_or(2.0);
  a.require(factor > 1, "bound-factor", "must be > 1");
  o.estimate = parse_estimate(a, nominal, factor);
  // A free decay read from a file: its spikes picked without its offset and trend (costs/cost.h).
  o.cost.pick_detrend = a.text_or(
      "detrend", o.experiment.excitation == simulation::kFreeDecay ? signal::kDetrendLinear : signal::kDetrendNone);
  a.require(signal::detrend_names().contains(o.cost.pick_detrend), "detrend",
            "must be one of " + signal::detrend_names().list());
  // --welch K: the spikes picked on Welch's average of the (detrended) record, then fitted on the whole record's DFT
  // near those frequencies (signal/spikes.h).
  if (a.has("welch")) {
    a.require(o.cost.spikes.frequencies_hz.empty(), "welch", "picks the spikes: leave out --spike-frequencies");
    const signal::Spectrum welch =
        signal::welch_spectrum(signal::detrend(data.values, o.cost.pick_detrend), data.dt_s, a.integer("welch"));
    // Each pick refined on the whole record's DFT: its largest local maximum within one Welch bin ((K + 1)/2 of the
    // record's), which the cost's +-5 % window around the frequency then finds however coarse the Welch bin was.
    signal::Dft dft(static_cast<int>(data.values.size()), data.dt_s);
    const signal::Spectrum full = dft.transform(signal::detrend(data.values, o.cost.pick_detrend));
    const std::vector<int> maxima = signal::local_maxima(full);
    for (const auto& p : signal::label_peaks(welch, o.cost.spikes)) {
      if (!p.skipped.empty()) continue;
      int best = -1;
      for (int k : maxima)
        if (std::abs(full.frequency_hz(k) - p.spike.frequency_hz) <= welch.df_hz() &&
            (best < 0 || full.magnitude(k) > full.magnitude(best)))
          best = k;
      const double f = best >= 0 ? full.frequency_hz(best) : p.spike.frequency_hz;
      if (std::find(o.cost.spikes.frequencies_hz.begin(), o.cost.spikes.frequencies_hz.end(), f) ==
          o.cost.spikes.frequencies_hz.end())
        o.cost.spikes.frequencies_hz.push_back(f);
    }
    std::sort(o.cost.spikes.frequencies_hz.begin(), o.cost.spikes.frequencies_hz.end());
    a.require(!o.cost.spikes.frequencies_hz.empty(), "welch", "found no peak to fit");
    o.cost.spikes.count = static_cast<int>(o.cost.spikes.frequencies_hz.size());
    c.welch_picked = true;
  }
  o.start = nominal;
  for (const auto& e : o.estimate)
    model::set_parameter_value(o.start, e.key, model::parameter_value(o.start, e.key) * start_scale);

  // Several channels: one record each, at its own --sensor-x, fitted jointly (fit/identification.h).
  c.sensors_m = a.numbers("sensor-x");
  const std::vector<double>& sensors = c.sensors_m;
  std::vector<fit::Record>& records = c.records;
  if (channels.size() > 1 || sensors.size() > 1) {
    a.require(sensors.size() == channels.size(), "sensor-x",
              "must list one position per --channel (" + std::to_string(channels.size()) + " channel(s))");
    for (std::size_t k = 0; k < channels.size(); ++k) {
      fit::Record record{channels[k].value_column, o.start, o.experiment, channels[k].values, {}};
      record.experiment.sensor_x_m = sensors[k];
      if (auto error = simulation::validation_error(record.experiment, o.start.l))
        a.require(false, "sensor-x", "channel " + std::to_string(k + 1) + ": " + *error);
      records.push_back(std::move(record));
    }
  }
  c.result = records.empty() ? fit::fit(o, data.values) : fit::fit(o, records);
  // --windows K: the spread over K disjoint windows (fit/window_spread.h), an uncertainty that admits model error.
  if (a.has("windows") && c.result.status != "failed") {
    try {
      c.spread = records.empty() ? fit::window_spread(o, data.values, c.result, a.integer("windows"))
                                 : fit::window_spread(o, records, c.result, a.integer("windows"));
    } catch (const InputError& error) {
      a.require(false, "windows", error.what());
    }
  }
  return c;
}

FitNotes fit_notes(const fit::FitResult& result) {
  FitNotes notes;
  std::string at_bound;
  for (const fit::ParameterEstimate& p : result.parameters)
    if (p.status == fit::kAtLowerBound || p.status == fit::kAtUpperBound)
      at_bound += (at_bound.empty() ? "" : ", ") + p.key + " " + p.status;
  if (!at_bound.empty())
    notes.on_bound =
        "on a bound: " + at_bound + " (the bound, not the data, set the value; its standard error is not defined)";
  if (result.status == "failed")
    notes.failed = "the fit failed, so no estimate is printed (NaN): " + result.termination;
  const fit::Identifiability& i = result.identifiability;
  if (i.status == "ok" && i.verdict != "identifiable") {
    std::ostringstream line;  // numbers as the stream prints them (6 significant digits)
    line << i.verdict << ": condition number of J (in ln q) " << i.condition << "; the record hardly constrains "
         << i.combination() << " (formal sd " << i.weakest_sd << ")"
         << (i.weak.size() > 1 ? " and " + std::to_string(i.weak.size() - 1) +
                                     " further combination(s) above 1e3 (listed in --report)"
                               : std::string());
    notes.identifiability = line.str();
  }
  return notes;
}

int run_fit(const Flags& a, std::ostream& out) {
  const std::vector<io::TimeSeries> channels = read_channels(a);
  const io::TimeSeries& data = channels.front();
  const std::string beam_name = a.text("beam");
  const FitComputation c = compute_fit(a, channels);
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
  const FitNotes notes = fit_notes(result);
  if (!notes.on_bound.empty()) std::cerr << "beamid fit: " << notes.on_bound << "\n";
  if (!notes.failed.empty()) std::cerr << "beamid fit: " << notes.failed << "\n";
  std::cerr << "beamid fit (commit " << io::commit_label() << "): " << data.path << ", beam " << beam_name
            << ", N = " << o.elements << ", cost " << o.cost.name << ", optimizer " << o.optimizer.method
            << ", strategy " << o.strategy << (o.strategy == fit::kHybrid ? " (refined by " + o.refine + ")" : "")
            << ": " << result.status << " (" << result.termination << "), cost " << result.cost << ", "
            << result.evaluations << " evaluations, " << result.wall_time_s << " s"
            << (result.final_evaluation.a4 != "ok" ? ", " + result.final_evaluation.a4 : "") << "\n";
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
  if (spread) {
    std::cerr << "beamid fit: " << spread->used << " of " << spread->windows << " windows fitted; sd over them:";
    for (std::size_t i = 0; i < spread->keys.size(); ++i)
      std::cerr << (i ? "," : "") << " " << spread->keys[i] << " " << spread->sd[i] << " (formal "
                << result.parameters[i].standard_error << ", sandwich " << result.parameters[i].robust_standard_error
                << ")";
    std::cerr << "\n";
  }
  const FitReportInput input{o, result, data, beam_name, a.arguments(), channels, spread ? &*spread : nullptr};
  std::cerr << "beamid fit: " << modes_line(compare_modes(input)) << "\n";
  if (a.has("report")) write_fit_report(a.text("report"), input);
  return result.status == "failed" ? 3 : 0;
}

std::vector<FlagSpec> fit_flags() {
  std::vector<FlagSpec> flags = {
      text_flag("data",
                "record to fit, CSV or LabVIEW .lvm; its time step and length fix dt and Nbar; with a --channel "
                "list, every channel is a record of one joint fit (one --sensor-x each)",
                true),
      text_flag("beam", "preset or TOML file: the known parameters and the start of the estimated ones", true),
      integer_flag("elements", "Galerkin order N of the fitted model", model::kMinElements, model::kMaxElements, true),
      text_flag("estimate", "comma-separated keys to estimate, e.g. EI,rho,cDI,gamma", true),
      text_flag("optimizer", fit::optimizer_names().alternatives() + " (default: lm, nelder-mead for spike)"),
      text_flag("strategy", fit::strategy_names().alternatives() + " (default direct)"),
      text_flag("refine", "hybrid: the cost of the second fit, time | freq-band (default time)"),
      number_flag("start-scale", "start of every estimated parameter = S x its --beam value (default 1)"),
      number_flag("bound-factor", "bounds [v/F, v F] around each --beam value v (default 2)"),
      text_flag("bounds", "explicit bounds KEY=LO:HI,... (override --bound-factor)"),
      text_flag("scaling", "linear | log optimizer coordinates (default linear)"),
      integer_flag("starts", "number of starts: the given one plus space-filling starts in the bounds (default 1)", 1,
                   model::kMaxStarts),
      integer_flag("seed", "seed of the extra starts and of stochastic optimizers (default 1)", 0,
                   std::numeric_limits<int>::max()),
      integer_flag("max-evaluations", "model evaluations per optimizer run (default 3000)", 1, model::kMaxEvaluations),
      text_flag("integrator", "fast | cvode model integrator (default fast)"),
      text_flag("report", "write a Markdown fit report to this file"),
      text_flag("record-weights",
                "several channels: rms (each channel's residuals relative to its RMS; default) | noise (each "
                "channel weighted by its own residual noise, maximum likelihood)"),
      text_flag("detrend",
                "none | mean | linear: removed from the record where the spikes are picked (default linear for a "
                "free decay, none otherwise)"),
      integer_flag("windows",
                   "also fit K disjoint windows of the record(s) and report the estimates' spread over them, an "
                   "uncertainty that admits model error (default: not done)",
                   2, 64)};
  for (const auto& more : {experiment_flag_specs(), cost_flags(true), import_flags()})
    flags.insert(flags.end(), more.begin(), more.end());
  for (FlagSpec& f : flags) {  // lists: one record per channel, each at its own sensor position
    if (f.name == "sensor-x")
      f = text_flag("sensor-x", "sensor position(s) xbar, m: one per --channel, e.g. 0.15,0.3 (default: the tip)");
    if (f.name == "channel")
      f = text_flag("channel",
                    "signal column(s) by name or 1-based index: a comma-separated list fits the channels jointly, "
                    "with shared parameters and each channel's residuals relative to its RMS (default: the only one)");
  }
  return flags;
}

}  // namespace beamid::apps
