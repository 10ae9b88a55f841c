// A sensor's anti-alias filter in the fitted model (fit/sensed_output.h): the sensed output's exact Jacobian against
// central differences, a record filtered before sampling recovered exactly with the filter in the model and not
// without it, the Cramér-Rao bound of the sensed record against differences built here from signal::sense, and the
// refusals. The banks-aluminium beam at N = 8 with model.md section 5's sampling (1 ms, 4096 samples, a 4 ms pulse at
// 0.7 l) and an order-4 Butterworth at 100 Hz: its phase lag at the beam's lowest modes (tens of Hz) is tenths of a
// radian, a delay of about 4 ms that a model without the filter must absorb into its parameters.
#include "fit/sensed_output.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "central_difference.h"
#include "core/errors.h"
#include "fit/cramer_rao.h"
#include "fit/identification.h"
#include "fit/objective.h"
#include "galerkin/second_order_system.h"
#include "simulation/modal_simulator.h"
#include "simulation/sensitivities.h"
#include "simulation/simulator.h"

namespace beamid::fit {
namespace {

constexpr int kElements = 8;
const signal::SensorFilter kFilter{100, 4, 16};

simulation::Experiment experiment_for(double length_m) {
  simulation::Experiment e;
  e.dt_s = 1e-3;
  e.samples = 4096;
  e.pulse_width_s = 4e-3;
  e.force_x_m = 0.7 * length_m;
  return e;
}

// The record of `beam` at N = 8 as `filter` delivers it: simulated 16 times finer, filtered, every 16th sample.
std::vector<double> sensed_record(const model::BeamParameters& beam, const simulation::Experiment& e,
                                  const signal::SensorFilter& filter) {
  const galerkin::SplineSpace space(kElements);
  const auto trace = simulation::simulate(galerkin::BeamForms(space, beam.l, beam.support), beam,
                                          simulation::finer(e, filter.oversampling), {});
  EXPECT_TRUE(trace.ok()) << trace.status;
  return signal::sense(filter, trace.y, e.dt_s);
}

FitOptions options_for(const model::BeamParameters& truth, const signal::SensorFilter& filter) {
  FitOptions o;
  o.start = truth;
  o.elements = kElements;
  o.experiment = experiment_for(truth.l);
  o.sensor = filter;
  o.cost.name = costs::kTimeCost;
  o.optimizer.method = default_optimizer(o.cost.name);
  for (const std::string key : {"EI", "rho", "cDI", "gamma"}) {
    double& v = o.start.*(model::find_parameter(key)->member);
    o.estimate.push_back({key, v / 2, v * 2});
    v *= 1.05;  // every parameter 5 % off
  }
  return o;
}

double worst_relative_error(const FitResult& r, const model::BeamParameters& truth) {
  double worst = 0;
  for (const auto& p : r.parameters)
    worst = std::max(worst, std::abs(p.estimate / (truth.*(model::find_parameter(p.key)->member)) - 1));
  std::printf("[ worst relative error %.2e ]\n", worst);
  return worst;
}

TEST(SensedOutput, TheExactJacobianIsTheSensedSensitivities) {
  const auto truth = model::preset("banks-aluminium");
  FitOptions o = options_for(truth, kFilter);
  Objective objective(o, sensed_record(truth, o.experiment, kFilter));
  ASSERT_TRUE(objective.has_exact_jacobian());
  std::vector<std::string> keys;
  for (const auto& e : o.estimate) keys.push_back(e.key);
  Eigen::MatrixXd jacobian;
  ASSERT_TRUE(objective.evaluate_with_jacobian(o.start, keys, jacobian).evaluation.ok());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    // Central differences at h = 1e-5 q. Without the filter they differ from the closed form by 3e-6 (EI) to 8e-6
    // (rho) of the column on this 4 s record (measured; the phase of the 100 Hz mode over 4 s makes the h^2 term
    // and the simulator's round-off over h of that size), and by the same with it: 3e-5 bounds both, far below a
    // wrong or missing filter (its phase lag of tenths of a radian changes the column by tens of per cent).
    const Eigen::VectorXd difference = testing::residual_central_difference(objective, o.start, keys[k]);
    EXPECT_LT((jacobian.col(static_cast<Eigen::Index>(k)) - difference).norm(), 3e-5 * difference.norm()) << keys[k];
  }
}

TEST(SensedOutput, AFilteredRecordIsRecoveredWithTheFilterInTheModelAndNotWithout) {
  const auto truth = model::preset("banks-aluminium");
  const std::vector<double> data = sensed_record(truth, experiment_for(truth.l), kFilter);
  // The same model, filter and sampling as the data: the cost's minimum is the truth, reached from 5 % off to the
  // optimizer's tolerance (1.4e-9 measured; 1e-6 asked).
  const FitResult with = fit(options_for(truth, kFilter), data);
  EXPECT_EQ(with.status, "converged") << with.termination;
  EXPECT_LT(worst_relative_error(with, truth), 1e-6);
  // Without it, the fit explains the filter's delay and attenuation with the beam's parameters: a minimum away from
  // the truth (measured: worst error 0.26; asked: above 1e-2, ten thousand times the filtered fit's bound).
  const FitResult without = fit(options_for(truth, {}), data);
  EXPECT_GT(worst_relative_error(without, truth), 1e-2);
}

TEST(SensedOutput, TheBoundIsThatOfTheSensedRecord) {
  const auto truth = model::preset("banks-aluminium");
  const simulation::Experiment e = experiment_for(truth.l);
  const std::vector<std::string> keys = {"EI", "rho", "cDI", "gamma"};
  const double sigma = 1e-6;
  const CramerRaoBound bound = beam_cramer_rao_bound(truth, kElements, e, keys, sigma, {}, {}, kFilter);
  ASSERT_EQ(bound.status, "ok");
  EXPECT_EQ(bound.method, "exact");
  // d y / d ln q of the sensed record by central differences of sensed_record in ln q (h = 1e-5), built here from
  // signal::sense: the bound's sensitivities agree to the differences' own error, 3e-5 of each column as above.
  const auto central = [&](const std::string& key, double h) {
    model::BeamParameters up = truth, down = truth;
    double model::BeamParameters::*member = model::find_parameter(key)->member;
    up.*member *= std::exp(h);
    down.*member *= std::exp(-h);
    const std::vector<double> yu = sensed_record(up, e, kFilter), yd = sensed_record(down, e, kFilter);
    Eigen::VectorXd d(static_cast<Eigen::Index>(yu.size()));
    for (std::size_t i = 0; i < yu.size(); ++i) d(static_cast<Eigen::Index>(i)) = (yu[i] - yd[i]) / (2 * h);
    return d;
  };
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const Eigen::VectorXd difference = central(keys[k], 1e-5);
    EXPECT_LT((bound.sensitivities.col(static_cast<Eigen::Index>(k)) - difference).norm(), 3e-5 * difference.norm())
        << keys[k];
  }
}

