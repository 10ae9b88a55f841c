// The parameter map: coordinates of order one, exact round trips between physical values and coordinates, the
// derivative used to propagate a covariance, and the refusal of what cannot be estimated.
#include "fit/parameter_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/errors.h"

namespace beamid::fit {
namespace {

TEST(ParameterMap, CoordinatesAreOfOrderOneAndRoundTrip) {
  const model::BeamParameters beam = model::preset("thick-steel");
  for (const std::string scaling : {"linear", "log"}) {
    const ParameterMap map(beam, {{"EI", beam.EI / 2, beam.EI * 2}, {"kAG", beam.kAG / 2, beam.kAG * 2}}, scaling);
    const Eigen::VectorXd x = map.coordinates(beam);
    // At the reference values the coordinates are 1 (linear) or 0 (log), whatever the units (kAG ~ 1e8 N).
    EXPECT_NEAR(x[0], scaling == "linear" ? 1.0 : 0.0, 1e-15);
    EXPECT_NEAR(x[1], scaling == "linear" ? 1.0 : 0.0, 1e-15);
    Eigen::VectorXd y = x;
    y[0] += 0.1;
    const model::BeamParameters b = map.beam(y);
    EXPECT_NEAR(map.coordinates(b)[0], y[0], 1e-14);
    EXPECT_EQ(b.rho, beam.rho) << "a parameter not estimated keeps its value";
    // dp/dx against a central difference (step 1e-6: truncation 1e-12, round-off 1e-10 relative).
    const double h = 1e-6;
    const double fd = (map.value(0, y[0] + h) - map.value(0, y[0] - h)) / (2 * h);
    EXPECT_NEAR(map.derivative(0, y[0]) / fd, 1.0, 1e-8) << scaling;
    EXPECT_NEAR(map.value(0, map.lower()[0]), beam.EI / 2, 1e-12 * beam.EI);
    EXPECT_NEAR(map.value(0, map.upper()[0]), beam.EI * 2, 1e-12 * beam.EI);
  }
}

TEST(ParameterMap, PhysicalValuesNeverLeaveTheirBounds) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  for (const std::string scaling : {"linear", "log"}) {
    const ParameterMap map(beam, {{"cDI", 1e-5, 1e-2}}, scaling);
    // Coordinates just outside the bounds (as an optimizer's last step may leave them) are reported on the bound.
    const double below = map.lower()[0] - 1e-6 * std::abs(map.lower()[0]) - 1e-12;
    const double above = map.upper()[0] + 1e-6 * std::abs(map.upper()[0]) + 1e-12;
    Eigen::VectorXd x(1);
    x[0] = below;
    EXPECT_EQ(map.estimate(x).cDI, 1e-5) << scaling;
    x[0] = above;
    EXPECT_EQ(map.estimate(x).cDI, 1e-2) << scaling;
    EXPECT_EQ(map.estimate(x).EI, beam.EI) << "a parameter not estimated keeps its value";
  }
}

TEST(ParameterMap, RefusesWhatCannotBeEstimated) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  EXPECT_THROW(ParameterMap(beam, {{"support.k_theta", 0.4, 0.5}}), InputError);       // a rigid clamp has no spring
  EXPECT_THROW(ParameterMap(beam, {{"EJ", 0.4, 0.5}}), InputError);                    // no such parameter
  EXPECT_THROW(ParameterMap(beam, {{"EI", 0.4, 0.5}, {"EI", 0.4, 0.5}}), InputError);  // repeated
  EXPECT_THROW(ParameterMap(beam, {{"EI", 0.5, 0.4}}), InputError);                    // lower above upper
  EXPECT_THROW(ParameterMap(beam, {{"gamma", 0, 1}}, "log"), InputError);              // log of a zero bound
}

}  // namespace
}  // namespace beamid::fit
