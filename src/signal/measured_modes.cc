#include "signal/measured_modes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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
  double low = std::numeric_limits<double>::infinity(), high = 0;
  for (const MeasuredMode& m : out.modes) {
    low = std::min(low, m.mode.frequency_hz * (1 - o.window));
    high = std::max(high, m.mode.frequency_hz * (1 + o.window));
  }
  p.min_frequency_hz = std::max(p.min_frequency_hz, low);
  p.max_frequency_hz = std::min(p.max_frequency_hz, high);
  p.modes = 3 * static_cast<int>(out.modes.size()) + 4;
  std::vector<IdentifiedMode> found;
  try {
    found = matrix_pencil(segment, dt_s, p);
  } catch (const InputError&) {
    return;
  } catch (const NumericalError&) {
    return;
  }
  std::vector<IdentifiedMode> whole;
  for (const MeasuredMode& m : out.modes) whole.push_back(m.mode);
  for (std::size_t k = 0; k < out.modes.size(); ++k) {
    MeasuredMode& m = out.modes[k];
    if (m.mode.frequency_hz * length * dt_s < kMinSegmentCycles) continue;
    const double w = search_window(whole, k, o.window);
    const IdentifiedMode* best = nullptr;
    double weighted = 0, decay = 0, total = 0, squares = 0;
    for (const IdentifiedMode& f : found) {
      if (std::abs(f.frequency_hz / m.mode.frequency_hz - 1) > w || f.damping_ratio > kHeavilyDampedRatio) continue;
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
    const auto i = static_cast<std::size_t>(s);
    m.segment_hz[i] = weighted / total;
    m.segment_sd_hz[i] = best->frequency_sd_hz;
    m.segment_amplitude[i] = amplitude;
    m.segment_decay_1_s[i] = decay / total;
  }
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

// Drift, span and uncertainty from the estimates gathered (the header's formulas).
void summarise(MeasuredMode& m) {
  double low = m.mode.frequency_hz, high = low;
  const auto widen = [&](double f) {
    if (std::isfinite(f)) low = std::min(low, f), high = std::max(high, f);
  };
  int first = -1, last = -1;
  for (std::size_t s = 0; s < m.segment_hz.size(); ++s) {
    if (std::isnan(m.segment_hz[s])) continue;
    widen(m.segment_hz[s]);
    if (first < 0) first = static_cast<int>(s);
    last = static_cast<int>(s);
  }
  for (double f : m.companions_hz) widen(f);
  m.span_low_hz = low, m.span_high_hz = high;
  if (first >= 0 && last > first) {
    const auto a = static_cast<std::size_t>(first), b = static_cast<std::size_t>(last);
    m.drift_hz = m.segment_hz[b] - m.segment_hz[a];
    m.drift_sd_hz = std::hypot(m.segment_sd_hz[a], m.segment_sd_hz[b]);
  }
  const double noise = std::isfinite(m.mode.frequency_sd_hz) ? m.mode.frequency_sd_hz : 0;
  m.uncertainty_hz = std::hypot(noise, 0.5 * (high - low));
  double slow = -m.mode.lambda.real(), fast = slow;
  for (double d : m.segment_decay_1_s)
    if (std::isfinite(d)) slow = std::min(slow, d), fast = std::max(fast, d);
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
  if (!(m.span_high_hz - m.span_low_hz >= kNotableSpan * f)) return "";
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
  if (!m.drifts() && m.companions_hz.empty()) s += " its segments' frequencies differ within their noise";
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
  for (MeasuredMode& m : out.modes) summarise(m);
  return out;
}

}  // namespace beamid::signal
