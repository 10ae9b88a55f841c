#include "apps/fit_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <tuple>

#include "api/record_requests.h"
#include "apps/command_flags.h"
#include "core/errors.h"
#include "costs/cost.h"
#include "costs/modal_cost.h"
#include "galerkin/modes.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/text.h"
#include "signal/measured_modes.h"
#include "signal/noise_spectrum.h"
#include "signal/spectrum.h"

namespace beamid::apps {
namespace {

std::string g(double v, int digits = 6) {
  std::ostringstream s;
  s << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace

std::vector<int> pair_modes(const std::vector<double>& data_hz, const std::vector<double>& model_hz) {
  // One model mode to one data mode, the closest pairs (relative frequency) first: a data pole of zeta 73 % was
  // paired with model mode 2 already paired (the third pass's P290). And only within kModePairingWindow: a 5.8 Hz
  // noise pole was shown as the model's 2.46 Hz mode (the fourth pass's Q335); at an estimate a mode the data and the
  // model share agrees far closer.
  std::vector<std::tuple<double, std::size_t, std::size_t>> candidates;  // (|f_m / f_d - 1|, data, model)
  for (std::size_t i = 0; i < data_hz.size(); ++i)
    for (std::size_t j = 0; j < model_hz.size(); ++j)
      candidates.emplace_back(std::abs(model_hz[j] / data_hz[i] - 1), i, j);
  std::sort(candidates.begin(), candidates.end());
  std::vector<int> partner(data_hz.size(), -1);
  std::vector<bool> taken(model_hz.size(), false);
  for (const auto& [distance, i, j] : candidates)
    if (distance <= kModePairingWindow && partner[i] < 0 && !taken[j])
      partner[i] = static_cast<int>(j), taken[j] = true;
  return partner;
}

namespace {

// A record's measured mode beside the model's it pairs with (none: NaN).
ModePair mode_pair(const signal::MeasuredMode& data, const galerkin::DampedMode* model) {
  ModePair pair;
  pair.data_hz = data.mode.frequency_hz, pair.data_damping_ratio = data.mode.damping_ratio;
  pair.data_uncertainty_hz = data.uncertainty_hz, pair.data_note = signal::uncertainty_note(data);
  pair.data_decay_1_s = -data.mode.lambda.real(), pair.data_decay_uncertainty_1_s = data.decay_uncertainty_1_s;
  pair.model_hz = pair.model_damping_ratio = std::nan("");
  if (model) {
    pair.model_hz = model->frequency_hz, pair.model_damping_ratio = model->damping_ratio;
    pair.model_decay_1_s = -model->lambda.real();
  }
  return pair;
}

}  // namespace

namespace {

// The pencil's uncertainties and its test of a pole against the noise take the residual as white. Coloured noise
// holds more power near some frequencies: g(f) times its average by an AR model of the pencil's residual
// (PencilDiagnostics::residual_colour, Akaike's order), 19 near 0 Hz for AR(0.9), 10 near 0 Hz and Nyquist for
// AR(0, 0.9), whose lag-1 autocorrelation is 0. In AR(0.9) noise every correct fit was told that the record's noise
// poles at 3.4 and 8.7 Hz (0.4 and 0.13 % of its largest value) had no model mode, "a local minimum", and the damping
// note fired on 6 of 14 fits whose record's decay rate was 5 white-noise uncertainties from the truth (the
// twenty-eighth pass's adv65 P4; with AR(0, 0.9) a noise pole near Nyquist took the 404 Hz mode: adv67 P1). So where
// the model's excess exceeds kColouredExcess somewhere, each measured mode's uncertainties are widened by sqrt(g(f))
// where g > 1, and a pole no model mode pairs with (or that misses its partner beyond kModeMismatch) whose energy
// over the record, A^2 / 2 sum_i |z|^2i, is below what noise of power sigma^2 g(f) puts into the best-fitting damped
// sinusoid with probability kNoiseFalseAlarm (signal/matrix_pencil.h: 2 sigma^2 g ln(n / p)) is set aside as the
// noise's (partner -2), and said. Not on a record the pencil fits to round-off (residual under 1e-9 of its rms: its
// "colour" is the arithmetic's, adv67 P3).
void weigh_coloured_residual(const signal::MeasuredModes& measured, const std::vector<double>& decay, double dt_s,
                             std::vector<int>& partner, ModeComparison& c) {
  const signal::PencilDiagnostics& d = measured.diagnostics;
  if (!(d.residual_fraction > 1e-9) || decay.size() < 64) return;
  const int samples = static_cast<int>(decay.size());
  const signal::ColourExcess colour = signal::colour_excess(d.residual_colour, samples);
  if (!colour.coloured) return;
  const std::vector<double>& excess_by_bin = colour.by_bin;
  double squares = 0, largest = 0;
  for (double v : decay) squares += v * v, largest = std::max(largest, std::abs(v));
  const double n = static_cast<double>(decay.size());
  const double sigma = d.residual_fraction * std::sqrt(squares / n);
  const auto excess = [&](double f_hz) {
    const auto bin = static_cast<long>(std::lround(std::abs(f_hz) * n * dt_s));
    return excess_by_bin[static_cast<std::size_t>(std::clamp<long>(bin, 0, samples / 2))];
  };
  double widest = 1;
  for (std::size_t i = 0; i < c.pairs.size(); ++i) {
    ModePair& p = c.pairs[i];
    const double g = excess(p.data_hz);
    if (g > 1) {
      p.data_uncertainty_hz *= std::sqrt(g), p.data_decay_uncertainty_1_s *= std::sqrt(g);
      widest = std::max(widest, std::sqrt(g));
    }
    // Unpaired, or paired beyond kModeMismatch (a noise pole at 23.5 Hz took the model's 26.7 Hz mode, whose own
    // pole the noise hid).
    if (partner[i] == -2 || (partner[i] >= 0 && !(std::abs(p.model_hz / p.data_hz - 1) > kModeMismatch))) continue;
    const signal::IdentifiedMode& m = measured.modes[i].mode;
    const double z2 = std::exp(2 * m.lambda.real() * dt_s);
    const double energy = m.amplitude * m.amplitude / 2 * (z2 < 1 ? (1 - std::pow(z2, n)) / (1 - z2) : n);
    if (energy >= 2 * sigma * sigma * std::max(g, 1.0) * std::log(n / signal::kNoiseFalseAlarm)) continue;
    p.set_aside = true, partner[i] = -2;
    c.notes.push_back("the record's pole at " + format_rounded(m.frequency_hz, 6) + " Hz (amplitude " +
                      format_rounded(m.amplitude / largest, 2) +
                      " of the record's largest value) is within its coloured noise (the pencil's residual: sd " +
                      format_rounded(sigma / largest, 2) + " of the largest value, about " +
                      format_rounded(std::max(g, 1.0), 2) +
                      " times its average power there): a pole of the noise, not compared");
  }
  if (widest > 1)
    c.notes.push_back("the record's residual is coloured (an AR(" + std::to_string(d.residual_colour.ar.size()) +
                      ") model of the pencil's residual): the measured modes' uncertainties are widened for the "
                      "comparison by the noise's excess power at their frequencies, up to " +
                      format_rounded(widest, 2) + " times");
}

}  // namespace

std::vector<double> model_frequency_uncertainties(const fit::FitResult& result, int elements,
                                                  const std::vector<galerkin::DampedMode>& model) {
  std::vector<double> u(model.size(), std::nan(""));
  const auto& estimates = result.parameters;
  const auto n = static_cast<Eigen::Index>(estimates.size());
  if (model.empty() || n == 0 || result.correlation.rows() != n) return u;
  Eigen::VectorXd relative(n);
  std::vector<std::string> keys;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& e = estimates[static_cast<std::size_t>(i)];
    if (!std::isfinite(e.standard_error) || e.estimate == 0) return u;
    relative(i) = e.standard_error / std::abs(e.estimate), keys.push_back(e.key);
  }
  const Eigen::MatrixXd log_covariance = relative.asDiagonal() * result.correlation * relative.asDiagonal();
  try {
    const galerkin::BeamForms forms(galerkin::SplineSpace(elements), result.beam.l, result.beam.support);
    // Every undamped mode (a heavily damped low mode may be missing from the underdamped ones).
    const galerkin::UndampedModes undamped = galerkin::undamped_modes(galerkin::combine(forms, result.beam));
    const int count = static_cast<int>(undamped.omega_rad_s.size());
    const Eigen::MatrixXd g = galerkin::frequency_sensitivities(forms, result.beam, keys, count);
    for (std::size_t j = 0; j < model.size(); ++j) {
      Eigen::Index nearest = 0;
      const double omega = 2 * std::numbers::pi * model[j].frequency_hz;
      (undamped.omega_rad_s.array() - omega).abs().minCoeff(&nearest);
      const double variance = g.row(nearest).dot(log_covariance * g.row(nearest).transpose());
      if (variance >= 0) u[j] = model[j].frequency_hz * std::sqrt(variance);
    }
  } catch (const std::exception&) {  // a key that is no beam parameter, or too few modes: unknown
  }
  return u;
}

ModeComparison compare_modes(const FitReportInput& in) {
  ModeComparison c;
  const auto& o = in.options;
  if (in.result.status == "failed") {
    c.status = "the fit failed";
    return c;
  }
  // A free-decay fit takes the record as a decay from its first sample: a hit left in it is fitted as one.
  if (o.experiment.excitation == simulation::kFreeDecay) {
    if (const std::string note = api::lead_in_note(in.data, "a free-decay fit"); !note.empty()) c.notes.push_back(note);
  } else if (const std::string note = api::glitch_note(in.data, "the fit"); !note.empty()) {
    c.notes.push_back(note);  // (the thirteenth pass's 2: said by spikes and modal-id, not by fit)
  }
  if (const std::string note = api::quantisation_note(in.data); !note.empty()) c.notes.push_back(note);
  std::vector<galerkin::DampedMode> model;
  try {
    model = galerkin::StateSpaceModes(galerkin::assemble(galerkin::SplineSpace(o.elements), in.result.beam))
                .underdamped_modes();
  } catch (const std::exception& e) {
    c.status = std::string("model modes: ") + e.what();
    return c;
  }
  signal::PencilOptions p;
  p.modes = std::min(o.cost.spikes.count, 8);
  p.min_frequency_hz = o.cost.spikes.min_frequency_hz;
  p.max_frequency_hz = o.cost.spikes.max_frequency_hz;
  // The free decay: after the pulse (a pluck and a free decay start free).
  const std::size_t first =
      o.experiment.excitation == "pulse" ? static_cast<std::size_t>(o.experiment.pulse_width_s / in.data.dt_s) + 1 : 0;
  try {
    if (first >= in.data.values.size()) throw InputError("the record ends within the pulse");
    const std::vector<double> decay(in.data.values.begin() + static_cast<std::ptrdiff_t>(first), in.data.values.end());
    // The chosen spikes' modes when there are any (a record's strongest modes may be ones the model lacks).
    const auto& wanted = o.cost.spikes.frequencies_hz;
    // Those the modal cost compares with: heavily damped poles are left out (the third pass's P290: a data pole of
    // zeta 73 %), and chosen frequencies' modes kept as they are.
    // With their uncertainty: the measured-frequency estimator that modal-id, spikes and real share.
    signal::MeasureOptions measure;
    measure.pencil = p;
    measure.wanted_hz = wanted;
    measure.window = o.cost.spikes.frequency_window;
    const signal::MeasuredModes measured = signal::measure_modes(decay, in.data.dt_s, measure);
    const std::vector<signal::MeasuredMode>& kept = measured.modes;
    std::vector<double> data_hz, model_hz;
    for (const auto& m : kept) data_hz.push_back(m.mode.frequency_hz);
    for (const auto& m : model) model_hz.push_back(m.frequency_hz);
    std::vector<int> partner = pair_modes(data_hz, model_hz);
    const std::vector<double> model_uncertainty = model_frequency_uncertainties(in.result, in.options.elements, model);
    for (std::size_t i = 0; i < kept.size(); ++i) {
      c.pairs.push_back(mode_pair(kept[i], partner[i] >= 0 ? &model[static_cast<std::size_t>(partner[i])] : nullptr));
      if (partner[i] >= 0)
        c.pairs.back().model_uncertainty_hz = model_uncertainty[static_cast<std::size_t>(partner[i])];
    }
    weigh_coloured_residual(measured, decay, in.data.dt_s, partner, c);
    if (costs::is_spike_cost(o.cost.name))
      if (const std::string note = api::window_transient_note(o.cost.window, in.data.values.size(), in.data.dt_s, kept);
          !note.empty())
        c.notes.push_back(note);
    // A pole of the record that no model mode pairs with is said, with its size: a mode the model lacks, or the
    // pencil's fit of what does not oscillate (the tenth pass's PH_f3: a noise-free record of a beam with three
    // underdamped modes listed "476.10 Hz, zeta 12.8 %", 3e-9 of the record's size, from its overdamped part).
    double largest = 0;
    for (double v : decay) largest = std::max(largest, std::abs(v));
    constexpr double kBelowResolution = 1e-6;
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (partner[i] < 0 && kept[i].mode.amplitude < kBelowResolution * largest) c.pairs[i].set_aside = true;
    // A model mode above the record's Nyquist frequency shows in it folded to |f - k fs| (no anti-alias filter in a
    // simulated record, nor in many a DAQ): a record at 500 Hz held the thin beam's 285.3 Hz mode at 214.8 Hz, and an
    // exact fit was told it was a local minimum (the twelfth pass's P5). Within 2 % of such an alias, a pole is said
    // to be one and set aside.
    const double rate_hz = 1 / in.data.dt_s;
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (partner[i] >= 0) continue;
      for (const auto& m : model) {
        if (m.frequency_hz <= rate_hz / 2) continue;
        const double alias = std::abs(m.frequency_hz - std::round(m.frequency_hz / rate_hz) * rate_hz);
        if (std::abs(alias / kept[i].mode.frequency_hz - 1) > 0.02) continue;
        c.pairs[i].set_aside = true;
        c.notes.push_back("the record's pole at " + format_rounded(kept[i].mode.frequency_hz, 6) +
                          " Hz is the model's " + format_rounded(m.frequency_hz, 6) +
                          " Hz mode aliased (above the record's Nyquist frequency " + format_rounded(rate_hz / 2, 6) +
                          " Hz, it folds to " + format_rounded(alias, 6) +
                          " Hz): not compared; sample faster, or low-pass the record, to measure it");
        partner[i] = -2;  // said; not a pole the model lacks
        break;
      }
    }
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (partner[i] == -1)
        c.notes.push_back("the record's pole at " + format_rounded(kept[i].mode.frequency_hz, 6) + " Hz (zeta " +
                          format_rounded(100 * kept[i].mode.damping_ratio, 3) + " %, amplitude " +
                          format_rounded(kept[i].mode.amplitude / largest, 2) +
                          " of the record's largest value) pairs with no mode of the model: a mode the model lacks "
                          "(a rig or torsion mode), or, when it is small, the pencil's fit of a part that does not "
                          "oscillate (overdamped modes); it is no measured mode of this model");
  } catch (const std::exception& e) {
    c.status = std::string("data modes: ") + e.what();
  }
  return c;
}

std::string modes_line(const ModeComparison& c) {
  if (c.status != "ok") return "modes at the estimate: not compared (" + c.status + ")";
  std::string s = "modes at the estimate (data by matrix pencil, +- its uncertainty | model):";
  for (std::size_t k = 0; k < c.pairs.size(); ++k)
    s += std::string(k ? ";" : "") + " " + g(c.pairs[k].data_hz) + " +- " + g(c.pairs[k].data_uncertainty_hz, 2) +
         " | " + g(c.pairs[k].model_hz) + " Hz, zeta " + g(100 * c.pairs[k].data_damping_ratio, 3) + " | " +
         g(100 * c.pairs[k].model_damping_ratio, 3) + " %";
  return s;
}

namespace {

// "41.4, 116.9": the data frequencies of the modes in `beyond` but `farthest`, for a note that names the farthest.
std::string other_frequencies(const std::vector<const ModePair*>& beyond, const ModePair* farthest) {
  std::string others;
  for (const ModePair* p : beyond)
    if (p != farthest) others += (others.empty() ? "" : ", ") + g(p->data_hz);
  return others;
}

// The uncertainty of a pair's frequency difference: the record's (at least the pencil's own exactness, the modal
// cost's floor of 1e-9 of the frequency: on a noise-free record u is round-off, 1.5e-13 Hz, and a fit that stopped
// 1.3e-11 % from it was said to miss by 72 u) and the fit's own, where known. An errors-in-variables freq-ml fit
// scatters the model's first mode 9 times more widely than the pencil's uncertainty of it (its likelihood down-weights
// the resonance bins), and its standard errors say so: 2 of 8 such fits were said to miss by 19 u, which their
// standard errors "do not include" (the twenty-seventh pass's adv63 P2).
double combined_uncertainty_hz(const ModePair& p) {
  const double data = std::max(p.data_uncertainty_hz, costs::kUncertaintyFloor * std::abs(p.data_hz));
  return std::isfinite(p.model_uncertainty_hz) ? std::hypot(data, p.model_uncertainty_hz) : data;
}

// Within kModeMismatch but beyond kFrequencyMismatchUncertainties of the record's own uncertainty: a second hit of 5 %
// at 6 s moved mode 1 by 17 u and EI by 9-13 standard errors with nothing said (the nineteenth pass's P3). Every mode
// that misses is named, the farthest with its numbers.
std::string precision_mismatch(const ModeComparison& c) {
  const ModePair* at = nullptr;
  double excess = 0;
  std::vector<const ModePair*> beyond;
  for (const ModePair& p : c.pairs) {
    if (p.set_aside || std::isnan(p.model_hz) || !(p.data_uncertainty_hz > 0)) continue;
    const double u = combined_uncertainty_hz(p);
    const double off = std::abs(p.model_hz - p.data_hz) / u;
    if (off > kFrequencyMismatchUncertainties) beyond.push_back(&p);
    if (off > excess) excess = off, at = &p;
  }
  if (!at || excess <= kFrequencyMismatchUncertainties) return "";
  const std::string others = other_frequencies(beyond, at);
  return "the estimate does not reproduce the record's modes to their measured precision: the model's mode at " +
         g(at->model_hz) + " Hz is " + g(excess, 3) +
         (std::isfinite(at->model_uncertainty_hz)
              ? " of the record's and the fit's uncertainties combined (the fit's: +- " +
                    g(at->model_uncertainty_hz, 2) + " Hz; "
              : " of the record's uncertainties (") +
         g(100 * std::abs(at->model_hz / at->data_hz - 1), 2) + " %) from its " + g(at->data_hz) + " +- " +
         g(at->data_uncertainty_hz, 2) + " Hz" +
         (others.empty() ? "" : " (also beyond " + g(kFrequencyMismatchUncertainties, 2) + " at " + others + " Hz)") +
         ": model error, a cost whose estimate is biased or weighted off the record's precision (noise on the spikes' "
         "magnitudes, a window, the modal cost's relative weighting), or a record "
         "that is no free decay of one linear beam (a second hit, a frequency that changes with the amplitude), which "
         "the standard errors do not include; quote the spread over windows (--windows K)";
}

}  // namespace

std::string modes_mismatch_note(const ModeComparison& c) {
  if (c.status != "ok") return "";
  double worst = 0, excess = 0;  // the largest relative misfit, and its ratio to its pair's tolerance
  const ModePair* at = nullptr;
  for (const ModePair& p : c.pairs) {
    if (p.set_aside) continue;  // said in the comparison's notes: no mode, no misfit (the eleventh pass's P2_alarm)
    const double off =
        std::isnan(p.model_hz) ? std::numeric_limits<double>::infinity() : std::abs(p.model_hz / p.data_hz - 1);
    const double tolerance = std::max(kModeMismatch, 2 * p.data_uncertainty_hz / p.data_hz);
    if (off / tolerance > excess) excess = off / tolerance, worst = off, at = &p;
  }
  if (!at || excess <= 1) return precision_mismatch(c);
  // An unpaired record mode beside a model mode that another record pole took: not "no model mode within 20 %" (the
  // nineteenth pass's P6: 192.014 Hz, with the model's 192.704 Hz mode 0.36 % away, paired with the record's 192.689).
  const ModePair* taken = nullptr;
  if (std::isinf(worst))
    for (const ModePair& p : c.pairs)
      if (!std::isnan(p.model_hz) && std::abs(p.model_hz / at->data_hz - 1) <= kModePairingWindow &&
          (!taken || std::abs(p.model_hz - at->data_hz) < std::abs(taken->model_hz - at->data_hz)))
        taken = &p;
  std::string what;
  if (!std::isinf(worst))
    what = "the model's mode at " + g(at->model_hz) + " Hz is " + g(100 * worst, 3) + " % from the record's " +
           g(at->data_hz) + " Hz";
  else if (taken)
    what = "the record's pole at " + g(at->data_hz) + " Hz has no model mode of its own: the model's " +
           g(taken->model_hz) + " Hz mode, " + g(100 * std::abs(taken->model_hz / at->data_hz - 1), 2) +
           " % from it, pairs with the record's " + g(taken->data_hz) +
           " Hz (two of the record's poles near one model mode: one mode split by a frequency that changes with its "
           "amplitude or by noise, or a mode the model lacks)";
  else
    what =
        "the record's mode at " + g(at->data_hz) + " Hz has no model mode within " + g(100 * kModePairingWindow) + " %";
  // Two record poles at one model mode are the record's doing, not the fit's: no "beyond 2 %" beside a pole 0.7 %
  // away, and no local minimum to try other starts for (the thirtieth pass's adv69 P2: a first mode split by
  // coloured noise).
  if (taken)
    return "the estimate does not reproduce the record's modes: " + what +
           "; the model has one pole per mode, so the standard errors do not include the split";
  const double tolerance = std::max(kModeMismatch, 2 * at->data_uncertainty_hz / at->data_hz);
  return "the estimate does not reproduce the record's modes: " + what + " (beyond " + g(100 * tolerance, 3) + " %" +
         (tolerance > kModeMismatch ? ", twice the record's own uncertainty" : "") +
         "): a local minimum or a model that cannot fit the record, which the standard errors do not include; try "
         "other starts (--starts) or another model";
}

std::string damping_mismatch_note(const ModeComparison& c) {
  if (c.status != "ok") return "";
  const ModePair* at = nullptr;
  double excess = 0;  // the largest |model - data| decay rate over its tolerance
  int compared = 0;
  std::vector<const ModePair*> beyond;  // every mode off by more than its tolerance, by frequency
  for (const ModePair& p : c.pairs) {
    if (p.set_aside || std::isnan(p.model_decay_1_s) || !(p.data_decay_1_s > 0)) continue;
    ++compared;
    const double off = std::abs(p.model_decay_1_s - p.data_decay_1_s);
    const double u = std::isnan(p.data_decay_uncertainty_1_s) ? 0 : p.data_decay_uncertainty_1_s;
    const double tolerance = std::max(kDampingMismatch * p.data_decay_1_s, kDampingMismatchUncertainties * u);
    if (off > tolerance) beyond.push_back(&p);
    if (off / tolerance > excess) excess = off / tolerance, at = &p;
  }
  if (!at || excess <= 1) return "";
  // Every mode that misses is named, not only the farthest: on the steel record 3 of 5 did, and the note that named
  // the 380 Hz mode alone read as one mode's problem (the eighteenth pass's U4).
  const std::string others = other_frequencies(beyond, at);
  return "the estimate does not reproduce the record's damping at " + std::to_string(beyond.size()) + " of its " +
         std::to_string(compared) + " compared modes" + (others.empty() ? "" : " (also at " + others + " Hz)") +
         "; the farthest: at " + g(at->data_hz) + " Hz the model decays at " + g(at->model_decay_1_s, 3) +
         " 1/s (zeta " + g(100 * at->model_damping_ratio, 3) + " %), the record at " + g(at->data_decay_1_s, 3) +
         " +- " + g(at->data_decay_uncertainty_1_s, 2) + " 1/s (zeta " + g(100 * at->data_damping_ratio, 3) +
         " %), beyond " + g(100 * kDampingMismatch, 2) + " % and " + g(kDampingMismatchUncertainties, 2) +
         " of its uncertainties: a damping model that cannot follow the record's modes, or a cost whose damping "
         "estimate is biased (a window that opens after the decay, noise on the spikes' magnitudes); the damping's "
         "standard errors do not include it";
}

namespace {

using Markdown = std::ostringstream;

// The command that ran, the record, the model, the cost and the optimizer.
void header_section(Markdown& md, const FitReportInput& in, const costs::Evaluation& first) {
  const auto& o = in.options;
  const auto& r = in.result;
  md << kReportHeading << "\n\n";
  md << "beamid " << io::version() << " (commit " << io::commit_label() << "): `beamid fit";
  for (const auto& arg : in.arguments) md << " " << arg;
  md << "`\n\n";
  md << "- data: `" << in.data.path << "`, " << in.data.values.size() << " samples at dt = " << g(in.data.dt_s)
     << " s (column `" << in.data.value_column << "`";
  for (std::size_t k = 1; k < in.channels.size(); ++k) md << ", `" << in.channels[k].value_column << "`";
  md << (in.channels.size() > 1 ? ", fitted jointly: the modes and spikes below are the first's" : "") << ")\n";
  md << "- model: beam `" << in.beam_name << "` (known parameters and start), N = " << o.elements << ", "
     << o.experiment.excitation << " excitation, " << o.experiment.output << " output, integrator "
     << o.simulator.integrator;
  if (o.sensor.cutoff_hz > 0)
    md << ", the sensor's order-" << o.sensor.order << " Butterworth low-pass at " << g(o.sensor.cutoff_hz)
       << " Hz in the model (simulated " << o.sensor.oversampling << " times finer)";
  md << "\n";
  md << "- cost `" << o.cost.name << "`";
  if (costs::is_spike_cost(o.cost.name))
    md << ", NM = " << o.cost.spikes.count << " spikes (rule " << o.cost.spikes.rule << "), window "
       << o.cost.window.name;
  if (o.cost.unknown_amplitude) md << ", unknown excitation amplitude (scale " << g(first.amplitude_scale) << ")";
  md << "\n- optimizer `" << o.optimizer.method << "`, strategy `" << o.strategy << "`, " << o.starts
     << " start(s) (best: " << r.best_start << "), scaling " << o.scaling << ", seed " << o.seed << "\n\n";
}

// The record's modes beside the model's at the estimate.
void modes_section(Markdown& md, const FitReportInput& in) {
  const ModeComparison modes = in.modes ? *in.modes : compare_modes(in);
  md << "## Modes\n\n";
  if (modes.status != "ok") {
    md << "Not compared: " << modes.status << ".\n\n";
  } else {
    md << "The record's modes (matrix pencil on its free decay, with the uncertainty of a measured frequency: its "
          "noise, its drift between the record's segments and the close poles that fit it) beside the model's at the "
          "estimate, paired by frequency:\n\n| mode | data f (Hz) | its uncertainty (Hz) | model f (Hz) | data zeta "
          "(%) | model zeta (%) |\n|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < modes.pairs.size(); ++k)
      md << "| " << k + 1 << " | " << g(modes.pairs[k].data_hz, 8) << " | " << g(modes.pairs[k].data_uncertainty_hz, 3)
         << " | " << g(modes.pairs[k].model_hz, 8) << " | " << g(100 * modes.pairs[k].data_damping_ratio, 4) << " | "
         << g(100 * modes.pairs[k].model_damping_ratio, 4) << " |\n";
    md << "\n";
    for (const ModePair& pair : modes.pairs)
      if (!pair.data_note.empty()) md << "- The record: " << pair.data_note << ".\n";
    for (const std::string& note : modes.notes) md << "- " << note << ".\n";
    for (const std::string& note : {modes_mismatch_note(modes), damping_mismatch_note(modes)})
      if (!note.empty()) md << "- " << note << ".\n";
    md << "\n";
  }
}

// The status, the estimates with their three uncertainties, and what each means.
void result_section(Markdown& md, const FitReportInput& in) {
  const auto& o = in.options;
  const auto& r = in.result;
  md << "## Result\n\n";
  md << "Status **" << r.status << "** (" << r.termination << "); cost " << g(r.cost, 10) << "; " << r.evaluations
     << " model evaluations; " << g(r.wall_time_s, 3) << " s.\n\n";
  const auto sd_text = [](double v) { return std::isnan(v) ? std::string("-") : g(v, 3); };
  md << "| parameter | estimate | standard error | sandwich | window sd | start | lower | upper | status "
        "|\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const auto& p = r.parameters[i];
    md << "| " << p.key << " | " << g(p.estimate, 10) << " | " << sd_text(p.standard_error) << " | "
       << sd_text(p.robust_standard_error) << " | " << (in.spread ? sd_text(in.spread->sd[i]) : "-") << " | "
       << g(p.start) << " | " << g(p.lower) << " | " << g(p.upper) << " | " << p.status << " |\n";
  }
  md << "\nThree uncertainties (`src/fit/optimizer.h`, `src/fit/window_spread.h`). The standard error and the "
        "correlations are formal: (J^T J)^-1 |r|^2/(m - n) at the estimate, valid only if the residuals are "
        "independent noise of equal variance, which is not so for the spike costs' mixed terms nor for model error. "
        "The sandwich admits residuals of unequal variance and, for the time cost, correlated over "
     << fit::robust_lags(o.cost.name, static_cast<int>(r.final_evaluation.residuals.size()))
     << " samples. The window sd is the scatter of the estimates over disjoint windows of the record (`--windows K`), "
        "which contains what the model gets wrong along the record and the windows' own noise (each window carries "
        "less information than the whole record). When the three agree, quote the formal one; when the sandwich is "
        "several times larger, or the window sd several times the windows' own formal error (the table of the "
        "windows below), the residuals are model error, not noise: quote the window sd (the conservative one). "
        "Covariance: "
     << r.covariance_status << "; sandwich: " << r.sandwich_status << ".\n\n";
}

// The estimates in each window (--windows).
void spread_section(Markdown& md, const FitReportInput& in) {
  if (in.spread) {
    md << "Estimates in each of the " << in.spread->windows << " windows (the first keeps the excitation; the others "
       << "are free decays from an unknown state):\n\n| window | status |";
    for (const auto& k : in.spread->keys) md << " " << k << " |";
    md << "\n|---|---|";
    for (std::size_t i = 0; i < in.spread->keys.size(); ++i) md << "---|";
    md << "\n";
    for (std::size_t w = 0; w < in.spread->estimates.size(); ++w) {
      md << "| " << w + 1 << " | " << in.spread->statuses[w] << " |";
      for (const double v : in.spread->estimates[w]) md << " " << g(v, 8) << " |";
      md << "\n";
    }
    md << "\nThe window sd counts only the " << in.spread->used
       << " window(s) whose fit converged: one stopped by the evaluation budget sits where the budget left it. "
       << (in.spread->bound_bias ? "Some windows hold a parameter on its bound, which biases their other estimates "
                                   "too: the sd holds that bias as well. "
                                 : "")
       << "Its "
          "yardstick is the windows' own formal error (each window carries less information than the record, the "
          "later ones being free decays): a window sd within twice it is the windows' noise; several times it is "
          "model error or drift along the record, or windows whose weaker modes lie near the noise, where the formal "
          "error understates the scatter (on a model-exact record at 2 % noise: up to 4.5 times).\n\n| parameter | "
          "window sd | the windows' own formal error | ratio "
          "|\n|---|---|---|---|\n";
    for (std::size_t i = 0; i < in.spread->keys.size(); ++i)
      md << "| " << in.spread->keys[i] << " | " << g(in.spread->sd[i], 3) << " | " << g(in.spread->window_formal[i], 3)
         << " | " << g(in.spread->sd[i] / in.spread->window_formal[i], 3) << " |\n";
    md << "\n";
  }
}

// The estimates' correlations (formal).
void correlation_section(Markdown& md, const fit::FitResult& r) {
  if (r.correlation.size() > 0) {
    md << "| correlation |";
    for (const auto& p : r.parameters) md << " " << p.key << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < r.parameters.size(); ++i) md << "---|";
    md << "\n";
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      md << "| " << r.parameters[i].key << " |";
      for (std::size_t j = 0; j < r.parameters.size(); ++j)
        md << " " << g(r.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), 3) << " |";
      md << "\n";
    }
    md << "\n";
  }
}