TEST(SensedOutput, TheModalCostReadsThePolesTheFilterLeavesAlone) {
  // Modal updating compares the record's identified poles with the model's eigenvalues: the filter moves neither
  // the model's poles nor the cost, so with and without it in the model the cost is the same number (both evaluate
  // the same eigen-decomposition; the record's own grid gives the poles), and no unfiltered output is handed on.
  const auto truth = model::preset("banks-aluminium");
  FitOptions o = options_for(truth, kFilter);
  o.cost.name = costs::kModalCost;
  o.cost.spikes.count = 3;
  const std::vector<double> data = sensed_record(truth, o.experiment, kFilter);
  Objective with(o, data);
  o.sensor = {};
  Objective without(o, data);
  const Objective::Output a = with.evaluate(o.start), b = without.evaluate(o.start);
  ASSERT_TRUE(a.evaluation.ok()) << a.evaluation.status;
  EXPECT_EQ(a.evaluation.value, b.evaluation.value);
  EXPECT_TRUE(a.y.empty());
  // Asked for the output (a report's overlay), it is the sensed one: the record itself at the truth, to round-off.
  const Objective::Output shown = with.evaluate(truth, Objective::Response::always);
  ASSERT_EQ(shown.y.size(), data.size());
  for (std::size_t i = 0; i < data.size(); ++i) EXPECT_NEAR(shown.y[i], data[i], 1e-12 * 1e3) << i;
}

