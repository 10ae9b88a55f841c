#include "api/record_requests.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>

#include "core/errors.h"
#include "core/limits.h"
#include "io/units.h"

namespace beamid::api {

signal::PoleEstimate SpikesResult::subbin(int bin) const {
  signal::PoleEstimate e;
  if (!welch) e = signal::three_bin_estimate(spectrum, bin);
  if (!e.ok || std::abs(e.frequency_hz - spectrum.frequency_hz(bin)) > spectrum.df_hz())
    e = {std::nan(""), std::nan(""), false};
  // A mode of a passive beam decays: a negative rate is the neighbours' leakage into the three bins of a short record
  // (-0.098 1/s printed for a mode decaying at 0.255 1/s: the twenty-second pass's P4), not a measurement. NaN.
  if (e.decay_rate_1_s < 0) e.decay_rate_1_s = std::nan("");
  return e;
}

namespace {

// A list as the flag took it: "31,1000" (the ninth pass's Q: only its first value was quoted).
std::string joined(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ",") + format_value(v);
  return text;
}

// The picks' modes by the shared estimator: one pencil for all of them; when one has no pole nearby, each alone (the
// kMaxSeparatelyMeasured largest of them: a pencil per pick on a long record takes seconds), NaN for those that fail
// or are not measured, each with its own reason.
constexpr int kMaxSeparatelyMeasured = 8;
void measure_picks(SpikesResult& r, const std::vector<double>& values, double dt_s, double window, double df_hz) {
  signal::MeasuredMode none;
  none.mode.frequency_hz = std::nan("");
  r.measured.assign(r.picks.size(), none);
  if (r.picks.empty()) return;
  if (static_cast<int>(values.size()) > core::kMaxPencilSamples) {
    r.measured_note = "measured frequencies not computed: the record has " + std::to_string(values.size()) +
                      " samples, more than the matrix pencil takes (" + std::to_string(core::kMaxPencilSamples) +
                      "); cut it (--start, --duration) or lower its rate (--resample-rate)";
    return;
  }
  const auto measure = [&](const std::vector<double>& wanted, double relative) {
    signal::MeasureOptions o;
    o.wanted_hz = wanted;
    o.window = relative;
    return signal::measure_modes(values, dt_s, o).modes;
  };
  std::vector<double> wanted;
  for (const auto& p : r.picks) wanted.push_back(p.frequency_hz);
  // A pick's pole is searched within three bins of it (at most the chosen window): a stronger mode 2 Hz away took a
  // 50.05 Hz spike's place, "48.000 +- 1e-14 Hz" (the ninth pass's N_f1). Three bins at the lowest pick are at least
  // three at every other.
  const double lowest = *std::min_element(wanted.begin(), wanted.end());
  const double joint = std::min(window, 3 * df_hz / lowest);
  // A pick measured alone is searched within a bin and a half of it at the least, where a bin is wider than the window:
  // a pick is a bin's centre, and a coarse spectrum's (Welch's, K = 8: 0.27 Hz) put 2.1978 Hz 12 % from the mode at
  // 2.4637 Hz, which went unmeasured (the seventeenth pass's P7). Per pick: the lowest pick's 18 % applied to every
  // pick took a 494 Hz pole for the 403.8 Hz mode (the eighteenth pass's P3).
  const auto alone = [&](double f) { return std::min(std::max(window, 1.5 * df_hz / f), 3 * df_hz / f); };
  std::string failure;
  std::vector<std::string> failures(wanted.size());  // each pick's own, when measured alone
  std::vector<bool> skipped(wanted.size(), false);   // not measured alone (beyond the largest picks)
  try {
    r.measured = measure(wanted, joint);
  } catch (const std::exception& all) {
    failure = all.what();
    // Beyond kMaxSeparatelyMeasured picks, the largest of them alone: every one of 18 picks was left NaN, the steel
    // record's clear 6.62 and 41.4 Hz modes too, each given the joint search's failure at another pick (the
    // twenty-eighth pass's adv65 P5).
    std::vector<std::size_t> order(wanted.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return r.picks[a].magnitude > r.picks[b].magnitude; });
    for (std::size_t rank = 0; rank < order.size(); ++rank) {
      const std::size_t k = order[rank];
      if (static_cast<int>(rank) >= kMaxSeparatelyMeasured) {
        skipped[k] = true;
        continue;
      }
      try {
        r.measured[k] = measure({wanted[k]}, alone(wanted[k])).front();
      } catch (const std::exception& one) {
        failures[k] = one.what();
      }
    }
  }
  // Two picks that find one pole have one measured frequency between them, not each its own: the one nearer the pole
  // keeps it (the ninth pass: 40 and 40.4 Hz spikes got one value in both rows, without a word).
  std::string shared;
  for (std::size_t a = 0; a < r.measured.size(); ++a)
    for (std::size_t b = a + 1; b < r.measured.size(); ++b) {
      signal::MeasuredMode &x = r.measured[a], &y = r.measured[b];
      if (std::isnan(x.mode.frequency_hz) || std::isnan(y.mode.frequency_hz) || x.mode.lambda != y.mode.lambda)
        continue;
      const double f = x.mode.frequency_hz;
      const std::size_t far = std::abs(wanted[a] - f) <= std::abs(wanted[b] - f) ? b : a;
      shared += (shared.empty() ? "" : "; ") + format_rounded(wanted[far], 6) + " Hz (the pole at " +
                format_rounded(f, 6) + " Hz is the spike at " + format_rounded(wanted[far == a ? b : a], 6) + " Hz's)";
      r.measured[far] = none;
    }
  if (!shared.empty())
    r.notes.push_back("no pole of its own for the spike(s) at " + shared +
                      ": a side lobe, a split peak or a mode the pencil merges with its neighbour; its "
                      "measured_frequency_hz is nan");
  // Each missing pick with its own reason (the joint search's first failure named another pick's frequency: the
  // twenty-second pass's P3).
  std::string missing, unmeasured;
  for (std::size_t k = 0; k < r.measured.size(); ++k) {
    if (std::isnan(r.measured[k].mode.frequency_hz)) {
      if (failure.empty()) continue;  // one without a pole of its own, said above
      if (skipped[k])
        unmeasured += (unmeasured.empty() ? "" : ", ") + format_rounded(wanted[k], 6);
      else
        missing += (missing.empty() ? "" : "; ") + format_rounded(wanted[k], 6) + " Hz (" +
                   (failures[k].empty() ? failure : failures[k]) + ")";
      continue;
    }
    if (const std::string note = signal::uncertainty_note(r.measured[k]); !note.empty()) r.notes.push_back(note);
  }
  if (!missing.empty())
    r.measured_note = "no measured frequency for the spike(s) at " + missing +
                      ": the pencil's poles near it are heavily damped, below the noise, or farther than the "
                      "search window";
  if (!unmeasured.empty())
    r.measured_note += (r.measured_note.empty() ? "" : "; ") + std::string("the spike(s) at ") + unmeasured +
                       " Hz were not measured: one pencil for all picks failed (" + failure + "), and only the " +
                       std::to_string(kMaxSeparatelyMeasured) +
                       " largest picks are measured one by one (ask for fewer --spikes)";
}