// Each record's own cost, weight and amplitude scale in a joint fit.
void records_section(Markdown& md, const fit::FitResult& r) {
  if (r.records.size() > 1) {
    md << "Records of the joint fit, each with its own cost at the estimate (the joint cost is the sum of weight^2 x "
          "cost: time-domain residuals relative to each record's RMS):\n\n| record | name | status | cost | weight | "
          "amplitude scale | (A4) |\n|---|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < r.records.size(); ++k) {
      const fit::RecordResult& part = r.records[k];
      md << "| " << k + 1 << " | " << part.name << " | " << part.evaluation.status << " | "
         << g(part.evaluation.value, 6) << " | " << g(part.weight, 6) << " | " << g(part.evaluation.amplitude_scale, 6)
         << " | " << part.evaluation.a4 << " |\n";
    }
    md << "\n";
  }
}

// The conditioning of J at the estimate and its weak combinations.
void identifiability_section(Markdown& md, const fit::FitResult& r) {
  const fit::Identifiability& id = r.identifiability;
  if (id.status != "ok") {
    md << "Identifiability: not computed (" << id.status << ").\n\n";
    return;
  }
  md << "Identifiability: J at the estimate (in ln q)" << id.scope() << " has condition number " << g(id.condition, 3)
     << " (" << id.verdict << "); the weakest combination is " << id.combination() << ", formal standard deviation "
     << g(id.weakest_sd, 3) << " (relative)."
     << (id.verdict == "not identifiable" ? " The record cannot separate the parameters in it: fix one of them." : "")
     << "\n\n";
  if (id.weak.size() > 1) {
    md << "Every combination with sqrt(lambda_max / lambda) above 1e3, weakest first:\n\n| combination | ratio | "
          "formal sd (relative) |\n|---|---|---|\n";
    for (const auto& w : id.weak)
      md << "| " << id.combination(w.components) << " | " << g(w.ratio, 3) << " | " << g(w.sd, 3) << " |\n";
    md << "\n";
  }
}

