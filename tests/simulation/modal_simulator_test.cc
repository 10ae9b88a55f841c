// The exact modal propagator ("fast"): closed forms against quadrature and analytic solutions, exactness in dt,
// and agreement with converged CVODE on both presets, all outputs, pulse and pluck, stiff and overdamped cases.
#include "simulation/modal_simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "model/beam_parameters.h"
#include "signal/noise.h"
#include "signal/spectrum.h"
#include "simulation/simulator.h"
#include "test_systems.h"

namespace beamid::simulation {
namespace {

using complex = std::complex<double>;

// int_0^t e^{lambda (t-s)} sin^2(pi s/tau) ds by composite 8-point Gauss-Legendre on 4000 panels: independent of the
// closed form and accurate to ~1e-15 relative for the smooth integrands used here.
complex quadrature(complex lambda, double t, double tau) {
  static const double x[] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static const double w[] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const int panels = 4000;
  const double h = t / panels;
  complex sum = 0;
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * h;
    for (int q = 0; q < 4; ++q)
      for (double sign : {-1.0, 1.0}) {
        const double s = mid + sign * x[q] * h / 2;
        const double sn = std::sin(std::numbers::pi * s / tau);
        sum += w[q] * h / 2 * std::exp(lambda * (t - s)) * sn * sn;
      }
  }
  return sum;
}

TEST(PulseResponse, MatchesQuadrature) {
  const double tau = 0.01;
  const double w = 2 * std::numbers::pi / tau;
  // Lightly damped, exactly resonant with the pulse's cos(w t) (undamped: the divided difference's limit),
  // nearly zero, real overdamped and very stiff eigenvalues.
  for (complex lambda : {complex(-3.0, 160.0), complex(0.0, w), complex(-1e-9, w + 1e-7), complex(-1e-12, 0.0),
                         complex(-250.0, 0.0), complex(-1e6, 0.0), complex(-4e5, 3e5)}) {
    for (double t : {1e-4, 3.3e-3, 0.01}) {
      const complex exact = quadrature(lambda, t, tau);
      const complex closed = pulse_response(lambda, t, tau);
      // Natural size: int_0^t |e^{lambda (t-s)}| ds >= |result|. Near t = tau a stiff mode's response is a tiny
      // residual of terms of this size, so round-off is relative to it (1e-14), not to the result. Otherwise 1e-11
      // relative: the quadrature's own error (the stiffest boundary layer is ~1e-6 s wide, panels 2.5e-6 s with
      // 8 points) is ~1e-13.
      const double size = lambda.real() < 0 ? -std::expm1(lambda.real() * t) / -lambda.real() : t;
      EXPECT_LT(std::abs(closed - exact), 1e-11 * std::abs(exact) + 1e-14 * size)
          << "lambda = " << lambda << ", t = " << t;
    }
  }
}

TEST(ModalSimulator, FreeDecayOfAnOscillatorIsExact) {
  // m x'' + c x' + k x = 0 from x0: analytic solution; all three outputs; 1e-12 relative is round-off in
  // the eigen-decomposition and the 2000-step recursion (each step ~1e-16).
  const double m = 2.0, c = 0.7, k = 5000.0, x0 = 0.01;
  const auto s = testing::oscillator(m, c, k);
  for (int derivative : {0, 1, 2}) {
    const auto p = testing::release(x0, derivative, 1e-3, 2000);
    const Trace trace = ModalSimulator().run(s, p);
    ASSERT_TRUE(trace.ok()) << trace.status;
    double scale = 0, error = 0;
    for (int i = 0; i < p.samples; ++i) {
      const double exact = testing::free_decay(m, c, k, x0, derivative, i * p.dt_s);
      scale = std::max(scale, std::abs(exact));
      error = std::max(error, std::abs(trace.y[i] - exact));
    }
    EXPECT_LT(error, 1e-12 * scale) << "derivative " << derivative;
  }
}

using testing::relative_difference;

Experiment preset_experiment(const std::string& preset, double length_m, const std::string& output) {
  Experiment e;
  e.output = output;
  e.force_x_m = 0.7 * length_m;
  if (preset == "banks-aluminium") {
    e.dt_s = 1e-3, e.samples = 4096, e.pulse_width_s = 4e-3;  // model.md's sampling for set A
  } else {
    e.dt_s = 1e-4, e.samples = 8192, e.pulse_width_s = 4e-4;  // and for set B
  }
  return e;
}

// Fast against CVODE at rtol 1e-10 on both presets and all outputs at order N, each preset's experiment changed by
// `adjust`: max |difference| < 1e-7 max |y|.
void expect_fast_matches_cvode(int elements, const std::function<void(Experiment&)>& adjust) {
  for (const auto& name : model::preset_names()) {
    const model::BeamParameters beam = model::preset(name);
    const galerkin::SplineSpace space(elements);
    const galerkin::BeamForms forms(space, beam.l);
    for (const std::string output : {"displacement", "velocity", "acceleration"}) {
      Experiment e = preset_experiment(name, beam.l, output);
      adjust(e);
      SimulatorOptions cvode;
      cvode.integrator = "cvode";
      cvode.cvode.rtol = 1e-10;
      const Trace reference = simulate(forms, beam, e, cvode);
      const Trace fast = simulate(forms, beam, e, SimulatorOptions{});
      ASSERT_TRUE(reference.ok() && fast.ok()) << reference.status << fast.status;
      EXPECT_LT(relative_difference(fast.y, reference.y), 1e-7) << name << " " << output;
    }
  }
}

TEST(ModalSimulator, AgreesWithCvodeOnPresets) {
  // Issue requirement: fast against CVODE at rtol 1e-10, both presets, all outputs: max |difference| < 1e-7 max |y|.
  expect_fast_matches_cvode(16, [](Experiment&) {});
}

// A hammer-like force sampled at the record's rate: a half sine of width tau (6 samples on the thin beam), and a
// noisy tail that keeps the force rough after the hit (a measured force channel's noise), as the force channel of
// a record gives it.
std::vector<double> hammer_force(const Experiment& e) {
  std::vector<double> f(static_cast<std::size_t>(e.samples), 0.0);
  const double tau = 1.5 * e.pulse_width_s;
  for (int i = 0; i < e.samples; ++i) {
    const double t = i * e.dt_s;
    if (t < tau) f[static_cast<std::size_t>(i)] = 10 * std::sin(std::numbers::pi * t / tau);
    f[static_cast<std::size_t>(i)] += 0.01 * std::sin(0.37 * i * i);  // deterministic, rough
  }
  return f;
}

TEST(ModalSimulator, ASampledForceAgreesWithCvodeOnPresets) {
  // The measured-force excitation (linear between samples) against CVODE at rtol 1e-10 stopping at every sample
  // (the force's kinks): both presets, all outputs, max |difference| < 1e-7 max |y|, as for the pulse.
  expect_fast_matches_cvode(8, [](Experiment& e) {
    e.samples = 1024;
    e.force_samples_N = hammer_force(e);
    e.excitation = kSampledForce;
  });
}

TEST(ModalSimulator, ASampledPulseApproachesThePulseAndTheResponseIsLinearInTheForce) {
  // The sin^2 pulse sampled 40 times over its width and held linear between samples: the response differs from the
  // exact pulse's by the interpolation error of the force, (dt^2/8) max |P''| = (pi/40)^2 / 2 = 0.3 % of its peak at
  // most, less after the beam's smoothing (bound 0.3 % of max |y|). And the response to 2 F1 - F2 is 2 y1 - y2 to
  // round-off (1e-12).
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  Experiment pulse = preset_experiment("banks-aluminium", beam.l, "velocity");
  pulse.dt_s = pulse.pulse_width_s / 40;
  pulse.samples = 4000;
  const Trace exact = simulate(forms, beam, pulse, SimulatorOptions{});
  Experiment sampled = pulse;
  sampled.excitation = kSampledForce;
  for (int i = 0; i < pulse.samples; ++i) {
    const double t = i * pulse.dt_s, s = std::sin(std::numbers::pi * t / pulse.pulse_width_s);
    sampled.force_samples_N.push_back(t <= pulse.pulse_width_s ? pulse.force_amplitude_N * s * s : 0.0);
  }
  const Trace held = simulate(forms, beam, sampled, SimulatorOptions{});
  ASSERT_TRUE(exact.ok() && held.ok());
  EXPECT_LT(relative_difference(held.y, exact.y), 3e-3);
  EXPECT_GT(relative_difference(held.y, exact.y), 0.0);  // not the pulse's closed form itself
  Experiment first = sampled, second = sampled, mixed = sampled;
  second.force_samples_N = hammer_force(second);
  for (std::size_t i = 0; i < mixed.force_samples_N.size(); ++i)
    mixed.force_samples_N[i] = 2 * first.force_samples_N[i] - second.force_samples_N[i];
  const Trace y1 = simulate(forms, beam, first, {}), y2 = simulate(forms, beam, second, {});
  const Trace ym = simulate(forms, beam, mixed, {});
  std::vector<double> combined(y1.y.size());
  for (std::size_t i = 0; i < combined.size(); ++i) combined[i] = 2 * y1.y[i] - y2.y[i];
  EXPECT_LT(relative_difference(ym.y, combined), 1e-12);
  // A force of the wrong length, or a sampled force under another excitation, is refused.
  first.force_samples_N.pop_back();
  EXPECT_THROW(simulate(forms, beam, first, {}), InputError);
  pulse.force_samples_N = second.force_samples_N;
  EXPECT_THROW(simulate(forms, beam, pulse, {}), InputError);
}

TEST(ModalSimulator, ASampledForcesTransferFunctionMapsTheForcesDftToTheResponses) {
  // With air damping gamma = 2 the slowest mode (2.47 Hz, zeta 0.11) decays by e^-28 within a 16.4 s record, so the
  // response to a force that starts and ends inside it is the steady state of the sampled system: Y(k) = G(z_k) U(k)
  // at every DFT bin, to round-off (1e-9 of max |Y|), for all three outputs (acceleration with its feedthrough).
  model::BeamParameters beam = model::preset("banks-aluminium");
  beam.gamma = 2;
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
  for (const std::string output : {"displacement", "velocity", "acceleration"}) {
    Experiment e = preset_experiment("banks-aluminium", beam.l, output);
    e.samples = 16384;
    e.excitation = kSampledForce;
    e.force_samples_N = hammer_force(e);
    for (std::size_t i = 100; i < e.force_samples_N.size(); ++i) e.force_samples_N[i] = 0;  // over within the record
    ResponseProblem p = make_problem(forms, system, e);
    p.frf = true;
    const Trace t = ModalSimulator().run(system, p);
    ASSERT_TRUE(t.ok()) << t.status;
    ASSERT_EQ(t.frf.size(), static_cast<std::size_t>(e.samples / 2 + 1));
    signal::Dft dft(e.samples, e.dt_s);
    const signal::Spectrum y = dft.transform(t.y), u = dft.transform(e.force_samples_N);
    double largest = 0, worst = 0;
    for (std::size_t k = 0; k < t.frf.size(); ++k) {
      largest = std::max(largest, std::abs(y.half[k]));
      worst = std::max(worst, std::abs(y.half[k] - t.frf[k] * u.half[k]));
    }
    EXPECT_LT(worst, 1e-9 * largest) << output;
  }
}

TEST(ModalSimulator, TheResponsesDftIsTheTransferFunctionTimesTheForcesPlusATransientPerMode) {
  // White noise as the force on every sample of 512 (thin beam, N = 4 and 6, every output): the response neither
  // starts nor ends at rest within the record, so its DFT is no product; it is exactly G(z_k) F(k) plus one transient
  // term t_m / (1 - e_m z_k^-1) per mode (e_m = e^{lambda_m dt}; conjugate modes with conjugate t, stiff modes with
  // e_m ~ 0 a constant) (modal_simulator.h). Fitting the t_m by least squares over every bin leaves 1e-9 of the
  // largest |Y(k)| (round-off); without them the remainder is of the response's own size.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  for (const int elements : {4, 6}) {
    for (const std::string output : {"displacement", "velocity", "acceleration"}) {
      const galerkin::SplineSpace space(elements);
      const galerkin::BeamForms forms(space, beam.l);
      const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
      Experiment e = preset_experiment("banks-aluminium", beam.l, output);
      e.samples = 512;
      e.excitation = kSampledForce;
      e.force_samples_N = signal::gaussian_deviates(1, 512);
      ResponseProblem p = make_problem(forms, system, e);
      p.frf = true;
      const Trace t = ModalSimulator().run(system, p);
      ASSERT_TRUE(t.ok()) << t.status;
      signal::Dft dft(e.samples, e.dt_s);
      const signal::Spectrum y = dft.transform(t.y), f = dft.transform(e.force_samples_N);
      const auto bins = static_cast<Eigen::Index>(y.half.size());
      const auto modes = static_cast<Eigen::Index>(t.poles_rad_s.size());
      Eigen::MatrixXcd basis(bins, 2 * modes + 1);
      Eigen::VectorXcd remainder(bins);
      double largest = 0;
      for (Eigen::Index k = 0; k < bins; ++k) {
        const std::complex<double> z_inverse = std::polar(1.0, -2 * std::numbers::pi * k / e.samples);
        basis(k, 0) = 1;
        for (Eigen::Index m = 0; m < modes; ++m) {
          const std::complex<double> em = std::exp(t.poles_rad_s[static_cast<std::size_t>(m)] * e.dt_s);
          basis(k, 1 + 2 * m) = 1.0 / (1.0 - em * z_inverse);
          basis(k, 2 + 2 * m) = 1.0 / (1.0 - std::conj(em) * z_inverse);
        }
        const auto i = static_cast<std::size_t>(k);
        remainder(k) = y.half[i] - t.frf[i] * f.half[i];
        largest = std::max(largest, std::abs(y.half[i]));
      }
      const Eigen::VectorXcd left = remainder - basis * basis.colPivHouseholderQr().solve(remainder);
      EXPECT_LT(left.cwiseAbs().maxCoeff(), 1e-9 * largest) << "N = " << elements << ", " << output;
      EXPECT_GT(remainder.cwiseAbs().maxCoeff(), 1e-2 * largest) << "N = " << elements << ", " << output;
    }
  }
}

