// The typed fit request (api/fit_request.h): a request filled in C++ fits like the command line's flags do, bit for
// bit; its defaults are the command line's; every field's constraint is refused in the command line's one-line form.
#include "api/fit_request.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "../fit/same_model_record.h"
#include "api/record_requests.h"
#include "apps/flag_requests.h"
#include "apps/flags.h"
#include "core/errors.h"
#include "signal/noise.h"

namespace beamid::api {
namespace {

// Four seconds of the thin beam's tip at N = 6 after a 4 ms pulse (README's example), from the model a fit at N = 6
// uses: the cost's minimum is the truth, so a fit from 2 % off must return it to the optimizer's tolerance.
io::TimeSeries record() {
  simulation::Experiment e;
  e.pulse_width_s = 0.004;
  io::TimeSeries s;
  s.path = "<test>";
  s.dt_s = e.dt_s;
  s.values = fit::same_model_record(model::preset("banks-aluminium"), e, 6);
  return s;
}

FitRequest request() {
  FitRequest r;
  r.beam_name = "banks-aluminium";
  r.beam = model::preset("banks-aluminium");
  r.elements = 6;
  r.experiment.pulse_width_s = 0.004;
  r.estimate = {"EI", "rho"};
  r.start_scale = 1.02;
  r.cost.name = "time";
  return r;
}

TEST(FitRequest, RecoversTheTruthFromAFilledStruct) {
  std::ostringstream warnings;
  const FitComputation c = compute_fit(request(), {record()}, warnings);
  ASSERT_EQ(c.result.status, "converged") << c.result.termination;
  const model::BeamParameters truth = model::preset("banks-aluminium");
  // Noise-free data from the fitted model itself: LM stops at a relative step of 1e-10, so 1e-6 leaves a wide margin
  // while a wrong start, bound or experiment (EI and rho 2 % off) would fail by four orders of magnitude.
  EXPECT_NEAR(c.result.parameters[0].estimate / truth.EI, 1, 1e-6);
  EXPECT_NEAR(c.result.parameters[1].estimate / truth.rho, 1, 1e-6);
  // The default bounds [v/2, 2v] around the beam's values (fit::bounds_around), the start 1.02 v.
  EXPECT_DOUBLE_EQ(c.options.estimate[0].lower, truth.EI / 2);
  EXPECT_DOUBLE_EQ(c.options.estimate[0].upper, truth.EI * 2);
  EXPECT_DOUBLE_EQ(c.options.start.rho, truth.rho * 1.02);
  EXPECT_EQ(c.options.optimizer.method, "lm");  // the time cost's default optimizer
  EXPECT_TRUE(warnings.str().empty());
}

TEST(FitRequest, AForceChannelItsSamplesDoNotResolveIsSaidToBe) {
  // A sin^2 pulse 4 samples wide as the measured force holds 7.6 % of its energy above a quarter of the rate: the fit
  // says so on its warnings (the model holds the force linear between samples, which biased EI by 0.4 %); 20 samples
  // wide it holds 1e-5 and nothing is said.
  for (const double width : {0.004, 0.02}) {
    simulation::Experiment e;
    e.pulse_width_s = width;
    const std::vector<double> force = simulation::sampled_pulse(e);
    e.excitation = simulation::kSampledForce;
    e.force_samples_N = force;
    io::TimeSeries response;
    response.path = "<test>";
    response.dt_s = e.dt_s;
    response.value_column = "displacement_m";
    response.values = fit::same_model_record(model::preset("banks-aluminium"), e, 6);
    FitRequest r = request();
    r.experiment.pulse_width_s.reset();
    r.experiment.force_samples_N = force;
    r.experiment.force_channel = "force_N";
    r.estimate = {"EI"};
    std::ostringstream warnings;
    const FitComputation c = compute_fit(r, {response}, warnings);
    EXPECT_EQ(c.result.status, "converged") << c.result.termination;
    const bool said = warnings.str().find("the force channel 'force_N' holds 7.") != std::string::npos;
    EXPECT_EQ(said, width < 0.01) << width << ": " << warnings.str();
  }
}

// The thin beam at N = 6 driven by a 4 ms pulse at the tip, as a force channel records it: the force and the
// response without noise.
struct HitRecord {
  simulation::Experiment experiment;
  std::vector<double> clean_force, clean;
};
HitRecord hit_record() {
  HitRecord h;
  h.experiment.pulse_width_s = 0.004;
  h.clean_force = simulation::sampled_pulse(h.experiment);
  h.experiment.excitation = simulation::kSampledForce;
  h.experiment.force_samples_N = h.clean_force;
  h.clean = fit::same_model_record(model::preset("banks-aluminium"), h.experiment, 6);
  return h;
}

TEST(FitRequest, AForceChannelsNoiseThatReachesPastTheResidualIsSaid) {
  // The thin beam at N = 6 driven by a 4 ms pulse as its force channel records it, the response with 1 % noise:
  // with 2 % noise on the force channel too, the time fit (output error) leaves out what that noise does through mode
  // 1, whose resonance passes it at more than the residual's power (the twenty-first pass's P2: standard errors 16x
  // too small): said, with the channel's noise sd measured after the hit (within 10 % of the true one: a MAD over
  // 3,900 samples has a relative sd of about 2 %). Without force noise nothing is said; nor with the
  // errors-in-variables form, which counts it.
  const HitRecord hit = hit_record();
  const simulation::Experiment& e = hit.experiment;
  const std::vector<double>& clean_force = hit.clean_force;
  const std::vector<double>& clean = hit.clean;
  // And with 30 % force noise, where the warning went quiet as the noise grew: it read only the bins where the
  // force stood 100 times above its noise (the twenty-third pass's adv55 P1, at the errors-in-variables study's 20 %
  // with a 4 ms pulse).
  // And at 150 %, where the hit's end was taken from a noise spike 2 s later and nothing was said (adv57 P3).
  for (const double force_noise : {0.02, 0.3, 1.5, 0.0}) {
    const double force_sd = force_noise * signal::rms(clean_force);
    io::TimeSeries response;
    response.path = "<test>";
    response.dt_s = e.dt_s;
    response.value_column = "displacement_m";
    response.values = signal::add_noise(clean, 0.01, 1);
    FitRequest r = request();
    r.experiment.pulse_width_s.reset();
    r.experiment.force_samples_N = force_noise > 0 ? signal::add_noise(clean_force, force_noise, 2) : clean_force;
    r.experiment.force_channel = "force_N";
    std::ostringstream warnings;
    const FitComputation c = compute_fit(r, {response}, warnings);
    const std::string said = warnings.str();
    const auto at = said.find("the force channel 'force_N' holds noise (sd ");
    EXPECT_EQ(at != std::string::npos, force_noise > 0) << said;
    if (at != std::string::npos) {
      EXPECT_NEAR(std::stod(said.substr(at + 44)) / force_sd, 1.0, 0.1) << said;
      if (force_noise > 1) continue;  // the errors-in-variables fits below are of usable channels
      FitRequest counted = r;
      counted.cost.name = "freq-ml";
      counted.cost.force_noise_sd = force_sd;
      counted.cost.noise_sd = 0.01 * signal::rms(clean);
      std::ostringstream quiet;
      const FitComputation direct = compute_fit(counted, {response}, quiet);
      EXPECT_EQ(quiet.str().find("holds noise"), std::string::npos) << quiet.str();
      EXPECT_EQ(direct.result.status, "converged") << direct.result.termination;
      // The same form as a hybrid's refinement: its force noise is the refinement's (it was refused as the global
      // cost's: the twenty-second pass's P2), and the refinement runs it.
      counted.cost.name = "spike-smooth";
      counted.strategy = fit::kHybrid;
      counted.refine = "freq-ml";
      std::ostringstream hybrid_warnings;
      const FitComputation hybrid = compute_fit(counted, {response}, hybrid_warnings);
      EXPECT_EQ(hybrid.result.status, "converged") << hybrid.result.termination;
      ASSERT_FALSE(hybrid.result.stages.empty());
      EXPECT_NE(hybrid.result.stages.back().name.find("freq-ml from the spike-smooth estimate"), std::string::npos)
          << hybrid.result.stages.back().name;
    }
  }
}

TEST(FitRequest, TheErrorsInVariablesTransientNoteNeedsAForceThatDoesNotDecide) {
  // The thin beam at N = 6, a 4 ms pulse, the response with 0.1 % noise and the force channel with 20 % (the
  // errors-in-variables study's level). The note that the form's free transient terms, not the force, account for
  // the response fired on a right channel whose negation, refitted, cost 200 more (the twenty-third pass's adv55
  // P2, at N = 8, with the terms taking out 79 %): it is now kept for forces whose negation costs under
  // kForceDecides more, or that leave the terms over 95 %. Here the right force leaves them 23 % (no note), and the
  // channel negated 99.9 %, its negation refitted costing 42 more: noted (measured).
  const HitRecord hit = hit_record();
  const simulation::Experiment& e = hit.experiment;
  const std::vector<double>& clean_force = hit.clean_force;
  const std::vector<double>& clean = hit.clean;
  io::TimeSeries response;
  response.path = "<test>";
  response.dt_s = e.dt_s;
  response.value_column = "displacement_m";
  response.values = signal::add_noise(clean, 0.001, 1);
  const std::vector<double> force = signal::add_noise(clean_force, 0.2, 2);
  for (const double sign : {1.0, -1.0}) {
    FitRequest r = request();
    r.experiment.pulse_width_s.reset();
    r.experiment.force_samples_N = force;
    for (double& f : r.experiment.force_samples_N) f *= sign;
    r.experiment.force_channel = "force_N";
    r.estimate = {"EI", "rho", "gamma"};
    r.cost.name = "freq-ml";
    r.cost.force_noise_sd = 0.2 * signal::rms(clean_force);
    r.cost.noise_sd = 0.001 * signal::rms(clean);
    std::ostringstream warnings;
    const FitComputation c = compute_fit(r, {response}, warnings);
    ASSERT_NE(c.result.status, "failed") << c.result.termination;
    const FitNotes notes = fit_notes(c.result, c.options.cost);
    if (sign > 0) {
      EXPECT_EQ(notes.transient, "") << c.result.negated_force_rise;
    } else {
      EXPECT_NE(notes.transient.find("the measured force accounts for little of the response"), std::string::npos)
          << notes.transient;
    }
  }
}

TEST(FitRequest, StandardErrorsOfFewDegreesOfFreedomAreSaidToBe) {
  // The modal cost of 3 modes (6 residuals) for 4 parameters leaves 2 degrees of freedom: a 95 % interval is +- 4.30
  // standard errors (Student's t), which the fit says (the twenty-third pass's adv55 P3: 9 of 24 model-exact fits
  // beyond 2 standard errors, with nothing said). The time cost's thousands of residuals say nothing.
  FitRequest r = request();
  r.estimate = {"EI", "rho", "cDI", "gamma"};
  r.cost.name = "modal";
  r.cost.spikes.count = 3;
  std::ostringstream warnings;
  const FitComputation modal = compute_fit(r, {record()}, warnings);
  ASSERT_EQ(modal.result.covariance_status, "ok");
  EXPECT_NE(fit_notes(modal.result, modal.options.cost)
                .few_degrees.find("2 degree(s) of freedom (6 residuals, 4 parameters)"),
            std::string::npos);
  EXPECT_NE(fit_notes(modal.result, modal.options.cost).few_degrees.find("+- 4.3 standard errors"), std::string::npos);
  // The relative weighting's formal errors do not hold (adv59 P1: 2 times too small with 4 modes, 3-5 times too
  // large with 6), said; the measured weighting's are not.
  EXPECT_NE(fit_notes(modal.result, modal.options.cost).weighting, "");
  r.cost.mode_weight = std::string("measured");
  const FitComputation measured = compute_fit(r, {record()}, warnings);
  EXPECT_EQ(fit_notes(measured.result, measured.options.cost).weighting, "");
  // So are spike-smooth's with its relative weighting (the default; the twenty-eighth pass's adv65 P3: 1.7-2.2 times
  // below the scatter).
  r.cost.name = "spike-smooth";
  r.cost.mode_weight.reset();
  r.estimate = {"EI", "rho"};
  const FitComputation smooth = compute_fit(r, {record()}, warnings);
  ASSERT_EQ(smooth.result.covariance_status, "ok");
  EXPECT_NE(fit_notes(smooth.result, smooth.options.cost).weighting.find("with the relative weighting across spikes"),
            std::string::npos);
  // And inverse-variance's (the twenty-ninth pass's adv67 P2: 3-8 times below the scatter on a velocity record).
  r.cost.frequency_weight = std::string("inverse-variance");
  const FitComputation inverse = compute_fit(r, {record()}, warnings);
  EXPECT_NE(fit_notes(inverse.result, inverse.options.cost).weighting.find("with the inverse-variance weighting"),
            std::string::npos);
  // A least-squares refinement's errors are the refinement's: no such note.
  r.strategy = "hybrid";
  r.refine = std::string("time");
  const FitComputation refined = compute_fit(r, {record()}, warnings);
  EXPECT_EQ(fit_notes(refined.result, refined.options.cost).weighting, "");
  const FitComputation time = compute_fit(request(), {record()}, warnings);
  EXPECT_EQ(fit_notes(time.result, time.options.cost).few_degrees, "");
}

TEST(FitRequest, CorrelatedTimeResidualsAreSaid) {
  // The twenty-eighth pass's adv65 P2: in AR(0.9) noise a time fit taken as white had formal errors 3.7-4 times below
  // the scatter, with nothing said. An AR model of its residuals (Akaike's order) puts about (1 + 0.9) / (1 - 0.9) =
  // 19 times their average power near 0 Hz: said. So is AR(0, 0.9) noise, whose lag-1 autocorrelation is 0 (the
  // twenty-ninth pass's adv67 P1). White noise: Akaike's order 0, or an excess within sampling error (quiet); whitened
  // by the right model (--noise-model ar:0.9) quiet again; a noise-free record fitted to round-off quiet (adv67 P3).
  std::ostringstream warnings;
  io::TimeSeries coloured = record(), white = record(), second = record();
  coloured.values = signal::add_noise(coloured.values, 0.05, 3, signal::parse_noise_model("ar:0.9"));
  second.values = signal::add_noise(second.values, 0.05, 3, signal::parse_noise_model("ar:0,0.9"));
  white.values = signal::add_noise(white.values, 0.05, 3);
  const FitComputation as_white = compute_fit(request(), {coloured}, warnings);
  const std::string note = fit_notes(as_white.result, as_white.options.cost).correlated_residuals;
  EXPECT_NE(note.find("the residuals are coloured: an AR("), std::string::npos) << note;
  EXPECT_NE(note.find("of the Nyquist frequency"), std::string::npos) << note;
  const FitComputation lag2 = compute_fit(request(), {second}, warnings);
  EXPECT_NE(fit_notes(lag2.result, lag2.options.cost).correlated_residuals, "");
  const FitComputation exact = compute_fit(request(), {record()}, warnings);
  EXPECT_EQ(fit_notes(exact.result, exact.options.cost).correlated_residuals, "");
  // Short white records: Akaike's order of 128 white residuals puts 1.5 times their power somewhere by chance; the
  // threshold grows as exp(3 sqrt(4 p / m)) (signal::coloured_excess_threshold), and 10 seeds stay quiet (the
  // thirtieth pass's adv69 P3: 8 in 40 at 128 samples were told of colour).
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    io::TimeSeries short_white = record();
    short_white.values.resize(128);
    short_white.values = signal::add_noise(short_white.values, 0.05, seed);
    const FitComputation fitted = compute_fit(request(), {short_white}, warnings);
    EXPECT_EQ(fit_notes(fitted.result, fitted.options.cost).correlated_residuals, "") << seed;
  }
  // freq-band and freq-ml take every bin's noise as equal: in AR(0.9) noise their band's low bins hold far more of
  // the residual's power than its average, said (adv69 P1: 2.6 times below the scatter, nothing said); white: quiet.
  for (const char* cost : {"freq-band", "freq-ml"}) {
    FitRequest frequency = request();
    frequency.cost.name = cost;
    const FitComputation band = compute_fit(frequency, {coloured}, warnings);
    EXPECT_NE(fit_notes(band.result, band.options.cost).correlated_residuals.find("uneven across the band"),
              std::string::npos)
        << cost;
    const FitComputation flat = compute_fit(frequency, {white}, warnings);
    EXPECT_EQ(fit_notes(flat.result, flat.options.cost).correlated_residuals, "") << cost;
  }
  const FitComputation of_white = compute_fit(request(), {white}, warnings);
  EXPECT_EQ(fit_notes(of_white.result, of_white.options.cost).correlated_residuals, "");
  FitRequest whitened = request();
  whitened.cost.noise_model = std::string("ar:0.9");
  const FitComputation gls = compute_fit(whitened, {coloured}, warnings);
  EXPECT_EQ(fit_notes(gls.result, gls.options.cost).correlated_residuals, "");
  // freq-ml with the colour estimated from the white fit's residuals: its standard errors take that estimate as known,
  // said (the twenty-eighth pass's adv65 P1: 2.5 times below the scatter over 30 displacement records).
  FitRequest estimated = request();
  estimated.cost.name = "freq-ml";
  estimated.cost.noise_model = std::string("estimated");
  const FitComputation ml = compute_fit(estimated, {coloured}, warnings);
  EXPECT_NE(fit_notes(ml.result, ml.options.cost).weighting.find("noise colour was estimated"), std::string::npos);
  estimated.cost.noise_model = std::string("ar:0.9");
  const FitComputation known = compute_fit(estimated, {coloured}, warnings);
  EXPECT_EQ(fit_notes(known.result, known.options.cost).weighting, "");
}

TEST(FitRequest, AFitThatFailsOnA4SaysSo) {
  // More spikes than the model's spectrum shows: every evaluation violates (A4), and the failure named the optimizer's
  // tolerance instead (the thirty-second pass's adv73 P1).
  FitRequest r = request();
  r.estimate = {"EI"};
  r.cost.name = "spike";
  r.cost.spikes.count = 4;  // the record's spectrum (N = 6) shows 4 maxima; an N = 1 model's fewer
  r.elements = 1;
  std::ostringstream warnings;
  const FitComputation c = compute_fit(r, {record()}, warnings);
  ASSERT_EQ(c.result.status, "failed");
  EXPECT_NE(fit_notes(c.result, c.options.cost).failed.find("(A4) violated: the model spectrum shows"),
            std::string::npos)
      << fit_notes(c.result, c.options.cost).failed;
}

TEST(FitRequest, FlagsMapToTheSameRequestAndTheSameNumbers) {
  const apps::Flags flags("fit", {{"beam", "banks-aluminium"},
                                  {"elements", "6"},
                                  {"pulse-width", "0.004"},
                                  {"estimate", "EI,rho"},
                                  {"start-scale", "1.02"},
                                  {"cost", "time"}});
  std::ostringstream warnings;
  const FitComputation from_flags = compute_fit(apps::fit_request_of(flags), {record()}, warnings);
  const FitComputation direct = compute_fit(request(), {record()}, warnings);
  ASSERT_EQ(from_flags.result.parameters.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {  // one body of code: bit for bit, not within a tolerance
    EXPECT_EQ(from_flags.result.parameters[i].estimate, direct.result.parameters[i].estimate);
    EXPECT_EQ(from_flags.result.parameters[i].standard_error, direct.result.parameters[i].standard_error);
  }
  EXPECT_EQ(from_flags.result.evaluations, direct.result.evaluations);
}

// The message compute_fit refuses the request with ("" when it does not).
std::string refusal(const FitRequest& r) {
  std::ostringstream warnings;
  try {
    fit_options(r, {record()}, warnings);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FitRequest, EveryConstraintIsRefusedInTheCommandLinesForm) {
  FitRequest r = request();
  r.bound_factor = 0.5;
  EXPECT_EQ(refusal(r), "beamid fit: --bound-factor = '0.5': must be > 1");
  // Bounds past twelve orders of magnitude, and an amplitude given beside --unknown-amplitude (the thirteenth pass's 7
  // and 9).
  r.bound_factor = 1e308;
  EXPECT_EQ(refusal(r).rfind("beamid fit: --bound-factor = '1e+308': must be at most 1e6", 0), 0u) << refusal(r);
  r = request();
  r.cost.unknown_amplitude = true;
  r.experiment.force_amplitude_N = 5;
  EXPECT_NE(refusal(r).find("--force-amplitude would be ignored"), std::string::npos) << refusal(r);
  r = request();
  r.start_scale = 0;
  EXPECT_EQ(refusal(r), "beamid fit: --start-scale = '0': must be > 0");
  r = request();
  r.estimate = {"EI", "foo"};
  EXPECT_EQ(refusal(r).rfind("beamid fit: --estimate = 'EI,foo': 'foo' is not a parameter of this beam (valid: l,", 0),
            0u)
      << refusal(r);
  r = request();
  r.bounds["rho_r2"] = {1e-9, 1e-7};
  EXPECT_EQ(refusal(r), "beamid fit: --bounds names 'rho_r2', which is not in --estimate");
  r = request();
  r.refine = "time";
  EXPECT_EQ(refusal(r), "beamid fit: --refine = 'time': is the second cost of --strategy hybrid only");
  r = request();
  r.experiment.dt_s = 2e-3;
  EXPECT_EQ(refusal(r), "beamid fit: --dt = '0.002': must equal the data's time step 0.001 s");
  r = request();
  r.seed = -1;
  EXPECT_EQ(refusal(r), "beamid fit: --seed = '-1': must be an integer >= 0");
  r = request();
  r.cost.spikes.frequencies_hz = {2.4, 26};
  r.cost.spikes.count = 3;
  EXPECT_EQ(refusal(r), "beamid fit: --spikes = '3': must equal the number of --spike-frequencies (or be left out)");
  r = request();
  r.caller.label = "beamid.fit";  // another front end's label
  r.record_weights = "equal";
  EXPECT_EQ(refusal(r), "beamid.fit: --record-weights = 'equal': must be one of rms, noise");
  // Choices the fit has no use for are said, not ignored (the adversarial pass's D029 and C019): record weights of a
  // one-record fit, and a spike weight given to a cost without spikes.
  r = request();
  r.record_weights = "noise";
  EXPECT_EQ(refusal(r),
            "beamid fit: --record-weights = 'noise': weighs the records of a joint fit against each other; this fit "
            "has one record (give several --channel)");
  r = request();
  r.cost.name = "time";
  r.cost.eps1 = 2.0;
  EXPECT_EQ(refusal(r),
            "beamid fit: --eps1 = '2': weighs a term of the spike costs (spike, spike-smooth); cost time "
            "has none");
  r = request();
  r.cost.name = "spike";
  r.cost.eps3 = 1.0;
  EXPECT_EQ(refusal(r), "beamid fit: --eps3 = '1': weighs a term of the spike-smooth cost; cost spike has none");
  EXPECT_EQ(refusal(request()), "");
}

TEST(FitRequest, ExplicitBoundsReplaceTheFactorRule) {
  FitRequest r = request();
  r.bounds["EI"] = {0.3, 0.7};
  const std::vector<fit::EstimatedParameter> p = estimated_parameters(r);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].lower, 0.3);
  EXPECT_EQ(p[0].upper, 0.7);
  EXPECT_DOUBLE_EQ(p[1].lower, r.beam.rho / 2);
  r.beam.gamma = 0;  // no nominal value to put a factor around
  r.estimate = {"gamma"};
  r.bounds.clear();
  EXPECT_THROW(estimated_parameters(r), InputError);
}

}  // namespace
}  // namespace beamid::api

