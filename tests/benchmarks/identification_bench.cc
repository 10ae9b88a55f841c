// Identification benchmarks (make bench): one evaluation of each cost at N = 16, Nbar = 4096 (model by `fast`, plus
// DFT and cost), one exact time-cost Jacobian, one full spike-smooth fit of EI, rho, cDI, gamma from a 5 % start and
// staged fits with the time and spike-smooth costs (banks-aluminium, pulse of 4 ms at 0.7 l, tip displacement; data
// from `fast` at N = 16 so that the benchmark needs no CVODE run).
#include <benchmark/benchmark.h>

#include "fit/identification.h"
#include "fit/objective.h"
#include "fit/sensed_output.h"
#include "galerkin/second_order_system.h"
#include "signal/sensor_filter.h"
#include "simulation/sensitivities.h"

namespace {

using namespace beamid;

fit::FitOptions options(const std::string& cost) {
  fit::FitOptions o;
  o.start = model::preset("banks-aluminium");
  o.elements = 16;
  o.experiment.dt_s = 1e-3;
  o.experiment.samples = 4096;
  o.experiment.pulse_width_s = 4e-3;
  o.experiment.force_x_m = 0.7 * o.start.l;
  o.cost.name = cost;
  o.cost.spikes.count = 3;
  o.optimizer.method = fit::default_optimizer(cost);
  for (const char* key : {"EI", "rho", "cDI", "gamma"}) {
    const double v = o.start.*(model::find_parameter(key)->member);
    o.estimate.push_back({key, v / 2, v * 2});
  }
  return o;
}

const std::vector<double>& data() {
  static const std::vector<double> y = [] {
    const auto o = options("time");
    const galerkin::SplineSpace space(16);
    return simulation::simulate(galerkin::BeamForms(space, o.start.l), o.start, o.experiment, {}).y;
  }();
  return y;
}

void BM_CostEvaluation(benchmark::State& state, const std::string& cost) {
  fit::Objective objective(options(cost), data());
  auto beam = model::preset("banks-aluminium");
  beam.EI *= 1.01;
  for (auto _ : state) benchmark::DoNotOptimize(objective.evaluate(beam).evaluation.value);
}
BENCHMARK_CAPTURE(BM_CostEvaluation, time, std::string("time"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CostEvaluation, spike, std::string("spike"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CostEvaluation, spike_smooth, std::string("spike-smooth"))->Unit(benchmark::kMillisecond);

// Scaling of one cost evaluation in the record length, N = 16, Nbar = 1024 .. 65536 (tests/benchmarks/scaling.py):
// the forward run, the DFT (n log n) and the cost's own sums must all stay near-linear.
void BM_CostSamples(benchmark::State& state, const std::string& cost) {
  auto o = options(cost);
  o.experiment.samples = static_cast<int>(state.range(0));
  const galerkin::SplineSpace space(16);
  const std::vector<double> y =
      simulation::simulate(galerkin::BeamForms(space, o.start.l), o.start, o.experiment, {}).y;
  fit::Objective objective(o, y);
  auto beam = model::preset("banks-aluminium");
  beam.EI *= 1.01;
  for (auto _ : state) benchmark::DoNotOptimize(objective.evaluate(beam).evaluation.value);
}
BENCHMARK_CAPTURE(BM_CostSamples, time, std::string("time"))
    ->RangeMultiplier(4)
    ->Range(1024, 65536)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CostSamples, spike_smooth, std::string("spike-smooth"))
    ->RangeMultiplier(4)
    ->Range(1024, 65536)
    ->Unit(benchmark::kMillisecond);

void BM_FullFit(benchmark::State& state) {
  auto o = options("spike-smooth");
  for (const char* key : {"EI", "rho", "cDI", "gamma"}) o.start.*(model::find_parameter(key)->member) *= 1.05;
  long evaluations = 0;
  for (auto _ : state) evaluations = fit::fit(o, data()).evaluations;
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK(BM_FullFit)->Unit(benchmark::kMillisecond)->Iterations(3);

// The paper's staged fit (stiffness and inertia, damping, all) from every estimated parameter 5 % high (the
// frequencies then start right, inside the time cost's basin): the time cost by Levenberg-Marquardt with its exact
// Jacobian (simulation/sensitivities.h), spike-smooth with central differences.
void BM_StagedFit(benchmark::State& state, const std::string& cost) {
  auto o = options(cost);
  o.strategy = fit::kStaged;
  for (const char* key : {"EI", "rho", "cDI", "gamma"}) o.start.*(model::find_parameter(key)->member) *= 1.05;
  long evaluations = 0;
  for (auto _ : state) evaluations = fit::fit(o, data()).evaluations;
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK_CAPTURE(BM_StagedFit, time, std::string("time"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_StagedFit, spike_smooth, std::string("spike-smooth"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// One exact Jacobian of the time cost's residuals (model run plus the sensitivities of four parameters) beside
// BM_CostEvaluation/time, the model run alone: a central-difference Jacobian costs 8 such runs.
void BM_TimeJacobian(benchmark::State& state) {
  fit::Objective objective(options("time"), data());
  auto beam = model::preset("banks-aluminium");
  beam.EI *= 1.01;
  Eigen::MatrixXd j;
  for (auto _ : state)
    benchmark::DoNotOptimize(objective.evaluate_with_jacobian(beam, {"EI", "rho", "cDI", "gamma"}, j));
}
BENCHMARK(BM_TimeJacobian)->Unit(benchmark::kMillisecond);

// One exact Jacobian of the time cost's residuals with the sensor's anti-alias filter in the model (issue 32), on the
// thick beam as the design's comparison-thick-sensor study fits it (N = 16; 8,192 samples of 0.1 ms, a 0.7 ms pulse
// at 0.21 m, acceleration; a 4 kHz 4th-order Butterworth run 16 times finer): "closed_form" carries the filter
// through the modal closed form on the record's grid (simulation/output_filter.h), "fine" is the path it replaced
// (the model and its six sensitivities simulated 16 times finer, filtered sample by sample and decimated), and
// "unfiltered" the same Jacobian without the filter, the floor.
void BM_SensedJacobianThick(benchmark::State& state, const std::string& path) {
  const model::BeamParameters beam = model::preset("thick-steel");
  simulation::Experiment e;
  e.dt_s = 1e-4;
  e.samples = 8192;
  e.pulse_width_s = 7e-4;
  e.force_x_m = 0.21;
  e.output = simulation::kAcceleration;
  const signal::SensorFilter filter{4000, 4, 16};
  const galerkin::SplineSpace space(16);
  const galerkin::BeamForms forms(space, beam.l, beam.support);
  const std::vector<std::string> keys = {"EI", "kAG", "rho", "cDI", "kAcs", "gamma"};
  const auto sensed = fit::output_filter(filter, e.dt_s);
  for (auto _ : state) {
    if (path == "fine") {
      simulation::SensitivityTrace s =
          simulation::simulate_with_sensitivities(forms, beam, simulation::finer(e, filter.oversampling), keys);
      fit::sense_output(filter, e, s.trace.y);
      Eigen::MatrixXd columns(e.samples, s.dy_dq.cols());
      for (Eigen::Index k = 0; k < s.dy_dq.cols(); ++k) {
        const std::vector<double> column(s.dy_dq.col(k).data(), s.dy_dq.col(k).data() + s.dy_dq.rows());
        const std::vector<double> out = signal::sense(filter, column, e.dt_s, 0.0);
        columns.col(k) = Eigen::Map<const Eigen::VectorXd>(out.data(), e.samples);
      }
      benchmark::DoNotOptimize(columns.data());
    } else {
      const simulation::SensitivityTrace s =
          simulation::simulate_with_sensitivities(forms, beam, e, keys, path == "closed_form" ? sensed : nullptr);
      benchmark::DoNotOptimize(s.dy_dq.data());
    }
  }
}
BENCHMARK_CAPTURE(BM_SensedJacobianThick, closed_form, std::string("closed_form"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SensedJacobianThick, fine, std::string("fine"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SensedJacobianThick, unfiltered, std::string("unfiltered"))->Unit(benchmark::kMillisecond);

}  // namespace

// main: bench_main.cc
