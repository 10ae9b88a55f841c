// Units of work that compute: the Galerkin frequencies of the truth beam against the exact ones (Rayleigh-Ritz: from
// above, closer as N grows), the overlay a case keeps in its record, read back exactly, and a measured force as the
// excitation, its channel's noise and the errors-in-variables fits.
#include "study/run/execute.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "signal/sensor_filter.h"
#include "signal/spectrum.h"
#include "study/plan/plan.h"
#include "study/spec/study_spec.h"
#include "study/tables/overlay.h"

namespace beamid::study {
namespace {

TEST(Execute, GalerkinFrequenciesBoundTheExactOnesFromAbove) {
  StudySpec spec;
  spec.truth.parameters = model::preset("banks-aluminium");
  const Record coarse = run_frequencies(spec, 8), fine = run_frequencies(spec, 16);
  ASSERT_EQ(fine.text("status"), "ok");
  const std::vector<double> exact = fine.numbers("exact_hz"), f8 = coarse.numbers("galerkin_hz"),
                            f16 = fine.numbers("galerkin_hz");
  ASSERT_EQ(exact.size(), 4u);
  ASSERT_EQ(f16.size(), 4u);
  EXPECT_NEAR(exact[0], 2.4636574, 1e-6);  // model.md's verification value for set A, mode 1
  for (std::size_t m = 0; m < 4; ++m) {
    // Rayleigh-Ritz: every Galerkin frequency lies above the exact one (up to the thin beam's round-off, 1e-8), and
    // the space of order 16 contains that of order 8, so f_16 <= f_8.
    EXPECT_GE(f16[m], exact[m] * (1 - 1e-8)) << m;
    EXPECT_LE(f16[m], f8[m] * (1 + 1e-8)) << m;
    // At N = 16 the first four modes are within 0.5 % (the verification table gives 3e-3 for mode 4).
    EXPECT_LT(f16[m] / exact[m] - 1, 5e-3) << m;
  }
}

// The truth is the exact modal closed form; the first truth of a study is also integrated by CVODE, an independent
// method, and the record states their agreement. N_truth = 24 and 512 samples keep CVODE to about a second.
TEST(Execute, TruthIsTheExactClosedFormAndCvodeAgreesWithIt) {
  StudySpec spec;
  spec.truth.parameters = model::preset("banks-aluminium");
  spec.truth.elements = 24;
  spec.truth.rtol = 1e-10;
  spec.truth.experiment.dt_s = 1e-3;
  spec.truth.experiment.samples = 512;
  spec.truth.experiment.pulse_width_s = 4e-3;
  Unit truth;
  truth.kind = UnitKind::Truth;
  truth.pulse_width_s = 4e-3;
  truth.samples = 512;
  truth.cvode_check = true;
  const Record r = run_truth(spec, truth);
  ASSERT_EQ(r.text("status"), "ok");
  EXPECT_EQ(r.text("integrator"), "fast");
  EXPECT_EQ(r.numbers("y").size(), 512u);
  ASSERT_EQ(r.text("cvode_status"), "ok");
  EXPECT_GT(r.number("cvode_steps"), 0);
  // At rtol 1e-10 CVODE's own error is about 1e-8 of max |y| for the displacement (results/verification): 1e-7 holds
  // with a margin, and a truth that were wrong by a time step or a mode would miss it by orders of magnitude.
  EXPECT_LT(r.number("cvode_max_difference_over_max_y"), 1e-7);
  truth.cvode_check = false;  // the other truths: no CVODE
  EXPECT_FALSE(run_truth(spec, truth).has("cvode_status"));
}

TEST(Execute, AModalDampingTruthAddsItsRatioToEveryModeOfTheTruth) {
  // [truth] modal_damping_ratio = 0.003 on the thin beam (N_truth = 24): the truth's modes keep their frequencies
  // (within 1e-5: the added damping shifts |lambda| by nothing and the damped frequency by zeta^2 / 2) and gain
  // about 0.003 in ratio each (within 3 % of it: the beam's own damping couples the modes weakly); its record differs
  // from the undamped-law truth's.
  StudySpec spec;
  spec.truth.parameters = model::preset("banks-aluminium");
  spec.truth.elements = 24;
  spec.truth.experiment.samples = 512;
  Unit truth;
  truth.kind = UnitKind::Truth;
  truth.pulse_width_s = 4e-3;
  truth.samples = 512;
  const Record plain = run_truth(spec, truth);
  spec.truth.modal_damping_ratio = 0.003;
  const Record damped = run_truth(spec, truth);
  ASSERT_EQ(damped.text("status"), "ok");
  const std::vector<double> f0 = plain.numbers("mode_frequency_hz"), f1 = damped.numbers("mode_frequency_hz");
  const std::vector<double> z0 = plain.numbers("mode_damping_ratio"), z1 = damped.numbers("mode_damping_ratio");
  ASSERT_GE(f1.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(f1[k] / f0[k], 1.0, 1e-5) << "mode " << k + 1;
    EXPECT_NEAR((z1[k] - z0[k]) / 0.003, 1.0, 0.03) << "mode " << k + 1;
  }
  EXPECT_NE(damped.numbers("y"), plain.numbers("y"));
}

TEST(Execute, AFiniteBandwidthSensorFiltersTheTruthByItsResponse) {
  // [truth] sensor_bandwidth_hz = 100 (order 4) on the thin beam with its damping raised so that modes 1 and 2 decay
  // within the record (N_truth = 24, 4096 samples at 1 ms): the truth is simulated 16 times finer, filtered and
  // sampled, so that at the two modes' peak bins (2.5 and 26.5 Hz) its DFT is the ideal sensor's times the filter's
  // response there: within 1 % in magnitude and 0.01 rad in phase (measured 1e-4 and 5e-6 rad at mode 1, 0.4 % and
  // 0.005 rad at mode 2, whose peak is 70 times lower; with the preset's damping, mode 1's undecayed end leaks into
  // mode 2's bin and the filter's 4 ms delay moves that leakage); its samples are not the ideal ones.
  StudySpec spec;
  spec.truth.parameters = model::preset("banks-aluminium");
  spec.truth.parameters.gamma *= 100;  // modes 1 and 2 decay within the record: no leakage from its end
  spec.truth.parameters.cDI *= 10;
  spec.truth.elements = 24;
  spec.truth.experiment.samples = 4096;
  spec.truth.experiment.output = "velocity";
  Unit truth;
  truth.kind = UnitKind::Truth;
  truth.pulse_width_s = 4e-3;
  truth.samples = 4096;
  const Record ideal = run_truth(spec, truth);
  spec.truth.sensor = signal::SensorFilter{100, 4, 16};
  const Record sensed = run_truth(spec, truth);
  ASSERT_EQ(sensed.text("status"), "ok");
  const std::vector<double> y0 = ideal.numbers("y"), y1 = sensed.numbers("y");
  ASSERT_EQ(y1.size(), 4096u);
  EXPECT_NE(y0, y1);
  signal::Dft dft(4096, 1e-3);
  const signal::Spectrum s0 = dft.transform(y0), s1 = dft.transform(y1);
  for (const double f : ideal.numbers("mode_frequency_hz")) {
    if (f > 30) break;
    const auto k = static_cast<std::size_t>(std::lround(f / s0.df_hz()));
    const std::complex<double> ratio = s1.half[k] / s0.half[k],
                               h = signal::sensor_response(spec.truth.sensor, 1e-3, k * s0.df_hz());
    EXPECT_NEAR(std::abs(ratio) / std::abs(h), 1.0, 0.01) << f << " Hz";
    EXPECT_NEAR(std::arg(ratio / h), 0.0, 0.01) << f << " Hz";
  }
  // A cut-off far below the modes leaves no vibration: the truth fails, saying why.
  spec.truth.sensor.cutoff_hz = 0.01;
  const std::string status = run_truth(spec, truth).text("status");
  EXPECT_EQ(status.rfind("failed: the sensor filter at 0.01 Hz keeps ", 0), 0u) << status;
}

TEST(Execute, AMeasuredForceDrivesTheTruthAndTheFitsAndItsNoiseReachesThem) {
  // excitation "force": the pulse's samples drive the truth and every fit, so a noise-free control fit (N = N_truth)
  // returns the truth (measured: exactly, the cost is 0 at the start; a force that drove the fit otherwise than the
  // truth would move it; bound 1e-6). On a noisy record the force channel carries its own noise: the output-error and
  // errors-in-variables fits of one record differ (the weights reach the cost), and each is the same when run again
  // (the force's noise is seeded by the record's).
  const StudySpec spec = parse_study(R"([study]
name = "force"
question = "q"
seed = 7
[truth]
beam = "banks-aluminium"
elements = 6
control = true
samples = 1024
excitation = "force"
force_x_m = 0.32
pulse_width_s = 0.004
output = "velocity"
force_noise = 0.2
[fit]
estimate = ["EI", "cDI"]
[starts.truth]
EI = 1.0
cDI = 1.0
[methods.oe]
strategy = "direct"
[methods.eiv]
strategy = "direct"
errors_in_variables = true
[sweep]
elements = [6]
cost = ["freq-ml"]
noise = [0.0, 0.01]
replicates = 1
method = ["oe", "eiv"]
start = ["truth"]
)",
                                     "force.toml", ".");
  const Plan plan = make_plan(spec);
  ASSERT_EQ(plan.truths.size(), 1u);
  std::map<std::pair<std::string, double>, const Unit*> cases;
  for (const Unit& u : plan.units)
    if (u.kind == UnitKind::Case) cases[{u.method, u.noise}] = &u;
  const Record truth = run_truth(spec, plan.truths.front());
  ASSERT_EQ(truth.text("status"), "ok");
  const Record clean = run_case(spec, *cases.at({"eiv", 0.0}), truth);
  ASSERT_EQ(clean.text("status"), "converged") << clean.text("termination");
  EXPECT_LT(std::abs(clean.number("relative_error.EI")), 1e-6);
  EXPECT_LT(std::abs(clean.number("relative_error.cDI")), 1e-6);
  const Record oe = run_case(spec, *cases.at({"oe", 0.01}), truth);
  const Record eiv = run_case(spec, *cases.at({"eiv", 0.01}), truth);
  ASSERT_EQ(oe.text("status"), "converged") << oe.text("termination");
  ASSERT_EQ(eiv.text("status"), "converged") << eiv.text("termination");
  EXPECT_NE(oe.number("estimate.cDI"), eiv.number("estimate.cDI"));
  EXPECT_EQ(run_case(spec, *cases.at({"eiv", 0.01}), truth).number("estimate.cDI"), eiv.number("estimate.cDI"));
}

TEST(Execute, OverlayKeptInARecordReadsBackExactly) {
  Overlay o;
  o.t_s = {0, 1e-3, 2e-3};
  o.data = {0.1, -0.2, 1.0 / 3.0};
  o.model = {0.1, -0.25, std::numeric_limits<double>::quiet_NaN()};
  o.frequency_hz = {0, 333.3};
  o.data_magnitude = {1, 2};
  o.model_magnitude = {1.5, 2.5};
  o.spike_bins = {1};
  o.support_left = {0};
  o.support_right = {1};
  Record r;
  store_overlay(r, o);
  const auto back = stored_overlay(Record::parse(r.serialise(), "case"));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->data, o.data);
  EXPECT_TRUE(std::isnan(back->model[2]));
  EXPECT_EQ(back->spike_bins, o.spike_bins);
  EXPECT_EQ(back->support_right, o.support_right);
  EXPECT_FALSE(stored_overlay(Record{}));  // a case without an overlay
  // The rendered files: one row per sample and per bin, and the spike's 20 % support in Hz.
  const RenderedFiles files = render_overlay_files({{"time", *back}});
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].path, "overlay.csv");
  EXPECT_EQ(std::count(files[0].text.begin(), files[0].text.end(), '\n'), 4);
  EXPECT_EQ(files[2].text,
            "spike,bin,frequency_hz,magnitude,support_low_hz,support_high_hz\n"
            "1,1,333.30000000000001,2,166.65000000000001,833.25\n");
}

}  // namespace
}  // namespace beamid::study
