// One measured-frequency estimator (issue 31): the frequency and uncertainty at which `modal-id`, `spikes` (beside
// its bins), a fit's modes comparison and the real-record study report a record's mode, so that the four agree.
//
// A mode's frequency is the matrix pencil's pole over the whole decay (matrix_pencil.h: near the Cramér-Rao bound at
// moderate SNR, where the three-bin DFT estimate is biased by the decay within its window). A measured beam's
// frequency is not one number, though: it changes with the amplitude (a clamp that slips, a geometric stiffening),
// and a linear model can only be asked to land within the span the record shows. The uncertainty has three parts:
//   noise: the pole's Cramér-Rao standard deviation (IdentifiedMode::frequency_sd_hz);
//   drift: the pencil run again on S consecutive equal segments of the decay, each segment's pole taken near the
//          whole record's: a frequency that changes as the amplitude decays moves from the first segment to the last
//          (the ARTS steel bar's modes by 0.1-0.6 % between windows: REPORT 2.8);
//   order: the pole at another model order of the pencil (a physical mode's pole stays put; one the exponentials
//          fit only approximately, a heavily damped or a nonlinear one, moves);
//   split: other lightly damped poles of the whole record within kSplitWindow of the mode and of at least
//          kCompanionEnergy of its energy: one mode whose changing frequency the pencil fits by several poles (an
//          aluminium strip's f1 at 9.406 and 9.421 Hz: issue 31; a decay whose frequency falls from 20.2 to 20 Hz
//          gave poles at 20.0, 20.03 and 20.19 Hz), or two close modes (bending in two planes).
// A segment's frequency is the energy-weighted mean of its poles near the mode (a single pole for a linear mode, the
// centre of the several that fit a changing frequency). The reported uncertainty is u = sqrt(noise^2 + (span / 2)^2),
// with span the largest minus the smallest of the whole record's, the segments', the other order's and the
// companions' frequencies (a segment's by what it differs from the whole record's beyond twice its own Cramér-Rao sd,
// so that its noise is not counted twice, and only where that sd is within kSegmentMaxSdBins of its bin):
// half the span is how far its ends lie from its centre.
// A model frequency within 2 u of the measured one fits it (the real-record study's verdict).
#pragma once

#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "signal/matrix_pencil.h"

