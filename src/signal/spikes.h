// Spikes of a DFT magnitude spectrum, as the paper reads plainly (model.md section 4), and sub-bin pole estimates.
//
// Peak rule "largest" (default): the local maxima of |Z|, i.e. bins 1 <= k <= Nbar/2 with
//   |Z(k)| > |Z(k-1)| and |Z(k)| >= |Z(k+1)|   (Z(Nbar/2 + 1) read through the full DFT, = conj Z(Nbar/2 - 1)),
// the NM largest of them, reported in order of frequency. Rule "prominence" ranks the same maxima by their prominence
// (height above the higher of the two minima between the peak and the nearest higher maximum, or the band edge, on
// either side) instead of their height, which keeps a rectangular window's sidelobes out. A band [min, max] Hz
// restricts the candidates either way.
// 20 % support (from the data only): n_l = the last i with |Z(k - i')| >= level |Z(k)| for every 0 <= i' <= i,
// the search stopping at k = 0; N_l likewise to the right, stopping at Nbar/2.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/names.h"
#include "signal/spectrum.h"

namespace beamid::signal {

struct SpikeOptions {
  int count = 4;                 // NM
  std::string rule = "largest";  // "largest" | "prominence"
  double min_frequency_hz = 0;   // candidates restricted to [min, max]
  double max_frequency_hz = std::numeric_limits<double>::infinity();
  double support_level = 0.2;  // the paper's 20 %
  // Chosen spikes (real records hold modes a model lacks, such as torsion, and mains lines): when not empty, the
  // spikes are the largest local maxima within +-frequency_window (relative) of each of these frequencies, and
  // count is their number; `rule` and the band are not used.
  std::vector<double> frequencies_hz;
  double frequency_window = 0.05;
  // Measured records (label_peaks below): a candidate at an integer multiple of a stronger peak, at a stronger peak
  // plus or minus a stronger lower one, or at the offset's leakage is labelled and skipped. Off for synthetic records.
  bool reject_artefacts = false;
};
// First violated constraint ("spikes = 0: must be >= 1"), or nothing.
std::optional<std::string> validation_error(const SpikeOptions& options);

struct Spike {
  int bin = 0;              // k
  double frequency_hz = 0;  // f_k = k df
  double magnitude = 0;     // |Z(k)|
  int n_left = 0;           // n_l
  int n_right = 0;          // N_l
};

// All local maxima of |Z| in 1..Nbar/2 - 1 (ascending bins). The last bin Nbar/2 (Nyquist for an even Nbar) is a band
// edge: a maximum there cannot be told from a peak above Nyquist folded back, and was reported as a spike with
// N_l = 0 (the second adversarial pass's N359).
std::vector<int> local_maxima(const Spectrum& spectrum);
// The support (n_l, N_l) of the peak at bin k at `level` times its height.
std::pair<int, int> support(const Spectrum& spectrum, int bin, double level);
// The NM spikes by the rule, ascending in frequency, with their supports. Fewer when fewer maxima exist.
std::vector<Spike> detect_spikes(const Spectrum& spectrum, const SpikeOptions& options);
// For messages, when detect_spikes found fewer spikes than options.frequencies_hz: the chosen frequencies no picked
// spike lies within frequency_window of, as "116.9, 5000 Hz (above the Nyquist frequency 826 Hz)"; when every one has
// a spike nearby, that two of them share one maximum.
std::string unmatched_frequencies(const std::vector<Spike>& picked, const SpikeOptions& options,
                                  const Spectrum& spectrum);

// The candidates of the "largest" or "prominence" rule in the order of that rule, each with the reason it was skipped
// ("" for a pick), down to the last pick (so that a user sees why a higher peak was passed over). With
// reject_artefacts, a candidate is skipped when (frequencies and decay rates sigma the three-bin estimates; within
// max(0.2 %, 0.75 bins) of its frequency, and only where that is at most 1 % of it: a coarser spectrum cannot tell a
// harmonic from a mode) it is
//   "side lobe of F Hz":       2-10 bins from a stronger peak F and below 1.5 |Z(F)| / (pi |k - k_F|), the
//                              rectangular window's leakage envelope;
//   "harmonic n of F Hz":      at n F for any n >= 2 below Nyquist, F a stronger peak not itself skipped, decaying at
//                              n sigma_F within 25 % or three sd of the rates' estimates (a nonlinearity, a clipped or
//                              rattling sensor; a beam's own modes are not integer multiples, and a mode near one
//                              decays at its own rate), of an amplitude at most 0.15 of F's (from the peaks' heights
//                              and rates: a mode at n F with F's damping ratio also decays at n sigma_F, and is as
//                              strong as a mode), and only where a chance coincidence is unlikely (2 x the tolerance
//                              below 5 % of F);
//   "sideband F1 +- F2 Hz":    at F1 + F2 or F1 - F2 for stronger peaks F1 > F2, decaying at sigma_1 + sigma_2 within
//                              the same tolerance (modulation, beating);
//   "offset leakage":          bin 1, one cycle in the record (what remains of an offset or a drift after detrending).
// A rate that cannot be estimated (a flat top, Welch's average) or that is too uncertain to tell (three sd above half
// the expected rate) keeps the peak: a peak is skipped only on evidence that it behaves as an artefact.
// The picks are the first `count` candidates not skipped. Chosen frequencies (frequencies_hz) are never skipped.
struct LabelledPeak {
  Spike spike;
  std::string skipped;  // why it was not picked ("" when it was)
};
std::vector<LabelledPeak> label_peaks(const Spectrum& spectrum, const SpikeOptions& options);

// Welch's averaged spectrum for picking: `segments` Hann-windowed segments of equal length overlapping by half, the
// magnitude of each bin the root mean square of theirs (a frequency resolution `segments`/2 + 1/2 times coarser than
// the whole record's, and a noise floor whose scatter falls as 1/sqrt(segments)). Its phases are 0: only for
// picking. InputError for segments < 2 or a segment shorter than 16 samples.
Spectrum welch_spectrum(const std::vector<double>& values, double dt_s, int segments);

// The record less its least-squares offset ("mean") or offset and linear trend ("linear"); "none" returns it as is.
// A free decay has no offset of its own: what the sensor or the DAQ adds would leak into the lowest bins.
inline const std::string kDetrendNone = "none";
inline const std::string kDetrendMean = "mean";
inline const std::string kDetrendLinear = "linear";
const core::NameSet& detrend_names();  // the registry every reader of a detrend mode uses
// InputError "detrend = 'x': must be one of none, mean, linear" for another mode.
std::vector<double> detrend(std::vector<double> values, const std::string& mode);

// Sub-bin pole estimate from the complex 3-bin ratio (Jacobsen), R = (Z(k-1) - Z(k+1)) / (2 Z(k) - Z(k-1) - Z(k+1)):
// for a sampled damped exponential e^{(j 2 pi f - sigma) t} on the rectangular window, Z(k) ~ 1/(f/df - k + j sigma
// T/(2 pi)) near the pole, which makes R = (f/df - k) + j sigma T / (2 pi) exactly in that approximation; Candan's
// factor tan(pi/Nbar)/(pi/Nbar) on Re R removes most of the bias of the small-angle step. With another window the
// estimates are still a smooth, consistent feature (the same on data and model) but biased by the window.
struct PoleEstimate {
  double frequency_hz = 0;
  double decay_rate_1_s = 0;  // sigma (the exponential window's alpha/T is not removed)
  bool ok = false;            // false when the denominator vanishes (a flat spectrum)
};
PoleEstimate three_bin_estimate(const Spectrum& spectrum, int bin);
// The first-order change of that estimate when the spectrum changes by `change` (a spectrum of the same length, e.g.
// the DFT of d y / d q): dR = [(da - dc) D - (a - c)(2 db - da - dc)] / D^2 with D = 2b - a - c, then the same
// linear maps to frequency and decay rate. Only where three_bin_estimate is ok.
PoleEstimate three_bin_change(const Spectrum& spectrum, const Spectrum& change, int bin);

// The Cramér-Rao bound on the angular frequency (rad/s) of one damped mode A e^{-alpha t} cos(omega t + phi), sampled
// at t_i = i dt, i = 0..samples-1, in white Gaussian noise of standard deviation noise_sd (Yao & Pandit 1995, many
// cycles: the oscillating sums, of relative size alpha / omega, neglected). With S_k = sum_i t_i^k e^{-2 alpha t_i},
//   var(omega_hat) = var(alpha_hat) = 2 noise_sd^2 S0 / (A^2 (S0 S2 - S1^2)),
// the same for the decay rate alpha. For alpha >= 0 and samples >= 2.
double damped_mode_frequency_sd(double amplitude, double decay_rate_1_s, double dt_s, int samples, double noise_sd);

}  // namespace beamid::signal
