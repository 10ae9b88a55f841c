// The study metrics on cases whose answer is known by hand: statistics of relative errors, landscape shapes, and the
// multi-start reach count with its reference minimum (the best of all fits of a cost, the truth start included).
#include "study/analysis/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "model/beam_parameters.h"
#include "study/analysis/claims.h"
#include "study/spec/study_spec.h"

namespace beamid::study {
namespace {

TEST(Metrics, WilsonIntervalsOfSuccessRates) {
  // comparison.md section 4's example: 18/20 gives [0.70, 0.97]; 0/n starts at 0 and is not empty.
  const auto [low, high] = wilson_interval(18, 20);
  EXPECT_NEAR(low, 0.699, 0.001);
  EXPECT_NEAR(high, 0.972, 0.001);
  const auto [zero_low, zero_high] = wilson_interval(0, 132);
  EXPECT_NEAR(zero_low, 0.0, 1e-15);
  EXPECT_NEAR(zero_high, 3.8416 / (132 + 3.8416), 1e-12);  // z^2 / (n + z^2) at k = 0
  EXPECT_EQ(count_with_interval(18, 20), "18/20 (95 % interval 69.9-97.2 %)");
}

TEST(Metrics, StatisticsOfRelativeErrors) {
  // Values 1, 2, 3, 4 and a NaN (a failed fit): the NaN is left out of every statistic.
  const Stats s = stats({1, 2, 3, 4, std::numeric_limits<double>::quiet_NaN()});
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));    // sum of squared deviations 5, over n - 1 = 3
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4.0));  // 1 + 4 + 9 + 16 = 30
  EXPECT_TRUE(std::isnan(stats({1}).std));          // one value has no spread
  EXPECT_TRUE(std::isnan(median({})));
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2);
}

TEST(LandscapeShape, BowlStaircaseAndRipplesAreToldApart) {
  std::vector<double> x, bowl, stairs, ripples;
  for (int j = 0; j <= 100; ++j) {
    const double r = std::pow(2.0, (j - 50) / 50.0);  // log-spaced ratios 1/2 .. 2, the truth at j = 50
    x.push_back(r);
    bowl.push_back(std::pow(std::log(r), 2));
    stairs.push_back(std::floor(10 * std::abs(std::log(r))));  // a staircase with a flat floor around the truth
    ripples.push_back(std::pow(std::log(r), 2) + 0.05 * (1 - std::cos(40 * std::log(r))));
  }
  const SliceShape b = slice_shape(x, bowl, 1);
  EXPECT_EQ(b.local_minima, 1);
  EXPECT_DOUBLE_EQ(b.basin_lower, -0.5);  // the whole range is one basin
  EXPECT_DOUBLE_EQ(b.basin_upper, 1.0);
  EXPECT_NEAR(b.total_variation_ratio, 2.0, 1e-12);  // down once and up once
  EXPECT_EQ(b.flat_share, 0);
  const SliceShape s = slice_shape(x, stairs, 1);
  EXPECT_EQ(s.local_minima, 1);  // the floor plateau counts once
  EXPECT_GT(s.flat_share, 0.8);  // 7 risers in 100 steps
  const SliceShape w = slice_shape(x, ripples, 1);
  EXPECT_GE(w.local_minima, 5);  // cos(40 ln r) has about 7 periods over ln r in [-ln 2, ln 2]
  EXPECT_LT(w.basin_upper - w.basin_lower, 0.3);
  EXPECT_GT(w.total_variation_ratio, 2.0);

  // A 2-D bowl: one minimum, every point descends to it; a bowl with a second dip: two minima, a shared basin.
  const int n = 21;
  std::vector<double> g, two;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = (i - 10) / 10.0, v = (j - 10) / 10.0;
      g.push_back(u * u + 2 * v * v);
      two.push_back(u * u + 2 * v * v - 0.6 * std::exp(-40 * ((u - 0.7) * (u - 0.7) + v * v)));
    }
  const GridShape gb = grid_shape(g, n, n);
  EXPECT_EQ(gb.local_minima, 1);
  EXPECT_DOUBLE_EQ(gb.descent_share, 1.0);
  const GridShape gt = grid_shape(two, n, n);
  EXPECT_EQ(gt.local_minima, 2);
  EXPECT_LT(gt.descent_share, 0.9);  // the dip's own basin takes its share of the grid
  EXPECT_GT(gt.descent_share, 0.0);
}

// A landscape study of one cost with a truth start and three random starts, with results made by hand.
struct MultistartCase {
  StudySpec spec;
  Plan plan;
  StudyResults results;

