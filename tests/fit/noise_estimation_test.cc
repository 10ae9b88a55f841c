// The noise a fit estimates from repeated records (fit/noise_estimation.h): a joint fit of M repeats of one test,
// weighed by the records' deviations from their mean, lands where the fit given the true noise model does; and what is
// not a repeat is refused.
#include "fit/noise_estimation.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../costs/thin_beam_fit.h"
#include "core/errors.h"
#include "signal/noise.h"

namespace beamid::fit {
namespace {

// Every parameter estimated within [v/2, 2 v], started a few per cent off in mixed directions.
void estimate_from_offsets(FitOptions& o) {
  const std::vector<std::pair<std::string, double>> scale = {
      {"EI", 1.005}, {"rho", 0.995}, {"cDI", 1.05}, {"gamma", 0.95}};
  for (const auto& [key, factor] : scale) {
    double& v = o.start.*(model::find_parameter(key)->member);
    o.estimate.push_back({key, v / 2, v * 2});
    v *= factor;
  }
}

// M repeats of the thin beam's pulse test: the clean record plus AR(0.9) noise of 2 % of its RMS, each its own draw.
std::vector<Record> repeats(const FitOptions& o, const std::vector<double>& clean, int count) {
  std::vector<Record> records;
  for (int m = 0; m < count; ++m) {
    Record r;
    r.name = "tap" + std::to_string(m + 1);
    r.start = o.start;
    r.experiment = o.experiment;
    r.data = signal::add_noise(clean, 0.02, 40 + static_cast<std::uint64_t>(m), signal::parse_noise_model("ar:0.9"));
    records.push_back(std::move(r));
  }
  return records;
}

TEST(RepeatedNoise, AJointFitOfRepeatsLandsWhereTheTrueNoiseModelsFitDoes) {
  // 4 repeats of 4,096 samples. The time cost's AR model comes from 3 x 4,096 samples' worth of deviations (a_1's sd
  // about 0.004; bound 0.03 also allows Akaike's occasional higher order, whose first coefficient moves by about as
  // much); freq-ml's bin variances have 3 complex dof per bin, 63 after averaging over 21 bins (relative sd 0.13).
  // Weights that far from the truth cost little efficiency, so each estimate lies within half a standard error of the
  // fit given the true model (measured: within 0.11 of one on these draws, freq-ml's gamma the furthest), and within 3
  // of the beam's value (measured: 0.66).
  const auto truth = model::preset("banks-aluminium");
  FitOptions o = costs::thin_beam_fit(costs::kTimeCost);
  const std::vector<double> clean = costs::thin_beam_data(o);
  estimate_from_offsets(o);
  const std::vector<Record> records = repeats(o, clean, 4);
  for (const std::string& name : {costs::kTimeCost, costs::kMaxLikelihoodCost}) {
    o.cost.name = name;
    o.optimizer.method = default_optimizer(name);
    o.cost.noise_model = "ar:0.9";
    const FitResult known = fit(o, records);
    o.cost.noise_model = costs::kRepeatedNoise;
    const FitResult repeated = fit(o, records);
    ASSERT_EQ(repeated.status, "converged") << name << " " << repeated.termination;
    const std::string& stage = repeated.stages.back().name;
    EXPECT_EQ(stage.rfind("the noise estimated from 4 repeated records (", 0), 0u) << stage;
    if (name == costs::kTimeCost) {
      const auto at = stage.find("(ar:");
      ASSERT_NE(at, std::string::npos) << stage;
      EXPECT_NEAR(std::stod(stage.substr(at + 4)), 0.9, 0.03) << stage;
    }
    for (std::size_t i = 0; i < known.parameters.size(); ++i) {
      const ParameterEstimate& k = known.parameters[i];
      EXPECT_LT(std::abs(repeated.parameters[i].estimate - k.estimate), 0.5 * k.standard_error) << name << " " << k.key;
      const double value = truth.*(model::find_parameter(k.key)->member);
      EXPECT_LT(std::abs(repeated.parameters[i].estimate - value), 3 * k.standard_error) << name << " " << k.key;
    }
  }
}

TEST(RepeatedNoise, RefusesWhatIsNotARepeat) {
  FitOptions o = costs::thin_beam_fit(costs::kMaxLikelihoodCost);
  const std::vector<double> clean = costs::thin_beam_data(o);
  estimate_from_offsets(o);
  o.cost.noise_model = costs::kRepeatedNoise;
  std::vector<Record> records = repeats(o, clean, 2);
  const auto message = [&o](const std::vector<Record>& r) {
    try {
      fit(o, r);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({records.front()}).find("at least 2 repeats"), std::string::npos);
  std::vector<Record> moved = records;
  moved[1].experiment.sensor_x_m = 0.5 * o.start.l;
  EXPECT_NE(message(moved).find("record 2 (tap2) is not a repeat of record 1: its sensor"), std::string::npos)
      << message(moved);
  std::vector<Record> same = {records.front(), records.front()};
  // Two records of the same samples are refused by every joint fit (they count one measurement twice).
  EXPECT_NE(message(same).find("hold the same samples"), std::string::npos) << message(same);
  // A tap at another force (or through another gain) shares no response with the others (the adversarial pass's P4),
  // and a copy rounded to 6 digits shares their noise (P3): neither is a repeat.
  std::vector<Record> louder = records;
  for (double& v : louder[1].data) v *= 2;
  EXPECT_NE(message(louder).find("times the records' mean response"), std::string::npos) << message(louder);
  std::vector<Record> rounded = {records.front(), records.front()};
  rounded[1].name = "copy";
  for (double& v : rounded[1].data) v = std::stod(format_rounded(v, 6));
  EXPECT_NE(message(rounded).find("they share their noise"), std::string::npos) << message(rounded);
  std::vector<Record> hammer = records;
  for (Record& r : hammer) {
    r.experiment.excitation = simulation::kSampledForce;
    r.experiment.force_samples_N.assign(clean.size(), 0.0);
    r.experiment.force_samples_N[1] = 1;
  }
  hammer[1].experiment.force_samples_N[2] = 0.1;
  EXPECT_NE(message(hammer).find("taps of a hammer are not repeats"), std::string::npos) << message(hammer);
}

}  // namespace
}  // namespace beamid::fit