namespace beamid::api {
namespace {

// The eighteenth pass's P1: freq-band with the exponential window reported standard errors 2.7-3.5x below its scatter
// (below the Cramer-Rao bound) with nothing said. The note comes with every DFT cost's window but the rectangular
// one (whose bins of white noise are uncorrelated), and not where no standard error is printed.
TEST(FitNotes, AWindowedDftCostsErrorsAreSaidToIgnoreTheBinsCorrelation) {
  fit::FitResult result;
  result.status = "converged";
  result.covariance_status = "ok";
  costs::CostOptions cost;
  cost.name = costs::kBandCost;
  cost.window.name = "exponential";
  EXPECT_NE(fit_notes(result, cost).correlated_bins.find("exponential window (noise bandwidth 2.3"), std::string::npos);
  cost.name = costs::kSpikeSmoothCost, cost.window.name = "hann";
  EXPECT_FALSE(fit_notes(result, cost).correlated_bins.empty());
  cost.window.name = "rectangular";
  EXPECT_TRUE(fit_notes(result, cost).correlated_bins.empty());
  // A nearly flat exponential window (noise bandwidth 1 + 8e-8) correlates nothing (the nineteenth pass's U2).
  cost.window.name = "exponential", cost.window.exponential_end = 0.999;
  EXPECT_TRUE(fit_notes(result, cost).correlated_bins.empty());
  cost.window.exponential_end = 0.01, cost.window.name = "rectangular";
  cost.name = costs::kTimeCost, cost.window.name = "hann";  // the time cost reads no window
  EXPECT_TRUE(fit_notes(result, cost).correlated_bins.empty());
  cost.name = costs::kBandCost, result.covariance_status = "no degrees of freedom";
  EXPECT_TRUE(fit_notes(result, cost).correlated_bins.empty());
}

// The twentieth pass's P2: a fit stopped by its evaluation budget printed its estimate as "free" with standard errors
// and exit 0, said only inside the summary line. Its note comes first, whether or not the estimate is on a bound.
TEST(FitNotes, AFitStoppedByItsBudgetIsSaidNotToBeAMinimum) {
  fit::FitResult result;
  result.covariance_status = "ok";
  result.evaluations = 5;
  costs::CostOptions cost;
  for (const std::string status : {"max-evaluations", "max-evaluations-at-bound"}) {
    result.status = status;
    const FitNotes notes = fit_notes(result, cost);
    EXPECT_NE(notes.budget.find("ran out (5 evaluations)"), std::string::npos) << status << ": " << notes.budget;
    ASSERT_FALSE(notes.lines().empty());
    EXPECT_EQ(notes.lines().front(), notes.budget);
  }
  for (const std::string status : {"converged", "converged-at-bound", "failed"}) {
    result.status = status;
    EXPECT_TRUE(fit_notes(result, cost).budget.empty()) << status;
  }
}

}  // namespace
}  // namespace beamid::api

