#include "signal/spikes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "core/errors.h"

namespace beamid::signal {

std::optional<std::string> validation_error(const SpikeOptions& o) {
  if (o.count < 1) return "spikes = " + std::to_string(o.count) + ": must be >= 1";
  if (o.rule != "largest" && o.rule != "prominence")
    return "spike_rule = '" + o.rule + "': must be one of largest, prominence";
  if (!(std::isfinite(o.min_frequency_hz) && o.min_frequency_hz >= 0))
    return "min_frequency_hz = " + format_value(o.min_frequency_hz) + ": must be finite and >= 0";
  if (!(o.max_frequency_hz > o.min_frequency_hz))
    return "max_frequency_hz = " + format_value(o.max_frequency_hz) +
           ": must be > min_frequency_hz = " + format_value(o.min_frequency_hz);
  for (double f : o.frequencies_hz)
    if (!(std::isfinite(f) && f > 0)) return "spike frequency = " + format_value(f) + ": must be > 0";
  if (!o.frequencies_hz.empty() && o.count != static_cast<int>(o.frequencies_hz.size()))
    return "spikes = " + std::to_string(o.count) + ": must equal the number of chosen spike frequencies (" +
           std::to_string(o.frequencies_hz.size()) + ")";
  if (!(o.frequency_window > 0 && o.frequency_window < 0.5))
    return "spike frequency window = " + format_value(o.frequency_window) + ": must be in (0, 0.5)";
  if (!(o.support_level > 0 && o.support_level < 1))
    return "support_level = " + format_value(o.support_level) + ": must be in (0, 1)";
  return std::nullopt;
}

std::vector<int> local_maxima(const Spectrum& s) {
  std::vector<int> peaks;
  for (int k = 1; k < s.last_bin(); ++k) {
    const double m = s.magnitude(k);
    if (m > s.magnitude(k - 1) && m >= s.magnitude(k + 1)) peaks.push_back(k);
  }
  return peaks;
}

std::pair<int, int> support(const Spectrum& s, int bin, double level) {
  const double threshold = level * s.magnitude(bin);
  int left = 0;
  while (bin - left - 1 >= 0 && s.magnitude(bin - left - 1) >= threshold) ++left;
  int right = 0;
  while (bin + right + 1 <= s.last_bin() && s.magnitude(bin + right + 1) >= threshold) ++right;
  return {left, right};
}

namespace {

// Prominence of the peak at `bin` among bins [lo, hi]: its height minus the higher of the lowest points between it
// and the nearest strictly higher bin on each side (or the band edge).
double prominence(const Spectrum& s, int bin, int lo, int hi) {
  const double h = s.magnitude(bin);
  double left_min = h;
  for (int k = bin - 1; k >= lo; --k) {
    const double m = s.magnitude(k);
    if (m > h) break;
    left_min = std::min(left_min, m);
  }
  double right_min = h;
  for (int k = bin + 1; k <= hi; ++k) {
    const double m = s.magnitude(k);
    if (m > h) break;
    right_min = std::min(right_min, m);
  }
  return h - std::max(left_min, right_min);
}

}  // namespace

namespace {

// How far from a stronger peak a weaker local maximum may be one of its side lobes, in bins.
constexpr int kSideLobeBins = 10;

Spike spike_at(const Spectrum& s, int k, double level) {
  Spike p;
  p.bin = k;
  p.frequency_hz = k * s.df_hz();
  p.magnitude = s.magnitude(k);
  std::tie(p.n_left, p.n_right) = support(s, k, level);
  return p;
}

// The candidates ranked by the rule (largest score first; ties towards the lower bin, so the order is deterministic),
// and whether the list holds the chosen frequencies' peaks.
std::vector<std::pair<double, int>> ranked_candidates(const Spectrum& s, const SpikeOptions& options) {
  const double df = s.df_hz();
  const int lo = static_cast<int>(std::ceil(options.min_frequency_hz / df - 1e-9));
  const int hi = std::min<double>(s.last_bin(), std::floor(options.max_frequency_hz / df + 1e-9));
  std::vector<std::pair<double, int>> ranked;  // (score, bin)
  if (!options.frequencies_hz.empty()) {
    // Chosen spikes: for each given frequency, the largest local maximum within +-window of it (so data and model
    // spikes are paired by frequency, whatever their heights). A frequency with no local maximum near it gives no
    // spike: for data that is an input error (see costs), for a model an (A4) violation.
    const auto maxima = local_maxima(s);
    for (double f : options.frequencies_hz) {
      int best = -1;
      for (int k : maxima)
        if (std::abs(k * df - f) <= options.frequency_window * f && (best < 0 || s.magnitude(k) > s.magnitude(best)))
          best = k;
      if (best >= 0 && std::none_of(ranked.begin(), ranked.end(), [&](const auto& r) { return r.second == best; }))
        ranked.emplace_back(s.magnitude(best), best);
    }
  }
  for (int k : options.frequencies_hz.empty() ? local_maxima(s) : std::vector<int>{}) {
    if (k < lo || k > hi) continue;
    const double score = options.rule == "prominence" ? prominence(s, k, std::max(lo, 0), hi) : s.magnitude(k);
    ranked.emplace_back(score, k);
  }
  std::sort(ranked.begin(), ranked.end(),
            [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  return ranked;
}

// Why the peak at bin k is an artefact of stronger peaks (label_peaks), or "". Frequencies and decay rates are the
// three-bin (sub-bin) estimates, so that an integer ratio is tested to a fraction of a bin; a harmonic must also decay
// as one (n times its fundamental's rate: A^n e^{-n sigma t}), and a sideband at the sum of its parents' rates. Two
// of a tip-mass bar's bending modes 0.35-0.47 % off 3 f were taken for harmonics by frequency alone (issue 31).
//
// The decay test's tolerance is 25 % of the expected rate, or three standard deviations of the two rates' estimates
// if larger (up to half the rate: beyond, the test cannot tell, and the peak is kept): the three-bin rate is 2 pi Im R
// / T, and R moves by about sqrt(3) floor / |Z(k)| when each of the three bins carries noise (or other modes' leakage)
// of the spectrum's median magnitude `floor`. A factor of 2 let a mode at 3 f decaying 1.5 times as fast as the
// harmonic would be pass as one (the fourth pass's Q274); noise-free, the estimates agree with the rates to 1e-4.
//
// Cost: each candidate is tested against at most kArtefactParents stronger peaks (the strongest: artefacts of a weak
// noise maximum are no concern), one harmonic order each (the nearest), and their pairs for sidebands; the three-bin
// estimates are computed once per bin (`estimates`). Every candidate of an 80 000-sample record against every
// stronger one, every order and every pair took minutes.
constexpr std::size_t kArtefactParents = 24;
// The largest amplitude of a harmonic relative to its fundamental's (-16 dB): the distortion of a sensor or an
// amplifier short of hard clipping puts a few percent of the fundamental into its second and third harmonics. A peak
// stronger than that at an integer multiple is taken for a mode: a mode there of 0.3 to 0.5 of the lower one's
// amplitude and of the same damping ratio was skipped at 0.5 (the eighth pass's H02, H05); a harmonic kept is listed
// as a pick, where a user sees it, a mode skipped is not.
constexpr double kHarmonicAmplitude = 0.15;

std::string artefact(const Spectrum& s, int k, const std::vector<int>& all_stronger, double floor,
                     std::map<int, PoleEstimate>& estimates) {
  if (k == 1) return "offset leakage";  // one cycle in the record: no oscillation a mode can be identified from
  const double df = s.df_hz();
  const auto estimate = [&](int bin) {
    if (const auto found = estimates.find(bin); found != estimates.end()) return found->second;
    PoleEstimate e = three_bin_estimate(s, bin);
    if (!e.ok || std::abs(e.frequency_hz - bin * df) > df) e = {bin * df, 0.0, false};
    return estimates[bin] = e;
  };
  const std::vector<int> stronger(
      all_stronger.begin(),
      all_stronger.begin() + static_cast<std::ptrdiff_t>(std::min(all_stronger.size(), kArtefactParents)));
  const PoleEstimate here = estimate(k);
  const double f = here.frequency_hz;
  const double tolerance = std::max(0.002 * f, 0.75 * df);
  // Too coarse a spectrum to tell: near the lowest bins a bin covers whole mode ratios (a cantilever's f2/f1 = 6.27
  // is "harmonic 6" of a mode at bin 5), so nothing is labelled where the tolerance exceeds 1 % of f.
  if (tolerance > 0.01 * f) return "";
  const auto text = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", v);
    return std::string(buffer);
  };
  // A side lobe of a stronger peak a few bins away: below the rectangular window's 1/(pi |k - p|) envelope of it
  // (leakage around a 77.9 Hz mode was called "harmonic 7 of 11.06 Hz" after a noise maximum).
  for (int p : stronger) {
    const int apart = std::abs(k - p);
    if (apart >= 2 && apart <= kSideLobeBins && s.magnitude(k) <= 1.5 * s.magnitude(p) / (std::numbers::pi * apart))
      return "side lobe of " + text(estimate(p).frequency_hz) + " Hz";
  }
  // Decays as `expected` within the tolerance above, `expected_sd` the sd of that expectation's estimate; or cannot
  // be told (a rate that is not estimated).
  const double rate_sd_per_bin = 2 * std::numbers::pi / (s.samples * s.dt_s) * std::sqrt(3.0) * floor;
  const auto rate_sd = [&](int bin) { return rate_sd_per_bin / std::max(s.magnitude(bin), 1e-300); };
  // A peak is called an artefact only on evidence: a rate that cannot be estimated (a flat top, Welch's phase-free
  // average) or whose estimate is too uncertain to tell (three sd beyond half the expected rate) keeps the peak as a
  // mode. Called on frequency alone, true modes were dropped in noise or with --welch (the fifth pass's R230, R240).
  const auto decays_as = [&](double expected, double expected_sd) {
    if (!here.ok || !(expected > 0) || !(here.decay_rate_1_s > 0)) return false;
    const double spread = 3 * std::hypot(rate_sd(k), expected_sd);
    if (spread > 0.5 * expected) return false;
    return std::abs(here.decay_rate_1_s - expected) <= std::max(0.25 * expected, spread);
  };
  const double nyquist = s.last_bin() * df;
  for (int p : stronger) {
    const PoleEstimate fundamental = estimate(p);
    // Multiples of F lie F apart, so any frequency is within the tolerance of one of them with probability
    // 2 tolerance / F: a harmonic is claimed only where that chance is below 5 % (a banks beam's third mode, 140 Hz,
    // was "harmonic 57 of 2.464 Hz" at 0.2 % over all orders).
    if (2 * tolerance > 0.05 * fundamental.frequency_hz) continue;
    // Every order below Nyquist (harmonics up to 19 f1 were kept at n <= 8).
    const int orders = static_cast<int>(std::min(1000.0, std::floor(nyquist / fundamental.frequency_hz)));
    // The nearest multiple only: the tolerance is below a twentieth of F (above), so no other can match.
    const auto n = static_cast<int>(std::lround(f / fundamental.frequency_hz));
    // And as weak as distortion leaves a harmonic: with equal damping ratios a mode at n F also decays at n sigma_F
    // (the seventh pass's A01: 60.05 Hz beside 20 Hz, both at zeta 1 %, was "harmonic 3"). A peak of a tone
    // A e^{-sigma t} over T is |Z| ~ A (1 - e^{-sigma T}) / (sigma dt) high, so amplitudes compare as |Z| sigma /
    // (1 - e^{-sigma T}) (|Z| / T as sigma -> 0; the rate n sigma_F where a rate is not estimated). A clipped or
    // rattling sensor's harmonics stay below kHarmonicAmplitude of the fundamental; a peak as strong is a mode.
    const double record_s = s.samples * s.dt_s;
    const auto amplitude = [record_s](double height, double rate) {
      return rate * record_s > 1e-9 ? height * rate / -std::expm1(-rate * record_s) : height / record_s;
    };
    const double fundamental_rate = fundamental.ok ? std::max(fundamental.decay_rate_1_s, 0.0) : 0.0;
    const double harmonic_rate = here.ok ? std::max(here.decay_rate_1_s, 0.0) : n * fundamental_rate;
    const bool weak =
        amplitude(s.magnitude(k), harmonic_rate) <= kHarmonicAmplitude * amplitude(s.magnitude(p), fundamental_rate);
    if (n >= 2 && n <= orders && std::abs(n * fundamental.frequency_hz - f) <= tolerance && weak &&
        decays_as(fundamental.ok ? n * fundamental.decay_rate_1_s : 0, n * rate_sd(p)))
      return "harmonic " + std::to_string(n) + " of " + text(fundamental.frequency_hz) + " Hz";
  }
  for (int a : stronger)
    for (int b : stronger) {
      if (b >= a) continue;
      const PoleEstimate ea = estimate(a), eb = estimate(b);
      const double rate = ea.ok && eb.ok ? ea.decay_rate_1_s + eb.decay_rate_1_s : 0;
      const double sd = std::hypot(rate_sd(a), rate_sd(b));
      if (std::abs(ea.frequency_hz + eb.frequency_hz - f) <= tolerance && decays_as(rate, sd))
        return "sideband " + text(ea.frequency_hz) + " + " + text(eb.frequency_hz) + " Hz";
      if (std::abs(ea.frequency_hz - eb.frequency_hz - f) <= tolerance && decays_as(rate, sd))
        return "sideband " + text(ea.frequency_hz) + " - " + text(eb.frequency_hz) + " Hz";
    }
  return "";
}

}  // namespace

std::vector<LabelledPeak> label_peaks(const Spectrum& s, const SpikeOptions& options) {
  if (auto error = validation_error(options)) throw InputError("spike detection: " + *error);
  const auto ranked = ranked_candidates(s, options);
  // The labels by magnitude whatever the rule: each candidate against the unlabelled candidates above it (a harmonic
  // that outranks its fundamental by prominence is still the fundamental's harmonic). A label depends only on the
  // candidates above it, so they are made lazily, down the heights only as far as the lowest candidate the picks
  // reach: every candidate of a noisy record against every real one above it was quadratic in the record's length
  // (16 million samples: 56 s, 20 million: 91 s without a word; the tenth pass's G_05).
  const bool labelling = options.reject_artefacts && options.frequencies_hz.empty();
  std::vector<int> by_height;
  double floor = 0;  // the spectrum's median magnitude: the noise (and leakage) each bin of a peak carries
  if (labelling) {   // (a spike cost's model spectrum comes here on every evaluation: nothing sorted it does not use)
    for (const auto& [score, k] : ranked) by_height.push_back(k);
    std::stable_sort(by_height.begin(), by_height.end(), [&](int a, int b) { return s.magnitude(a) > s.magnitude(b); });
    std::vector<double> magnitudes;
    for (int k = 1; k <= s.last_bin(); ++k) magnitudes.push_back(s.magnitude(k));
    std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<long>(magnitudes.size() / 2),
                     magnitudes.end());
    floor = magnitudes.empty() ? 0.0 : magnitudes[magnitudes.size() / 2];
  }
  std::map<int, std::string> label;
  std::vector<int> real;
  std::map<int, PoleEstimate> estimates;
  std::size_t labelled = 0;  // by_height[0 .. labelled) have their labels
  const auto label_of = [&](int k) -> const std::string& {
    while (!label.count(k)) {
      const int next = by_height[labelled++];
      std::vector<int> higher;
      for (int p : real)
        if (s.magnitude(p) > s.magnitude(next)) higher.push_back(p);
      label[next] = artefact(s, next, higher, floor, estimates);
      if (label[next].empty()) real.push_back(next);
    }
    return label.at(k);
  };
  static const std::string none;
  std::vector<LabelledPeak> out;
  int picks = 0;
  for (const auto& [score, k] : ranked) {
    if (picks == options.count && options.frequencies_hz.empty()) break;
    LabelledPeak peak{spike_at(s, k, options.support_level), labelling ? label_of(k) : none};
    if (peak.skipped.empty()) ++picks;
    out.push_back(peak);
  }
  return out;
}

std::vector<Spike> detect_spikes(const Spectrum& s, const SpikeOptions& options) {
  if (auto error = validation_error(options)) throw InputError("spike detection: " + *error);
  std::vector<Spike> spikes;
  if (options.reject_artefacts) {
    for (const LabelledPeak& p : label_peaks(s, options))
      if (p.skipped.empty()) spikes.push_back(p.spike);
  } else {
    auto ranked = ranked_candidates(s, options);
    if (options.frequencies_hz.empty() && static_cast<int>(ranked.size()) > options.count)
      ranked.resize(static_cast<std::size_t>(options.count));
    for (const auto& [score, k] : ranked) spikes.push_back(spike_at(s, k, options.support_level));
  }
  std::sort(spikes.begin(), spikes.end(), [](const Spike& a, const Spike& b) { return a.bin < b.bin; });
  return spikes;
}

Spectrum welch_spectrum(const std::vector<double>& values, double dt_s, int segments) {
  if (segments < 2) throw InputError("--welch = '" + std::to_string(segments) + "'" + ": must be >= 2");
  // K segments of length L overlapping by L/2 cover (K + 1) L / 2 samples.
  const auto length = static_cast<int>(2 * values.size() / static_cast<std::size_t>(segments + 1));
  if (length < 16)
    throw InputError("--welch = '" + std::to_string(segments) + "'" + ": segments of " + std::to_string(length) +
                     " samples: must be >= 16 (fewer segments)");
  Dft dft(length, dt_s, WindowOptions{"hann", 0.01});
  Spectrum mean;
  std::vector<double> power;
  for (int k = 0; k < segments; ++k) {
    const auto begin = values.begin() + static_cast<std::ptrdiff_t>(k) * (length / 2);
    const Spectrum segment = dft.transform(std::vector<double>(begin, begin + length));
    if (power.empty()) power.assign(segment.half.size(), 0.0), mean = segment;
    for (std::size_t b = 0; b < power.size(); ++b) power[b] += std::norm(segment.half[b]) / segments;
  }
  for (std::size_t b = 0; b < power.size(); ++b) mean.half[b] = std::sqrt(power[b]);
  return mean;
}

const core::NameSet& detrend_names() {
  static const core::NameSet names({{kDetrendNone, "the record as it is"},
                                    {kDetrendMean, "less its mean"},
                                    {kDetrendLinear, "less its least-squares offset and linear trend"}});
  return names;
}

std::vector<double> detrend(std::vector<double> values, const std::string& mode) {
  if (auto error = detrend_names().violation("detrend", mode)) throw InputError(*error);
  if (mode == kDetrendNone || values.empty()) return values;
  const auto n = static_cast<double>(values.size());
  double mean = 0;
  for (double v : values) mean += v / n;
  double slope = 0;
  const double centre = (n - 1) / 2;
  if (mode == kDetrendLinear && values.size() > 1) {  // least squares on i - centre, which is orthogonal to 1
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double x = static_cast<double>(i) - centre;
      sxy += x * values[i];
      sxx += x * x;
    }
    slope = sxy / sxx;
  }
  for (std::size_t i = 0; i < values.size(); ++i) values[i] -= mean + slope * (static_cast<double>(i) - centre);
  return values;
}

