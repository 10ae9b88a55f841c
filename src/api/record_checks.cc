#include "api/record_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "fit/identification.h"
#include "io/units.h"
#include "signal/spectrum.h"
#include "simulation/experiment.h"

namespace beamid::api {

// The model's time base is the record's: a forced experiment starts at t = 0 (a free decay is timed from its first
// sample), and a --dt or --samples given must agree with the data.
void match_record(const FitRequest& request, const io::TimeSeries& data, simulation::Experiment& experiment) {
  const Caller& caller = request.caller;
  // --resample-rate leaves out the low-pass's half-length at each end (io/time_series.h), so a resampled record no
  // longer starts at the excitation: said by name (the error blamed a cut the user had not made: the seventeenth
  // pass's P5).
  if (experiment.excitation != simulation::kFreeDecay && std::abs(data.t0_s) > 1e-9 * data.dt_s &&
      data.notes.find("resampled from") != std::string::npos)
    refuse(caller, "--data = '" + data.path + "': resampled (--resample-rate), it starts at t = " +
                       format_value(data.t0_s) + " s, not at the " + experiment.excitation +
                       "'s t = 0: the resampler leaves out its low-pass's first samples, where the filter is cut "
                       "short; fit it as a free decay (--excitation free-decay) or resample the record beforehand");
  if (experiment.excitation != simulation::kFreeDecay && std::abs(data.t0_s) > 1e-9 * data.dt_s)
    refuse(caller, "--data = '" + data.path + "': first time " + format_value(data.t0_s) +
                       " s: must be 0 (the experiment starts at t = 0; a record cut from later is a free decay: "
                       "--excitation free-decay)");
  if (request.experiment.dt_s && std::abs(experiment.dt_s - data.dt_s) > 1e-9 * data.dt_s)
    refuse(caller, "dt", format_value(*request.experiment.dt_s),
           "must equal the data's time step " + format_value(data.dt_s) + " s");
  if (request.experiment.samples && experiment.samples != static_cast<int>(data.values.size()))
    refuse(caller, "samples", std::to_string(*request.experiment.samples),
           "must equal the data's " + std::to_string(data.values.size()));
  experiment.dt_s = data.dt_s;
  experiment.samples = static_cast<int>(data.values.size());
}

// A measured force (--force-channel) and what reads it: the same length as the response, not a response channel too
// (by name or by index), and only where it is modelled.
void check_force_channel(const FitRequest& request, const std::vector<io::TimeSeries>& channels,
                         const simulation::Experiment& experiment) {
  const Caller& caller = request.caller;
  const std::string& force = request.experiment.force_channel;
  if (request.cost.force_noise_sd && experiment.excitation != simulation::kSampledForce)
    refuse(caller, "force-noise-sd", format_value(*request.cost.force_noise_sd),
           "is the measured force's noise: give the record's force with --force-channel");
  if (experiment.excitation != simulation::kSampledForce) return;
  if (request.windows)
    refuse(caller, "windows", std::to_string(*request.windows),
           "cuts the record into windows that start after the force; with --force-channel each window's force "
           "history is not modelled yet");
  for (const io::TimeSeries& channel : channels) {
    if (channel.value_column == force)
      refuse(caller, "force-channel", force, "is also a response --channel: the force drives the model");
    if (experiment.force_samples_N.size() != channel.values.size())
      refuse(caller, "force-channel", force,
             "has " + std::to_string(experiment.force_samples_N.size()) + " samples; the response '" +
                 channel.value_column + "' has " + std::to_string(channel.values.size()));
  }
  // The modal cost's pencil reads the free decay after a pulse; after a measured force it would read the forced part.
  if (request.cost.name == costs::kModalCost)
    refuse(caller, "cost", costs::kModalCost,
           "identifies the free decay after a modelled pulse; with --force-channel use time, freq-band, freq-ml or a "
           "spike cost");
  // The errors-in-variables form reads the model's transfer function, which the exact propagator gives.
  if (request.cost.force_noise_sd && request.integrator && *request.integrator != simulation::kFast)
    refuse(caller, "integrator", *request.integrator,
           "has no transfer function for --force-noise-sd's errors-in-variables form: use the default (fast)");
}

// A force that few samples resolve (a hammer pulse a few samples wide) is not linear between them, as the model holds
// it: a sin^2 pulse 4 samples wide holds 7.6 % of its energy above a quarter of the rate and biased EI by 0.4 %, one
// 20 samples wide 1e-5 of it and 1e-5 of EI (README). Said on `warnings`, not refused: a noisy channel has energy there
// too (white noise: half of its own), so the line is drawn at 5 % of the force's.
void warn_unresolved_force(const FitRequest& request, const fit::FitOptions& o, std::ostream& warnings) {
  if (o.experiment.excitation != simulation::kSampledForce) return;
  signal::Dft dft(static_cast<int>(o.experiment.force_samples_N.size()), o.experiment.dt_s);
  const double upper = signal::upper_band_energy_fraction(dft.transform(o.experiment.force_samples_N));
  if (upper > 0.05)
    warnings << request.caller.label << ": the force channel '" << request.experiment.force_channel << "' holds "
             << format_rounded(100 * upper) << " % of its energy above a quarter of the sampling rate ("
             << format_rounded(0.25 / o.experiment.dt_s)
             << " Hz): its samples do not resolve it, and the model holds it linear between them (a sin^2 pulse "
                "4 samples wide holds 7.6 % and biased EI by 0.4 %); sample faster, or low-pass the channel before "
                "sampling\n";
}

namespace {

// The sd of a measured force's noise, robustly (1.4826 x the median absolute deviation) from its samples after the hit:
// from one hit's length past the last sample above a tenth of the peak to the end. 0 when fewer than 64 samples are
// left (a force that lasts the record: a shaker, a stepped sine) or the peak is 0.
double force_noise_after_hit(const std::vector<double>& force) {
  double peak = 0;
  for (double f : force) peak = std::max(peak, std::abs(f));
  if (!(peak > 0)) return 0;
  // The hit: the run of samples above a tenth of the peak around the peak itself. (Every sample above it, anywhere,
  // took a noise spike 2 s later for the hit's end when the noise reached 4 % of the peak, and nothing was said
  // where the noise was worst: the twenty-fourth pass's adv57 P3.)
  std::size_t first = 0;
  for (std::size_t i = 0; i < force.size(); ++i)
    if (std::abs(force[i]) == peak) {
      first = i;
      break;
    }
  std::size_t last = first;
  while (first > 0 && std::abs(force[first - 1]) > 0.1 * peak) --first;
  while (last + 1 < force.size() && std::abs(force[last + 1]) > 0.1 * peak) ++last;
  const std::size_t from = last + 1 + (last - first + 1);
  if (from + 64 > force.size()) return 0;
  std::vector<double> quiet(force.begin() + static_cast<std::ptrdiff_t>(from), force.end());
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double centre = median(quiet);
  for (double& q : quiet) q = std::abs(q - centre);
  return 1.4826 * median(quiet);
}

}  // namespace

// Output error takes the force as exact; its noise n_u reaches the response as G n_u, and the residual's bins carry
// sd_Y^2 + |G(f_k)|^2 sd_U^2 (per sample, white), concentrated at the resonances, where the parameters are decided.
// The formal errors count sd_Y only: on the thin beam with 2 % force noise they were 16-17x smaller than the
// estimates' scatter over 25 records, with nothing said (the twenty-first pass's P2; REPORT C.6.4: 25-70x, and a
// damping bias). Here sd_U comes from the channel after the hit, |G|^2 from the fitted model's response over the
// force at the bins the force resolves (|U_k| at least 10 times its noise), and sd_Y^2 + (its share) from the
// residual's mean square: said when the force's noise exceeds the residual's in some bin.
void warn_noisy_force(const FitRequest& request, const fit::FitOptions& o, const std::vector<double>& data,
                      const fit::FitResult& result, std::ostream& warnings) {
  const std::vector<double>& force = o.experiment.force_samples_N;
  if (o.experiment.excitation != simulation::kSampledForce || o.cost.force_noise_sd > 0 || result.status == "failed" ||
      result.model_output.size() != data.size() || force.size() != data.size() || o.cost.name == costs::kModalCost)
    return;
  const double noise_sd_N = force_noise_after_hit(force);
  double residual_square = 0;
  for (std::size_t i = 0; i < data.size(); ++i)
    residual_square += (data[i] - result.model_output[i]) * (data[i] - result.model_output[i]);
  residual_square /= static_cast<double>(data.size());
  if (!(noise_sd_N > 0) || !(residual_square > 0)) return;
  const auto n = static_cast<int>(data.size());
  signal::Dft dft(n, o.experiment.dt_s);
  const signal::Spectrum u = dft.transform(force), y = dft.transform(result.model_output);
  // The DFT here is (1/Nbar) sum_i x_i e^{-j 2 pi k i / Nbar} (spectrum.h: Parseval over Nbar): white noise of sd s
  // has s^2 / Nbar in each bin.
  const double force_bin_variance = noise_sd_N * noise_sd_N / n;
  // The model's output is its response to the measured force, so Y_k / U_k is its transfer function in every bin
  // where U_k is not near zero, noise or not: the bins where |U_k|^2 stands 4 times above the noise's bin variance.
  // (At 100 times, a 4 ms pulse over 4096 samples with 20 % force noise had no bin, or one lucky bin off the
  // resonances, and the warning went quiet as the noise grew: the twenty-third pass's adv55 P1.)
  double worst = 0, at_hz = 0;
  bool used = false;
  for (std::size_t k = 1; k < u.half.size(); ++k) {
    if (std::norm(u.half[k]) < 4 * force_bin_variance) continue;
    used = true;
    const double ratio = std::norm(y.half[k]) / std::norm(u.half[k]) * noise_sd_N * noise_sd_N / residual_square;
    if (ratio > worst) worst = ratio, at_hz = u.frequency_hz(static_cast<double>(k));
  }
  if (!used) {
    warnings << request.caller.label << ": the force channel '" << request.experiment.force_channel
             << "' is mostly noise: its noise (sd " << format_rounded(noise_sd_N, 3)
             << " N, from its samples after the hit) reaches a quarter of its spectrum in every bin, and the "
             << o.cost.name
             << " cost takes the force as exact, so its estimate is biased and its standard errors leave that noise "
                "out; fit freq-ml with --force-noise-sd "
             << format_rounded(noise_sd_N, 3) << " --noise-sd S, or check the channel (its unit, its gain)\n";
    return;
  }
  if (worst <= 1) return;
  warnings << request.caller.label << ": the force channel '" << request.experiment.force_channel
           << "' holds noise (sd " << format_rounded(noise_sd_N, 3)
           << " N, from its samples after the hit), which the model passes on through its resonances: near "
           << format_rounded(at_hz, 4) << " Hz it reaches " << format_rounded(worst, 2)
           << " times the residual's power, and the " << o.cost.name
           << " cost takes the force as exact, so its standard errors leave it out and understate the scatter "
              "(16x with 2 % force noise on the thin beam), and the damping is biased (errors in variables: REPORT "
              "C.6.4); fit freq-ml with --force-noise-sd "
           << format_rounded(noise_sd_N, 3) << " --noise-sd S, or zero the channel after the hit (a force window)\n";
}

double negated_force_rise(const fit::FitOptions& o, const std::vector<double>& data, const fit::FitResult& result) {
  if (!(o.cost.force_noise_sd > 0) || result.status == "failed" || o.experiment.excitation != simulation::kSampledForce)
    return std::numeric_limits<double>::quiet_NaN();
  // Refitted, from the estimate: at fixed parameters the comparison says little, the estimate being the measured
  // force's (the wrong-sign channel's estimate cost 46 more with the right sign put back).
  fit::FitOptions negated = o;
  for (double& f : negated.experiment.force_samples_N) f = -f;
  negated.start = result.beam;
  negated.starts = 1;
  try {
    const fit::FitResult refit = fit::fit(negated, data);
    if (refit.status == "failed") return std::numeric_limits<double>::quiet_NaN();
    return refit.cost - result.cost;
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

// A record that states what it measures (its unit, io/units.h) is not fitted as another quantity: a velocity in m/s
// fitted as a displacement "converged" with EI on its bound, without a word (the adversarial pass's V013-V016). A
// free decay's mode amplitudes are solved for, so its quantity does not matter (simulation/free_decay.h).
void check_quantity(const Caller& caller, const std::vector<io::TimeSeries>& channels,
                    const simulation::Experiment& experiment) {
  if (experiment.excitation == simulation::kFreeDecay) return;
  for (const io::TimeSeries& record : channels) {
    if (io::is_non_motion_unit(record.unit))
      refuse(caller, "data", record.path,
             record.value_column + " is in " + record.unit +
                 ", a raw sensor signal, not a motion: convert it to m, m/s "
                 "or m/s^2 with the sensor's sensitivity (or fit it as --excitation free-decay, whose amplitudes are "
                 "free)");
    const std::string quantity = io::quantity_of(record.unit);
    if (!quantity.empty() && quantity != experiment.output)
      refuse(caller, "output", experiment.output,
             "the record " + record.path + " (" + record.value_column + ") is in " + record.unit + ", a " + quantity +
                 ": give --output " + quantity + " (or name the column for what it holds)");
  }
}

}  // namespace beamid::api
