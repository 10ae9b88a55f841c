// Uncertainty that admits model error (issue 11 item 7): the sandwich standard error beside the formal one, and the
// spread over disjoint windows. With white noise and the right model, all three agree with the formal error; with
// model error the formal error understates the scatter and the other two must say so.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "fit/identification.h"
#include "fit/window_spread.h"
#include "galerkin/second_order_system.h"
#include "same_model_record.h"
#include "signal/noise.h"
#include "simulation/simulator.h"

namespace beamid::fit {
namespace {

constexpr int kElements = 8;
constexpr std::uint64_t kBoundSeed = 4;

// thick-steel's pulse test at the tip (model.md section 5's sampling), EI, rho and cDI estimated by least squares
// from the truth's values (the basin is not what is tested here).
struct PulseFit {
  FitOptions options;
  std::vector<double> clean;
};
PulseFit pulse_fit(const model::BeamParameters& truth, const model::BeamParameters& model) {
  PulseFit s;
  s.options.elements = kElements;
  s.options.experiment.dt_s = 1e-4;
  s.options.experiment.samples = 8192;
  s.options.experiment.pulse_width_s = 4e-4;
  s.options.experiment.force_x_m = 0.7 * truth.l;
  s.options.cost.name = "time";
  s.options.optimizer.method = default_optimizer("time");
  s.options.start = model;
  for (const char* key : {"EI", "rho", "cDI"}) {
    const double v = model::parameter_value(truth, key);
    s.options.estimate.push_back({key, v / 2, v * 2});
  }
  s.clean = same_model_record(truth, s.options.experiment, kElements);
  return s;
}

TEST(Uncertainty, WithWhiteNoiseAndTheRightModelTheSandwichIsTheFormalError) {
  // 1 % white noise: the residuals at the estimate are that noise, so the sandwich's meat S estimates s^2 J^T J. Its
  // relative sampling error is about sqrt(2 (2L + 1) / m) = sqrt(42 / 8192) = 7 % for L = 10 lags (Newey-West's
  // rule at m = 8192); asserted within 20 % (measured: 0.99, 0.99, 1.04 for EI, rho, cDI).
  const model::BeamParameters truth = model::preset("thick-steel");
  const PulseFit s = pulse_fit(truth, truth);
  const FitResult r = fit(s.options, signal::add_noise(s.clean, 0.01, 7));
  ASSERT_EQ(r.status, "converged") << r.termination;
  EXPECT_EQ(robust_lags("time", 8192), 10);
  for (const auto& p : r.parameters) {
    ASSERT_GT(p.standard_error, 0) << p.key;
    EXPECT_NEAR(p.robust_standard_error / p.standard_error, 1.0, 0.2) << p.key;
  }
}

TEST(Uncertainty, NoiseFreeWindowsOfTheRightModelAllRecoverTheTruth) {
  // Four windows of 2048 samples of a noise-free record of the fitted model: the first keeps its pulse, the others
  // are free decays; every window's minimum is the truth, so the spread is round-off (measured ~1e-10 relative;
  // asserted 1e-6). EI and rho are separable only with the pulse, so they are estimated with cDI only in window 1:
  // here EI and cDI, which a free decay determines (frequencies and decay rates).
  const model::BeamParameters truth = model::preset("thick-steel");
  PulseFit s = pulse_fit(truth, truth);
  s.options.estimate = {{"EI", truth.EI / 2, truth.EI * 2}, {"cDI", truth.cDI / 2, truth.cDI * 2}};
  const FitResult full = fit(s.options, s.clean);
  const WindowSpread w = window_spread(s.options, s.clean, full, 4);
  ASSERT_EQ(w.used, 4) << w.statuses[0] << " " << w.statuses[1] << " " << w.statuses[2] << " " << w.statuses[3];
  for (std::size_t i = 0; i < w.keys.size(); ++i) {
    EXPECT_LT(w.sd[i] / w.mean[i], 1e-6) << w.keys[i];
    EXPECT_NEAR(w.mean[i] / model::parameter_value(truth, w.keys[i]), 1.0, 1e-6) << w.keys[i];
  }
  EXPECT_THROW(window_spread(s.options, s.clean, full, 1), InputError);   // K >= 2
  EXPECT_THROW(window_spread(s.options, s.clean, full, 64), InputError);  // 128-sample windows
}

TEST(Uncertainty, WithModelErrorTheWindowsAndTheSandwichExceedTheFormalError) {
  // The data's beam has a tip mass 20 % heavier than the model's (fixed at the nominal value): a model error that
  // moves the modes by different fractions, so the least-squares compromise between them depends on which modes are
  // strong, and they decay at different rates along the record. The windows' EI then scatters by far more than the
  // formal error of the full fit (measured: EI 1450 in the pulse window, 1483 in the three free-decay windows, whose
  // free amplitudes absorb the error differently; sd 16.6 against a formal 0.21, 78x), and the sandwich exceeds the
  // formal error (measured 2.6x): asserted > 5x and > 1.2x. 0.1 % noise keeps the noise from hiding the model error.
  model::BeamParameters truth = model::preset("thick-steel");
  const model::BeamParameters nominal = truth;
  truth.m *= 1.2;
  PulseFit s = pulse_fit(truth, nominal);
  s.options.estimate = {{"EI", truth.EI / 2, truth.EI * 2}, {"cDI", truth.cDI / 2, truth.cDI * 2}};
  const std::vector<double> data = signal::add_noise(s.clean, 0.001, 11);
  const FitResult full = fit(s.options, data);
  ASSERT_NE(full.status, "failed");
  const WindowSpread w = window_spread(s.options, data, full, 4);
  ASSERT_GE(w.used, 3);
  // The windows' cDI absorbs the model error onto its bound (measured: in every window): its spread is over the
  // windows off the bound only, here none, so it has no sd; EI, interior in each, keeps all of them (R284).
  ASSERT_EQ(w.used_per_parameter.size(), 2u);
  EXPECT_EQ(w.used_per_parameter[0], w.used);
  EXPECT_EQ(w.used_per_parameter[1], 0) << w.statuses[0];
  EXPECT_TRUE(std::isnan(w.sd[1]));
  EXPECT_TRUE(w.bound_bias);  // no window is free of a bound: EI's spread holds the bound's bias, and says so
  const ParameterEstimate& ei = full.parameters[0];
  EXPECT_GT(w.sd[0], 5 * ei.standard_error);
  EXPECT_GT(ei.robust_standard_error, 1.2 * ei.standard_error);
}

TEST(Uncertainty, AResidualThatAloneSeparatesTwoParametersFormsNoSandwich) {
  // The thin beam's six modes in a tip-struck 3 ms pulse, fitted by the modal cost: two rows a mode, and every mode's
  // frequency moves with EI/rho alike except the first, whose tip body makes it move by EI alone, so that row fixes
  // the split of EI and rho nearly by itself (leverage measured 0.992). Its residual is then mostly the other rows'
  // noise, and a sandwich from the residuals was 15x below the scatter of EI over 30 noise seeds (HC1; HC2 2.3x
  // below, HC3 5x above): none is formed, and the status says which row and why. The formal error stays.
  const model::BeamParameters truth = model::preset("banks-aluminium");
  FitOptions o;
  o.elements = 16;
  o.experiment.force_x_m = 0.32;
  o.experiment.pulse_width_s = 0.003;
  o.experiment.output = "acceleration";
  o.cost.name = "modal";
  o.cost.spikes.count = 6;
  o.optimizer.method = default_optimizer("modal");
  o.start = truth;
  for (const char* key : {"EI", "rho", "cDI", "gamma"}) {
    const double v = model::parameter_value(truth, key);
    o.estimate.push_back({key, v / 2, v * 2});
  }
  const FitResult r = fit(o, signal::add_noise(same_model_record(truth, o.experiment, o.elements), 0.01, 1));
  ASSERT_EQ(r.status, "converged") << r.termination;
  ASSERT_EQ(r.covariance_status, "ok");
  EXPECT_NE(r.sandwich_status.find("residual 1 of 12 has leverage 0.992"), std::string::npos) << r.sandwich_status;
  for (const auto& p : r.parameters) {
    EXPECT_GT(p.standard_error, 0) << p.key;
    EXPECT_TRUE(std::isnan(p.robust_standard_error)) << p.key;
  }
}

TEST(Uncertainty, AWindowWithAParameterOnItsBoundIsSaidToBiasTheSpread) {
  // The twenty-second pass's P6: on a clean record of the model (1 % white noise), windows whose cDI ended on its
  // lower bound had their EI and rho biased by it (EI 0.4883 against 0.4905-0.4911 in the others), and the spread
  // was called model error, 3.3 times the windows' own formal error. Those windows still count for EI (on a measured
  // record a window driven onto a bound may be the model error the spread shows), and bound_bias says the spread
  // holds a bound's bias: the verdict names it.
  const model::BeamParameters truth = model::preset("banks-aluminium");
  FitOptions o;
  o.elements = kElements;
  o.experiment.samples = 8192;
  o.cost.name = "time";
  o.optimizer.method = default_optimizer("time");
  o.start = truth;
  for (const char* key : {"EI", "rho", "gamma", "cDI"}) {
    const double v = model::parameter_value(truth, key);
    o.estimate.push_back({key, v / 2, v * 2});
  }
  const std::vector<double> data =
      signal::add_noise(same_model_record(truth, o.experiment, kElements), 0.01, kBoundSeed);
  const FitResult full = fit(o, data);
  ASSERT_EQ(full.status, "converged") << full.termination;
  const WindowSpread w = window_spread(o, data, full, 4);
  int at_bound = 0;
  for (std::size_t k = 0; k < w.statuses.size(); ++k) {
    at_bound += w.statuses[k] == "converged-at-bound" ? 1 : 0;
    EXPECT_EQ(w.counted[k], w.statuses[k].rfind("converged", 0) == 0) << "window " << k + 1 << ": " << w.statuses[k];
  }
  ASSERT_GE(at_bound, 1);
  EXPECT_EQ(w.used_per_parameter[0], w.used);  // EI is off its bound in every window, so every window counts for it
  EXPECT_TRUE(w.bound_bias);
}

}  // namespace
}  // namespace beamid::fit
