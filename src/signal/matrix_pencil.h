// Modal identification of a free decay by the matrix pencil method (Hua & Sarkar, IEEE Trans. ASSP 38, 1990;
// ../shared/docs/comparison.md section 5), the practitioners' first step before updating a physical model.
//
// A sampled free decay is a sum of damped complex exponentials, y_i = sum_k c_k z_k^i with z_k = e^{lambda_k dt}.
// With the Hankel matrix Y(i, j) = y_{i+j} (pencil parameter L columns minus one), Y = A diag(c) B^T where B(j, k) =
// z_k^j, so the M dominant right singular vectors V span the columns of B. V1 and V2 (V without its last and without
// its first row) then satisfy V2 = V1 T^-1 Z T, and the eigenvalues of pinv(V1) V2 are the z_k: exact for a noise-free
// signal of at most M exponentials, and near the Cramér-Rao bound at moderate SNR (Hua & Sarkar). The SVD truncation
// at M filters the noise; the amplitudes c_k follow by linear least squares on the whole record.
//
// Chosen over ESPRIT (the same subspace idea with a TLS step) and Prony (noise-sensitive polynomial rooting) for its
// robustness to noise at a cost of one SVD. Reported per mode: natural frequency |lambda| / (2 pi) and damping ratio
// -Re(lambda) / |lambda|, as `beamid modes` reports the model's, so that the two compare directly.
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "signal/noise.h"