// A band that starts at or above the record's Nyquist frequency holds nothing: modal-id printed an empty table with
// exit 0 (the twelfth pass's P11).
void refuse_band_above_nyquist(const Caller& caller, double min_frequency_hz, const io::TimeSeries& data) {
  const double nyquist_hz = 0.5 / data.dt_s;
  if (min_frequency_hz >= nyquist_hz)
    refuse(caller, "min-frequency", format_value(min_frequency_hz),
           "must be below the Nyquist frequency of --data = '" + data.path + "', " + format_rounded(nyquist_hz, 6) +
               " Hz (the band would hold nothing)");
}

}  // namespace

SpikesResult compute_spikes(const SpikesRequest& request, const io::TimeSeries& data) {
  const Caller& caller = request.caller;
  // A record read from a file: its offset and trend removed by default (signal/spikes.h), so that their leakage into
  // the lowest bins is not picked as a mode.
  const std::string mode = request.detrend.value_or(signal::kDetrendLinear);
  if (!signal::detrend_names().contains(mode))
    refuse(caller, "detrend", mode, "must be one of " + signal::detrend_names().list());
  if (request.welch && request.window.name)
    refuse(caller, "window", *request.window.name, "Welch's segments are Hann-windowed: leave out --window");
  const std::vector<double> values = signal::detrend(data.values, mode);
  // What the detrend leaves of a straight line (the time channel chosen as the signal, a drift alone) is rounding,
  // whose "spikes" were 1e-16 high with negative decay rates (the seventh pass's N22).
  double before = 0, after = 0;
  for (double v : data.values) before = std::max(before, std::abs(v));
  for (double v : values) after = std::max(after, std::abs(v));
  if (mode != signal::kDetrendNone && after <= 1e-12 * before)
    refuse(caller, "--data = '" + data.path + "': " + data.value_column + " is a straight line in time (the time " +
                       "channel itself, or a drift alone): after the " + mode + " detrend nothing is left to analyse");
  SpikesResult r;
  const signal::SpikeOptions options = spike_options(request.spikes, caller);
  refuse_band_above_nyquist(caller, options.min_frequency_hz, data);
  if (request.welch) {
    r.welch = true;
    r.spectrum = signal::welch_spectrum(values, data.dt_s, *request.welch);
  } else {
    signal::Dft dft(static_cast<int>(values.size()), data.dt_s, window_options(request.window, caller));
    r.spectrum = dft.transform(values);
  }
  r.requested = options.count;
  r.peaks = signal::label_peaks(r.spectrum, options);
  for (const auto& p : r.peaks)
    if (p.skipped.empty()) r.picks.push_back(p.spike);
  std::sort(r.picks.begin(), r.picks.end(), [](const auto& x, const auto& y) { return x.bin < y.bin; });
  // A chosen frequency with no peak near it (above the Nyquist frequency, say) is an error, as in fit and cost, not
  // a run with fewer spikes (the eighth pass's E38: exit 0 and no spike).
  if (!options.frequencies_hz.empty() && r.picks.size() < options.frequencies_hz.size())
    refuse(caller, "spike-frequencies", joined(options.frequencies_hz),
           signal::unmatched_frequencies(r.picks, options, r.spectrum));
  measure_picks(r, values, data.dt_s, options.frequency_window, r.spectrum.df_hz());
  // The measured frequencies are a free decay's: a record that still holds its hit misleads them (the eighth pass's
  // P13: 30 Hz measured at 31.35 +- 0.005 Hz without a word).
  if (!r.picks.empty())
    if (const std::string note = lead_in_note(data, "the pencil (the measured frequencies)"); !note.empty())
      r.notes.push_back(note);
  std::vector<double> picked;
  for (const auto& p : r.picks) picked.push_back(r.spectrum.frequency_hz(p.bin));
  if (const std::string note = pass_band_note(data, picked, "spike"); !note.empty()) r.notes.push_back(note);
  if (!r.welch)
    if (const std::string note =
            window_transient_note(window_options(request.window, caller), values.size(), data.dt_s, r.measured);
        !note.empty())
      r.notes.push_back(note);
  if (const std::string note = raw_signal_note(data, "magnitudes"); !note.empty()) r.notes.push_back(note);
  if (const std::string note = quantisation_note(data); !note.empty()) r.notes.push_back(note);
  return r;
}