namespace beamid::api {
namespace {

// The nineteenth pass's P4: a 5-bit record (32 levels over its range) gave steady lines and spurious poles with no
// word of its quantisation. Said under 10 bits over the range (512 steps over the peak), not for 16 bits or for
// floating-point values.
TEST(RecordNotes, ACoarselyQuantisedRecordIsSaidToBe) {
  io::TimeSeries data;
  const auto decay = [&](double quantum) {
    data.values.clear();
    for (int i = 0; i < 4000; ++i) {
      const double x = std::exp(-2e-3 * i) * std::sin(0.05 * i + 0.3);
      data.values.push_back(quantum > 0 ? quantum * std::round(x / quantum) : x);
    }
  };
  decay(1.0 / 16);  // 5 bits over [-1, 1]; the decay peaks at 15/16
  EXPECT_NE(quantisation_note(data).find("quantised coarsely: its step is 0.0625, 1/15 of its peak (4.9 bits"),
            std::string::npos)
      << quantisation_note(data);
  decay(1.0 / 32768);  // 16 bits
  EXPECT_EQ(quantisation_note(data), "");
  decay(0);
  EXPECT_EQ(quantisation_note(data), "");
  // Eight full-precision samples of a sine: their smallest step is no quantum (the twenty-third pass's P5 called them
  // 4.6 bits), and with so few samples nothing is said.
  data.values.clear();
  for (int i = 0; i < 8; ++i) data.values.push_back(std::sin(0.7 * i + 0.1));
  EXPECT_EQ(quantisation_note(data), "");
}

}  // namespace
}  // namespace beamid::api
