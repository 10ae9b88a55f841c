// Forward-model benchmarks (make bench): assembly of M, C, K from the parameter-free forms, and one `fast` and one
// `cvode` simulation of banks-aluminium (dt = 1 ms, Nbar = 4096, sin^2 pulse of 4 ms at 0.7 l, tip displacement)
// for N in {4, 8, 16, 32}. CVODE runs at rtol 1e-8, where it agrees with `fast` to about 1e-6 of max |y|
// (results/verification/fast_vs_cvode.md), and at 1e-10 (about 1e-8).
#include <benchmark/benchmark.h>

#include <cmath>

#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "simulation/simulator.h"

namespace {

using namespace beamid;

simulation::Experiment banks_experiment(double length_m) {
  simulation::Experiment e;
  e.dt_s = 1e-3;
  e.samples = 4096;
  e.pulse_width_s = 4e-3;
  e.force_x_m = 0.7 * length_m;
  return e;
}

void BM_SplineSpace(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(galerkin::SplineSpace(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_SplineSpace)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMicrosecond);

// Re-assembly during a fit: combine the parameter-free forms with new parameter values.
void BM_Combine(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(static_cast<int>(state.range(0)));
  const galerkin::BeamForms forms(space, beam.l);
  for (auto _ : state) benchmark::DoNotOptimize(galerkin::combine(forms, beam));
}
BENCHMARK(BM_Combine)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMicrosecond);

void BM_StateSpaceModes(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const auto system = galerkin::assemble(galerkin::SplineSpace(static_cast<int>(state.range(0))), beam);
  for (auto _ : state) benchmark::DoNotOptimize(galerkin::StateSpaceModes(system));
}
BENCHMARK(BM_StateSpaceModes)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

// The same with the dense decomposition of the state matrix forced (what StateSpaceModes did before the Jacobi
// iteration in the undamped basis, and still does for strongly coupling damping such as thick-steel's): the ratio
// to BM_StateSpaceModes is the iteration's gain, measured side by side.
void BM_StateSpaceModesDense(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const auto system = galerkin::assemble(galerkin::SplineSpace(static_cast<int>(state.range(0))), beam);
  for (auto _ : state) benchmark::DoNotOptimize(galerkin::StateSpaceModes(system, galerkin::DampedModesMethod::dense));
}
BENCHMARK(BM_StateSpaceModesDense)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);

void simulate(benchmark::State& state, const std::string& integrator, double rtol) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(static_cast<int>(state.range(0)));
  const galerkin::BeamForms forms(space, beam.l);
  const auto e = banks_experiment(beam.l);
  simulation::SimulatorOptions options;
  options.integrator = integrator;
  options.cvode.rtol = rtol;
  long steps = 0;
  for (auto _ : state) {
    // Includes assembly and the problem set-up, as one cost evaluation of a fit would.
    const auto trace = simulation::simulate(forms, beam, e, options);
    if (!trace.ok()) state.SkipWithError(trace.status.c_str());
    steps = trace.stats.steps;
    benchmark::DoNotOptimize(trace.y.data());
  }
  state.counters["cvode_steps"] = static_cast<double>(steps);
}
void BM_SimulateFast(benchmark::State& state) { simulate(state, "fast", 1e-10); }  // rtol unused by fast
void BM_SimulateCvode1e8(benchmark::State& state) { simulate(state, "cvode", 1e-8); }
void BM_SimulateCvode1e10(benchmark::State& state) { simulate(state, "cvode", 1e-10); }
BENCHMARK(BM_SimulateFast)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

// The simulation of one evaluation of freq-ml's errors-in-variables form: the response to a sampled force (the 4 ms
// pulse, 1 ms samples) and the transfer function at every bin 0..Nbar/2, N in {4, 8, 16}.
void BM_SimulateForceTransferFunction(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(static_cast<int>(state.range(0)));
  const galerkin::BeamForms forms(space, beam.l);
  auto e = banks_experiment(beam.l);
  e.excitation = simulation::kSampledForce;
  e.force_samples_N.assign(static_cast<std::size_t>(e.samples), 0.0);
  for (int i = 1; i < 4; ++i) e.force_samples_N[static_cast<std::size_t>(i)] = std::pow(std::sin(M_PI * i / 4.0), 2);
  for (auto _ : state) {
    const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
    simulation::ResponseProblem p = simulation::make_problem(forms, system, e, beam.l);
    p.frf = true;
    const auto trace = simulation::make_simulator({})->run(system, p);
    if (!trace.ok()) state.SkipWithError(trace.status.c_str());
    benchmark::DoNotOptimize(trace.frf.data());
  }
}
BENCHMARK(BM_SimulateForceTransferFunction)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

// Scaling in the record length: N = 16, Nbar = 1024 .. 65536 at the same dt (tests/benchmarks/scaling.py fits the
// exponent).
void BM_SimulateFastSamples(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(16);
  const galerkin::BeamForms forms(space, beam.l);
  auto e = banks_experiment(beam.l);
  e.samples = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const auto trace = simulation::simulate(forms, beam, e, {});
    if (!trace.ok()) state.SkipWithError(trace.status.c_str());
    benchmark::DoNotOptimize(trace.y.data());
  }
}
BENCHMARK(BM_SimulateFastSamples)->RangeMultiplier(4)->Range(1024, 65536)->Unit(benchmark::kMillisecond);

// The computation of tests/benchmarks/peers.py (NumPy modal closed form, SciPy BDF): N = 16, dt = 10 us, Nbar = 4096
// (41 ms of record, so that SciPy's BDF at rtol 1e-8 finishes in about a minute), the same pulse and sensor.
void BM_SimulateFastPeer(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(16);
  const galerkin::BeamForms forms(space, beam.l);
  auto e = banks_experiment(beam.l);
  e.dt_s = 1e-5;
  for (auto _ : state) {
    const auto trace = simulation::simulate(forms, beam, e, {});
    if (!trace.ok()) state.SkipWithError(trace.status.c_str());
    benchmark::DoNotOptimize(trace.y.data());
  }
}
BENCHMARK(BM_SimulateFastPeer)->Unit(benchmark::kMillisecond);

// The thick beam's forward run beside the thin one's (BM_SimulateFast) at the same N and Nbar = 4096: thick-steel
// (studies/thick.toml's experiment: dt = 0.1 ms, a 0.4 ms pulse at 0.21 m, tip acceleration), whose Kelvin-Voigt and
// shear damping couple its modes too strongly for the Jacobi iteration, so that its damped modes come from the dense
// decomposition of the state matrix (galerkin/modes.h). Issue 32 asks for it within 2x of the thin beam's.
void BM_SimulateFastThick(benchmark::State& state) {
  const model::BeamParameters beam = model::preset("thick-steel");
  const galerkin::SplineSpace space(static_cast<int>(state.range(0)));
  const galerkin::BeamForms forms(space, beam.l);
  simulation::Experiment e;
  e.dt_s = 1e-4;
  e.samples = 4096;
  e.pulse_width_s = 4e-4;
  e.force_x_m = 0.21;
  e.output = simulation::kAcceleration;
  for (auto _ : state) {
    const auto trace = simulation::simulate(forms, beam, e, {});
    if (!trace.ok()) state.SkipWithError(trace.status.c_str());
    benchmark::DoNotOptimize(trace.y.data());
  }
}
BENCHMARK(BM_SimulateFastThick)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateCvode1e8)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_SimulateCvode1e10)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

// main: bench_main.cc
