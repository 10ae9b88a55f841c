// Experiment design (fit/experiment_design.h): each candidate's bound is beamid crb's for that experiment, the
// information of several sensors adds, a sensor that sees nothing has no bound and is ranked last, the criteria are
// what they say, and the ranking shows in Monte-Carlo fits: at the design ranked best and at a poor one, the RMSE of
// the fitted stiffness differs as the bounds do. The banks-aluminium beam at N = 6 (the same model fits and makes
// the data, so the fits' only error is the noise's and the bound is the efficient estimator's spread).
#include "fit/experiment_design.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "fit/cramer_rao.h"
#include "fit/identification.h"
#include "same_model_record.h"
#include "signal/noise.h"

namespace beamid::fit {
namespace {

constexpr int kElements = 6;

DesignOptions options() {
  DesignOptions o;
  o.beam = model::preset("banks-aluminium");
  o.elements = kElements;
  o.keys = {"EI", "rho", "cDI", "gamma"};
  o.base.dt_s = 1e-3;
  o.base.samples = 2048;
  const double l = o.beam.l;
  o.sensor_positions_m = {0.0, 0.2 * l, 0.5 * l, 0.8 * l, l};
  o.force_positions_m = {0.7 * l};
  o.pulse_widths_s = {4e-3};
  o.dts_s = {1e-3};
  o.samples = {2048};
  o.noise_sd = 1e-6;
  return o;
}

TEST(ExperimentDesign, EachCandidatesBoundIsTheCramerRaoBoundOfItsExperiment) {
  // One sensor: the design's relative sds are beam_cramer_rao_bound's for that experiment (the same sensitivities;
  // the inverse by eigen-decomposition instead of an SVD: 1e-9 relative, far below any ranking's differences).
  const DesignOptions o = options();
  const std::vector<DesignRow> rows = rank_designs(o);
  ASSERT_EQ(rows.size(), 5u);
  for (const DesignRow& row : rows) {
    if (row.status != "ok") continue;
    simulation::Experiment e = o.base;
    e.sensor_x_m = row.candidate.sensors_x_m.front();
    e.force_x_m = row.candidate.force_x_m;
    e.pulse_width_s = row.candidate.pulse_width_s;
    const CramerRaoBound b = beam_cramer_rao_bound(o.beam, kElements, e, o.keys, o.noise_sd);
    ASSERT_EQ(b.status, "ok");
    for (Eigen::Index k = 0; k < b.relative_sd.size(); ++k)
      EXPECT_NEAR(row.relative_sd(k) / b.relative_sd(k), 1.0, 1e-9) << row.candidate.sensors_x_m.front();
    // D: the geometric mean of the semi-axes, det(F^-1)^(1/2p); with one key it would be that key's sd.
    EXPECT_NEAR(row.criterion, std::pow(b.covariance.determinant(), 1.0 / 8), 1e-9 * row.criterion);
  }
  // The sensor at the clamp sees nothing: no bound, ranked last, saying why.
  EXPECT_EQ(rows.back().candidate.sensors_x_m.front(), 0.0);
  EXPECT_NE(rows.back().status, "ok");
  EXPECT_TRUE(std::isnan(rows.back().criterion));
  // Ranked by the criterion, ascending.
  for (std::size_t i = 1; i + 1 < rows.size(); ++i) EXPECT_LE(rows[i - 1].criterion, rows[i].criterion);
}

TEST(ExperimentDesign, SensorsAddInformationAndTheCriteriaAreWhatTheySay) {
  DesignOptions o = options();
  o.sensor_positions_m.erase(o.sensor_positions_m.begin());  // not the clamp
  o.criterion = "EI";
  const std::vector<DesignRow> one = rank_designs(o);
  o.sensor_count = 2;
  const std::vector<DesignRow> two = rank_designs(o);
  ASSERT_EQ(two.size(), 6u);  // C(4, 2)
  // Information adds: a pair's bound on EI is at most either sensor's alone (to round-off).
  const auto alone = [&](double x) {
    for (const DesignRow& r : one)
      if (r.candidate.sensors_x_m.front() == x) return r.criterion;
    return std::nan("");
  };
  for (const DesignRow& pair : two) {
    ASSERT_EQ(pair.status, "ok");
    EXPECT_LE(pair.criterion, alone(pair.candidate.sensors_x_m[0]) * (1 + 1e-12));
    EXPECT_LE(pair.criterion, alone(pair.candidate.sensors_x_m[1]) * (1 + 1e-12));
    EXPECT_EQ(pair.criterion, pair.relative_sd(0));  // a key's criterion is its own relative sd
  }
  // A: the root mean square of the relative sds.
  o.criterion = kAOptimal;
  for (const DesignRow& r : rank_designs(o))
    EXPECT_NEAR(r.criterion, std::sqrt(r.relative_sd.squaredNorm() / 4), 1e-12 * r.criterion);
  // Refused: a criterion that is no key of interest, more sensors than positions, both noises or none.
  o.criterion = "kAG";
  EXPECT_THROW(rank_designs(o), InputError);
  o.criterion = kDOptimal;
  o.sensor_count = 5;
  EXPECT_THROW(rank_designs(o), InputError);
  o.sensor_count = 1;
  o.noise_level = 0.01;
  EXPECT_THROW(rank_designs(o), InputError);
}

// The RMSE of the relative EI error over `records` noisy records of one design, each fitted by least squares (the
// efficient estimator here) from the truth.
double monte_carlo_rmse(const DesignOptions& o, double sensor_x, int records) {
  simulation::Experiment e = o.base;
  e.sensor_x_m = sensor_x;
  e.force_x_m = o.force_positions_m.front();
  e.pulse_width_s = o.pulse_widths_s.front();
  const std::vector<double> clean = same_model_record(o.beam, e, kElements);
  FitOptions f;
  f.start = o.beam;
  f.elements = kElements;
  f.experiment = e;
  f.cost.name = costs::kTimeCost;
  f.optimizer.method = default_optimizer(f.cost.name);
  for (const std::string& key : o.keys) {
    const double v = model::parameter_value(o.beam, key);
    f.estimate.push_back({key, v / 2, v * 2});
  }
  double sum = 0;
  for (int r = 0; r < records; ++r) {
    std::vector<double> data = clean;
    const std::vector<double> noise = signal::gaussian_deviates(1000 + static_cast<std::uint64_t>(r), data.size());
    for (std::size_t i = 0; i < data.size(); ++i) data[i] += o.noise_sd * noise[i];
    const FitResult fit_result = fit(f, data);
    EXPECT_EQ(fit_result.status, "converged") << fit_result.termination;
    const double error = fit_result.parameters.front().estimate / o.beam.EI - 1;
    sum += error * error;
  }
  return std::sqrt(sum / records);
}

TEST(ExperimentDesign, TheRankingShowsInMonteCarloFits) {
  // Ranked by EI's bound, the sensor at the tip against one at 0.2 l, near the clamp, where the pulse's response is
  // small: the bounds differ by about 10x. Over 24 records each, the RMSE of the fitted EI estimates the bound to
  // 1/sqrt(2 x 24) = 14 % (the efficient estimator's error is Gaussian), so the RMSEs' ratio is the bounds' within
  // a factor 1.5 (three standard errors of the ratio, 20 %, with room), and each RMSE within 1.5x of its bound.
  DesignOptions o = options();
  o.criterion = "EI";
  const double l = o.beam.l;
  o.sensor_positions_m = {0.2 * l, l};
  const std::vector<DesignRow> rows = rank_designs(o);
  ASSERT_EQ(rows.front().candidate.sensors_x_m.front(), l);
  const double best_bound = rows.front().criterion, poor_bound = rows.back().criterion;
  const double best = monte_carlo_rmse(o, l, 24), poor = monte_carlo_rmse(o, 0.2 * l, 24);
  std::printf("[ EI bound %.3g at the tip, %.3g at 0.2 l (%.1fx); RMSE %.3g and %.3g (%.1fx) ]\n", best_bound,
              poor_bound, poor_bound / best_bound, best, poor, poor / best);
  EXPECT_GT(poor_bound / best_bound, 3.0);  // a ranking worth testing
  EXPECT_NEAR(std::log((poor / best) / (poor_bound / best_bound)), 0.0, std::log(1.5));
  EXPECT_NEAR(std::log(best / best_bound), 0.0, std::log(1.5));
  EXPECT_NEAR(std::log(poor / poor_bound), 0.0, std::log(1.5));
}

}  // namespace
}  // namespace beamid::fit