// Each stage of the best start.
void stages_section(Markdown& md, const fit::FitResult& r) {
  md << "| stage | parameters | status | cost | evaluations | termination |\n|---|---|---|---|---|---|\n";
  for (const auto& s : r.stages) {
    std::string keys;
    for (const auto& k : s.keys) keys += (keys.empty() ? "" : ", ") + k;
    md << "| " << s.name << " | " << keys << " | " << s.result.status << " | " << g(s.result.cost, 6) << " | "
       << s.result.evaluations << " | " << s.result.termination << " |\n";
  }
}

// The spike table and the spectra around each spike (spike costs), then the full spectra's file name; returns the
// full spectra as CSV (bin, frequency_hz, data_magnitude, model_magnitude).
std::string spectra_section(Markdown& md, const FitReportInput& in, const costs::Evaluation& first,
                            const std::string& spectra_path) {
  const auto& o = in.options;
  const auto& r = in.result;
  // Spectra of data and fitted model (same window as the cost).
  signal::Dft dft(static_cast<int>(in.data.values.size()), in.data.dt_s, o.cost.window);
  const signal::Spectrum z = dft.transform(in.data.values);
  const bool have_model = r.model_output.size() == in.data.values.size();
  const signal::Spectrum u = have_model ? dft.transform(r.model_output) : z;
  const auto& pairs = first.pairs;
  // The modal cost pairs the data's matrix-pencil poles with the model's eigenvalues: no bins, supports or (A4), so
  // its table is of frequencies and decay rates (a spike table at bin 0 was printed: issue 31).
  if (!pairs.empty() && o.cost.name == costs::kModalCost) {
    md << "\n## Modes: the data's (matrix pencil) and the model's eigenvalues\n\n"
          "| mode | data f (Hz) | data sigma (1/s) | model f (Hz) | model sigma (1/s) | f error (%) |\n"
          "|---|---|---|---|---|---|\n";
    for (std::size_t l = 0; l < pairs.size(); ++l) {
      const auto& p = pairs[l];
      md << "| " << l + 1 << " | " << g(p.data_frequency_hz, 8) << " | " << g(p.data_decay_rate_1_s, 5) << " | "
         << g(p.model_frequency_hz, 8) << " | " << g(p.model_decay_rate_1_s, 5) << " | "
         << g(100 * (p.model_frequency_hz / p.data_frequency_hz - 1), 3) << " |\n";
    }
  } else if (!pairs.empty()) {
    md << "\n## Spikes and (A4)\n\n(A4) check at the estimate: " << first.a4 << ".\n\n";
    md << "| spike | data bin | data f (Hz) | data sigma (1/s) | n_l | N_l | model bin | model f (Hz) | model sigma "
          "(1/s) | data abs Z | model abs U | jumps |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t l = 0; l < pairs.size(); ++l) {
      const auto& p = pairs[l];
      md << "| " << l + 1 << " | " << p.data.bin << " | " << g(p.data_frequency_hz, 8) << " | "
         << (std::isnan(p.data_decay_rate_1_s) ? "-" : g(p.data_decay_rate_1_s, 5)) << " | " << p.data.n_left << " | "
         << p.data.n_right << " | " << (p.model_bin >= 0 ? std::to_string(p.model_bin) : "-") << " | "
         << g(p.model_frequency_hz, 8) << " | "
         << (std::isnan(p.model_decay_rate_1_s) ? "-" : g(p.model_decay_rate_1_s, 5)) << " | " << g(p.data.magnitude, 4)
         << " | " << g(p.model_magnitude, 4) << " | " << (p.jumps ? "yes" : "no") << " |\n";
    }
    md << "\nData and model spectra around each data spike (|Z| and |U| on the same bins):\n\n"
          "| spike | bin | f (Hz) | data abs Z | model abs U |\n|---|---|---|---|---|\n";
    for (std::size_t l = 0; l < pairs.size(); ++l)
      for (int j = -3; j <= 3; ++j) {
        const int k = pairs[l].data.bin + j;
        if (k < 0 || k > z.last_bin()) continue;
        md << "| " << l + 1 << " | " << k << " | " << g(z.frequency_hz(k), 8) << " | " << g(z.magnitude(k), 4) << " | "
           << (have_model ? g(u.magnitude(k), 4) : "-") << " |\n";
      }
  }
  md << "\nFull spectra: `" << spectra_path << "` (bin, frequency_hz, data_magnitude, model_magnitude).\n";

  std::ostringstream csv;
  csv << kSpectraHeader << "\n";
  for (int k = 0; k <= z.last_bin(); ++k) {
    csv << k << ",";
    io::write_row(csv, {z.frequency_hz(k), z.magnitude(k), have_model ? u.magnitude(k) : std::nan("")});
  }
  return csv.str();
}

}  // namespace