// The largest |a_i - b_i| over the largest |b_i|.
double relative_difference(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(SensedOutput, TheClosedFormFilterIsTheFinePath) {
  // The fast simulator carries the filter through its closed form on the record's grid (simulation/output_filter.h):
  // the record, and a pulse's sensitivities, are those of the model simulated 16 times finer, filtered sample by
  // sample and decimated (the truth's path), to round-off. Both are exact, so what differs is the order of the sums:
  // the fine path runs the filter's recursion over 65,536 fine samples. Measured: at most 1.3e-13 of the record's peak
  // (thin and thick, pulse and pluck, every output) and 1.8e-13 of a sensitivity column's; 1e-12 and 2e-12 asked, far
  // below what a wrong filter start (tenths of the peak), a missing transient (percent) or a wrong H'(mu) in the
  // sensitivities (the size of the b term, percent of the column) would leave.
  struct Case {
    std::string beam, excitation, output;
    double dt_s, pulse_width_s;
    signal::SensorFilter filter;
  };
  const std::vector<Case> cases = {
      {"banks-aluminium", simulation::kPulse, simulation::kDisplacement, 1e-3, 4e-3, kFilter},
      {"banks-aluminium", simulation::kPulse, simulation::kAcceleration, 1e-3, 4e-3, {300, 5, 16}},
      {"banks-aluminium", simulation::kPluck, simulation::kDisplacement, 1e-3, 4e-3, kFilter},
      {"banks-aluminium", simulation::kPluck, simulation::kAcceleration, 1e-3, 4e-3, kFilter},
      {"thick-steel", simulation::kPulse, simulation::kAcceleration, 1e-4, 7e-4, {4000, 4, 16}},
      {"thick-steel", simulation::kPulse, simulation::kVelocity, 1e-4, 7e-4, {2000, 3, 8}}};
  for (const Case& c : cases) {
    const model::BeamParameters beam = model::preset(c.beam);
    simulation::Experiment e = experiment_for(beam.l);
    e.excitation = c.excitation;
    e.output = c.output;
    e.dt_s = c.dt_s;
    e.pulse_width_s = c.pulse_width_s;
    const galerkin::SplineSpace space(kElements);
    const galerkin::BeamForms forms(space, beam.l, beam.support);
    const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
    simulation::Trace fine = simulation::simulate(forms, beam, simulation::finer(e, c.filter.oversampling), {});
    ASSERT_TRUE(fine.ok()) << fine.status;
    sense_output(c.filter, e, fine.y);
    simulation::ResponseProblem problem = simulation::make_problem(forms, system, e, beam.l);
    problem.output_filter = output_filter(c.filter, e.dt_s);
    const simulation::Trace closed = simulation::ModalSimulator().run(system, problem);
    ASSERT_TRUE(closed.ok()) << closed.status;
    ASSERT_EQ(closed.y.size(), fine.y.size());
    const auto map = [](const std::vector<double>& y) {
      return Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
    };
    EXPECT_LT(relative_difference(map(closed.y), map(fine.y)), 1e-12)
        << c.beam << " " << c.excitation << " " << c.output;
    if (c.excitation != simulation::kPulse) continue;
    const std::vector<std::string> keys = {"EI", "rho", "cDI", "gamma"};
    const simulation::SensitivityTrace with =
        simulation::simulate_with_sensitivities(forms, beam, e, keys, output_filter(c.filter, e.dt_s));
    simulation::SensitivityTrace finer =
        simulation::simulate_with_sensitivities(forms, beam, simulation::finer(e, c.filter.oversampling), keys);
    ASSERT_TRUE(with.trace.ok() && finer.trace.ok());
    EXPECT_EQ(with.trace.y, closed.y);  // the trace is the simulator's
    for (Eigen::Index k = 0; k < finer.dy_dq.cols(); ++k) {
      const std::vector<double> column(finer.dy_dq.col(k).data(), finer.dy_dq.col(k).data() + finer.dy_dq.rows());
      const std::vector<double> sensed = signal::sense(c.filter, column, e.dt_s, 0.0);  // from rest
      EXPECT_LT(relative_difference(with.dy_dq.col(k), map(sensed)), 2e-12)
          << c.beam << " " << c.output << " " << keys[k];
    }
  }
  // cvode simulates finer and filters: handed the closed form's filter, it refuses.
  const auto beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(kElements);
  const galerkin::BeamForms forms(space, beam.l, beam.support);
  const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
  simulation::ResponseProblem problem = simulation::make_problem(forms, system, experiment_for(beam.l), beam.l);
  problem.output_filter = output_filter(kFilter, 1e-3);
  simulation::SimulatorOptions cvode;
  cvode.integrator = simulation::kCvode;
  EXPECT_THROW(simulation::make_simulator(cvode)->run(system, problem), InputError);
}

TEST(SensedOutput, ThePluckedAccelerationStartsFromRest) {
  // A pluck's acceleration is -c^T M^-1 K w0 at the release and 0 before it: the sensor sees a step, and the model
  // with the filter delivers the record that signal::sense gives from a level of 0, not from its first sample.
  const auto truth = model::preset("banks-aluminium");
  simulation::Experiment e = experiment_for(truth.l);
  e.excitation = simulation::kPluck;
  e.output = simulation::kAcceleration;
  e.samples = 512;
  const galerkin::SplineSpace space(kElements);
  const auto fine = simulation::simulate(galerkin::BeamForms(space, truth.l, truth.support), truth,
                                         simulation::finer(e, kFilter.oversampling), {});
  ASSERT_TRUE(fine.ok());
  ASSERT_GT(std::abs(fine.y.front()), 0.0);
  std::vector<double> y = fine.y;
  sense_output(kFilter, e, y);
  EXPECT_EQ(y, signal::sense(kFilter, fine.y, e.dt_s, 0.0));
  EXPECT_NE(y, signal::sense(kFilter, fine.y, e.dt_s));
}

TEST(SensedOutput, RefusesWhatItCannotModel) {
  const auto truth = model::preset("banks-aluminium");
  simulation::Experiment decay = experiment_for(truth.l);
  decay.excitation = simulation::kFreeDecay;
  EXPECT_TRUE(sensed_validation_error(kFilter, decay).has_value());
  EXPECT_FALSE(sensed_validation_error({}, decay).has_value());  // no filter: nothing to refuse
  // A cut-off past a quarter of the fine record's Nyquist frequency (16 kHz / 8 = 2 kHz here).
  EXPECT_TRUE(sensed_validation_error({2500, 4, 16}, experiment_for(truth.l)).has_value());
  // A measured force went through the acquisition's filter too: the filter would be counted twice.
  simulation::Experiment forced = experiment_for(truth.l);
  forced.excitation = simulation::kSampledForce;
  EXPECT_NE(sensed_validation_error(kFilter, forced).value_or("").find("count it twice"), std::string::npos);
  // The finer record past the simulator's limits: too many samples, or a step below 1e-9 s.
  simulation::Experiment huge = experiment_for(truth.l);
  huge.samples = 1 << 25;  // 2^29 fine samples, above core::kMaxSamples = 2^28
  EXPECT_NE(sensed_validation_error(kFilter, huge).value_or("").find("samples: at most"), std::string::npos);
  simulation::Experiment fast = experiment_for(truth.l);
  fast.dt_s = 1e-8;
  EXPECT_NE(sensed_validation_error({1e5, 4, 16}, fast).value_or("").find("at least 1e-9 s"), std::string::npos);
  FitOptions o = options_for(truth, kFilter);
  o.experiment.excitation = simulation::kFreeDecay;
  EXPECT_THROW(Objective(o, std::vector<double>(4096, 1.0)), InputError);
}

}  // namespace
}  // namespace beamid::fit