TEST(ModalSimulator, IteratedAndDenseModesGiveTheSameResponse) {
  // The thin beam's damped modes come from the Jacobi iteration in the undamped basis (galerkin/damped_iteration.cc);
  // the same experiment through the dense decomposition's modes, all three outputs, at the study's sampling (dt = 1 ms,
  // 4 s) and the benchmark's (dt = 10 us, where the 4 ms pulse covers 400 samples and the shear relaxation block lives
  // for a few samples). Measured: 3.4e-9 of max |y| at dt = 1 ms, the phase over 4 s of mode 1's frequency, which the
  // two methods get from x^T K x with different round-off (4e-11 apart, the cancellation of a bending mode against the
  // shear stiffness); below 1e-10 at dt = 10 us. Bound 1e-8, against the 1e-7 that both keep to CVODE.
  // The same off the truth, as a fit sees the beam: cDI 0.9x and kAcs 1.1x, where the two relaxation times differ by
  // 10 % and the slow shear roots spread into the wide blocks of galerkin/damped_iteration.cc.
  const std::vector<std::pair<double, double>> factors = {{1.0, 1.0}, {0.9, 1.0}, {1.0, 1.1}};  // cDI, kAcs
  for (const auto& [cdi_factor, kacs_factor] : factors) {
    model::BeamParameters beam = model::preset("banks-aluminium");
    beam.cDI *= cdi_factor;
    beam.kAcs *= kacs_factor;
    const galerkin::BeamForms forms(galerkin::SplineSpace(16), beam.l);
    const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
    const galerkin::StateSpaceModes iterated(system), dense(system, galerkin::DampedModesMethod::dense);
    ASSERT_TRUE(iterated.iterated()) << "cDI x " << cdi_factor << ", kAcs x " << kacs_factor;
    for (const std::string output : {"displacement", "velocity", "acceleration"})
      for (const double dt_s : {1e-3, 1e-5}) {
        Experiment e = preset_experiment("banks-aluminium", beam.l, output);
        e.dt_s = dt_s;
        const ResponseProblem problem = make_problem(forms, system, e, beam.l);
        const Trace a = ModalSimulator().run(iterated, system, problem);
        const Trace b = ModalSimulator().run(dense, system, problem);
        ASSERT_TRUE(a.ok() && b.ok()) << a.status << b.status;
        EXPECT_LT(relative_difference(a.y, b.y), 1e-8)
            << output << " dt = " << dt_s << ", cDI x " << cdi_factor << ", kAcs x " << kacs_factor;
      }
  }
}

