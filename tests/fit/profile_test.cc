// Profile-likelihood intervals (issue 34 item 1): where the cost is quadratic in the profiled parameter the profile
// interval is the formal one, estimate +- z SE; where the bounds cut it, the open side is said.
#include "fit/profile.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "same_model_record.h"
#include "signal/noise.h"

namespace beamid::fit {
namespace {

// banks-aluminium's pulse test (model.md section 5's sampling), `keys` estimated by least squares from the truth's
// values, on a record with `noise` white noise.
struct Case {
  FitOptions options;
  std::vector<Record> records;
};
Case pulse_case(const std::vector<std::string>& keys, double noise, double bound_factor) {
  const model::BeamParameters truth = model::preset("banks-aluminium");
  Case c;
  c.options.elements = 6;
  c.options.experiment.pulse_width_s = 0.004;
  c.options.cost.name = "time";
  c.options.optimizer.method = default_optimizer("time");
  c.options.start = truth;
  for (const std::string& key : keys) {
    const double v = model::parameter_value(truth, key);
    c.options.estimate.push_back({key, v / bound_factor, v * bound_factor});
  }
  Record r;
  r.name = "record1";
  r.start = truth;
  r.experiment = c.options.experiment;
  r.data = signal::add_noise(same_model_record(truth, c.options.experiment, 6), noise, 11);
  c.records = {r};
  return c;
}

TEST(Profile, WhereTheCostIsQuadraticTheProfileIntervalIsTheFormalOne) {
  // 0.1 % noise on 4096 samples: the estimates lie within about 1e-4 of the truth, where the cost's third-order term
  // moves a 2 SE interval end by O(SE / q) ~ 1e-4 of itself; the signed root's linear interpolation is exact for a
  // quadratic. So both ends of both intervals lie within 2 % of the formal half-widths z SE (z = 1, 1.96), with EI
  // profiled against rho refitted (their correlation enters both the formal error and the profile alike).
  const Case c = pulse_case({"EI", "rho"}, 1e-3, 2);
  const FitResult best = fit(c.options, c.records);
  ASSERT_EQ(best.status, "converged") << best.termination;
  for (const std::string key : {"EI", "rho"}) {
    const Profile p = profile(c.options, c.records, best, key);
    ASSERT_GT(p.standard_error, 0) << key;
    EXPECT_NEAR((p.upper68 - p.estimate) / p.standard_error, 1.0, 0.02) << key;
    EXPECT_NEAR((p.estimate - p.lower68) / p.standard_error, 1.0, 0.02) << key;
    EXPECT_NEAR((p.upper95 - p.estimate) / p.standard_error, 1.96, 0.04) << key;
    EXPECT_NEAR((p.estimate - p.lower95) / p.standard_error, 1.96, 0.04) << key;
    EXPECT_FALSE(p.open_below || p.open_above) << key;
    EXPECT_EQ(p.lower_minimum, "") << key;
    EXPECT_NE(p.line().find(key + " profile: 68 % ["), std::string::npos) << p.line();
  }
}

TEST(Profile, OneParameterIsProfiledByItsCostAlone) {
  // With EI alone estimated there is nothing to refit: the profile is the cost along EI, and the same agreement holds.
  const Case c = pulse_case({"EI"}, 1e-3, 2);
  const FitResult best = fit(c.options, c.records);
  ASSERT_EQ(best.status, "converged") << best.termination;
  const Profile p = profile(c.options, c.records, best, "EI");
  EXPECT_NEAR((p.upper95 - p.estimate) / p.standard_error, 1.96, 0.04);
  EXPECT_NEAR((p.estimate - p.lower95) / p.standard_error, 1.96, 0.04);
}

TEST(Profile, BoundsInsideTheIntervalLeaveItOpenAndSaySo) {
  // Bounds one formal standard error either side of EI's estimate (1 % noise) cut its 95 % interval on both sides:
  // the profile stops at each bound below the 95 % level, and the line says the data do not bound it there.
  Case c = pulse_case({"EI"}, 1e-2, 2);
  const FitResult wide = fit(c.options, c.records);
  ASSERT_EQ(wide.status, "converged") << wide.termination;
  const double estimate = wide.parameters[0].estimate, se = wide.parameters[0].standard_error;
  c.options.estimate[0].lower = estimate - se, c.options.estimate[0].upper = estimate + se;
  c.options.start.EI = c.records[0].start.EI = estimate;
  const FitResult best = fit(c.options, c.records);
  ASSERT_EQ(best.parameters[0].status, kFree);
  const Profile p = profile(c.options, c.records, best, "EI");
  EXPECT_TRUE(p.open_below && p.open_above) << p.line();
  EXPECT_TRUE(std::isnan(p.lower95) && std::isnan(p.upper95));
  EXPECT_NE(p.line().find("not bounded below or above by the data within its bounds"), std::string::npos) << p.line();
  EXPECT_THROW(profile(c.options, c.records, best, "cDI"), InputError);  // not estimated
}

TEST(Profile, ItsLevelsAreStudentsTSquaredAtTheFitsDegreesOfFreedom) {
  // With the noise level from the residuals, D is F(1, nu) = t_nu^2 (the thirty-first pass's adv71 P4: the chi^2 level
  // 3.84 covered 89 % at nu = 6). Tables: t_1(0.975) = 12.706, t_2 = 4.303, t_6 = 2.447, t_30 = 2.042; t_6(0.8413) =
  // 1.0906 (by quadrature of t's density); for many residuals the chi^2_1 levels 1 and 3.8415.
  EXPECT_NEAR(std::sqrt(profile_level(0.975, 1)), 12.706, 1e-3);
  EXPECT_NEAR(std::sqrt(profile_level(0.975, 2)), 4.303, 1e-3);
  EXPECT_NEAR(std::sqrt(profile_level(0.975, 6)), 2.447, 1e-3);
  EXPECT_NEAR(std::sqrt(profile_level(0.975, 30)), 2.042, 1e-3);
  EXPECT_NEAR(std::sqrt(profile_level(0.8413447460685429, 6)), 1.0906, 1e-3);
  EXPECT_NEAR(profile_level(0.975, 100000), 3.8415, 1e-3);
  EXPECT_NEAR(profile_level(0.8413447460685429, 100000), 1.0, 1e-3);
}

TEST(Profile, AnEstimateOnABoundIsProfiledInwardsToItsLevel) {
  // EI bounded just below its estimate ends on that bound, with no formal error: the profile steps a fiftieth of the
  // log range, halving any step that raises D by more than 2, so the 95 % end is bracketed by D within 2 of its level
  // (a single coarse step put it where D was 8-14: adv71 P2); the bound's side stays open, and a refit a hair below
  // the fit is no lower minimum (adv71 P3).
  Case c = pulse_case({"EI", "rho"}, 1e-2, 2);
  const double ei = model::parameter_value(c.options.start, "EI");
  c.options.estimate[0].upper = ei * (1 - 2e-4);
  c.options.start.EI = c.records[0].start.EI = ei * (1 - 3e-4);
  const FitResult best = fit(c.options, c.records);
  ASSERT_EQ(best.parameters[0].status, "at-upper-bound") << best.termination;
  const Profile p = profile(c.options, c.records, best, "EI");
  EXPECT_TRUE(p.open_above) << p.line();
  ASSERT_FALSE(std::isnan(p.lower95)) << p.line();
  for (std::size_t i = 0; i + 1 < p.points.size(); ++i)
    if (p.points[i].value <= p.lower95 && p.points[i + 1].value >= p.lower95)
      EXPECT_LE(p.points[i].statistic - p.points[i + 1].statistic, 2.0 + 1e-9) << p.line();
  EXPECT_EQ(p.lower_minimum, "") << p.line();
  // Records weighted by their noise would have every refit weigh them anew: refused.
  Case joint = pulse_case({"EI", "rho"}, 1e-2, 2);
  joint.records.push_back(joint.records.front());
  joint.records.back().name = "record2";
  joint.options.record_weights = kNoiseWeights;
  EXPECT_THROW(profile(joint.options, joint.records, best, "EI"), InputError);
}

}  // namespace
}  // namespace beamid::fit
