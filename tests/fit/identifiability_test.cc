// The identifiability verdict's scope (fit/identifiability.h): about the parameters of interest, with the nuisances
// marginalised and the parameters on a bound left out.
#include "fit/identifiability.h"

#include <gtest/gtest.h>

#include "model/beam_parameters.h"

namespace beamid::fit {
namespace {

TEST(Identifiability, TheVerdictIsAboutTheParametersOfInterest) {
  // Information in ln q (log scaling: x = ln q up to a constant, so d x / d ln q = 1) for EI, cDI and gamma: EI well
  // determined (eigenvalue 1) and only weakly coupled to the damping, while cDI and gamma are nearly one combination
  // (their 2 x 2 block has eigenvalues 1 and 1e-12: condition 1e6 in J, "ill-conditioned" over all three). About EI
  // alone, with the damping marginalised, the Schur complement is 1 - 2 (0.01)^2 = 0.9998 (the coupling lies along
  // the damping's determined combination): identifiable, and the formal sd of ln EI is sqrt(s^2 / 0.9998), 1e-4
  // relative above sqrt(s^2) = 0.01 (asserted to 1e-3 relative).
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const ParameterMap map(beam,
                         {{"EI", beam.EI / 2, beam.EI * 2},
                          {"cDI", beam.cDI / 2, beam.cDI * 2},
                          {"gamma", beam.gamma / 2, beam.gamma * 2}},
                         "log");
  const Eigen::VectorXd x = map.coordinates(beam);
  Covariance c;
  c.residual_variance = 1e-4;
  const double e = 1e-12, coupling = 0.01;
  c.information.resize(3, 3);
  c.information << 1, coupling, coupling, coupling, 0.5 * (1 + e), 0.5 * (1 - e), coupling, 0.5 * (1 - e),
      0.5 * (1 + e);
  const Identifiability all = identifiability_of(c, map, x);
  ASSERT_EQ(all.status, "ok");
  EXPECT_EQ(all.verdict, "ill-conditioned") << all.condition;
  EXPECT_EQ(all.keys.size(), 3u);

  VerdictScope scope;
  scope.of_interest = {true, false, false};
  const Identifiability ei = identifiability_of(c, map, x, scope);
  ASSERT_EQ(ei.status, "ok");
  EXPECT_EQ(ei.verdict, "identifiable");
  EXPECT_EQ(ei.keys, (std::vector<std::string>{"EI"}));
  EXPECT_EQ(ei.nuisance, (std::vector<std::string>{"cDI", "gamma"}));
  EXPECT_NEAR(ei.weakest_sd, 0.01, 1e-5);

  // gamma on its bound is left out: the verdict about EI and cDI (of interest here) sees a well-posed 2 x 2 block.
  scope.of_interest = {true, true, false};
  scope.on_bound = {false, false, true};
  const Identifiability bound = identifiability_of(c, map, x, scope);
  ASSERT_EQ(bound.status, "ok");
  EXPECT_EQ(bound.on_bound, (std::vector<std::string>{"gamma"}));
  EXPECT_TRUE(bound.nuisance.empty());
  EXPECT_EQ(bound.verdict, "identifiable") << bound.condition;

  // Nothing free of interest: the verdict is about every free parameter.
  scope.of_interest = {false, false, false};
  scope.on_bound = {};
  EXPECT_EQ(identifiability_of(c, map, x, scope).keys.size(), 3u);
}

}  // namespace
}  // namespace beamid::fit