// max |y(dt/2 run)[2i] - y(dt run)[i]| / max |y|: the experiment sampled at dt and at dt/2 by the fast propagator,
// compared on the common sample times.
double halved_step_difference(const galerkin::BeamForms& forms, const model::BeamParameters& beam,
                              const Experiment& coarse) {
  Experiment fine = coarse;
  fine.dt_s /= 2, fine.samples *= 2;
  const Trace a = simulate(forms, beam, coarse, SimulatorOptions{});
  const Trace b = simulate(forms, beam, fine, SimulatorOptions{});
  std::vector<double> every_second;
  for (int i = 0; i < fine.samples; i += 2) every_second.push_back(b.y[static_cast<std::size_t>(i)]);
  return relative_difference(every_second, a.y);
}

TEST(ModalSimulator, HasNoTimeSteppingError) {
  // The same experiment sampled at dt and dt/2: every second fine sample equals the coarse one to round-off
  // (1e-11 of max |y|). A time-stepping method would differ at O(dt^p) times its error constant.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  Experiment coarse = preset_experiment("banks-aluminium", beam.l, "velocity");
  coarse.samples = 1024;
  coarse.pulse_width_s = 3.3e-3;  // ends between samples
  EXPECT_LT(halved_step_difference(forms, beam, coarse), 1e-11);
}