costs::Evaluation compute_cost(const CostEvaluationRequest& request, const io::TimeSeries& data,
                               const io::TimeSeries& prediction) {
  const Caller& caller = request.caller;
  if (prediction.values.size() != data.values.size() || std::abs(prediction.dt_s - data.dt_s) > 1e-9 * data.dt_s)
    refuse(caller, "--prediction = '" + prediction.path + "': " + std::to_string(prediction.values.size()) +
                       " samples at dt = " + format_value(prediction.dt_s) + " s: must match the data's " +
                       std::to_string(data.values.size()) + " at " + format_value(data.dt_s) + " s");
  // Two records that state what they measure must measure the same (C021: a velocity record costed against a
  // displacement prediction without a word).
  const std::string measured = io::quantity_of(data.unit), predicted = io::quantity_of(prediction.unit);
  // A raw sensor signal (V, mV, N, Pa) is no motion to compare a motion with, as fit refuses it (the seventh pass's
  // U079-U084: a cost was printed without a word); with --unknown-amplitude only its shape is compared.
  for (const io::TimeSeries* record : {&data, &prediction})
    if (io::is_non_motion_unit(record->unit) && !request.cost.unknown_amplitude &&
        !io::is_non_motion_unit((record == &data ? prediction : data).unit))
      refuse(caller, std::string(record == &data ? "--data" : "--prediction") + " = '" + record->path +
                         "': " + record->value_column + " is in " + record->unit +
                         ", a raw sensor signal, not a motion: convert it to m, m/s or m/s^2 with the sensor's "
                         "sensitivity (or give --unknown-amplitude to compare shapes only)");
  if (!measured.empty() && !predicted.empty() && measured != predicted)
    refuse(caller, "--prediction = '" + prediction.path + "': in " + prediction.unit + ", a " + predicted +
                       ": the data are in " + data.unit + ", a " + measured + " (compare like with like)");
  // Two records carry no eigenvalues, which the modal cost compares (it ended in exit 3 naming --integrator, a flag
  // `cost` does not have: the fourth pass's Q539).
  if (request.cost.name == costs::kModalCost)
    refuse(caller, "cost", costs::kModalCost,
           "compares the model's eigenvalues with the record's modes, and a prediction file carries no eigenvalues: "
           "use it in fit");
  if (request.cost.force_noise_sd)
    refuse(caller, "force-noise-sd", format_value(*request.cost.force_noise_sd),
           "weighs the force's noise through the model's transfer function, which a prediction file does not carry: "
           "use it in fit with --force-channel");
  // A noise model a fit estimates (from its residuals, or from repeated records) needs the fit.
  if (request.cost.noise_model && costs::is_estimated_noise(*request.cost.noise_model))
    refuse(caller, "noise-model", *request.cost.noise_model,
           "is estimated by fit (from its white fit's residuals, or from repeated records); cost compares a given "
           "prediction: give a model (white, ar:a1,..., power:alpha)");
  // What picks spikes (their number, chosen frequencies) and their band, where the cost reads neither: in fit they
  // also choose the modes compared at the estimate; here nothing reads them (the fourth pass's Q511, Q524-Q537).
  const bool picks = costs::is_spike_cost(request.cost.name), band = picks || costs::is_band_cost(request.cost.name);
  const SpikeRequest& spikes = request.cost.spikes;
  if (!picks && spikes.count)
    refuse(caller, "spikes", std::to_string(*spikes.count),
           "is read by the spike costs; cost " + request.cost.name + " picks no spikes");
  if (!picks && !spikes.frequencies_hz.empty())
    refuse(caller, "spike-frequencies", format_value(spikes.frequencies_hz.front()),
           "is read by the spike costs; cost " + request.cost.name + " picks no spikes");
  if (!band && (spikes.min_frequency_hz || spikes.max_frequency_hz))
    refuse(caller, spikes.min_frequency_hz ? "min-frequency" : "max-frequency",
           format_value(spikes.min_frequency_hz.value_or(spikes.max_frequency_hz.value_or(0))),
           "is read by the spike costs and freq-band; cost " + request.cost.name + " has no band");
  const costs::CostOptions options = cost_options(request.cost, caller);
  if (options.model_poles == costs::kEigenvaluePoles)
    refuse(caller, "--model-poles = 'eigenvalues': a prediction file carries no eigenvalues");
  auto cost = costs::make_cost(options, data.values, data.dt_s);
  const std::vector<std::complex<double>> none;
  costs::Evaluation e = cost->evaluate(costs::ModelResponse{prediction.values, none});
  if (!e.ok()) throw NumericalError(caller.label + ": " + e.status);
  return e;
}