PoleEstimate three_bin_change(const Spectrum& s, const Spectrum& change, int bin) {
  const std::complex<double> a = s.at(bin - 1), b = s.at(bin), c = s.at(bin + 1);
  const std::complex<double> da = change.at(bin - 1), db = change.at(bin), dc = change.at(bin + 1);
  const std::complex<double> denominator = 2.0 * b - a - c;
  const std::complex<double> dr =
      ((da - dc) * denominator - (a - c) * (2.0 * db - da - dc)) / (denominator * denominator);
  const double x = std::numbers::pi / s.samples;
  PoleEstimate e;
  e.frequency_hz = std::tan(x) / x * dr.real() * s.df_hz();
  e.decay_rate_1_s = 2 * std::numbers::pi * dr.imag() / (s.samples * s.dt_s);
  e.ok = std::isfinite(e.frequency_hz) && std::isfinite(e.decay_rate_1_s);
  return e;
}

PoleEstimate three_bin_estimate(const Spectrum& s, int bin) {
  const std::complex<double> a = s.at(bin - 1), b = s.at(bin), c = s.at(bin + 1);
  const std::complex<double> denominator = 2.0 * b - a - c;
  PoleEstimate e;
  if (std::abs(denominator) == 0 || !std::isfinite(std::abs(denominator))) return e;
  const std::complex<double> r = (a - c) / denominator;
  const double x = std::numbers::pi / s.samples;
  const double candan = std::tan(x) / x;
  const double record_s = s.samples * s.dt_s;
  e.frequency_hz = (bin + candan * r.real()) * s.df_hz();
  e.decay_rate_1_s = 2 * std::numbers::pi * r.imag() / record_s;
  e.ok = std::isfinite(e.frequency_hz) && std::isfinite(e.decay_rate_1_s);
  return e;
}