TEST(ModalSimulator, StepsInsideALongPulseAreExact) {
  // Inside the pulse the response advances by an exact one-step recurrence, re-anchored on the closed form every
  // 256 samples. A 4 ms pulse sampled at 10 us and at 5 us (400 and 800 samples inside it, anchored at different
  // samples): every second fine sample equals the coarse one to round-off, 1e-11 of max |y|; a recurrence with a
  // wrong increment would drift by its error per step times hundreds of steps.
  const model::BeamParameters beam = model::preset("thick-steel");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  for (const char* output : {"displacement", "acceleration"}) {
    Experiment coarse = preset_experiment("thick-steel", beam.l, output);
    coarse.dt_s = 1e-5;
    coarse.samples = 600;
    coarse.pulse_width_s = 4e-3;
    EXPECT_LT(halved_step_difference(forms, beam, coarse), 1e-11) << output;
  }
}

TEST(ModalSimulator, APulseFarLongerThanTheRecordIsRefusedNotRoundedOff) {
  // Within a record far shorter than the pulse the force is A sin^2(pi t / tau) ~ A (pi t / tau)^2, so the response
  // scales as 1 / tau^2 while the closed form's terms (~1 / |lambda|) do not: a 1e6 s pulse on an 8 ms record came
  // out 100x too large with the wrong sign, 1e3 s 14 % off CVODE (the thirteenth adversarial pass's problem 6). Those
  // are refused, naming the cause; a 10 s or 20 s pulse on a 64 ms record is computed, and follows the 1 / tau^2 law to
  // the law's own accuracy: y tau^2 differs between the two by the next term of sin^2, (pi T / tau)^2 / 3 < 1.4e-4.
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  Experiment e = preset_experiment("banks-aluminium", beam.l, "displacement");
  e.samples = 8;
  for (const double tau : {1e3, 1e6}) {
    e.pulse_width_s = tau;
    const Trace trace = simulate(forms, beam, e, {});
    EXPECT_FALSE(trace.ok()) << tau;
    EXPECT_NE(trace.status.find("so its force barely starts within it"), std::string::npos) << trace.status;
  }
  e.samples = 64;
  std::vector<double> scaled[2];
  for (int k = 0; k < 2; ++k) {
    e.pulse_width_s = 10.0 * (k + 1);
    const Trace trace = simulate(forms, beam, e, {});
    ASSERT_TRUE(trace.ok()) << trace.status;
    for (const double y : trace.y) scaled[k].push_back(y * e.pulse_width_s * e.pulse_width_s);
  }
  EXPECT_LT(relative_difference(scaled[0], scaled[1]), 1.4e-4);
}