namespace beamid::signal {

// Which poles are the record's modes: the K strongest (modal-id: heavily damped ones included, and said), the K
// strongest lightly damped (lightly_damped_modes: what the modal cost compares with), or those nearest chosen
// frequencies (modes_near).
enum class ModeSelection { strongest, lightly_damped };

struct MeasureOptions {
  PencilOptions pencil;                                     // K = pencil.modes, the band, the order
  ModeSelection selection = ModeSelection::lightly_damped;  // when no frequency is chosen
  std::vector<double> wanted_hz;                            // chosen frequencies (modes_near), in their order
  double window = 0.05;                                     // relative, around each chosen frequency
  int segments = 3;                                         // S, for the drift (fewer when the decay is short)
};

// A companion pole is within this relative distance of the mode: the strip's split poles were 0.2-1.8 % apart, and a
// beam's distinct bending modes are tens of percent apart (two planes of a near-square section excepted).
inline constexpr double kSplitWindow = 0.02;
// ... and holds at least this fraction of the mode's energy over the record (about 10 % of its amplitude): weaker
// poles near a strong mode are what any order fits to a decay that is not quite exponential, at a size that moves
// the mode's estimate by no more than its noise.
inline constexpr double kCompanionEnergy = 0.01;
// A segment estimates a mode only over at least this many of its cycles: one pole's frequency is estimated to far
// less than 1/T, but two poles closer than about 1/T (10 % of the frequency at 10 cycles) merge, and then the
// segment's frequency is their mean. The steel bar's f1 holds 17.7 cycles in a third of its 8 s record.
inline constexpr double kMinSegmentCycles = 10;
// A segment's pole of a mode is searched within this relative distance of the previous segment's frequency (of the
// whole record's for the first), narrowed to half the distance to a neighbouring mode.
inline constexpr double kSegmentWindow = 0.1;
// A segment's poles are the mode's only when their amplitude is within this factor of the whole record's mode
// decayed to the segment's start: an amplitude-dependent damping changes the decay rate by tens of percent over a
// record (a factor e^{0.3 x 3} = 2.5 at most over three e-folds), a different mode is another amplitude altogether.
inline constexpr double kSegmentAmplitudeFactor = 4;
// A segment's pole estimates the mode only when its Cramér-Rao sd is at most this fraction of the segment's bin 1/T:
// for a sinusoid sd_f = sqrt(3 / SNR) / (2 pi T) with SNR = A^2 n / (2 sigma^2), so 0.05 asks for SNR >= 30 (15 dB),
// above the threshold region where the estimate leaves its bound for noise peaks.
inline constexpr double kSegmentMaxSdBins = 0.05;
// The segments' pencil parameter L at most: the drift is wanted to a fraction of a percent, not to the noise's 1e-5,
// and the pencil's cost grows as L^2 (a third of the whole record's L = 599 costs a ninth).
inline constexpr int kSegmentColumns = 200;

struct MeasuredMode {
  IdentifiedMode mode;  // over the whole decay; mode.frequency_sd_hz is the noise part
  // Per segment s = 0..S-1 (the decay's consecutive S-ths): the frequency (the poles' energy-weighted mean), the
  // strongest pole's Cramér-Rao sd and the root sum of squares of the poles' amplitudes at the segment's start, NaN
  // where the segment holds fewer than kMinSegmentCycles cycles or no pole within the search window.
  std::vector<double> segment_hz, segment_sd_hz, segment_amplitude;
  std::vector<double> segment_decay_1_s;  // the poles' energy-weighted mean decay rate -Re(lambda), per segment
  double drift_hz = std::numeric_limits<double>::quiet_NaN();     // last estimated segment minus the first
  double drift_sd_hz = std::numeric_limits<double>::quiet_NaN();  // its noise sd, from the two segments' bounds
  std::vector<double> companions_hz;  // the split's other poles (kSplitWindow, kCompanionEnergy), ascending
  // The mode's pole at another model order (MeasuredModes::other_order), NaN where none: its change is in the span.
  double order_hz = std::numeric_limits<double>::quiet_NaN();
  int segments_due = 0, segments_found = 0;  // segments holding kMinSegmentCycles of it; those that estimated it
  double span_low_hz = 0, span_high_hz = 0;  // the smallest and largest of all the estimates above
  double uncertainty_hz = std::numeric_limits<double>::quiet_NaN();  // u (the file's head)
  // The decay rate's uncertainty, 1/s, alike: sqrt(noise^2 + (span / 2)^2) over the whole record's and the segments'
  // decay rates (an amplitude-dependent damping; a segment's by what it differs beyond twice its own noise, as for
  // the frequencies), its noise part the Cramér-Rao bound, which for one damped mode equals the angular frequency's
  // (matrix_pencil.h: damped_mode_frequency_sd). Companions are not in its span: a pole that fits a changing
  // frequency takes whatever decay rate fits best. Over 36 noise draws of a four-mode record (1 % noise) u matches
  // the damping ratios' scatter within 0.9-1.05 for every mode but the weakest, lowest one (2.46 Hz, 1.5 on the full
  // 8.2 s record): with the pencil's width capped at L = 599 of 8,192 samples (1.5 of its periods) the pencil is
  // not efficient for it, and its frequency scatters 1.3 times its bound too.
  double decay_uncertainty_1_s = std::numeric_limits<double>::quiet_NaN();
  // |drift| > 3 drift_sd: the frequency changes with the amplitude beyond what noise does.
  bool drifts() const;
  // The damping ratio's uncertainty, zeta = sigma / |lambda|: the decay rate's over |lambda| (|lambda|'s own is
  // smaller by zeta and left out). modal-id printed damping ratios without one, which scatter by +-20 % on a record
  // of two cycles (the eighteenth pass's P6).
  double damping_ratio_uncertainty() const { return decay_uncertainty_1_s / std::abs(mode.lambda); }
};

struct MeasuredModes {
  std::vector<MeasuredMode> modes;  // ascending in frequency (chosen frequencies: in their order)
  PencilDiagnostics diagnostics;    // the whole record's pencil
  int heavily_damped = 0;           // poles left out by ModeSelection::lightly_damped
  int segments = 0;                 // S used (0: the decay is too short for two segments of kMinWindowSamples)
  int other_order = 0;              // the second model order the modes were sought at (0: none)
};

// The modes of the decay sampled at dt_s with their uncertainty. InputError as matrix_pencil (and modes_near for a
// chosen frequency that has no mode).
MeasuredModes measure_modes(const std::vector<double>& decay, double dt_s, const MeasureOptions& options);

// A free decay is largest within its first cycle. The index of a record's largest |y| when what comes before it is a
// quieter lead-in (the first half of the samples before it holds a mean |y| under 10 % of it; a decay from rest has
// 37 % there at the least: the mean of sin over its first eighth of a period), or -1: the record is then no free decay
// from its start, and a pencil or a free-decay fit of it fits the rise as well (the whole real steel record gave
// damping ratios 100 to 3600 times too low: the sixth pass's S434; a hammer hit left in gave EI 4.5 % off: the
// seventh pass's RU09). modal-id, fit and real say so.
long quiet_lead_in(const std::vector<double>& y);

// The smallest segment, in samples (as a window fit's: fit/window_spread.h).
inline constexpr int kMinSegmentSamples = 256;

// A span a user is told about: 0.1 % of the frequency, the size of a frequency's error that moves a stiffness
// estimate by 0.2 % (EI ~ f^2), beyond a careful test's other errors. Smaller drifts still widen u.
inline constexpr double kNotableSpan = 1e-3;

// One line on what widens a mode's uncertainty beyond its noise, when its span is at least kNotableSpan of its
// frequency: the drift between the first and the last segment with the amplitudes it fell between, and the close
// poles that fit it; "" otherwise. For modal-id's and fit's notes.
std::string uncertainty_note(const MeasuredMode& m);

}  // namespace beamid::signal