  // fits: (index, status, final cost, EI estimate)
  explicit MultistartCase(const std::vector<std::tuple<int, std::string, double, double>>& fits) {
    spec.truth.parameters = model::preset("banks-aluminium");
    spec.fit.estimate = {"EI"};
    spec.fit.success_tolerance = spec.fit.damping_tolerance = 0.01;
    spec.landscape.enabled = true;
    spec.landscape.cost = {"time"};
    spec.sweep.pulse_width_s = {0.004};
    spec.sweep.samples = {256};
    for (const auto& [index, status, cost, ei] : fits) {
      Unit u;
      u.kind = UnitKind::Multistart;
      u.cost = "time";
      u.index = index;
      plan.units.push_back(u);
    }
    results.spec = &spec;
    results.plan = &plan;
    for (std::size_t i = 0; i < fits.size(); ++i) {
      Record r;
      r.set("status", std::get<1>(fits[i]));
      r.set("cost", std::get<2>(fits[i]));
      r.set("estimate.EI", std::get<3>(fits[i]));
      results.landscape.push_back({&plan.units[i], r});
    }
  }
};

TEST(Metrics, ReachCountsTakeTheReferenceFromEveryFitTheTruthStartIncluded) {
  // The truth start finds the global minimum (cost 1e-20 at EI = 0.491); one random start gets within 0.5 % of it
  // (inside the 1 % tolerance), two stop in a spurious minimum (EI = 0.6, cost 1e-6): 1/3 reach the reference.
  const MultistartCase one({{-1, "converged", 1e-20, 0.491},
                            {0, "converged", 1e-6, 0.6},
                            {1, "converged", 2e-20, 0.4935},
                            {2, "converged", 1e-6, 0.6}});
  const LandscapeMetrics m = landscape_metrics(one.results);
  ASSERT_EQ(m.multistarts.size(), 1u);
  const MultistartSummary& s = m.multistarts[0];
  EXPECT_EQ(s.started, 3);
  EXPECT_EQ(s.reached, 1);
  EXPECT_EQ(s.reference_start, -1);
  EXPECT_DOUBLE_EQ(s.reference_cost, 1e-20);
  ASSERT_EQ(s.fits.size(), 4u);
  EXPECT_DOUBLE_EQ(s.fits[1].cost_gap, 1e-6 - 1e-20);
  EXPECT_TRUE(s.fits[0].reached);  // the reference reaches itself, but is not a random start

  // Every random start spurious or failed: 0/3. Were the reference the best random start (start 0, cost 1e-6), that
  // start would reach itself and the count would read 1/3 (the defect this metric had).
  const MultistartCase none({{-1, "converged", 1e-20, 0.491},
                             {0, "converged", 1e-6, 0.6},
                             {1, "failed: no finite evaluation", 0, 0.491},
                             {2, "converged", 3e-6, 0.7}});
  const LandscapeMetrics n = landscape_metrics(none.results);
  const MultistartSummary& t = n.multistarts[0];
  EXPECT_EQ(t.reached, 0) << "a failed fit never reaches, and spurious minima do not count themselves";
  EXPECT_EQ(t.started, 3);
}

TEST(Metrics, ReachCountIsAFindingWithItsEvidence) {
  const MultistartCase c({{-1, "converged", 1e-20, 0.491}, {0, "converged", 1e-6, 0.6}});
  const LandscapeMetrics m = landscape_metrics(c.results);
  const Findings f = study_findings(c.results, {}, m, {});
  ASSERT_EQ(f.counts.size(), 1u);
  EXPECT_EQ(f.counts[0].count, 0);
  EXPECT_EQ(f.counts[0].total, 1);
  for (const Claim& claim : f.claims) EXPECT_FALSE(claim.text.empty());
}