// Undamped free vibration from a pluck: y(t) = sum_k (c^T phi_k)(phi_k^T M w0) cos(omega_k t) from the symmetric
// undamped eigenproblem, a route independent of the state-space decomposition (and exact, where BDF would need
// millions of steps for modes that never decay).
TEST(ModalSimulator, UndampedPluckMatchesCosineSeries) {
  for (const auto& name : model::preset_names()) {
    model::BeamParameters beam = model::preset(name);
    beam.cDI = beam.kAcs = beam.gamma = 0;
    for (int n : {4, 16}) {
      const galerkin::SplineSpace space(n);
      const galerkin::BeamForms forms(space, beam.l);
      const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
      Experiment e = preset_experiment(name, beam.l, "displacement");
      e.excitation = "pluck";
      e.samples = 2048;
      const ResponseProblem p = make_problem(forms, system, e);
      const galerkin::UndampedModes modes = galerkin::undamped_modes(system);
      std::vector<double> reference(static_cast<std::size_t>(e.samples), 0.0);
      for (Eigen::Index k = 0; k < modes.omega_rad_s.size(); ++k) {
        const double a = p.sensor.dot(modes.shapes.col(k)) * modes.shapes.col(k).dot(system.M * p.w0);
        for (int i = 0; i < e.samples; ++i) reference[i] += a * std::cos(modes.omega_rad_s(k) * i * e.dt_s);
      }
      const Trace fast = ModalSimulator().run(system, p);
      ASSERT_TRUE(fast.ok()) << fast.status;
      // Both routes sit on the round-off floor of the assembled thin-beam matrices (measured 6e-9 for
      // banks-aluminium, 1e-10 for thick-steel): 1e-7 leaves margin and still catches any modelling error.
      EXPECT_LT(relative_difference(fast.y, reference), 1e-7) << name << " N=" << n;
    }
  }
}

