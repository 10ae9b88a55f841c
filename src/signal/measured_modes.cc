#include "signal/measured_modes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/errors.h"

namespace beamid::signal {

namespace {

// The whole decay's modes by the selection (the same poles modal-id, the modal cost and a fit's modes comparison
// report), with the pencil's diagnostics.
std::vector<IdentifiedMode> whole_record_modes(const std::vector<double>& decay, double dt_s, const MeasureOptions& o,
                                               MeasuredModes& out) {
  if (o.selection == ModeSelection::strongest && o.wanted_hz.empty())
    return matrix_pencil(decay, dt_s, o.pencil, &out.diagnostics);
  return lightly_damped_modes(decay, dt_s, o.pencil, o.wanted_hz, o.window, &out.heavily_damped, &out.diagnostics);
}

// The relative window a segment's pole of mode k is searched in: the chosen window, narrowed to half the distance to
// the neighbouring modes so that two modes never take one pole.
double search_window(const std::vector<IdentifiedMode>& modes, std::size_t k, double window) {
  double w = window;
  for (std::size_t j = 0; j < modes.size(); ++j)
    if (j != k) w = std::min(w, 0.5 * std::abs(modes[j].frequency_hz / modes[k].frequency_hz - 1));
  return w;
}

// The pencil's poles of y within [low, high] Hz (narrowed to the options' band), or none where it cannot run (too
// short a segment for its order, a segment of zeros at the end of a decay): a part of the uncertainty that is not
// measured, which the notes say, rather than a failed command.
std::optional<std::vector<IdentifiedMode>> poles_between(const std::vector<double>& y, double dt_s, PencilOptions p,
                                                         double low, double high) {
  p.min_frequency_hz = std::max(p.min_frequency_hz, low);
  p.max_frequency_hz = std::min(p.max_frequency_hz, high);
  try {
    return matrix_pencil(y, dt_s, p);
  } catch (const InputError&) {
    return std::nullopt;
  } catch (const NumericalError&) {
    return std::nullopt;
  }
}

// Each mode's pole in segment s of length `length` (its frequency, sd and amplitude), NaN where the segment is too
// short for the mode or the pencil finds none near it. A segment the pencil cannot take (too short for its order, a
// zero segment at the end of a decay) estimates nothing.
void estimate_segment(const std::vector<double>& decay, double dt_s, const MeasureOptions& o, int s, int length,
                      MeasuredModes& out) {
  const auto begin = decay.begin() + static_cast<std::ptrdiff_t>(s) * length;
  const std::vector<double> segment(begin, begin + length);
  PencilOptions p = o.pencil;
  p.max_columns = std::min(p.max_columns, kSegmentColumns);
  p.order = 0;
  // Each mode is followed from segment to segment: searched around the last segment's frequency that was found
  // (the whole record's before), within kSegmentWindow, so that a frequency that moves by more than the window over
  // the record is still followed (a decay from 24 to 20 Hz lost its later segments at +-5 % of its mean, and its
  // drift went unmeasured: the eighth pass's M47).
  std::vector<IdentifiedMode> centres;
  for (const MeasuredMode& m : out.modes) {
    IdentifiedMode c = m.mode;
    for (int before = s - 1; before >= 0; --before)
      if (const double f = m.segment_hz[static_cast<std::size_t>(before)]; std::isfinite(f)) {
        c.frequency_hz = f;
        break;
      }
    centres.push_back(c);
  }
  double low = std::numeric_limits<double>::infinity(), high = 0;
  for (const IdentifiedMode& c : centres) {
    low = std::min(low, c.frequency_hz * (1 - kSegmentWindow));
    high = std::max(high, c.frequency_hz * (1 + kSegmentWindow));
  }
  p.modes = 3 * static_cast<int>(out.modes.size()) + 4;
  const auto poles = poles_between(segment, dt_s, p, low, high);
  if (!poles) return;
  const std::vector<IdentifiedMode>& found = *poles;
  for (std::size_t k = 0; k < out.modes.size(); ++k) {
    MeasuredMode& m = out.modes[k];
    if (m.mode.frequency_hz * length * dt_s < kMinSegmentCycles) continue;
    ++m.segments_due;
    const double centre = centres[k].frequency_hz, w = search_window(centres, k, kSegmentWindow);
    const IdentifiedMode* best = nullptr;
    double weighted = 0, decay = 0, total = 0, squares = 0;
    for (const IdentifiedMode& f : found) {
      if (std::abs(f.frequency_hz / centre - 1) > w || f.damping_ratio > kHeavilyDampedRatio) continue;
      const double e = mode_energy(f, dt_s, length);
      weighted += e * f.frequency_hz, decay -= e * f.lambda.real(), total += e, squares += f.amplitude * f.amplitude;
      if (!best || f.amplitude > best->amplitude) best = &f;
    }
    if (!best) continue;
    // The same mode, not a weaker neighbour that outlasts it: the segment's amplitude within kSegmentAmplitudeFactor
    // of the whole record's mode decayed to the segment's start (the steel bar's 116.9 Hz mode, decayed to 6e-5 of
    // its start by the last third, left a neighbour at 119.9 Hz of 7e-4 there, read as a 2.6 % drift).
    const double expected = m.mode.amplitude * std::exp(m.mode.lambda.real() * s * length * dt_s);
    const double amplitude = std::sqrt(squares);
    if (!(amplitude <= kSegmentAmplitudeFactor * expected && amplitude >= expected / kSegmentAmplitudeFactor)) continue;
    // Above the noise by enough to be the mode's and not a pole the noise put near it: below about 15 dB of effective
    // SNR a frequency estimate leaves its Cramér-Rao bound for outliers anywhere in the window (the threshold effect),
    // and a decayed segment's 86.06 Hz pole on a linear record's 85.63 Hz mode was read as an amplitude-dependent
    // frequency, with u 500 times its scatter (the seventeenth pass's P3).
    if (!(best->frequency_sd_hz * length * dt_s <= kSegmentMaxSdBins)) continue;
    const auto i = static_cast<std::size_t>(s);
    m.segment_hz[i] = weighted / total;
    m.segment_sd_hz[i] = best->frequency_sd_hz;
    m.segment_amplitude[i] = amplitude;
    m.segment_decay_1_s[i] = decay / total;
    ++m.segments_found;
  }
}

// The pencil's model order M for these options (matrix_pencil's default where none is given), and another one: the
// poles of a physical mode stay where they are when M changes, a fit of noise or of a decay that is no sum of
// exponentials moves (a stabilisation diagram's test). The UnB bar's 160 Hz mode, damped at 16 %, came out at 164.2
// or 165.1 Hz as the other peaks asked for changed M (the eighth pass's KS14.3_26_164).
int pencil_order(const MeasureOptions& o, const std::vector<double>& decay) {
  PencilOptions asked = o.pencil;  // the modes the selection asks the pencil for (lightly_damped_modes, modes_near)
  const int k = static_cast<int>(o.wanted_hz.size());
  asked.modes = !o.wanted_hz.empty()                      ? 3 * k + 4
                : o.selection == ModeSelection::strongest ? o.pencil.modes
                                                          : o.pencil.modes + 4;
  return model_order(asked, decay);
}

// Each mode's pole at another model order (M + max(4, M / 2), or fewer when M is already the largest the record
// allows): the strongest lightly damped pole within the search window of the mode. NaN where none, or where the
// record cannot take another order.
void other_order(const std::vector<double>& decay, double dt_s, const MeasureOptions& o, MeasuredModes& out) {
  const int n = static_cast<int>(decay.size());
  const int columns = pencil_columns(o.pencil, n), order = pencil_order(o, decay);
  int other = std::min(columns, order + std::max(4, order / 2));
  if (other == order) other = std::max(2, order - std::max(4, order / 3));
  if (other == order || out.modes.empty()) return;
  PencilOptions p = o.pencil;
  p.order = other;
  p.modes = other / 2;  // every pole, to choose from
  double low = std::numeric_limits<double>::infinity(), high = 0;
  for (const MeasuredMode& m : out.modes) {
    low = std::min(low, m.mode.frequency_hz * (1 - o.window));
    high = std::max(high, m.mode.frequency_hz * (1 + o.window));
  }
  const auto poles = poles_between(decay, dt_s, p, low, high);
  if (!poles) return;
  const std::vector<IdentifiedMode>& found = *poles;
  std::vector<IdentifiedMode> modes;
  for (const MeasuredMode& m : out.modes) modes.push_back(m.mode);
  for (std::size_t k = 0; k < out.modes.size(); ++k) {
    const double w = search_window(modes, k, o.window);
    const IdentifiedMode* best = nullptr;
    for (const IdentifiedMode& f : found)
      if (std::abs(f.frequency_hz / modes[k].frequency_hz - 1) <= w && f.damping_ratio <= kHeavilyDampedRatio &&
          (!best || mode_energy(f, dt_s, n) > mode_energy(*best, dt_s, n)))
        best = &f;
    if (best) out.modes[k].order_hz = best->frequency_hz;
  }
  out.other_order = other;
}

// The lightly damped poles the pencil did not report within kSplitWindow of the mode and of at least
// kCompanionEnergy of its energy (d.weaker is ascending, and so are they).
std::vector<double> companions(const IdentifiedMode& mode, const PencilDiagnostics& d, double dt_s, int n) {
  std::vector<double> found;
  const double energy = mode_energy(mode, dt_s, n);
  for (const IdentifiedMode& p : d.weaker)
    if (p.damping_ratio <= kHeavilyDampedRatio && p.damping_ratio > 0 &&
        std::abs(p.frequency_hz / mode.frequency_hz - 1) <= kSplitWindow &&
        mode_energy(p, dt_s, n) >= kCompanionEnergy * energy)
      found.push_back(p.frequency_hz);
  return found;
}

// A segment's estimate moved toward the whole record's by twice its own sd: what of its difference its noise cannot
// explain (an sd that is not finite counts as 0).
double beyond_noise(double whole, double segment, double sd) {
  const double d = segment - whole, noise = std::isfinite(sd) ? sd : 0;
  return whole + std::copysign(std::max(0.0, std::abs(d) - 2 * noise), d);
}

// Drift, span and uncertainty from the estimates gathered (the header's formulas).
void summarise(MeasuredMode& m) {
  double low = m.mode.frequency_hz, high = low;
  const auto widen = [&](double f) {
    if (std::isfinite(f)) low = std::min(low, f), high = std::max(high, f);
  };
  int first = -1, last = -1;
  for (std::size_t s = 0; s < m.segment_hz.size(); ++s) {
    if (std::isnan(m.segment_hz[s])) continue;
    // By what it differs beyond twice its own noise: a weak mode's later segments scattered by their noise alone and
    // took u to 4.5 times the scatter over noise draws (26.6 Hz; the seventeenth pass's P3), while a drift many times
    // its noise (a nonlinear clamp's) is kept whole but for 2 sd.
    widen(beyond_noise(m.mode.frequency_hz, m.segment_hz[s], m.segment_sd_hz[s]));
    if (first < 0) first = static_cast<int>(s);
    last = static_cast<int>(s);
  }
  for (double f : m.companions_hz) widen(f);
  widen(m.order_hz);
  m.span_low_hz = low, m.span_high_hz = high;
  if (first >= 0 && last > first) {
    const auto a = static_cast<std::size_t>(first), b = static_cast<std::size_t>(last);
    m.drift_hz = m.segment_hz[b] - m.segment_hz[a];
    m.drift_sd_hz = std::hypot(m.segment_sd_hz[a], m.segment_sd_hz[b]);
  }
  const double noise = std::isfinite(m.mode.frequency_sd_hz) ? m.mode.frequency_sd_hz : 0;
  m.uncertainty_hz = std::hypot(noise, 0.5 * (high - low));
  // The segments' decay rates, alike beyond twice their own noise (2 pi times the frequency's sd, the same bound):
  // counted whole, a 0.8 s record's weak segments put their scatter in u and took it to 100 times the damping ratio's
  // scatter over noise draws (192.7 Hz; the nineteenth pass's P7).
  const double whole = -m.mode.lambda.real();
  double slow = whole, fast = whole;
  for (std::size_t s = 0; s < m.segment_decay_1_s.size(); ++s) {
    if (!std::isfinite(m.segment_decay_1_s[s])) continue;
    const double beyond = beyond_noise(whole, m.segment_decay_1_s[s], 2 * std::numbers::pi * m.segment_sd_hz[s]);
    slow = std::min(slow, beyond), fast = std::max(fast, beyond);
  }
  m.decay_uncertainty_1_s = std::hypot(2 * std::numbers::pi * noise, 0.5 * (fast - slow));
}

}  // namespace

long quiet_lead_in(const std::vector<double>& y) {
  if (y.empty()) return -1;
  const auto peak = static_cast<std::size_t>(
      std::max_element(y.begin(), y.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }) - y.begin());
  double lead = 0;
  for (std::size_t i = 0; i < peak / 2; ++i) lead += std::abs(y[i]) / static_cast<double>(peak / 2);
  return peak > 10 && lead < 0.1 * std::abs(y[peak]) ? static_cast<long>(peak) : -1;
}