ModalIdResult compute_modal_id(const ModalIdRequest& request, const io::TimeSeries& data) {
  const Caller& caller = request.caller;
  ModalIdResult r;
  signal::PencilOptions& o = r.options;
  o.modes = request.modes.value_or(o.modes);
  o.order = request.order.value_or(o.order);
  o.min_frequency_hz = request.min_frequency_hz.value_or(o.min_frequency_hz);
  o.max_frequency_hz = request.max_frequency_hz.value_or(o.max_frequency_hz);
  if (!(o.min_frequency_hz >= 0)) refuse(caller, "min-frequency", format_value(o.min_frequency_hz), "must be >= 0");
  if (!(o.max_frequency_hz > o.min_frequency_hz))
    refuse(caller, "max-frequency", format_value(o.max_frequency_hz),
           "must exceed --min-frequency = '" + format_value(o.min_frequency_hz) + "'");
  refuse_band_above_nyquist(caller, o.min_frequency_hz, data);
  signal::MeasureOptions measure;
  measure.pencil = o;
  measure.selection = signal::ModeSelection::strongest;
  signal::MeasuredModes measured;
  try {
    measured = signal::measure_modes(data.values, data.dt_s, measure);
  } catch (const InputError& error) {
    const std::string what = error.what();
    if (what.rfind("order M = ", 0) == 0) refuse(caller, what);  // --order's own (in_flags), not the record's
    refuse(caller, "--data = '" + data.path + "': " + what);
  }
  r.measured = measured.modes;
  for (const signal::MeasuredMode& m : r.measured) r.modes.push_back(m.mode);
  r.notes = modal_id_notes(r.modes, measured.diagnostics, o, static_cast<double>(data.values.size()) * data.dt_s);
  for (const signal::MeasuredMode& m : r.measured)
    if (const std::string note = signal::uncertainty_note(m); !note.empty()) r.notes.push_back(note);
  if (const std::string note = lead_in_note(data, "the pencil"); !note.empty()) r.notes.push_back(note);
  std::vector<double> found;
  for (const signal::IdentifiedMode& m : r.modes) found.push_back(m.frequency_hz);
  if (const std::string note = pass_band_note(data, found, "pole"); !note.empty()) r.notes.push_back(note);
  if (const std::string note = raw_signal_note(data, "amplitudes"); !note.empty()) r.notes.push_back(note);
  if (const std::string note = quantisation_note(data); !note.empty()) r.notes.push_back(note);
  return r;
}