TEST(ModalSimulator, OverdampedAndPluckedBeamsMatchCvode) {
  // 1000x Kelvin-Voigt damping makes most modes overdamped; a pluck starts from a static deflection that excites
  // every mode, stiff ones included. The bound is 1e-7 as for the pulse, except:
  // - the heavily damped beam gets 1e-6: all its shear modes relax at nearly the same rate kAG/kAcs (75.7 1/s),
  //   a near-multiple eigenvalue whose eigenvector basis is ill-conditioned (measured 3.4e-7 over the first 0.3 s);
  // - a thin-beam pluck's acceleration gets 1e-6 because CVODE is the inexact one there: its lightly damped kHz
  //   modes dominate the early acceleration and BDF's error at rtol 1e-10 is still 2-5e-7 (2.4e-6 at 1e-8).
  // Wherever the gap exceeds 1e-8 it must also shrink 5x from CVODE rtol 1e-8 to 1e-10, showing it is CVODE's.
  model::BeamParameters heavy = model::preset("banks-aluminium");
  heavy.cDI *= 1000, heavy.kAcs *= 1000, heavy.gamma *= 100;
  const galerkin::SplineSpace space(8);
  struct Case {
    std::string label, preset;
    model::BeamParameters beam;
    std::string excitation;
    double tolerance;
  };
  for (const Case& c : {Case{"heavy pulse", "banks-aluminium", heavy, "pulse", 1e-6},
                        Case{"heavy pluck", "banks-aluminium", heavy, "pluck", 1e-6},
                        Case{"pluck", "banks-aluminium", model::preset("banks-aluminium"), "pluck", 1e-7},
                        Case{"thick pluck", "thick-steel", model::preset("thick-steel"), "pluck", 1e-7}}) {
    const galerkin::BeamForms forms(space, c.beam.l);
    for (const std::string output : {"displacement", "velocity", "acceleration"}) {
      Experiment e = preset_experiment(c.preset, c.beam.l, output);
      e.samples = 1024;
      e.excitation = c.excitation;
      SimulatorOptions tight, loose;
      tight.integrator = loose.integrator = "cvode";
      loose.cvode.rtol = 1e-8;
      const Trace reference = simulate(forms, c.beam, e, tight);
      const Trace fast = simulate(forms, c.beam, e, SimulatorOptions{});
      ASSERT_TRUE(reference.ok() && fast.ok()) << reference.status << fast.status;
      const double gap = relative_difference(fast.y, reference.y);
      const bool thin_pluck_acceleration = c.label == "pluck" && output == "acceleration";
      EXPECT_LT(gap, thin_pluck_acceleration ? 1e-6 : c.tolerance) << c.label << " " << output;
      if (gap > 1e-8 && c.tolerance < 1e-6) {
        const double loose_gap = relative_difference(fast.y, simulate(forms, c.beam, e, loose).y);
        EXPECT_LT(gap, loose_gap / 5) << c.label << " " << output << ": the gap does not shrink with CVODE's rtol";
      }
    }
  }
}

