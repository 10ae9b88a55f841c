#include "api/fit_request.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include "api/model_notes.h"
#include "api/record_checks.h"
#include "core/errors.h"
#include "core/limits.h"
#include "fit/sensed_output.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "io/resources.h"
#include "io/units.h"
#include "signal/noise.h"
#include "signal/noise_spectrum.h"
#include "signal/spectrum.h"
#include "signal/spikes.h"
#include "simulation/simulator.h"

namespace beamid::api {

std::vector<fit::EstimatedParameter> estimated_parameters(const FitRequest& request) {
  const model::BeamParameters& nominal = request.beam;
  std::string listed;  // the --estimate list as given, for its errors
  for (const std::string& key : request.estimate) listed += (listed.empty() ? "" : ",") + key;
  std::map<std::string, std::pair<double, double>> explicit_bounds = request.bounds;
  std::vector<fit::EstimatedParameter> estimate;
  bool factor_read = false;
  for (const std::string& key : request.estimate) {
    if (!model::describe_parameter(nominal, key))
      refuse(request.caller, "estimate", listed,
             "'" + key + "' is not a parameter of this beam (valid: " + model::estimable_keys(nominal) + ")");
    if (auto b = explicit_bounds.find(key); b != explicit_bounds.end()) {
      estimate.push_back({key, b->second.first, b->second.second});
      explicit_bounds.erase(b);
      continue;
    }
    const double v = model::parameter_value(nominal, key);
    if (!(v > 0))
      refuse(request.caller, "--estimate " + key + ": the --beam value is " + format_value(v) +
                                 ", so --bound-factor gives no range: give --bounds " + key + "=LO:HI");
    estimate.push_back(fit::bounds_around(key, v, request.bound_factor.value_or(kDefaultBoundFactor)));
    factor_read = true;
  }
  // A bound factor that no estimated key takes (--bounds gives every one) is read by nothing (the fourth pass's Q110).
  if (request.bound_factor && !factor_read)
    refuse(request.caller, "bound-factor", format_value(*request.bound_factor),
           "sets the bounds of estimated keys --bounds leaves out; --bounds gives every one");
  if (!explicit_bounds.empty())
    refuse(request.caller, "--bounds names '" + explicit_bounds.begin()->first + "', which is not in --estimate");
  return estimate;
}

namespace {

// --welch K: the spikes picked on Welch's average of the (detrended) record, each refined on the whole record's DFT:
// its largest local maximum within one Welch bin ((K + 1)/2 of the record's), which the cost's +-5 % window around
// the frequency then finds however coarse the Welch bin was (signal/spikes.h).
std::vector<double> welch_picks(const FitRequest& request, const io::TimeSeries& data, const costs::CostOptions& cost) {
  const Caller& caller = request.caller;
  if (!cost.spikes.frequencies_hz.empty())
    refuse(caller, "welch", std::to_string(*request.welch), "picks the spikes: leave out --spike-frequencies");
  const std::vector<double> values = signal::detrend(data.values, cost.pick_detrend);
  const signal::Spectrum welch = signal::welch_spectrum(values, data.dt_s, *request.welch);
  signal::Dft dft(static_cast<int>(data.values.size()), data.dt_s);
  const signal::Spectrum full = dft.transform(values);
  const std::vector<int> maxima = signal::local_maxima(full);
  std::vector<double> picks;
  for (const auto& p : signal::label_peaks(welch, cost.spikes)) {
    if (!p.skipped.empty()) continue;
    int best = -1;
    for (int k : maxima)
      if (std::abs(full.frequency_hz(k) - p.spike.frequency_hz) <= welch.df_hz() &&
          (best < 0 || full.magnitude(k) > full.magnitude(best)))
        best = k;
    const double f = best >= 0 ? full.frequency_hz(best) : p.spike.frequency_hz;
    if (std::find(picks.begin(), picks.end(), f) == picks.end()) picks.push_back(f);
  }
  std::sort(picks.begin(), picks.end());
  if (picks.empty()) refuse(caller, "welch", std::to_string(*request.welch), "found no peak to fit");
  return picks;
}

}  // namespace

namespace {

// The longest a fit may take, said before it starts when over a minute: its evaluation budget over all starts times
// one evaluation, which grows with the samples and N (measured: 0.034 s for 1e6 samples at N = 8, time cost, about
// 4.3e-9 s per sample and element) plus the N^3 decomposition. A 6e6-sample free decay and --starts 1000 ran
// silently past 30 s (the third pass's P302, P491).
void warn_long_fit(const fit::FitOptions& o, double samples, const Caller& caller, std::ostream& warnings) {
  const double n = o.elements;
  const double per_evaluation = core::kSecondsPerSampleAndElement * samples * n + core::seconds_per_evaluation(n);
  const double evaluations =
      static_cast<double>(o.optimizer.max_evaluations) * std::max(1, o.starts) * (o.strategy == fit::kHybrid ? 2 : 1);
  const double worst = per_evaluation * evaluations;
  if (worst > 60)
    warnings << caller.label << ": one model evaluation takes about " << format_rounded(per_evaluation) << " s"
             << " here (" << static_cast<long long>(samples) << " samples at N = " << o.elements
             << "), and the fit may "
             << "take up to " << evaluations << " of them, " << io::seconds_text(worst)
             << ": cut the record (--start, --duration), lower its rate (--resample-rate) or the budget "
                "(--max-evaluations, --starts)\n";
}

// Where the spikes are picked: the record less its offset and trend (--detrend), and Welch's average (--welch).
void pick_spikes(const FitRequest& request, const io::TimeSeries& data, fit::FitOptions& o, bool* welch_picked) {
  const Caller& caller = request.caller;
  // A free decay read from a file: its spikes picked without its offset and trend (costs/cost.h).
  o.cost.pick_detrend = request.detrend.value_or(
      o.experiment.excitation == simulation::kFreeDecay ? signal::kDetrendLinear : signal::kDetrendNone);
  if (!signal::detrend_names().contains(o.cost.pick_detrend))
    refuse(caller, "detrend", o.cost.pick_detrend, "must be one of " + signal::detrend_names().list());
  // Read only where spikes are picked: --detrend with the time, freq-band or modal cost changed nothing while the
  // user believed the drift removed (the seventeenth pass's P6). Their models fit what they compare: the free
  // decay's constant c0 (simulation/free_decay.h), the pencil's poles under one cycle, left out as the trend.
  // A free decay fitted by the time or freq-band cost: --detrend linear fits a linear trend beside the constant in
  // the closed-form amplitudes (simulation/free_decay.h), which a drifting sensor needs (the eighteenth pass's P5:
  // refused, the drift was left in the residual); mean is the constant they always fit.
  const bool least_squares = o.cost.name == costs::kTimeCost || costs::is_band_cost(o.cost.name);
  if (request.detrend && least_squares && o.experiment.excitation == simulation::kFreeDecay && !request.welch) {
    if (*request.detrend == signal::kDetrendNone)
      refuse(caller, "detrend", *request.detrend,
             "a free decay's constant (a sensor offset) is always fitted; give mean (that constant) or linear (with a "
             "trend)");
    o.experiment.free_decay_trend = *request.detrend == signal::kDetrendLinear;
    return;
  }
  if (request.detrend && !costs::is_spike_cost(o.cost.name) && !request.welch &&
      !(o.strategy == fit::kHybrid && costs::is_spike_cost(o.refine)))
    refuse(caller, "detrend", *request.detrend,
           "is read where the spike costs (or --welch) pick their spikes, and for a free decay by the time and "
           "freq-band costs (its trend); the " +
               o.cost.name +
               " cost here picks none. The modal cost's pencil leaves an offset or drift out as poles of under one "
               "cycle in the record");
  if (request.welch) {
    // The time and freq-band costs pick no spike: --welch changed nothing there, while stderr said the spikes were
    // picked on Welch's average (the sixteenth pass's P5).
    if (o.cost.name == costs::kTimeCost || costs::is_band_cost(o.cost.name))
      refuse(caller, "welch", std::to_string(*request.welch),
             "picks the spikes of the spike, spike-smooth and modal costs; the " + o.cost.name + " cost has none");
    o.cost.spikes.frequencies_hz = welch_picks(request, data, o.cost);
    o.cost.spikes.count = static_cast<int>(o.cost.spikes.frequencies_hz.size());
    if (welch_picked) *welch_picked = true;
  }
}

}  // namespace

namespace {

// --sensor-bandwidth and its order and oversampling: the record's anti-alias filter in the model, validated.
// The model with the filter runs R times finer: its record and, for an exact Jacobian, a sensitivity column per
// estimated parameter, at that length, are guarded against the machine's memory (`samples`: the records' total).
signal::SensorFilter sensor_filter_of(const FitRequest& request, const simulation::Experiment& experiment,
                                      double samples, std::ostream& warnings) {
  const Caller& caller = request.caller;
  signal::SensorFilter f;
  if (!request.sensor_bandwidth_hz) {
    if (request.sensor_filter_order)
      refuse(caller, "sensor-filter-order", std::to_string(*request.sensor_filter_order),
             "is the order of the --sensor-bandwidth filter: give its cut-off too");
    if (request.sensor_oversampling)
      refuse(caller, "sensor-oversampling", std::to_string(*request.sensor_oversampling),
             "is how finely the --sensor-bandwidth filter's model is simulated: give its cut-off too");
    return f;
  }
  f.cutoff_hz = *request.sensor_bandwidth_hz;
  f.order = request.sensor_filter_order.value_or(f.order);
  f.oversampling = request.sensor_oversampling.value_or(f.oversampling);
  if (!(f.cutoff_hz > 0))
    refuse(caller, "sensor-bandwidth", format_value(f.cutoff_hz), "must be > 0 Hz (leave it out for no filter)");
  if (auto error = fit::sensed_validation_error(f, experiment))
    refuse(caller, "sensor-bandwidth", format_value(f.cutoff_hz), *error);
  // --windows fits every window after the first as a free decay from an unknown state, which the filter's transient
  // would not match (fit/sensed_output.h): every one would fail after the whole fit had run.
  if (request.windows)
    refuse(caller, "windows", std::to_string(*request.windows),
           "fits the windows after the first as free decays, which a model with --sensor-bandwidth cannot (leave out "
           "one of them)");
  guard_run_size(caller, request.elements, samples * f.oversampling,
                 core::kSimulateBytesPerSample + 8.0 * static_cast<double>(request.estimate.size()), warnings);
  return f;
}

}  // namespace

// --of-interest: estimated keys, each named once.
void check_of_interest(const FitRequest& request, const fit::FitOptions& o) {
  const Caller& caller = request.caller;
  for (std::size_t k = 0; k < request.of_interest.size(); ++k) {
    const std::string& key = request.of_interest[k];
    if (std::none_of(o.estimate.begin(), o.estimate.end(), [&](const auto& e) { return e.key == key; }))
      refuse(caller, "of-interest", key, "is not estimated (--estimate names the keys the verdict can be about)");
    // Named once, as in --estimate and --bounds (the twenty-third pass's P6 of adv55).
    if (std::find(request.of_interest.begin(), request.of_interest.begin() + static_cast<std::ptrdiff_t>(k), key) !=
        request.of_interest.begin() + static_cast<std::ptrdiff_t>(k))
      refuse(caller, "of-interest", key, "is given twice: name each parameter once");
  }
}

fit::FitOptions fit_options(const FitRequest& request, const std::vector<io::TimeSeries>& channels,
                            std::ostream& warnings, bool* welch_picked) {
  const Caller& caller = request.caller;
  if (channels.empty()) refuse(caller, "no record to fit");
  const io::TimeSeries& data = channels.front();
  fit::FitOptions o;
  check_elements(caller, request.elements);
  o.elements = request.elements;
  if (const std::string note = attachment_convergence_note(request.beam, o.elements); !note.empty())
    warnings << caller.label << ": at the start's values, " << note << "\n";
  o.experiment = experiment_of(request.experiment, request.beam.l, caller);
  guard_run_size(caller, o.elements, static_cast<double>(data.values.size() * channels.size()),
                 core::kRecordBytesPerSample, warnings);
  match_record(request, data, o.experiment);
  check_force_channel(request, channels, o.experiment);
  check_quantity(caller, channels, o.experiment);
  o.simulator.integrator = request.integrator.value_or(simulation::kFast);
  // A free decay is computed from the model's modes with its initial state solved in closed form (simulation/
  // experiment.h), whatever the integrator: --integrator cvode was ignored without a word.
  if (request.integrator && o.experiment.excitation == simulation::kFreeDecay)
    refuse(caller, "integrator", *request.integrator,
           "applies to --excitation pulse or pluck; a free decay is computed from the model's modes in closed form");
  // A free decay's modal amplitudes are solved against the record already (simulation/free_decay.h): a free scale on
  // top changes nothing (the output was byte-identical with and without: the fourth pass's Q116).
  if (request.cost.unknown_amplitude && o.experiment.excitation == simulation::kFreeDecay)
    refuse(caller,
           "--unknown-amplitude frees the excitation's amplitude; a free decay has none, and its modal amplitudes are "
           "solved against the record already");
  // The free decay's modal amplitudes are solved by unweighted least squares against the record
  // (simulation/free_decay.h): with a coloured noise model that synthesis is not the generalised one the cost assumes,
  // so the fit would be neither least squares nor maximum likelihood. Refused until the synthesis is whitened too.
  if (request.cost.noise_model && o.experiment.excitation == simulation::kFreeDecay &&
      (costs::is_estimated_noise(*request.cost.noise_model) ||
       parsed_noise_model(caller, *request.cost.noise_model).kind != "white"))
    refuse(caller, "noise-model", *request.cost.noise_model,
           "needs a modelled excitation (pulse, pluck): a free decay's modal amplitudes are fitted unweighted, which "
           "a coloured noise model's likelihood does not allow");
  // A hybrid fit's refinement reads the same request's options (its window, its spikes).
  o.cost = cost_options(request.cost, caller,
                        request.strategy == fit::kHybrid ? std::vector<std::string>{request.refine.value_or(o.refine)}
                                                         : std::vector<std::string>{});
  o.optimizer.method = request.optimizer.value_or(fit::default_optimizer(o.cost.name));
  o.optimizer.max_evaluations = request.max_evaluations.value_or(o.optimizer.max_evaluations);
  o.strategy = request.strategy;
  if (request.refine && o.strategy != fit::kHybrid)
    refuse(caller, "refine", *request.refine, "is the second cost of --strategy hybrid only");
  o.refine = request.refine.value_or(o.refine);
  // The default refinement is the time cost: a hybrid of --cost time alone was told "refine = 'time': must differ",
  // naming a flag the user had not given (the seventeenth pass's P8).
  if (o.strategy == fit::kHybrid && !request.refine && o.refine == o.cost.name)
    refuse(caller, "strategy", fit::kHybrid,
           "refines the global --cost " + o.cost.name + " with --refine, whose default is " + o.refine +
               ", the same cost: give --refine freq-band or spike-smooth, or a global --cost (modal, spike-smooth)");
  o.scaling = request.scaling;
  o.record_weights = request.record_weights.value_or(fit::kRmsWeights);
  if (!fit::record_weight_names().contains(o.record_weights))
    refuse(caller, "record-weights", o.record_weights, "must be one of " + fit::record_weight_names().list());
  // Weights between records mean nothing for one: said, not ignored.
  if (request.record_weights && channels.size() == 1)
    refuse(caller, "record-weights", o.record_weights,
           "weighs the records of a joint fit against each other; this fit has one record (give several --channel)");
  o.starts = request.starts;
  const long long seed = request.seed.value_or(1);
  if (seed < 0) refuse(caller, "seed", std::to_string(seed), "must be an integer >= 0");
  o.seed = static_cast<std::uint64_t>(seed);
  // The seed draws the multistart's space-filling starts and crs2-lm's population; a fit with neither draws nothing.
  if (request.seed && o.starts == 1 && o.optimizer.method != "crs2-lm")
    refuse(caller, "seed", std::to_string(seed),
           "seeds the multistart (--starts > 1) and crs2-lm's population; this fit has one start and optimizer " +
               o.optimizer.method + ", with nothing random");
  if (!(request.start_scale > 0)) refuse(caller, "start-scale", format_value(request.start_scale), "must be > 0");
  if (request.bound_factor && !(*request.bound_factor > 1))
    refuse(caller, "bound-factor", format_value(*request.bound_factor), "must be > 1");
  // 1e6 spans twelve orders of magnitude around the start; 1e308 put EI's bound at 4.9e307, past any beam file's
  // limit, and the multistart's starts there evaluated nothing (the thirteenth pass's 7).
  if (request.bound_factor && !(*request.bound_factor <= 1e6))
    refuse(caller, "bound-factor", format_value(*request.bound_factor),
           "must be at most 1e6 (bounds [v/F, v F] over twelve orders of magnitude; give --bounds for more)");
  // The amplitude is solved for with --unknown-amplitude: a stated one would be ignored (the thirteenth pass's 9).
  if (request.cost.unknown_amplitude && request.experiment.force_amplitude_N)
    refuse(caller,
           "--unknown-amplitude solves for the excitation's amplitude: --force-amplitude would be ignored "
           "(leave out one of them)");
  o.estimate = estimated_parameters(request);
  check_of_interest(request, o);
  o.of_interest = request.of_interest;
  const double samples = static_cast<double>(data.values.size() * channels.size());
  o.sensor = sensor_filter_of(request, o.experiment, samples, warnings);
  pick_spikes(request, data, o, welch_picked);
  o.start = request.beam;
  for (const auto& e : o.estimate)
    model::set_parameter_value(o.start, e.key, model::parameter_value(o.start, e.key) * request.start_scale);
  warn_long_fit(o, samples * (o.sensor.cutoff_hz > 0 ? o.sensor.oversampling : 1), caller, warnings);
  return o;
}

namespace {

// A simulated experiment (pulse or pluck) whose model response is zero at the start, at every record's sensor: the
// sensor or the force at a rigid clamp, or no force. Every parameter then leaves the cost alone, and the fit
// "converged" at the start with NaN errors where simulate and crb refuse (the fourteenth pass's P5).
void refuse_zero_model(const fit::FitOptions& o, const std::vector<fit::Record>& records, const Caller& caller) {
  if (o.experiment.excitation == simulation::kFreeDecay) return;
  std::vector<simulation::Experiment> experiments{o.experiment};
  for (const fit::Record& r : records) experiments.push_back(r.experiment);
  const galerkin::SplineSpace space(o.elements);
  const galerkin::BeamForms forms(space, o.start.l, o.start.support);
  for (const simulation::Experiment& e : experiments) {
    const simulation::Trace trace = simulation::simulate(forms, o.start, e, {});  // the fast one: zero either way
    double peak = 0;
    for (const double y : trace.y) peak = std::max(peak, std::abs(y));
    if (trace.ok() && !(peak >= 1e-150))
      refuse(caller, "the model's response at the start is zero at every sample (peak " + format_value(peak) +
                         "): the sensor or the force is at a rigid clamp (--sensor-x, --force-x 0) or the force is 0 "
                         "(--force-amplitude), so no parameter moves the cost");
  }
}

}  // namespace

namespace {

// --profile: each named key's profile-likelihood interval about the fit (fit/profile.h), a refit per point; a key
// named once and estimated, and a failed fit none.
void compute_profiles(const FitRequest& request, const std::vector<double>& data, FitComputation& c) {
  for (std::size_t k = 0; k < request.profile.size(); ++k) {
    const std::string& key = request.profile[k];
    if (std::find(request.profile.begin(), request.profile.begin() + static_cast<std::ptrdiff_t>(k), key) !=
        request.profile.begin() + static_cast<std::ptrdiff_t>(k))
      refuse(request.caller, "profile", key, "is given twice: name each parameter once");
    if (std::none_of(c.options.estimate.begin(), c.options.estimate.end(),
                     [&](const fit::EstimatedParameter& e) { return e.key == key; }))
      refuse(request.caller, "profile", key, "is not estimated (a profile refits the others with it fixed)");
  }
  if (request.profile.empty() || c.result.status == "failed") return;
  std::vector<fit::Record> records = c.records;
  if (records.empty()) records.push_back({"record1", c.options.start, c.options.experiment, data, {}, {}, {}});
  for (const std::string& key : request.profile) try {
      c.profiles.push_back(fit::profile(c.options, records, c.result, key));
    } catch (const InputError& error) {
      refuse(request.caller, "profile", key, error.what());
    }
}

// --posterior: the posterior about the fit (fit/posterior.h), on the cores the machine has (the draws do not depend
// on them); a failed fit has none.
// --posterior's request, before the fit runs: a least-squares cost, and --posterior-steps only with it.
void check_posterior(const FitRequest& request, const FitComputation& c) {
  if (!request.posterior && request.posterior_steps)
    refuse(request.caller, "posterior-steps", std::to_string(*request.posterior_steps),
           "sets the length of --posterior's chains: give --posterior too");
  if (!request.posterior) return;
  if (const std::string problem = fit::posterior_problem(c.options, c.records); !problem.empty())
    refuse(request.caller, "--posterior: " + problem);
}

void compute_posterior(const FitRequest& request, const std::vector<double>& data, FitComputation& c) {
  if (!request.posterior || c.result.status == "failed") return;
  std::vector<fit::Record> records = c.records;
  if (records.empty()) records.push_back({"record1", c.options.start, c.options.experiment, data, {}, {}, {}});
  fit::PosteriorOptions o;
  if (request.posterior_steps) o.sampler.steps = *request.posterior_steps;
  o.sampler.seed = static_cast<std::uint64_t>(request.seed.value_or(1));
  o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  try {
    c.posterior = fit::posterior(c.options, records, c.result, o);
  } catch (const InputError& error) {
    refuse(request.caller, "--" + std::string(error.what()));  // "posterior: ..."
  }
}

}  // namespace

FitComputation compute_fit(const FitRequest& request, const std::vector<io::TimeSeries>& channels,
                           std::ostream& warnings) {
  FitComputation c;
  c.options = fit_options(request, channels, warnings, &c.welch_picked);
  const fit::FitOptions& o = c.options;
  warn_unresolved_force(request, o, warnings);
  const Caller& caller = request.caller;
  // Several channels: one record each, at its own sensor position, fitted jointly (fit/identification.h).
  const std::vector<double>& sensors = request.experiment.sensor_x_m;
  std::string listed;  // the --sensor-x list, for its errors
  for (double x : sensors) listed += (listed.empty() ? "" : ",") + format_value(x);
  // Repeats of one test (--noise-model repeated) share their sensor: one position, or none (the tip), serves all.
  const bool shared = o.cost.noise_model == costs::kRepeatedNoise && sensors.size() <= 1;
  if (channels.size() > 1 || sensors.size() > 1) {
    if (!shared && sensors.size() != channels.size())
      refuse(caller, "sensor-x", listed,
             "must list one position per --channel (" + std::to_string(channels.size()) + " channel(s))");
    for (std::size_t k = 0; k < channels.size(); ++k) {
      fit::Record record{channels[k].value_column, o.start, o.experiment, channels[k].values, {}, {}, {}};
      if (!shared) record.experiment.sensor_x_m = sensors[k];
      if (auto error = simulation::validation_error(record.experiment, o.start.l))
        refuse(caller, "sensor-x", listed, "channel " + std::to_string(k + 1) + ": " + *error);
      c.records.push_back(std::move(record));
    }
    // Every record's position, the shared one included (the tip when none was given).
    c.sensors_m.clear();
    for (const fit::Record& r : c.records) c.sensors_m.push_back(r.experiment.sensor_x_m.value_or(o.start.l));
  }
  refuse_zero_model(o, c.records, caller);
  check_posterior(request, c);
  const std::vector<double>& data = channels.front().values;
  // The lower layers' input errors ("cost spike: spikes = 8: the data spectrum has only 5 local maxima ...") name
  // the command (they did not: the fifth pass's R258-R263).
  try {
    c.result = c.records.empty() ? fit::fit(o, data) : fit::fit(o, c.records);
  } catch (const InputError& error) {
    const std::string what = error.what();
    if (what.rfind(caller.label, 0) == 0) throw;
    refuse(caller, what);
  }
  if (c.records.empty()) warn_noisy_force(request, o, data, c.result, warnings);
  if (c.records.empty() && c.result.final_evaluation.transient_share > 0.5)
    c.result.negated_force_rise = negated_force_rise(o, data, c.result);
  compute_profiles(request, data, c);
  compute_posterior(request, data, c);
  // windows K: the spread over K disjoint windows (fit/window_spread.h), an uncertainty that admits model error.
  if (request.windows && c.result.status != "failed") {
    try {
      c.spread = c.records.empty() ? fit::window_spread(o, data, c.result, *request.windows)
                                   : fit::window_spread(o, c.records, c.result, *request.windows);
    } catch (const InputError& error) {
      refuse(caller, "windows", std::to_string(*request.windows), error.what());
    }
  }
  return c;
}

std::vector<std::string> FitNotes::lines() const {
  std::vector<std::string> out;
  for (const std::string* note :
       {&budget, &rough, &other_minimum, &few_degrees, &weighting, &transient, &on_bound, &explains_nothing, &pairing,
        &no_errors, &no_sandwich, &correlated_bins, &correlated_residuals, &failed, &identifiability})
    if (!note->empty()) out.push_back(*note);
  return out;
}

namespace {
// Below half explained, the residual's sum of squares exceeds the model's: the record is mostly something the model
// is not (noise at a signal-to-noise ratio below 1, another quantity, units, a scale or a force off by a factor). A
// record 102 times the model (milli-g read as m/s^2) was 2 % explained and a record 30 times it 6.6 %, both in
// silence, where only 1 % was said (the fourth pass's Q252, Q257). Said, not refused: a very noisy record is data.
constexpr double kLeastExplainedFraction = 0.5;

// What a least-squares fit leaves of each record (every record of a joint fit, a hybrid fit's refinement: the fifth
// pass's R251-R254), against the record's own cost at a zero model: "" when it explains at least half.
std::string explained_note(const fit::FitResult& result) {
  if (result.status == "failed") return "";
  std::ostringstream line;
  for (const fit::RecordResult& r : result.records) {
    if (!r.evaluation.ok() || !std::isfinite(r.zero_model_value) || !(r.zero_model_value > 0)) continue;
    const std::string which = result.records.size() > 1 ? " of record '" + r.name + "'" : " of the record";
    const double cost = r.evaluation.value, energy = r.zero_model_value;
    // A record of integer counts 1e6 times the model's scale left 99.99999 % of its sum of squares unexplained, with
    // an EI standard error 1600 times the value and no word (the third pass's P055, P095, P116).
    if (cost >= energy) {
      line << (line.tellp() > 0 ? "; " : "") << "the fitted model explains none" << which
           << ": its residual sum of squares " << cost << " is at least the record's own " << energy
           << ", which a zero model attains (is the record noise, another beam's, or another quantity?)";
    } else if (1 - cost / energy < kLeastExplainedFraction) {
      line << (line.tellp() > 0 ? "; " : "") << "the fitted model explains only " << 100 * (1 - cost / energy)
           << " % of the sum of squares" << which << " in what the cost compares (residual " << cost << " of " << energy
           << "): the residual outweighs the model; is the record mostly noise, another beam's, another quantity, "
              "or in other units or scale (or the force off by a factor)?";
    }
  }
  return line.str();
}

// What the cost's shape around the estimate says of its standard errors: a jump (rough), a cliff or curvature
// within them (not quadratic), another minimum nearly as low (other_minimum).
void basin_notes(const fit::FitResult& result, FitNotes& notes) {
  if (result.status == "failed") return;
  // A cost that is not smooth at the estimate (a jump between parameters 1e-10 apart: the twenty-first pass's P1)
  // gives finite differences of garbage: the standard errors, and a "converged" that rests on them, say so.
  if (!result.roughness.empty())
    notes.rough = "the cost is not smooth at the estimate (" + result.roughness +
                  "): its standard errors are finite differences across a jump and cannot be trusted, nor can the "
                  "optimizer's convergence; refit from other starts (--starts) or with another cost, and quote the "
                  "spread over windows (--windows K)";
  // A cliff or a strong curvature within one standard error (the twenty-second pass's P5): the standard errors
  // describe a quadratic the cost is not.
  else if (!result.nonquadratic.empty())
    notes.rough = "the cost is not quadratic within the standard errors (" + result.nonquadratic +
                  "): a cliff or a strong curvature lies within them, so they are no interval and cannot be "
                  "trusted, nor can the optimizer's convergence; refit from other starts (--starts) or with a "
                  "smooth cost (time, spike-smooth, freq-ml), and quote the spread over windows (--windows K)";
  // Several minima the data hardly tell apart (adv51 P3: kAG 13 standard errors from a minimum 20 noise variances
  // lower, "converged" with nothing said).
  if (!result.other_minimum.empty())
    notes.other_minimum = "the cost has another minimum nearly as low (" + result.other_minimum +
                          "): the data hardly tell the two apart, and the standard errors describe the estimate's own "
                          "basin only; compare the two (--start-scale, --bounds), fix what else is known, or use a "
                          "cost whose basin is wider (modal, spike-smooth)";
}

// Standard errors from a residual variance of few degrees of freedom nu = m - n are themselves uncertain (relative sd
// about 1/sqrt(2 nu)), and an interval needs Student's t: the modal cost of 3 modes for 4 parameters (nu = 2) put 9
// of 24 model-exact fits beyond 2 standard errors, with nothing said but that the sandwich was undefined (the
// twenty-third pass's adv55 P3). Said below 10 degrees of freedom, with the 97.5 % quantile of t.
void few_degrees_note(const fit::FitResult& result, FitNotes& notes) {
  const auto m = static_cast<long>(result.final_evaluation.residuals.size());
  const auto n = static_cast<long>(result.parameters.size());
  const long nu = m - n;
  if (result.status == "failed" || result.covariance_status != "ok" || nu < 1 || nu >= 10) return;
  static constexpr double kT975[] = {12.71, 4.30, 3.18, 2.78, 2.57, 2.45, 2.36, 2.31, 2.26};
  notes.few_degrees = "the standard errors rest on a residual variance of " + std::to_string(nu) +
                      " degree(s) of freedom (" + std::to_string(m) + " residuals, " + std::to_string(n) +
                      " parameters): they are themselves uncertain by about " +
                      format_rounded(100 / std::sqrt(2.0 * static_cast<double>(nu)), 2) +
                      " %, and a 95 % interval is the estimate +- " + format_rounded(kT975[nu - 1], 3) +
                      " standard errors (Student's t), not +- 2; compare the Cramer-Rao bound (beamid crb), fit more "
                      "modes or spikes, or quote the spread over windows (--windows K)";
}

void transient_note(const fit::FitResult& result, FitNotes& notes) {
  // The errors-in-variables form's free transient terms span every mode's free decay, and with them the response to a
  // hit: a force of the wrong sign, a hundredth of its size or at the wrong place "converged" as well, EI within 1 SE,
  // where the time cost explained none of the record (the twenty-second pass's P9). When they take out more than half
  // of the weighted residual, the force did little to decide the fit: said, with what its negation, refitted, costs,
  // as a fact and no verdict on the channel. At 20 % force noise a right channel's terms take out 50-80 %, and its
  // negation cost 200 more on some seeds and 108 less on others (the twenty-third pass's adv55 P2, the twenty-fourth's
  // adv57 P2): the form cannot tell the sign there, and a note that asked to check a right channel, or suggested its
  // sign was wrong, misled. So it is not given where the negation costs over kForceDecides (25 on the likelihood-scaled
  // cost, a likelihood ratio of 4e-6) more, unless the terms take out over 95 % (the force then accounts for under a
  // twentieth: a channel of the wrong sign took 99.9 %, and its negation cost 42 more).
  const double share = result.final_evaluation.transient_share;
  const double rise = result.negated_force_rise;
  if (result.status != "failed" && share > 0.5 && (share > 0.95 || !(rise > kForceDecides)))
    notes.transient =
        "the errors-in-variables form's free transient terms take out " + format_rounded(100 * share, 3) +
        " % of its weighted residual at the estimate: the measured force accounts for little of the response, and "
        "the estimate rests mostly on the modes' frequencies and decay" +
        (std::isfinite(rise) ? " (the force negated, refitted, costs " + format_rounded(std::abs(rise), 3) +
                                   (rise < 0 ? " less" : " more") + ")"
                             : std::string()) +
        "; at this force noise the form does not check the channel's sign, scale or position, so check them "
        "yourself (--force-x, the channel's unit), and compare a time-cost fit";
}

// The frequency-domain least squares (freq-band, freq-ml) take every bin's noise as equally large (white, or as the
// noise model weighs it): in AR(0.9) noise with the default white model their formal errors were 2.6 times below the
// scatter and nothing was said (the thirtieth pass's adv69 P1). Their residuals are (Re, Im) per bin of the band: the
// mean power of blocks of W = max(16, bins / 32) bins against the band's, said beyond max(kColouredExcess,
// 1 + 4 / sqrt(W)) (a block mean of white bins has relative sd 1 / sqrt(W)).
std::string uneven_bins_note(const Eigen::VectorXd& e) {
  const auto bins = static_cast<int>(e.size() / 2);
  const int width = std::max(16, bins / 32);
  if (bins < 2 * width) return "";
  double total = 0;
  for (Eigen::Index k = 0; k < 2 * bins; ++k) total += e(k) * e(k);
  if (!(total > 0)) return "";
  double worst = 0;
  int at = 0;
  for (int start = 0; start + width <= bins; start += width) {
    const double block = e.segment(2 * start, 2 * width).squaredNorm() / width / (total / bins);
    if (block > worst) worst = block, at = start;
  }
  if (!(worst > std::max(signal::kColouredExcess, 1 + 4 / std::sqrt(static_cast<double>(width))))) return "";
  return "the residuals' power is uneven across the band: bins " + std::to_string(at + 1) + "-" +
         std::to_string(at + width) + " of its " + std::to_string(bins) + " hold " + format_rounded(worst, 2) +
         " times their average; the standard errors take every bin's noise as the noise model weighs it and "
         "understate the scatter of what the record holds there (in AR(0.9) noise, fitted as white, 2.6 times); "
         "coloured noise or model error: fit freq-ml with --noise-model estimated (or ar:A) to weigh the noise's "
         "colour";
}

// The time cost's formal errors take its residuals (whitened by a given noise model) as white, and the sandwich's
// Newey-West errors as correlated over its few lags (fit::robust_lags): on records in AR(0.9) noise fitted as white
// the formal errors were 3.7-4 times and the sandwich's 1.5 times below the scatter over 14 seeds, with nothing said
// (the twenty-eighth pass's adv65 P2). The residuals' colour is an AR model of them of order up to 20 by Akaike's
// criterion (signal::fit_autoregressive, as --noise-model estimated takes it): a lag-1 test missed AR(0, 0.9) noise,
// whose lag-1 autocorrelation is 0 and whose power near 0 Hz and Nyquist is 10 times its average (3.2 times below the
// scatter: the twenty-ninth pass's adv67 P1). Said where that model puts more than kColouredExcess times the average
// power in a bin (the standard error of a mode's parameters there about sqrt of it too small); quiet on a record fitted
// to round-off (residual rms under 1e-9 of the record's: its residuals are the arithmetic's, adv67 P3).
std::string correlated_residuals_note(const fit::FitResult& result) {
  const Eigen::VectorXd& e = result.final_evaluation.residuals;
  if (result.status == "failed" || result.covariance_status != "ok" || e.size() < 32) return "";
  const bool frequency = result.final_cost == costs::kBandCost || result.final_cost == costs::kMaxLikelihoodCost;
  if (result.final_cost != costs::kTimeCost && !frequency) return "";
  bool above_round_off = false;
  for (const fit::RecordResult& r : result.records)
    above_round_off |= !(r.evaluation.value <= 1e-18 * r.zero_model_value);
  if (!above_round_off) return "";
  if (frequency) return uneven_bins_note(e);
  const auto m = static_cast<int>(e.size());
  const signal::NoiseModel colour = signal::fit_autoregressive(std::vector<double>(e.data(), e.data() + m), 20);
  const signal::ColourExcess excess = signal::colour_excess(colour, m);
  if (!excess.coloured) return "";
  const std::vector<double>& g = excess.by_bin;
  const std::size_t peak = excess.peak_bin;
  return "the residuals are coloured: an AR(" + std::to_string(colour.ar.size()) +
         ") model of them (Akaike's order) puts " + format_rounded(g[peak], 2) + " times their average power at " +
         format_rounded(2.0 * static_cast<double>(peak) / m, 2) +
         " of the Nyquist frequency; the formal standard errors take them as white and understate the scatter of "
         "what the record holds there (in AR(0.9) noise 3.7-4 times), and the sandwich's, which allow correlation "
         "over " +
         std::to_string(fit::robust_lags(costs::kTimeCost, m)) +
         " lags, too when it lasts longer; coloured noise or model error: fit with --noise-model estimated (or "
         "ar:A) to weigh the noise's colour";
}

void weighting_note(const fit::FitResult& result, const costs::CostOptions& cost, FitNotes& notes) {
  // The modal cost's relative weighting takes every mode's frequency and decay-rate errors as equally precise
  // fractions, which a record does not measure them to (its first mode to 3e-6, a weak high one to 2.5e-4): over
  // model-exact records its formal standard errors were 2 times too small with 4 modes and 3-5 times too large with 6
  // (the twenty-fifth pass's adv59 P1); the measured weighting's held within 15 %.
  // The cost whose standard errors are printed: a hybrid's refinement's, not its modal global stage's (the
  // twenty-sixth pass's adv61 P3).
  if (result.status == "failed" || result.covariance_status != "ok") return;
  // The same for the spike costs, whatever their weighting across spikes: a spike's frequency, decay-rate and magnitude
  // residuals are neither equally precise nor independent, and their few residuals leave the sandwich undefined. Over
  // noise seeds of model-exact records spike-smooth's formal errors were 1.7-2.2 times below the scatter with the
  // relative weighting and 4-15 times with the absolute one (the twenty-eighth pass's adv65 P3), and 3-8 times with
  // inverse-variance on a velocity record (the twenty-ninth pass's adv67 P2; within 1.4 times on adv65's).
  if (costs::is_spike_cost(result.final_cost))
    notes.weighting =
        "the spike cost's standard errors take its residuals (each spike's frequency, decay rate and "
        "magnitude, with the " +
        cost.frequency_weight +
        " weighting across spikes) as equally precise and independent, which they are not: over noise "
        "seeds of model-exact records they were 1.7-15 times below the scatter (every weighting); quote "
        "the spread over windows (--windows K), or refine with a least-squares cost (--strategy hybrid "
        "--refine freq-ml or time) for standard errors that hold";
  // freq-ml's colour estimated from the white fit's residuals is taken as known by its standard errors: over 30
  // displacement records in AR(0.9) noise (5 %) the scatter was 2.5 times them, 1.3 times with the colour known (the
  // twenty-eighth pass's adv65 P1; the local polynomial method overstates the noise at a lightly damped peak narrower
  // than its window, where the displacement's first mode sits in the noise's strongest band).
  if (result.final_cost == costs::kMaxLikelihoodCost && cost.noise_model == costs::kEstimatedNoise)
    notes.weighting =
        "freq-ml's noise colour was estimated from the white fit's residuals (each bin's variance by the local "
        "polynomial method) and its standard errors take it as known: the estimate's own uncertainty is not in them, "
        "and at a lightly damped peak the method overstates the noise (in AR(0.9) noise on displacement records the "
        "scatter was 2.5 times the standard errors); give the colour when it is known (--noise-model ar:A), or "
        "estimate it from repeats (--noise-model repeated)";
  if (result.final_cost == costs::kModalCost && cost.mode_weight == costs::kRelativeModeWeight)
    notes.weighting =
        "the modal cost's relative weighting (the default) takes every mode's errors as equally "
        "precise fractions, which the record does not measure them to: its formal standard errors "
        "can be several times too small or too large; fit with --mode-weight measured (each mode "
        "by its measured uncertainty) for standard errors that hold";
}

}  // namespace

std::vector<std::string> posterior_lines(const fit::Posterior& p) {
  std::vector<std::string> lines;
  for (std::size_t k = 0; k < p.parameters.size(); ++k) lines.push_back("posterior " + p.line(k));
  std::ostringstream s;
  s << "posterior: " << p.status << " (" << p.samples.chains << " chains of " << p.samples.walkers << " walkers, "
    << p.samples.steps << " steps after a warm-up, acceptance " << std::lround(100 * p.samples.acceptance) << " %, "
    << p.samples.evaluations << " model evaluations, " << std::lround(p.wall_time_s) << " s); uniform prior on the "
    << "bounds, the noise level integrated out";
  lines.push_back(s.str());
  s.str("");
  s.precision(8);
  s << "posterior evidence ln p(data): Laplace " << p.log_evidence_laplace << ", sampled " << p.log_evidence_sampled
    << " +- " << p.log_evidence_sampled_se << " (compare models of this record only)";
  if (!p.evidence_note.empty()) s << "; " << p.evidence_note;
  lines.push_back(s.str());
  return lines;
}

std::string profile_line(const fit::Profile& profile, const FitNotes& notes) {
  const bool doubted = !notes.weighting.empty() || !notes.correlated_residuals.empty() ||
                       !notes.correlated_bins.empty() || !notes.rough.empty();
  return profile.line() + (doubted ? "; it weighs the residuals as the standard errors do, which the notes on them "
                                     "doubt: its coverage fails with theirs"
                                   : "");
}

FitNotes fit_notes(const fit::FitResult& result, const costs::CostOptions& cost) {
  FitNotes notes;
  // The formal and sandwich errors take the residuals as uncorrelated (the sandwich lags only the time cost's). A
  // window multiplies the record before its DFT, which smears each bin's noise over its neighbours: freq-band with the
  // exponential window reported errors 2.7-3.5x below its scatter over 12 noise seeds, below the Cramer-Rao bound
  // (the eighteenth pass's P1; Hann 1.0-1.4x). Said until the covariance carries the window's correlation.
  // A nearly flat window (--exponential-end 0.999) correlates nothing and gave the rectangular window's errors to 4
  // digits (the nineteenth pass's U2): said only when the window's equivalent noise bandwidth, Nbar sum w^2 /
  // (sum w)^2 (1 for a flat window, 1.5 for Hann, 2.3 for the exponential window to 0.01), exceeds 1 by a percent.
  if (result.status != "failed" && result.covariance_status == "ok" &&
      (cost.name == costs::kBandCost || costs::is_spike_cost(cost.name))) {
    const std::vector<double> w = signal::window_weights(cost.window, 4096);
    double sum = 0, squares = 0;
    for (double v : w) sum += v, squares += v * v;
    const double bandwidth = sum > 0 ? static_cast<double>(w.size()) * squares / (sum * sum) : 1.0;
    if (bandwidth > 1.01)
      notes.correlated_bins = "the standard errors take the DFT bins as uncorrelated, which the " + cost.window.name +
                              " window (noise bandwidth " + format_rounded(bandwidth, 3) +
                              " bins) makes them not: they can understate the estimates' scatter (freq-band with the "
                              "exponential window to 0.01: 2.7-3.5x, below the Cramer-Rao bound); quote the spread "
                              "over windows (--windows K)";
  }
  notes.correlated_residuals = correlated_residuals_note(result);
  notes.explains_nothing = explained_note(result);
  // (A4) at the estimate: two data spikes or modes pair with one of the model's, so the cost jumped where the
  // pairing changed and the estimate is no minimum of a smooth cost (the modal cost with --spikes 10 on a record of
  // fewer resolvable modes ended with every mode 8 % high and only a tag at the end of the summary: the fourth
  // pass's Q140).
  if (result.status != "failed" && !result.final_evaluation.a4.empty() && result.final_evaluation.a4 != "ok")
    notes.pairing = "the estimate is not reliable: " + result.final_evaluation.a4 +
                    " at the estimate, where the cost is not smooth (its pairing of data and model is ambiguous); ask "
                    "for fewer (--spikes) or name "
                    "them (--spike-frequencies)";
  std::string at_bound;
  for (const fit::ParameterEstimate& p : result.parameters)
    if (p.status == fit::kAtLowerBound || p.status == fit::kAtUpperBound)
      at_bound += (at_bound.empty() ? "" : ", ") + p.key + " " + p.status;
  if (!at_bound.empty())
    notes.on_bound =
        "on a bound: " + at_bound + " (the bound, not the data, set the value; its standard error is not defined)";
  // Where (A4) fails at the last evaluation, that is why no cost was finite: more spikes asked for than the model's
  // spectrum shows (the thirty-second pass's adv73 P1 named only the optimizer's tolerance here).
  if (result.status == "failed")
    notes.failed = "the fit failed, so no estimate is printed (NaN): " +
                   (result.final_evaluation.a4 != "ok" && !result.final_evaluation.a4.empty()
                        ? result.final_evaluation.a4 +
                              " (ask for fewer --spikes, or a model of more elements whose spectrum shows them)"
                        : result.termination);
  // The budget ran out before the optimizer converged: --max-evaluations 5 printed EI 35 standard errors from the
  // minimum as "free" with its standard error, and 1 or 2 evaluations the start itself, said only inside the summary
  // line (the twentieth pass's P2). The estimate is kept (a study's capped Nelder-Mead fits are results too), and said.
  if (result.status.rfind("max-evaluations", 0) == 0)
    notes.budget = "the evaluation budget ran out (" + std::to_string(result.evaluations) +
                   " evaluations) before the optimizer converged: the estimate is where it stopped, not a minimum of "
                   "the cost, and its standard errors take it for one; raise --max-evaluations or start nearer";
  // Exactly determined or underdetermined: NaN standard errors were printed with nothing said (only --report did).
  if (result.status != "failed" && result.covariance_status.rfind("no degrees of freedom", 0) == 0)
    notes.no_errors = result.covariance_status +
                      ": the fit is exactly determined or underdetermined, so its standard errors are not defined "
                      "(NaN); fit more spikes or records, or fewer parameters";
  else if (result.status != "failed" && result.covariance_status != "ok")
    // Every other reason the standard errors are NaN is said too (the twelfth pass's P4 printed NaN with no word).
    notes.no_errors = "the standard errors are not defined (NaN): " + result.covariance_status;
  transient_note(result, notes);
  basin_notes(result, notes);
  few_degrees_note(result, notes);
  weighting_note(result, cost, notes);
  if (result.status != "failed" && result.covariance_status == "ok" && result.sandwich_status != "ok")
    notes.no_sandwich = "the sandwich standard errors are not defined (NaN): " + result.sandwich_status +
                        "; quote the spread over windows (--windows K) instead";
  const fit::Identifiability& i = result.identifiability;
  if (i.status == "ok" && i.verdict != "identifiable") {
    std::ostringstream line;  // numbers as the stream prints them (6 significant digits)
    line << i.verdict << ": condition number of J (in ln q) " << i.condition << i.scope()
         << "; the record hardly constrains " << i.combination() << " (formal sd " << i.weakest_sd << ")"
         << (i.weak.size() > 1 ? " and " + std::to_string(i.weak.size() - 1) +
                                     " further combination(s) above 1e3 (listed in --report)"
                               : std::string());
    notes.identifiability = line.str();
  }
  return notes;
}

}  // namespace beamid::api
