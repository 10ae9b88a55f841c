// Start-distance curves: the starts land at the frequency offset asked for, the sensitivities obey the scaling
// identities of the Galerkin model, and the 50 % radius is the hand-computed crossing.
#include "study/analysis/start_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "galerkin/spline_space.h"

namespace beamid::study {
namespace {

TEST(StartDistance, FrequencySensitivitiesObeyTheScalingIdentities) {
  // K = EI B + kAG S and M = rho T + rho_r2 R + tip terms (m, J_o): scaling every stiffness by c scales omega^2 by c,
  // every inertia by c scales it by 1/c, so the sensitivities of log f sum to +1/2 and -1/2 exactly (round-off:
  // 1e-10). Damping does not move an undamped frequency at all.
  const auto beam = model::preset("thick-steel");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  const std::vector<std::string> keys = {"EI", "kAG", "rho", "rho_r2", "m", "J_o", "cDI", "gamma"};
  const Eigen::MatrixXd g = frequency_sensitivities(forms, beam, keys, 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(g(k, 0) + g(k, 1), 0.5, 1e-10) << "mode " << k + 1;
    EXPECT_NEAR(g(k, 2) + g(k, 3) + g(k, 4) + g(k, 5), -0.5, 1e-10) << "mode " << k + 1;
    EXPECT_EQ(g(k, 6), 0.0);
    EXPECT_EQ(g(k, 7), 0.0);
  }
  // Against central differences of the frequencies in log EI (step 1e-5: error ~1e-10, far below 1e-7).
  const double h = 1e-5;
  auto plus = beam, minus = beam;
  plus.EI *= std::exp(h), minus.EI *= std::exp(-h);
  const auto fp = galerkin::undamped_modes(galerkin::combine(forms, plus)).omega_rad_s;
  const auto fm = galerkin::undamped_modes(galerkin::combine(forms, minus)).omega_rad_s;
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(g(k, 0), (std::log(fp(k)) - std::log(fm(k))) / (2 * h), 1e-7);
}

TEST(StartDistance, StartsLandAtTheRequestedFrequencyOffset) {
  const auto beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  const std::vector<std::string> keys = {"EI", "rho", "cDI", "gamma"};
  for (int d = 0; d < 5; ++d) {
    const Eigen::VectorXd u = random_direction(1000 + d, 4);
    EXPECT_NEAR(u.norm(), 1.0, 1e-15);
    // First order in r: the exact offset differs from r by O(r^2) (the curvature of log f in log q is O(1)).
    for (double r : {1e-3, 1e-2}) {
      const OffsetStart s = offset_start(forms, beam, keys, 3, u, r, 2.0);
      if (s.shrunk) continue;
      EXPECT_NEAR(s.frequency_offset, r, 2 * r * r) << "direction " << d << ", offset " << r;
    }
  }
  // A direction that moves no frequency (damping only) goes as far as the bounds allow, 0.9 log 2, and is marked.
  Eigen::VectorXd damping(4);
  damping << 0, 0, 0.6, 0.8;
  const OffsetStart s = offset_start(forms, beam, keys, 3, damping, 0.01, 2.0);
  EXPECT_TRUE(s.shrunk);
  EXPECT_EQ(s.frequency_offset, 0.0);
  EXPECT_NEAR(s.start.gamma / beam.gamma, std::pow(2.0, 0.9), 1e-12);
  EXPECT_EQ(s.start.EI, beam.EI);
  // The same seed gives the same direction: every run and offset shares them.
  EXPECT_EQ(random_direction(7, 4), random_direction(7, 4));
}

TEST(StartDistance, HalfRadiusIsTheCrossingInLogOffset) {
  // 0.75 at 1 % and 0.25 at 10 %: halfway in log, sqrt(0.01 * 0.1).
  const HalfRadius r = half_radius({0.001, 0.01, 0.1}, {1.0, 0.75, 0.25});
  EXPECT_NEAR(r.value, std::sqrt(0.01 * 0.1), 1e-15);
  EXPECT_FALSE(r.below || r.above);
  EXPECT_EQ(radius_text(r), "3.16 %");
  // The leading run of rates >= 1/2 decides: a later recovery does not extend the radius.
  EXPECT_NEAR(half_radius({0.001, 0.01, 0.1}, {0.9, 0.1, 0.9}).value, std::exp(std::log(0.001) + 0.5 * std::log(10.0)),
              1e-15);
  const HalfRadius below = half_radius({0.001, 0.01}, {0.4, 0.0});
  EXPECT_TRUE(below.below);
  EXPECT_EQ(radius_text(below), "< 0.1 %");
  const HalfRadius above = half_radius({0.001, 0.01}, {1.0, 0.5});
  EXPECT_TRUE(above.above);
  EXPECT_EQ(radius_text(above), "> 1 %");
  EXPECT_THROW(half_radius({}, {}), InputError);
}

TEST(StartDistance, ReachingMeansAgreeingWithTheFitFromTheTruth) {
  StudySpec spec;
  spec.fit.estimate = {"EI", "gamma"};
  spec.start_distance.agreement = 1e-3;
  spec.start_distance.damping_agreement = 1e-2;
  const auto record = [](const std::string& status, double ei, double gamma) {
    Record r;
    r.set("status", status);
    r.set("estimate.EI", ei);
    r.set("estimate.gamma", gamma);
    return r;
  };
  const Record reference = record("converged", 10.0, 2.0);
  EXPECT_TRUE(reaches(spec, reference, record("converged", 10.009, 2.019)));  // 9e-4 and 9.5e-3
  EXPECT_FALSE(reaches(spec, reference, record("converged", 10.011, 2.0)));   // EI 1.1e-3 off
  EXPECT_FALSE(reaches(spec, reference, record("converged", 10.0, 2.021)));   // damping 1.05e-2 off
  EXPECT_FALSE(reaches(spec, reference, record("failed", 10.0, 2.0)));        // a failed fit reaches nothing
  EXPECT_FALSE(reaches(spec, reference, record("converged", std::nan(""), 2.0)));
}

TEST(StartDistance, PredictedBasinsTakeTheMostRestrictiveFittedMode) {
  // Where a mode decays within the record (1/sigma < T) its basin 1/(2 f T_eff) is sigma/(2 f) = pi zeta exactly.
  // Thin beam (T = 4.096 s): modes 2.46, 26.5, 81.7 Hz with damping ratios 8.1e-4, 1.5e-3, 3.5e-3, so
  // 1/sigma = 79.9, 4.004, 0.5566 s: mode 1 lasts the record (1/(2 x 2.46 x 4.096) = 4.96 %), modes 2 and 3 give
  // pi zeta = 0.471 % and 1.10 %. The record-length basin is the highest mode's 1/(2 f T) = 0.149 %.
  StartDistanceMetrics thin;
  thin.fitted_modes = 3;
  predict_basins({2.46, 26.5, 81.7, 160.0}, {8.1e-4, 1.5e-3, 3.5e-3, 7e-3}, 4.096, thin);
  EXPECT_NEAR(thin.predicted_basin, 1 / (2 * 81.7 * 4.096), 1e-15);
  EXPECT_EQ(thin.limiting_mode, 2);
  EXPECT_DOUBLE_EQ(thin.limiting_mode_hz, 26.5);
  EXPECT_NEAR(thin.decay_rate_1_s, 2 * M_PI * 26.5 * 1.5e-3, 1e-15);
  EXPECT_NEAR(thin.predicted_basin_decay, M_PI * 1.5e-3, 1e-15);
  EXPECT_NEAR(thin.predicted_basin_highest_decay, M_PI * 3.5e-3, 1e-15);
  // Thick beam (T = 0.8192 s): 81.7, 579, 1666 Hz with 7.57e-4, 4.16e-3, 1.34e-2: mode 1 lasts the record
  // (1/(2 x 81.7 x 0.8192) = 0.747 %), modes 2 and 3 give pi zeta = 1.31 % and 4.21 %: mode 1 limits, and the
  // highest mode alone would predict 5.6x wider.
  StartDistanceMetrics thick;
  thick.fitted_modes = 3;
  predict_basins({81.7, 579.0, 1666.0}, {7.57e-4, 4.16e-3, 1.34e-2}, 0.8192, thick);
  EXPECT_EQ(thick.limiting_mode, 1);
  EXPECT_NEAR(thick.predicted_basin_decay, 1 / (2 * 81.7 * 0.8192), 1e-15);
  EXPECT_NEAR(thick.predicted_basin_highest_decay, M_PI * 1.34e-2, 1e-15);
  // Fewer modes known than fitted: no prediction.
  StartDistanceMetrics none;
  none.fitted_modes = 3;
  predict_basins({81.7}, {7.57e-4}, 0.8192, none);
  EXPECT_EQ(none.limiting_mode, 0);
  EXPECT_TRUE(std::isnan(none.predicted_basin));
  EXPECT_TRUE(std::isnan(none.predicted_basin_decay));
}

}  // namespace
}  // namespace beamid::study