TEST(Metrics, BiasDecompositionSeparatesTheMinimumsBiasFromTheNoises) {
  // One setting (time, N = 8): the noise-free fit errs by +1 % in EI (the bias of the minimum); four noisy replicates
  // err by 1.1, 1.3, 1.2 and 1.4 % and a fifth left the minimum (30 %, not a success). Mean of the four 1.25 %, sd
  // sqrt(0.05/3) % = 0.1291 %, MCSE = sd / 2 = 0.0645 %: the total bias is significant, and so is the noise-induced
  // 0.25 % (3.9 MCSE). With replicates 1.0, 1.2, 0.8, 1.0 % the noise adds 0 +- 0.082 %: not significant.
  for (const bool shifted : {true, false}) {
    StudySpec spec;
    spec.truth.parameters = model::preset("banks-aluminium");
    spec.fit.estimate = {"EI"};
    spec.fit.success_tolerance = 0.05;
    spec.outputs.bias_decomposition = true;
    const std::vector<double> noisy = shifted ? std::vector<double>{0.011, 0.013, 0.012, 0.014, 0.3}
                                              : std::vector<double>{0.010, 0.012, 0.008, 0.010, 0.3};
    Plan plan;
    plan.units.resize(1 + noisy.size());
    StudyResults results;
    results.spec = &spec;
    results.plan = &plan;
    for (std::size_t i = 0; i < plan.units.size(); ++i) {
      Unit& u = plan.units[i];
      u.kind = UnitKind::Case;
      u.cost = "time", u.method = "direct", u.start = "truth";
      u.elements = 8, u.pulse_width_s = 0.004, u.samples = 4096;
      u.noise = i == 0 ? 0.0 : 0.01;
      const double error = i == 0 ? 0.01 : noisy[i - 1];
      Record r;
      r.set("status", "converged");
      r.set("relative_error.EI", error);
      results.cases.push_back({&u, r, std::abs(error) <= 0.05});
    }
    const std::vector<BiasRow> rows = bias_rows(results, group_cases(results.cases));
    ASSERT_EQ(rows.size(), 1u);
    const BiasRow& b = rows[0];
    EXPECT_EQ(b.fits, 5);
    EXPECT_EQ(b.stayed, 4);
    EXPECT_DOUBLE_EQ(b.noise_free, 0.01);
    EXPECT_NEAR(b.errors.mean, shifted ? 0.0125 : 0.0100, 1e-15);
    EXPECT_NEAR(b.mcse, (shifted ? std::sqrt(0.05 / 3) : std::sqrt(0.08 / 3)) * 1e-2 / 2, 1e-15);
    EXPECT_NEAR(b.noise_induced(), shifted ? 0.0025 : 0.0, 1e-15);
    EXPECT_TRUE(b.significant_total());
    EXPECT_EQ(b.significant_noise_induced(), shifted);
  }
}

TEST(Metrics, LandscapeResolutionFlagsSlicesCoarserThanTheLeastSquaresBasin) {
  // The thin beam with the truth's modes 2.46, 26.5, 81.7 Hz at damping ratios 8.1e-4, 1.5e-3, 3.5e-3 on a 4.096 s
  // record: the predicted basin is mode 2's pi zeta = 0.471 %. An EI slice over [v/1.5, 1.5 v] steps
  // 2 ln 1.5 / (points - 1) in log EI, times |d log f / d log EI| ~ 0.5 in frequency: 0.169 % at 241 points (more
  // than a third of 0.471 %: unresolved, as the landscape study's slices were) and 0.0563 % at 721 (resolved).
  for (const int points : {241, 721}) {
    StudySpec spec;
    spec.truth.parameters = model::preset("banks-aluminium");
    spec.truth.experiment.dt_s = 1e-3;
    spec.fit.estimate = {"EI"};
    spec.fit.spikes = 3;
    spec.landscape.enabled = true;
    spec.landscape.elements = {16};
    spec.landscape.cost = {"time"};
    spec.sweep.pulse_width_s = {0.004};
    spec.sweep.samples = {4096};
    Plan plan;
    Unit u;
    u.kind = UnitKind::Slice;
    u.cost = "time";
    u.parameters = {"EI"};
    u.truth = 0;
    u.pulse_width_s = 0.004;
    u.samples = 4096;
    u.elements = 16;
    plan.units.push_back(u);
    StudyResults results;
    results.spec = &spec;
    results.plan = &plan;
    Record truth;
    truth.set("mode_frequency_hz", std::vector<double>{2.46, 26.5, 81.7});
    truth.set("mode_damping_ratio", std::vector<double>{8.1e-4, 1.5e-3, 3.5e-3});
    results.truths.push_back(truth);
    std::vector<double> x, c;
    for (int j = 0; j < points; ++j) {
      x.push_back(0.491 * std::exp(std::log(1.5) * (2.0 * j / (points - 1) - 1)));
      c.push_back(std::pow(std::log(x.back() / 0.491), 2));
    }
    Record slice;
    slice.set("x", x);
    slice.set("cost", c);
    results.landscape.push_back({&plan.units[0], slice});
    const LandscapeMetrics m = landscape_metrics(results);
    ASSERT_EQ(m.slices.size(), 1u);
    const Resolution& r = m.slices[0].resolution;
    EXPECT_NEAR(r.predicted_basin, M_PI * 1.5e-3, 1e-15);
    // d log f / d log EI of the bending modes is just below 1/2 (shear takes a little of the strain energy).
    const double log_step = 2 * std::log(1.5) / (points - 1);
    EXPECT_GT(r.frequency_step, 0.45 * log_step);
    EXPECT_LE(r.frequency_step, 0.5 * log_step);
    EXPECT_EQ(r.resolved(), points == 721) << points;
  }
}

}  // namespace
}  // namespace beamid::study