namespace beamid::signal {

// A lightly damped beam's modes have damping ratios of a few percent; an identified pole far above that (0.2) fits
// the excitation or noise more likely than a mode: modal-id says so, and a fit's mode comparison leaves it out.
inline constexpr double kHeavilyDampedRatio = 0.2;

struct PencilOptions {
  int modes = 3;          // K: the K strongest underdamped modes in the band are reported
  int order = 0;          // M, the number of exponentials kept (0: the record's, model_order)
  int max_columns = 600;  // L + 1 at most (the SVD costs ~ Nbar L^2): L = min(Nbar / 3, max_columns - 1)
  double min_frequency_hz = 0;
  double max_frequency_hz = std::numeric_limits<double>::infinity();
};

// The pencil parameter L = min(Nbar / 3, max_columns - 1) for a record of `samples` samples, and the model order M
// matrix_pencil uses on the record y (for callers that run it at another order): options.order when given, else the
// larger of 2 K + 8 and the exponentials a clean record holds (significant_order), capped at L.
// 2 K + 8 alone was too few on a record of more modes than K: --modes 1 above 300 Hz on a noise-free record of four
// modes gave zeta 2.3 times the truth and the frequency 1.15 Hz off, mode 1's zeta 12 % high (the seventeenth
// pass's P2).
int pencil_columns(const PencilOptions& options, int samples);
int model_order(const PencilOptions& options, const std::vector<double>& y);
// The exponentials a clean record holds: the count of the Hankel matrix's singular values before their last gap of a
// factor kSingularGap or more (among the first kMaxRecordOrder, above kNegligibleAmplitude of the largest), 0 where
// they fall without one (a measured record's, or a noisy one's).
int significant_order(const std::vector<double>& y, const PencilOptions& options);
inline constexpr double kSingularGap = 10;
inline constexpr int kMaxRecordOrder = 64;  // 32 modes: the amplitudes' least squares costs Nbar M^2

struct IdentifiedMode;
// The modes of chosen frequencies (a record may hold modes a model lacks, such as torsion): the pencil is run over
// the band the choices span (each widened by +-window, relative) for 3 K + 4 modes, and the strongest within +-window
// of each wanted frequency is kept, in the order of `wanted_hz`. InputError naming a frequency that has none.
// `diagnostics`, when given, is the pencil's, with the poles not chosen in `weaker`.
struct PencilDiagnostics;
// Only poles of damping ratio at most `max_damping_ratio` are candidates (lightly_damped_modes: kHeavilyDampedRatio).
std::vector<IdentifiedMode> modes_near(const std::vector<double>& decay, double dt_s, PencilOptions options,
                                       const std::vector<double>& wanted_hz, double window,
                                       PencilDiagnostics* diagnostics = nullptr,
                                       double max_damping_ratio = std::numeric_limits<double>::infinity());

struct IdentifiedMode {
  double frequency_hz = 0;      // |lambda| / (2 pi)
  double damping_ratio = 0;     // -Re(lambda) / |lambda|
  double amplitude = 0;         // of the real mode: 2 |c_k| (y_i contains 2 Re(c_k z_k^i))
  double phase_rad = 0;         // arg c_k
  std::complex<double> lambda;  // rad/s, Im > 0
  // The Cramér-Rao bound on the frequency (Hz) of this mode alone in white noise of the pencil's residual sd (all M
  // exponentials fitted, n - 2 M degrees of freedom): what no unbiased estimator beats, and what the pencil attains
  // near moderate SNR with L near Nbar / 3 (Hua & Sarkar). With L capped (max_columns) on a long record a lightly
  // damped mode's scatter is up to 1.9 times it (2.46 Hz, 8192 samples, L = 599: the seventeenth pass's P3), which a
  // maximum-likelihood refinement of the poles would remove. Neighbouring modes and model error add to it.
  double frequency_sd_hz = std::numeric_limits<double>::quiet_NaN();
};

// An identified pole whose amplitude is below this fraction of the record's largest |y| is rounding, not a mode: no
// recorder resolves it (a 24-bit converter resolves 1.2e-7 of its full scale), and the amplitudes' least squares
// leaves ~1e-13 of it in poles that fit nothing (a noise-free record of one mode gave "modes" of amplitude 1e-17).
inline constexpr double kNegligibleAmplitude = 1e-9;

// A pole whose amplitude grows by at most this factor over the whole record is steady, not growing (matrix_pencil).
inline constexpr double kSteadyGrowth = 1.1;

// A pole neither decays nor grows measurably when its decay rate -Re(lambda) is within three of its Cramér-Rao sds
// (for one damped mode the decay rate's bound equals the angular frequency's) of 0, or within kSteadyRounding of
// |lambda| on a noise-free record: a steady line (mains, a driven source) or a mode too lightly damped for the record's
// length. A noise-free steady sine came out at zeta +4.5e-16 or -6.4e-16 as rounding decided, listed as a mode without
// a word in the first case (the seventh pass's F02).
inline constexpr double kSteadyRounding = 1e-9;
bool is_steady(const IdentifiedMode& m);

// What the pencil found besides the modes it reports.
// A pole of fewer cycles than this over the record is its offset or drift, never a mode (matrix_pencil.cc).
inline constexpr double kTrendCycles = 1;
struct PencilDiagnostics {
  // oscillatory poles in the band that grow (damping ratio < 0), not negligible, of two cycles in the record or more
  std::vector<IdentifiedMode> growing;
  int negligible = 0;   // decaying poles in the band dropped as negligible (kNegligibleAmplitude)
  int below_noise = 0;  // decaying poles in the band dropped as below the noise (kNoiseFalseAlarm)
  // Poles in the band, not negligible, of under kTrendCycles in the record (their natural frequencies): its offset or
  // drift, or a mode too slow for the record to resolve.
  std::vector<double> trend_hz;
  // Decaying poles in the band, above the noise, that were not reported: weaker than the K reported (ascending in
  // frequency). What measured_modes reads for a mode split into close poles.
  std::vector<IdentifiedMode> weaker;
  // What the M exponentials leave of the record: the residual's sd over the record's RMS, and the residual's lag-1
  // autocorrelation (about 0 for white noise, near 1 for a step, and for an unmodelled low mode sampled finely: the
  // steel record's amplitude-dependent 6.6 Hz mode from 2 s on, 12 %, at 1,652 Hz, the nineteenth pass's U1). A record
  // that is a sum of decaying exponentials in white noise leaves its noise (1 % noise: 0.011 and -0.02); the measured
  // records leave a few % of coloured residual (the steel record 0.07 and 0.14, the UnB records 0.02-0.04 and
  // 0.13-0.91); a step of 3 x the record's RMS 0.85 and 0.98 (the eighteenth pass's P7).
  double residual_fraction = 0, residual_lag1 = 0;
  // The residual's colour: an AR model of it of order up to 16 by Akaike's criterion (signal::fit_autoregressive;
  // white where it picks order 0). What the pencil's uncertainties and noise threshold, which take the residual as
  // white, miss in coloured noise (apps/fit_report.cc).
  NoiseModel residual_colour;
};
// The residual above which a record is said to hold more than decaying exponentials: over kUnmodelledFraction of
// its RMS, and slowly varying (lag-1 autocorrelation over kUnmodelledLag1).
inline constexpr double kUnmodelledFraction = 0.1;
inline constexpr double kUnmodelledLag1 = 0.5;

// A decaying pole is a mode only if its energy over the record, sum_i (2 Re c z^i)^2 ~ |c|^2 2 sum |z|^2i, exceeds
// what white noise of the residual's sd sigma puts into the best-fitting damped sinusoid with this probability. The
// noise's projection on one sinusoid of given frequency (two quadratures) has energy sigma^2 chi^2_2, whose tail is
// e^{-x / 2 sigma^2}; over the record's ~n/2 independent frequencies, and a factor 2 for the free decay rate, the
// largest exceeds x = 2 sigma^2 ln(n / p) with probability p. On a record of one 50 Hz mode and 1 % white noise the
// pencil listed poles at 397 and 409 Hz of amplitude 5e-4 (zeta 0.01 %) as modes 2 and 3 (the fifth pass's R178);
// an undamped mode of amplitude sigma over 1000 samples, 18 times the threshold, is kept.
inline constexpr double kNoiseFalseAlarm = 1e-3;

// The modes a fit compares with (the modal cost, a fit's modes comparison): those of chosen frequencies (modes_near,
// lightly damped ones only: a pole of zeta 0.44 from a hammer hit left in the record was paired with the chosen
// 164 Hz, EI 4.5 % off: the seventh pass's RU09) when `wanted_hz` is given; else the K = options.modes strongest
// decaying modes of damping ratio at most kHeavilyDampedRatio, from a pencil asked for K + 4 (the pulse's 447 Hz pole
// at zeta 0.83 was paired with a beam mode, EI 2.4 % off and "converged": the sixth pass's S212). `heavily_damped`,
// when given, counts the poles left out. `diagnostics`, when given, is the pencil's, with the lightly damped poles not
// chosen in `weaker`.
std::vector<IdentifiedMode> lightly_damped_modes(const std::vector<double>& decay, double dt_s, PencilOptions options,
                                                 const std::vector<double>& wanted_hz, double window,
                                                 int* heavily_damped = nullptr,
                                                 PencilDiagnostics* diagnostics = nullptr);

// A^2 sum_{i<n} |z|^2i with A = 2 |c| and z = e^{lambda dt}: twice the real mode's sum of squares over n samples, the
// strength by which modes are ranked (a heavily damped pole with a large initial amplitude does not outrank a
// lasting mode).
double mode_energy(const IdentifiedMode& m, double dt_s, int n);

// The modes of the record y sampled at dt_s, sorted by frequency (fewer than K when fewer decaying oscillatory poles
// of more than negligible amplitude lie in the band). A growing oscillation is no mode of a stable beam and is not
// reported as one; `diagnostics`, when given, lists it. InputError for options or a record that cannot support them
// (too short for M, non-finite).
std::vector<IdentifiedMode> matrix_pencil(const std::vector<double>& y, double dt_s, const PencilOptions& options,
                                          PencilDiagnostics* diagnostics = nullptr);

}  // namespace beamid::signal