std::string window_transient_note(const signal::WindowOptions& window, std::size_t samples, double dt_s,
                                  const std::vector<signal::MeasuredMode>& modes) {
  if (window.name == "rectangular") return "";
  const std::vector<double> weights = signal::window_weights(window, static_cast<int>(samples));
  double worst = 1;
  const signal::MeasuredMode* at = nullptr;
  for (const signal::MeasuredMode& m : modes) {
    if (std::isnan(m.mode.frequency_hz)) continue;
    const double rho = signal::window_snr_retention(weights, -m.mode.lambda.real(), dt_s);
    if (rho < worst) worst = rho, at = &m;
  }
  if (!at || worst >= kWindowRetention) return "";
  const double record_s = static_cast<double>(samples) * dt_s;
  return "the " + window.name + " window keeps " + format_rounded(100 * worst, 2) +
         " % of the signal-to-noise ratio of the record's mode at " + format_rounded(at->mode.frequency_hz, 6) +
         " Hz (it decays by e^-" + format_rounded(-at->mode.lambda.real() * record_s / 2, 3) +
         " by the record's middle, where the window is widest): on a noisy record that spike's magnitude and decay "
         "rate are the noise's, and the spike costs then estimate a lighter damping (1 % noise halved cDI on a thin "
         "beam's pulse record); a transient that dies out within the record wants --window rectangular or "
         "exponential";
}

