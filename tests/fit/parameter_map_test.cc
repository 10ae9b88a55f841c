// The parameter map: coordinates of order one, exact round trips between physical values and coordinates, the
// derivative used to propagate a covariance, and the refusal of what cannot be estimated.
#include "fit/parameter_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"

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

TEST(ParameterMap, SharedKeysActOnEveryRecordAndRecordKeysOnTheirOwn) {
  // Two records of one bar at two lengths: EI shared, each record's own length (fit/parameter_map.h).
  model::BeamParameters a = model::preset("thick-steel");
  model::BeamParameters b = a;
  b.l = 0.8 * a.l;
  b.EI = 3 * a.EI;  // a shared parameter's reference is record 1's value
  const ParameterMap map({a, b}, {{"EI", a.EI / 2, a.EI * 2}, {"record2.l", 0.2, 0.3}});
  EXPECT_EQ(map.records(), 2);
  EXPECT_EQ(map.reference(0), a.EI);
  EXPECT_EQ(map.reference(1), b.l);
  Eigen::VectorXd x(2);
  x << 1.1, 1.05;
  const auto beams = map.beams(x);
  ASSERT_EQ(beams.size(), 2u);
  EXPECT_EQ(beams[0].EI, 1.1 * a.EI);
  EXPECT_EQ(beams[1].EI, 1.1 * a.EI) << "a shared value is set in every record";
  EXPECT_EQ(beams[0].l, a.l) << "a record's own key leaves the other records alone";
  EXPECT_EQ(beams[1].l, 1.05 * b.l);
  EXPECT_EQ(map.coordinates(beams), x);
  ASSERT_EQ(map.acting_on(0).size(), 1u);
  ASSERT_EQ(map.acting_on(1).size(), 2u);
  EXPECT_EQ(map.acting_on(1)[1].key, "l");
  EXPECT_EQ(map.with_roles({"geometry"}), std::vector<int>{1}) << "the role of record2.l is l's";
  EXPECT_EQ(record_key("record12.attachment1.m")->first, 11);
  EXPECT_EQ(record_key("record12.attachment1.m")->second, "attachment1.m");
  EXPECT_FALSE(record_key("attachment1.m"));
}

TEST(ParameterMap, RefusesRecordKeysThatDoNotFitTheRecords) {
  model::BeamParameters a = model::preset("thick-steel");
  model::BeamParameters b = a;
  b.attachments = {{0.1, 0.01, 0, 0}};
  EXPECT_THROW(ParameterMap({a, b}, {{"record3.l", 0.2, 0.3}}), InputError);                   // two records only
  EXPECT_THROW(ParameterMap({a, b}, {{"record0.l", 0.2, 0.3}}), InputError);                   // numbered from 1
  EXPECT_THROW(ParameterMap({a, b}, {{"recordx.l", 0.2, 0.3}}), InputError);                   // not a number
  EXPECT_THROW(ParameterMap({a, b}, {{"attachment1.m", 0.005, 0.02}}), InputError);            // record 1 has no body
  EXPECT_NO_THROW(ParameterMap({a, b}, {{"record2.attachment1.m", 0.005, 0.02}}));             // record 2 has one
  EXPECT_THROW(ParameterMap({a, b}, {{"l", 0.2, 0.4}, {"record1.l", 0.2, 0.4}}), InputError);  // shared and own
  EXPECT_THROW(ParameterMap(std::vector<model::BeamParameters>{}, {{"EI", 1, 2}}), InputError);
}

}  // namespace
}  // namespace beamid::fit