bool MeasuredMode::drifts() const { return std::abs(drift_hz) > 3 * drift_sd_hz; }

std::string uncertainty_note(const MeasuredMode& m) {
  const double f = m.mode.frequency_hz;
  // A drift that could not be measured is said, whatever the span: u then holds less than it should (a record too
  // short for segments, or one whose later segments lost the mode: the eighth pass's M47, M04).
  std::string unmeasured;
  if (m.segments_due == 0)
    unmeasured = "its change along the record is not measured (a third of the record holds fewer than " +
                 format_rounded(kMinSegmentCycles) + " of its cycles), so its uncertainty is the noise's alone";
  else if (m.segments_found < m.segments_due)
    unmeasured = "it was followed through " + std::to_string(m.segments_found) + " of the " +
                 std::to_string(m.segments_due) +
                 " segments that hold enough of its cycles (it decays into the noise, or moves by more than " +
                 format_rounded(100 * kSegmentWindow) + " % between segments), so its drift may exceed the span";
  if (!(m.span_high_hz - m.span_low_hz >= kNotableSpan * f))
    return unmeasured.empty() ? "" : "the mode at " + format_rounded(f, 6) + " Hz: " + unmeasured;
  std::string s = "the mode at " + format_rounded(f, 6) + " Hz spans " + format_rounded(m.span_low_hz, 6) + "-" +
                  format_rounded(m.span_high_hz, 6) + " Hz (" +
                  format_rounded(100 * (m.span_high_hz - m.span_low_hz) / f, 2) + " %):";
  const std::size_t last = m.segment_hz.empty() ? 0 : m.segment_hz.size() - 1;
  if (m.drifts()) {
    std::size_t a = 0, b = last;
    while (std::isnan(m.segment_hz[a])) ++a;
    while (std::isnan(m.segment_hz[b])) --b;
    s += " its frequency moves from " + format_rounded(m.segment_hz[a], 6) + " to " +
         format_rounded(m.segment_hz[b], 6) + " Hz between the record's segments " + std::to_string(a + 1) + " and " +
         std::to_string(b + 1) + " of " + std::to_string(m.segment_hz.size()) + " as its amplitude falls from " +
         format_rounded(m.segment_amplitude[a], 3) + " to " + format_rounded(m.segment_amplitude[b], 3) +
         " (amplitude-dependent: a nonlinear clamp or stiffness; a linear model's frequency can only fall within "
         "the span, and a later window, --start, is the small-amplitude one)";
  }
  if (!m.companions_hz.empty()) {
    s += std::string(m.drifts() ? ";" : "") + " the pencil fits it with " + std::to_string(m.companions_hz.size() + 1) +
         " close poles (";
    for (std::size_t k = 0; k < m.companions_hz.size(); ++k)
      s += (k ? ", " : "") + format_rounded(m.companions_hz[k], 6);
    s += " Hz beside it): one mode whose frequency changes with its amplitude, or close modes";
  }
  const bool moved = std::isfinite(m.order_hz) && std::abs(m.order_hz - f) >= 0.5 * kNotableSpan * f;
  if (moved)
    s += std::string(m.drifts() || !m.companions_hz.empty() ? ";" : "") + " at another model order its pole lies at " +
         format_rounded(m.order_hz, 6) + " Hz (a mode the pencil's exponentials fit only approximately)";
  if (!m.drifts() && m.companions_hz.empty() && !moved)
    s += unmeasured.empty() ? " its segments' frequencies differ within their noise" : " " + unmeasured;
  else if (!unmeasured.empty())
    s += "; " + unmeasured;
  return s + "; its uncertainty " + format_rounded(m.uncertainty_hz, 3) + " Hz covers the span";
}