// Issue 30: with cDI = 1e3 N m^2 s and kAcs = 1e9 N s (damping rates from 5e-4 to 5e16 1/s) the propagator grew to
// 3.8e88 where CVODE decays (and was 47 % off at 20 s here), because the dense decomposition's spurious
// right-half-plane poles entered the sum. With the checked, graded eigen-analysis (galerkin/modes.h) it follows CVODE
// over 50 s (the slowest relaxation time is 2,000 s) to 1e-6 of max |y|: measured 1e-9, CVODE's own error at rtol
// 1e-10.
TEST(ModalSimulator, AHeavilyDampedThinBeamDecaysAsCvodeSays) {
  model::BeamParameters beam = model::preset("banks-aluminium");
  beam.cDI = 1e3;
  beam.kAcs = 1e9;
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  Experiment e = preset_experiment("banks-aluminium", beam.l, "displacement");
  e.dt_s = 0.01;
  e.samples = 5000;
  SimulatorOptions cvode;
  cvode.integrator = "cvode";
  const Trace reference = simulate(forms, beam, e, cvode);
  const Trace fast = simulate(forms, beam, e, SimulatorOptions{});
  ASSERT_TRUE(reference.ok() && fast.ok()) << reference.status << fast.status;
  EXPECT_LT(relative_difference(fast.y, reference.y), 1e-6);
}

TEST(ModalSimulator, ReportsModesUsed) {
  const model::BeamParameters beam = model::preset("thick-steel");
  const galerkin::SplineSpace space(8);
  const galerkin::BeamForms forms(space, beam.l);
  const Trace t = simulate(forms, beam, preset_experiment("thick-steel", beam.l, "displacement"), SimulatorOptions{});
  ASSERT_TRUE(t.ok());
  EXPECT_GT(t.stats.modes, 0);
  EXPECT_LE(t.stats.modes, 2 * forms.dimension());  // at most one per eigenvalue of the 2 x 2(N+2) state
  EXPECT_GT(t.stats.eigenvector_rcond, 0);
}

}  // namespace
}  // namespace beamid::simulation