std::string raw_signal_note(const io::TimeSeries& data, const std::string& what) {
  if (!io::is_non_motion_unit(data.unit)) return "";
  return "the record is in " + data.unit + ", a raw sensor signal and no motion: its " + what + " are in " + data.unit +
         " (frequencies and damping ratios do not depend on the unit; beamid fit needs the motion)";
}

// Whether the record's steps lie on a grid of `quantum`: at least 90 % of its nonzero steps within 1 % of a whole
// number of quanta. The smallest step of a few full-precision samples is no quantum: 8 samples of a sine were called
// "quantised coarsely (4.6 bits)" (the twenty-third pass's P5).
bool on_grid(const std::vector<double>& v, double quantum) {
  std::size_t steps = 0, on = 0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (const double q = std::abs(v[i] - v[i - 1]) / quantum; q > 0) {
      ++steps;
      on += std::abs(q - std::round(q)) <= 0.01 ? 1 : 0;
    }
  return steps > 0 && on >= 0.9 * static_cast<double>(steps);
}

std::string quantisation_note(const io::TimeSeries& data) {
  const double quantum = io::record_quantum(data.values);
  double peak = 0;
  for (double v : data.values) peak = std::max(peak, std::abs(v));
  if (!std::isfinite(quantum) || !(peak / quantum < io::kFineQuantisation)) return "";
  if (data.values.size() < kMinQuantisationSamples || !on_grid(data.values, quantum)) return "";
  return "the record is quantised coarsely: its step is " + format_rounded(quantum, 3) + ", 1/" +
         format_rounded(peak / quantum, 3) + " of its peak (" + format_rounded(std::log2(2 * peak / quantum), 2) +
         " bits over its range): below a few steps its quantisation error follows the signal instead of being white "
         "noise, so weak modes and late decay show as steady lines, growing or spurious poles";
}

std::string pass_band_note(const io::TimeSeries& data, const std::vector<double>& frequencies_hz,
                           const std::string& what) {
  std::string above;
  for (double f : frequencies_hz)
    if (f > data.pass_band_hz) above += (above.empty() ? "" : ", ") + format_rounded(f, 6);
  if (above.empty()) return "";
  return "the " + what + "(s) at " + above + " Hz lie above the resampling low-pass's pass band (" +
         format_rounded(data.pass_band_hz) +
         " Hz), where the low-pass bends a mode and its edge makes poles of a removed peak's tail: not to be read as "
         "modes (a higher --resample-rate keeps them in its pass band or removes them)";
}

std::string glitch_note(const io::TimeSeries& data, const std::string& what) {
  // One sample above kGlitchRatio times every other one is a glitch of the acquisition, or an impact shorter than a
  // sample: either way lead_in_note's advice ("cut the record after t") would throw away whatever precedes it (the
  // twelfth pass's P6: one sample at 50x the peak, half the record advised away).
  constexpr double kGlitchRatio = 10;
  std::size_t top = 0;
  double rest = 0;
  for (std::size_t i = 1; i < data.values.size(); ++i)
    if (std::abs(data.values[i]) > std::abs(data.values[top])) top = i;
  for (std::size_t i = 0; i < data.values.size(); ++i)
    if (i != top) rest = std::max(rest, std::abs(data.values[i]));
  if (data.values.size() > 2 && std::abs(data.values[top]) > kGlitchRatio * rest)
    return "sample " + std::to_string(top + 1) +
           " (t = " + format_rounded(data.t0_s + static_cast<double>(top) * data.dt_s, 6) + " s) is " +
           format_rounded(std::abs(data.values[top]) / rest, 3) +
           " times every other sample: a glitch of the acquisition, or an impact shorter than a sample, which " + what +
           " takes as a mode's content; remove it, or keep the record on one side of it (--start, --duration)";
  return "";
}

