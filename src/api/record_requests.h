// The requests that compute from a record alone (no model): beamid spikes, cost (of a given prediction) and
// modal-id. The record comes read (io::TimeSeries: a file through the import options, or an array); each compute
// function validates the request against it and returns values.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "api/cost_request.h"
#include "api/request.h"
#include "costs/cost.h"
#include "io/time_series.h"
#include "signal/matrix_pencil.h"
#include "signal/measured_modes.h"
#include "signal/spectrum.h"
#include "signal/spikes.h"

namespace beamid::api {

// beamid spikes: every peak of the (detrended) record's spectrum with its label, and the picks (no label) by bin.
struct SpikesRequest {
  Caller caller{"beamid spikes"};
  SpikeRequest spikes;
  WindowRequest window;                // not with welch (its segments are Hann-windowed)
  std::optional<std::string> detrend;  // --detrend (default linear: a record read from a file is a measured one)
  std::optional<int> welch;            // --welch K: Welch's average of K segments instead of the record's DFT
};
struct SpikesResult {
  signal::Spectrum spectrum;
  std::vector<signal::LabelledPeak> peaks;
  std::vector<signal::Spike> picks;
  int requested = 0;   // spikes.count
  bool welch = false;  // the spectrum is Welch's average (magnitudes only)
  // The sub-bin frequency and decay rate of the peak at `bin` (the three-bin estimate, signal/spikes.h): a bin's
  // frequency is up to half a bin off (4.293 against 4.268 Hz). NaN on Welch's average (it has no phases) or where
  // the estimate fails or strays beyond a bin; a negative decay rate (leakage, not a decay) is NaN too.
  signal::PoleEstimate subbin(int bin) const;
  // Per pick, its mode by the measured-frequency estimator that modal-id, fit and real share (signal/measured_modes.h:
  // the matrix pencil's pole nearest the pick, with its uncertainty); mode.frequency_hz NaN where none was measured,
  // and then `measured_note` says why. Notes on what widens a pick's uncertainty follow in `notes`.
  std::vector<signal::MeasuredMode> measured;
  std::string measured_note;
  std::vector<std::string> notes;
};
SpikesResult compute_spikes(const SpikesRequest& request, const io::TimeSeries& data);

// beamid cost: the cost of a prediction (same length and step as the data) against the data.
struct CostEvaluationRequest {
  Caller caller{"beamid cost"};
  CostRequest cost;
};
costs::Evaluation compute_cost(const CostEvaluationRequest& request, const io::TimeSeries& data,
                               const io::TimeSeries& prediction);

// beamid modal-id: the modes of a free decay by the matrix pencil, with the options the request gave.
struct ModalIdRequest {
  Caller caller{"beamid modal-id"};
  std::optional<int> modes;                // --modes K
  std::optional<int> order;                // --order M
  std::optional<double> min_frequency_hz;  // --min-frequency
  std::optional<double> max_frequency_hz;  // --max-frequency
};
struct ModalIdResult {
  signal::PencilOptions options;
  std::vector<signal::IdentifiedMode> modes;
  // The same modes with their uncertainty (signal/measured_modes.h: noise, drift between segments, close poles), the
  // frequency every command reports as measured.
  std::vector<signal::MeasuredMode> measured;
  // What the modes do not say: fewer than K found, a pole more likely the excitation than a mode, a growing
  // oscillation (no mode of a stable beam), one line each without the command's name.
  std::vector<std::string> notes;
};
ModalIdResult compute_modal_id(const ModalIdRequest& request, const io::TimeSeries& data);
// signal::quiet_lead_in in words, naming `what` fits the record ("the pencil", "a free-decay fit"), or a single
// sample over 10 times every other (a glitch, which the lead-in advice would misplace), or "".
std::string lead_in_note(const io::TimeSeries& data, const std::string& what);
// The glitch part of lead_in_note alone, for a record that is no free decay (a pulse fit's): "" when none.
std::string glitch_note(const io::TimeSeries& data, const std::string& what);
// A window that opens after the record's modes have died out: their spikes are then the noise's (magnitudes raised by
// it, decay rates its), and a spike cost's damping goes light (signal::window_snr_retention). Said for the mode the
// window serves worst, when it keeps under kWindowRetention of that mode's signal-to-noise ratio; "" otherwise, and
// for the rectangular window.
inline constexpr double kWindowRetention = 0.1;
std::string window_transient_note(const signal::WindowOptions& window, std::size_t samples, double dt_s,
                                  const std::vector<signal::MeasuredMode>& modes);
// "the record is in V, a raw sensor signal ...: its <what> are in V ..." for a record in a unit of no motion (V, mV, N,
// Pa), which spikes and modal-id read (their frequencies do not depend on the unit) and report in that unit; else "".
std::string raw_signal_note(const io::TimeSeries& data, const std::string& what);
// A record of fewer than io::kFineQuantisation steps over its peak (under 10 bits over its range), said with its step:
// a 5-bit record (32 levels), accepted once it was no longer taken for a dropout (the nineteenth pass's P4), listed a
// steady 17.2 Hz line, a growing 12.3 Hz one and mode 1 with a negative damping ratio. "" otherwise, and "" when the
// record has fewer than kMinQuantisationSamples samples or its steps are not whole numbers of its smallest one (no
// grid: a few full-precision samples).
inline constexpr std::size_t kMinQuantisationSamples = 64;
std::string quantisation_note(const io::TimeSeries& data);
// The frequencies above a resampled record's pass band (io::TimeSeries::pass_band_hz) named, with why they are no
// modes ("" when none is); `what` is "pole" or "spike".
std::string pass_band_note(const io::TimeSeries& data, const std::vector<double>& frequencies_hz,
                           const std::string& what);
// The notes of ModalIdResult for the modes the pencil reported and what else it found, in a record of record_s.
std::vector<std::string> modal_id_notes(const std::vector<signal::IdentifiedMode>& modes,
                                        const signal::PencilDiagnostics& found, const signal::PencilOptions& options,
                                        double record_s);

}  // namespace beamid::api