FitReport render_fit_report(const std::string& path, const FitReportInput& in) {
  const auto& r = in.result;
  // The first record's own evaluation (a single record's is the fit's): its amplitude scale, spikes and (A4).
  const costs::Evaluation& first = r.records.empty() ? r.final_evaluation : r.records.front().evaluation;
  Markdown md;
  header_section(md, in, first);
  modes_section(md, in);
  result_section(md, in);
  spread_section(md, in);
  correlation_section(md, r);
  records_section(md, r);
  identifiability_section(md, r);
  stages_section(md, r);
  FitReport report;
  report.spectra_path = path + ".spectra.csv";
  report.spectra_csv = spectra_section(md, in, first, report.spectra_path);
  report.markdown = md.str();
  if (in.beam_toml)
    report.markdown += "\n## The beam (given as a dict from Python; save as beam.toml to re-run)\n\n```toml\n" +
                       *in.beam_toml + "```\n";
  return report;
}

// The report and its side file, REPORT.spectra.csv, are checked before the fit: a regular file there that beamid did
// not write (its first line is not the report's heading, or the spectra header) is refused, not replaced (a user's
// mine.md.spectra.csv, mine.md and even a data file named as the report were overwritten without a word: the third
// pass's P509, the fourth's Q320, Q476).
void check_report_outputs(const Flags& a) {
  if (!a.has("report")) return;
  check_output_file(a, "report");
  refuse_overwriting_inputs(a, {"report"}, {"", ".tmp", ".spectra.csv", ".spectra.csv.tmp"}, {"data", "beam"});
  const std::string report = a.text("report");
  if (io::is_existing_file(report)) {
    const std::string head = io::read_file_head(report, "cannot read the existing report", 256);
    a.require(head.rfind(kReportHeading, 0) == 0, "report",
              "exists and is not a fit report beamid wrote: move it, or choose another report name");
  }
  const std::string side = report + ".spectra.csv";
  // A name the file system cannot hold failed the report after the fit (the twenty-second pass's P13): said before.
  for (const std::string& output : {report, side})
    if (std::filesystem::path(output).filename().string().size() > 255)
      a.require(false, "report",
                "'" + std::filesystem::path(output).filename().string().substr(0, 40) + "...' is " +
                    std::to_string(std::filesystem::path(output).filename().string().size()) +
                    " bytes long: a file name holds at most 255 (the report's spectra go to REPORT.spectra.csv)");
  const std::string problem = io::replaceable_output_problem(side);
  a.require(problem.empty(), "report", "its side file '" + side + "' " + problem);
  if (!io::is_existing_file(side)) return;
  const std::string head = io::read_file_head(side, "cannot read the report's side file", 256);
  a.require(head.rfind(kSpectraHeader, 0) == 0, "report",
            "its side file '" + side +
                "' exists and is not a spectra table beamid wrote: move it, or choose another report name");
}

void write_fit_report(const std::string& path, const FitReportInput& in) {
  const FitReport report = render_fit_report(path, in);
  // Both files by atomic rename: a reader (or a killed run) sees the old file or the new one, never half. The spectra
  // first: a report is never left pointing at a spectra file that could not be written (a full disk did: the
  // twentieth pass's P4).
  try {
    io::write_file_atomic(report.spectra_path, report.spectra_csv);
    io::write_file_atomic(path, report.markdown);
  } catch (const InputError& error) {
    throw InputError("beamid fit: --report = '" + path + "': " + error.what());
  } catch (const OutputError& error) {
    throw OutputError("beamid fit: --report = '" + path + "': " + error.what());
  }
}

}  // namespace beamid::apps