std::string lead_in_note(const io::TimeSeries& data, const std::string& what) {
  if (std::string glitch = glitch_note(data, what); !glitch.empty()) return glitch;
  const long peak = signal::quiet_lead_in(data.values);
  if (peak < 0) return "";
  const std::string t = format_rounded(data.t0_s + static_cast<double>(peak) * data.dt_s, 4);
  // Largest in its last tenth: a growing trend (an offset that drifts quadratically: the pencil leaves it out as poles
  // of under one cycle) or a record that ends at its hit; a cut after it leaves nothing (the eighteenth pass's P8
  // advised a start at the record's last sample, and called exact damping ratios wrong).
  if (static_cast<double>(peak) >= 0.9 * static_cast<double>(data.values.size()))
    return "the record is largest at t = " + t + " s, in its last tenth: a drift that grows (which " + what +
           " fits as poles of under one cycle and leaves out) or a record that ends at a hit (which leaves no decay "
           "after it to analyse); look at the record before trusting " +
           what;
  return "the record is largest at t = " + t + " s after a quieter lead-in: it is no free decay from its start, and " +
         what +
         " fits what comes before the excitation too (its damping ratios and amplitudes are then wrong); cut the "
         "record after the excitation (--start, a little after " +
         t + " s)";
}

std::vector<std::string> modal_id_notes(const std::vector<signal::IdentifiedMode>& modes,
                                        const signal::PencilDiagnostics& found, const signal::PencilOptions& o,
                                        double record_s) {
  std::vector<std::string> notes;
  // A step in the record made mode 1's damping ratio 9x the truth, and only a side pole was noted (the eighteenth
  // pass's P7): the pencil's residual says when the record is more than decaying exponentials in white noise.
  if (found.residual_fraction > signal::kUnmodelledFraction && found.residual_lag1 > signal::kUnmodelledLag1)
    notes.push_back("the pencil's exponentials leave " + format_rounded(100 * found.residual_fraction, 2) +
                    " % of the record's RMS, and what they leave is no white noise (lag-1 correlation " +
                    format_rounded(found.residual_lag1, 2) +
                    "): the record holds what no sum of decaying oscillations does (a mode whose frequency changes "
                    "with its amplitude, a step, a clipped or saturated stretch, a drift, a second hit), which the "
                    "modes above are fitted to as well, their damping ratios first; look at the record");
  if (static_cast<int>(modes.size()) < o.modes)
    notes.push_back("--modes " + std::to_string(o.modes) + ": the record shows only " + std::to_string(modes.size()) +
                    " decaying oscillation(s) in the band: " + std::to_string(modes.size()) + " printed" +
                    (found.negligible > 0
                         ? " (" + std::to_string(found.negligible) + " more pole(s) of amplitude below " +
                               format_value(signal::kNegligibleAmplitude) +
                               " of the record's largest value are rounding, not modes)"
                         : "") +
                    (found.below_noise > 0
                         ? " (" + std::to_string(found.below_noise) +
                               " more pole(s) below the noise: white noise of the residual's sd puts as much energy "
                               "into one damped sinusoid with probability " +
                               format_value(signal::kNoiseFalseAlarm) + " or more)"
                         : ""));
  if (!found.trend_hz.empty()) {
    std::string at;
    for (double f : found.trend_hz) at += (at.empty() ? "" : ", ") + format_rounded(f, 3);
    notes.push_back("the pole(s) at " + at + " Hz, under one cycle in the " + format_rounded(record_s, 4) +
                    " s record, left out: its offset or drift, or a mode below " + format_rounded(1 / record_s, 3) +
                    " Hz that the record is too short to resolve (the eighteenth pass's P9: a 2.46 Hz mode in a 0.3 s "
                    "record was called a drift; a longer record measures it)");
  }
  // A record that still holds its pulse gave a "mode" at 422 Hz with zeta 0.81 among three asked for. Said, not
  // dropped: a heavily damped structure exists, and the user decides.
  for (const signal::IdentifiedMode& m : modes)
    if (m.damping_ratio > signal::kHeavilyDampedRatio)
      notes.push_back("the pole at " + format_rounded(m.frequency_hz) + " Hz has damping ratio " +
                      format_rounded(m.damping_ratio, 3) + " (> " + format_value(signal::kHeavilyDampedRatio) +
                      "): more likely the excitation or noise than a mode of the beam; cut the record after the "
                      "excitation (--start) or lower --order");
  // Two poles within kClosePoles of each other: one mode whose frequency changes with its amplitude (a strip's f1
  // split into 9.406 and 9.421 Hz, with nothing said: issue 31; a mode drifting from 34 to 40 Hz listed as three
  // poles 2.2-2.6 % apart: the ninth pass's d1), or two close modes (bending in two planes). Said with its size; the
  // record's later, smaller part tells which (--start). A beam's distinct bending modes lie far further apart.
  constexpr double kClosePoles = 0.05;
  for (std::size_t k = 1; k < modes.size(); ++k) {
    const signal::IdentifiedMode &a = modes[k - 1], &b = modes[k];
    if (b.frequency_hz - a.frequency_hz <= kClosePoles * a.frequency_hz &&
        a.damping_ratio <= signal::kHeavilyDampedRatio && b.damping_ratio <= signal::kHeavilyDampedRatio)
      notes.push_back("the poles at " + format_rounded(a.frequency_hz, 6) + " and " +
                      format_rounded(b.frequency_hz, 6) + " Hz are " +
                      format_rounded(100 * (b.frequency_hz / a.frequency_hz - 1), 2) +
                      " % apart: one mode whose frequency changes with its amplitude, or two close modes; the "
                      "record's later part (--start) tells which");
  }
  // A pole that neither decays nor grows over the record (matrix_pencil: kSteadyGrowth): a mains line at 50 Hz was
  // called a growing oscillation (the sixth pass's S225).
  for (const signal::IdentifiedMode& m : modes)
    if (signal::is_steady(m))
      notes.push_back("the pole at " + format_rounded(m.frequency_hz) +
                      " Hz neither decays nor grows over the record " + "(damping ratio " +
                      format_rounded(m.damping_ratio, 2) +
                      "): a steady line (mains, a driven source) or a mode too lightly damped for this record's "
                      "length to measure its damping");
  // A growing oscillation (the fourth pass's Q278: a 50 Hz oscillation growing as e^{0.31 t} was not listed and
  // nothing said so) is no free decay of a stable beam: a self-excited or driven record, or one cut before the
  // excitation ended. Named when it is at least 1 % of the largest mode (weaker ones fit the noise).
  double strongest = 0;
  for (const auto& m : modes) strongest = std::max(strongest, m.amplitude);
  for (const signal::IdentifiedMode& g : found.growing)
    if (g.amplitude >= 0.01 * strongest)
      notes.push_back("the record holds a growing oscillation at " + format_rounded(g.frequency_hz) +
                      " Hz (damping ratio " + format_rounded(g.damping_ratio, 3) + ", amplitude " +
                      format_rounded(g.amplitude, 3) +
                      " at the record's end): no mode of a stable beam decays so; it is not listed (is the record a "
                      "free decay after the excitation ended?)");
  return notes;
}

}  // namespace beamid::api