double damped_mode_frequency_sd(double amplitude, double decay_rate_1_s, double dt_s, int samples, double noise_sd) {
  // Sums in t / T (T the record length) so that S0 S2 - S1^2 does not cancel catastrophically in absolute units.
  const double record_s = dt_s * samples;
  double s0 = 0, s1 = 0, s2 = 0;
  for (int i = 0; i < samples; ++i) {
    const double u = static_cast<double>(i) / samples, w = std::exp(-2 * decay_rate_1_s * i * dt_s);
    s0 += w, s1 += u * w, s2 += u * u * w;
  }
  const double spread = (s0 * s2 - s1 * s1) * record_s * record_s;  // S0 S2 - S1^2 in s^2
  return std::sqrt(2 * noise_sd * noise_sd * s0 / (amplitude * amplitude * spread));
}

std::string unmatched_frequencies(const std::vector<Spike>& picked, const SpikeOptions& options,
                                  const Spectrum& spectrum) {
  const double nyquist_hz = spectrum.last_bin() * spectrum.df_hz();
  std::string missing, above;
  for (double f : options.frequencies_hz) {
    const bool near = std::any_of(picked.begin(), picked.end(), [&](const Spike& s) {
      return std::abs(s.frequency_hz - f) <= options.frequency_window * f;
    });
    if (near) continue;
    missing += (missing.empty() ? "" : ", ") + format_value(f);
    if (f > nyquist_hz) above += (above.empty() ? "" : ", ") + format_value(f);
  }
  if (missing.empty())
    return "two of them share one local maximum of the spectrum (df = " + format_rounded(spectrum.df_hz()) +
           " Hz): choose frequencies further apart, or a longer record";
  return missing + " Hz have no local maximum of the spectrum within +-" +
         format_value(100 * options.frequency_window) + " %" +
         (above.empty() ? std::string()
                        : " (" + above + " Hz above the Nyquist frequency " + format_rounded(nyquist_hz) + " Hz)");
}

}  // namespace beamid::signal
