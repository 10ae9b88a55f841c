#include "api/record_requests.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/errors.h"
#include "io/units.h"

namespace beamid::api {

signal::PoleEstimate SpikesResult::subbin(int bin) const {
  signal::PoleEstimate e;
  if (!welch) e = signal::three_bin_estimate(spectrum, bin);
  if (!e.ok || std::abs(e.frequency_hz - spectrum.frequency_hz(bin)) > spectrum.df_hz())
    e = {std::nan(""), std::nan(""), false};
  return e;
}

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
  SpikesResult r;
  const signal::SpikeOptions options = spike_options(request.spikes, caller);
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
  if (!measured.empty() && !predicted.empty() && measured != predicted)
    refuse(caller, "--prediction = '" + prediction.path + "': in " + prediction.unit + ", a " + predicted +
                       ": the data are in " + data.unit + ", a " + measured + " (compare like with like)");
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
    refuse(caller, "max-frequency", format_value(o.max_frequency_hz), "must exceed --min-frequency");
  try {
    r.modes = signal::matrix_pencil(data.values, data.dt_s, o);
  } catch (const InputError& error) {
    refuse(caller, "--data = '" + data.path + "': " + error.what());
  }
  return r;
}

}  // namespace beamid::api