MeasuredModes measure_modes(const std::vector<double>& decay, double dt_s, const MeasureOptions& o) {
  if (o.segments < 1) throw InputError("segments = " + std::to_string(o.segments) + ": must be >= 1");
  MeasuredModes out;
  const std::vector<IdentifiedMode> modes = whole_record_modes(decay, dt_s, o, out);
  const int n = static_cast<int>(decay.size());
  out.segments = std::min(o.segments, n / kMinSegmentSamples);
  if (out.segments < 2) out.segments = 0;
  for (const IdentifiedMode& mode : modes) {
    MeasuredMode m;
    m.mode = mode;
    m.segment_hz.assign(static_cast<std::size_t>(out.segments), std::numeric_limits<double>::quiet_NaN());
    m.segment_sd_hz = m.segment_amplitude = m.segment_decay_1_s = m.segment_hz;
    m.companions_hz = companions(mode, out.diagnostics, dt_s, n);
    out.modes.push_back(m);
  }
  if (!out.modes.empty())
    for (int s = 0; s < out.segments; ++s) estimate_segment(decay, dt_s, o, s, n / out.segments, out);
  other_order(decay, dt_s, o, out);
  for (MeasuredMode& m : out.modes) summarise(m);
  return out;
}

}  // namespace beamid::signal
