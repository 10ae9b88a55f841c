#include "fit/noise_estimation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/errors.h"
#include "signal/noise.h"
#include "signal/noise_spectrum.h"
#include "signal/spectrum.h"

namespace beamid::fit {

namespace {

// The first way in which record `b`'s experiment is not a repeat of record `a`'s, or nothing.
std::optional<std::string> not_a_repeat(const simulation::Experiment& a, const simulation::Experiment& b) {
  if (a.excitation != b.excitation) return "its excitation is " + b.excitation + ", record 1's " + a.excitation;
  if (a.excitation == simulation::kFreeDecay)
    return std::string("a free decay starts from a state of its own, which differs from record to record");
  if (a.output != b.output) return "it records " + b.output + ", record 1 " + a.output;
  if (a.dt_s != b.dt_s || a.samples != b.samples)
    return "it has " + std::to_string(b.samples) + " samples at dt " + format_value(b.dt_s) + " s, record 1 " +
           std::to_string(a.samples) + " at " + format_value(a.dt_s) + " s";
  if (a.sensor_x_m != b.sensor_x_m) return std::string("its sensor is elsewhere than record 1's");
  if (a.force_x_m != b.force_x_m) return std::string("its force acts elsewhere than record 1's");
  if (a.force_amplitude_N != b.force_amplitude_N || a.pulse_width_s != b.pulse_width_s)
    return std::string("its force's amplitude or width differs from record 1's");
  if (a.force_samples_N != b.force_samples_N)
    return std::string(
        "its measured force differs from record 1's (taps of a hammer are not repeats: use noise_model "
        "'estimated')");
  return std::nullopt;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// What makes records repeats beyond their experiments (the adversarial pass's P3, P4): they share their response and
// differ by noise. Each record's least-squares scale on the records' mean, a = <z, zbar> / <zbar, zbar>, is 1 within
// its noise (sd about sigma / |zbar|); a tap at another force or through another gain is not a repeat. And their
// differences are their noise, not less: the median over the bins of the repeats' variance is not 100 times below that
// of the first record's own noise floor by the local polynomial method (unbiased where the response is smooth, so its
// median is the floor's; a genuine repeat's ratio is about 1), or the records share their noise (a copy, a channel
// recorded twice, rounded).
void check_repeats(const std::string& key, const std::vector<Record>& records, const std::vector<double>& mean,
                   double noise_variance) {
  double mean_square = 0;
  for (const double v : mean) mean_square += v * v;
  const double sd = std::sqrt(noise_variance / mean_square);
  for (std::size_t r = 0; r < records.size(); ++r) {
    double dot = 0;
    for (std::size_t i = 0; i < mean.size(); ++i) dot += records[r].data[i] * mean[i];
    const double scale = dot / mean_square;
    if (std::abs(scale - 1) > std::max(0.1, 5 * sd))
      throw InputError(key + ": record " + std::to_string(r + 1) + " (" + records[r].name + ") is " +
                       format_rounded(scale, 3) +
                       " times the records' mean response: repeats share their response and differ by noise (another "
                       "force or gain is not a repeat)");
  }
  const int samples = static_cast<int>(mean.size());
  if (samples < 28) return;  // too short for one local polynomial window
  signal::Dft dft(samples, records.front().experiment.dt_s);
  std::vector<signal::Spectrum> spectra;
  for (const Record& r : records) spectra.push_back(dft.transform(r.data));
  const std::vector<double> repeated = signal::repeated_record_variance(spectra, 0).variance;
  const std::vector<double> floor = signal::local_polynomial_variance(spectra.front(), {}).variance;
  const auto inner = [](const std::vector<double>& v) { return std::vector<double>(v.begin() + 1, v.end() - 1); };
  const double ratio = median(inner(repeated)) / median(inner(floor));
  if (ratio < 0.01)
    throw InputError(key + ": the records differ by " + format_rounded(ratio, 2) +
                     " of record 1's own noise floor (median over the bins): they share their noise (a copy, one "
                     "channel recorded twice, or rounded), and their differences are not the noise of a repeat");
}

}  // namespace

// A fit of a cost that reads the noise model, with the model estimated from the residuals of its own white-noise fit
// (CostOptions::noise_model "estimated"): the white fit, then each record's noise estimated from its residual at that
// estimate (time: an AR model of order <= 20 by Akaike's criterion; freq-ml: each bin's variance by the local
// polynomial method on the residual's DFT, which holds no resonance peak once the model's response is taken out), then
// the fit again from the white estimate with it. Only the noise's colour matters: its level is the residuals'.
FitResult fit_with_estimated_noise(const FitOptions& o, const std::vector<Record>& records) {
  FitOptions white = o;
  white.cost.noise_model = "white";
  FitResult first = fit(white, records);
  // Said in the stages, never a white fit passed off as one with its noise estimated.
  const auto unestimated = [&first](const std::string& why) {
    for (StageResult& stage : first.stages)
      stage.name = "white noise (the noise not estimated: " + why + "): " + stage.name;
    return first;
  };
  if (first.status == "failed") return unestimated("the white fit failed");
  std::vector<Record> estimated = records;
  std::string described;
  for (std::size_t r = 0; r < records.size(); ++r) {
    const std::vector<double>& y = first.records[r].model_output;
    const std::vector<double>& z = records[r].data;
    if (y.size() != z.size()) return unestimated("no model output at the white estimate");
    // The residual of the fitted output a y (a: the closed-form amplitude, 1 unless --unknown-amplitude).
    const double a = first.records[r].evaluation.amplitude_scale;
    std::vector<double> residual(z.size());
    double power = 0;
    for (std::size_t i = 0; i < z.size(); ++i) {
      residual[i] = z[i] - a * y[i];
      power += residual[i] * residual[i] / static_cast<double>(z.size());
    }
    if (!(power > 0)) return unestimated("a residual of zeros");
    Record& e = estimated[r];
    e.start = first.records[r].beam;
    if (o.cost.name == costs::kMaxLikelihoodCost) {
      // Scaled to unit process variance, as the models' bin variances are: the colour, not the level (whose ratio
      // between records a joint fit's record weights set).
      signal::Dft dft(static_cast<int>(residual.size()), records[r].experiment.dt_s);
      e.bin_variance = signal::local_polynomial_variance(dft.transform(residual), {}).variance;
      for (double& v : e.bin_variance) v /= power;
      e.noise_model = costs::kEstimatedNoise;
    } else {
      e.noise_model = signal::fit_autoregressive(residual, kEstimatedArOrder).text();
      try {
        signal::parse_noise_model(e.noise_model);  // Yule-Walker is stationary; within 1e-6 of a unit root is not taken
      } catch (const InputError&) {
        return unestimated("the residual's AR model " + e.noise_model + " has a root at the unit circle");
      }
    }
    described += (described.empty() ? "" : "; ") + (o.cost.name == costs::kMaxLikelihoodCost
                                                        ? std::string("each bin's variance by local polynomials")
                                                        : e.noise_model);
  }
  FitOptions again = o;
  again.strategy = kDirect;
  again.starts = 1;
  return chained(first, fit(again, estimated),
                 "white noise: ", "the noise estimated from its residuals (" + described + "): ");
}

FitResult fit_with_repeated_noise(const FitOptions& o, const std::vector<Record>& records) {
  const std::string key = "noise_model = '" + costs::kRepeatedNoise + "'";
  if (records.size() < 2)
    throw InputError(key + ": " + std::to_string(records.size()) +
                     " record: the noise is estimated from at least 2 repeats of one experiment (a joint fit's "
                     "records)");
  for (std::size_t r = 1; r < records.size(); ++r)
    if (auto why = not_a_repeat(records.front().experiment, records[r].experiment))
      throw InputError(key + ": record " + std::to_string(r + 1) + " (" + records[r].name +
                       ") is not a repeat of record 1: " + *why);
  // The deviations d_m = z_m - zbar: noise alone when the records are repeats, of variance (M - 1) / M sigma^2 each.
  const std::size_t samples = records.front().data.size();
  const auto count = static_cast<double>(records.size());
  std::vector<double> mean(samples, 0.0);
  for (const Record& r : records)
    for (std::size_t i = 0; i < samples; ++i) mean[i] += r.data[i] / count;
  std::vector<std::vector<double>> deviations;
  // sum of d^2 over (M - 1) Nbar: the noise's variance, unbiased; > 0, as fit::fit refuses two records of the same
  // samples
  double power = 0;
  for (const Record& r : records) {
    std::vector<double> d(samples);
    for (std::size_t i = 0; i < samples; ++i) {
      d[i] = r.data[i] - mean[i];
      power += d[i] * d[i] / ((count - 1) * static_cast<double>(samples));
    }
    deviations.push_back(std::move(d));
  }
  check_repeats(key, records, mean, power);
  std::vector<Record> weighed = records;
  std::string described;
  if (o.cost.name == costs::kMaxLikelihoodCost) {
    signal::Dft dft(static_cast<int>(samples), records.front().experiment.dt_s);
    std::vector<signal::Spectrum> spectra;
    for (const Record& r : records) spectra.push_back(dft.transform(r.data));
    std::vector<double> variance = signal::repeated_record_variance(spectra, kRepeatedSmoothingBins).variance;
    for (double& v : variance) v /= power;
    for (Record& r : weighed) {
      r.noise_model = costs::kRepeatedNoise;
      r.bin_variance = variance;
    }
    described = "each bin's variance across the records";
  } else {
    const std::string model = signal::fit_autoregressive(deviations, kEstimatedArOrder).text();
    try {
      signal::parse_noise_model(model);  // Yule-Walker is stationary; within 1e-6 of a unit root is not taken
    } catch (const InputError&) {
      throw InputError(key + ": the records' deviations give the AR model " + model +
                       ", which has a root at the unit circle: they are not stationary noise");
    }
    for (Record& r : weighed) r.noise_model = model;
    described = model;
  }
  FitResult result = fit(o, weighed);
  for (StageResult& stage : result.stages)
    stage.name = "the noise estimated from " + std::to_string(records.size()) + " repeated records (" + described +
                 "): " + stage.name;
  return result;
}

}  // namespace beamid::fit
