// The three costs on signals whose spectra are known exactly: hand-computed values of (3.5), the closed-form
// amplitude, the (A4) checks, and the staircase of (3.5) against the continuity of the smooth variant.
#include "costs/cost.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace beamid::costs {
namespace {

constexpr int kSamples = 256;
constexpr double kDt = 1.0 / 256;  // df = 1 Hz: bins are hertz

// sum of amplitude cos(2 pi (bin df) t) e^{-sigma t}
std::vector<double> tones(const std::vector<std::array<double, 3>>& parts) {
  std::vector<double> y(kSamples, 0.0);
  for (int i = 0; i < kSamples; ++i)
    for (const auto& [amplitude, bin, sigma] : parts)
      y[static_cast<std::size_t>(i)] +=
          amplitude * std::exp(-sigma * i * kDt) * std::cos(2 * std::numbers::pi * bin * i * kDt);
  return y;
}

Evaluation evaluate(Cost& cost, const std::vector<double>& y) {
  const std::vector<std::complex<double>> none;
  return cost.evaluate(ModelResponse{y, none});
}

TEST(TimeCost, IsTheSumOfSquaresAndSolvesTheAmplitude) {
  const auto z = tones({{1.0, 10.3, 0.5}});
  const auto y = tones({{1.0, 10.5, 0.4}});
  double expected = 0;
  for (int i = 0; i < kSamples; ++i)
    expected += std::pow(y[static_cast<std::size_t>(i)] - z[static_cast<std::size_t>(i)], 2);
  CostOptions o;
  auto cost = make_cost(o, z, kDt);
  const auto e = evaluate(*cost, y);
  ASSERT_TRUE(e.ok());
  EXPECT_NEAR(e.value, expected, 1e-12 * expected);
  EXPECT_EQ(e.residuals.size(), kSamples);
  // Unknown amplitude: a model 3x too large fits exactly with a = 1/3.
  o.unknown_amplitude = true;
  auto free = make_cost(o, z, kDt);
  std::vector<double> big(z);
  for (double& v : big) v *= 3;
  const auto f = evaluate(*free, big);
  EXPECT_NEAR(f.amplitude_scale, 1.0 / 3, 1e-15);
  EXPECT_LT(f.value, 1e-28);
}

TEST(SpikeCost, MatchesAHandComputedValueOfThePapersFormula) {
  // Data: tones on bins 20 (amplitude 2, |Z| = 1) and 50 (amplitude 1, |Z| = 0.5), every other bin 0 up to
  // round-off, so each 20 % support is the peak bin alone (n_l = N_l = 0) and eps2 = 1/(1 + 0.25) = 0.8.
  // Model: bins 21 (|U| = 1) and 48 (amplitude 1.2, |U| = 0.6). By (3.5) with eps1 = 1/df^2 = 1:
  //   J = (21 - 20)^2 + (48 - 50)^2 + 0.8 [(1 - 1)^2 + (0.6 - 0.5)^2] = 5.008.
  CostOptions o;
  o.name = "spike";
  o.spikes.count = 2;
  auto cost = make_cost(o, tones({{2.0, 20, 0}, {1.0, 50, 0}}), kDt);
  ASSERT_EQ(cost->data_spikes().size(), 2u);
  EXPECT_EQ(cost->data_spikes()[0].data.n_left + cost->data_spikes()[0].data.n_right, 0);
  EXPECT_EQ(cost->residual_count(), 4);
  const auto e = evaluate(*cost, tones({{2.0, 21, 0}, {1.2, 48, 0}}));
  ASSERT_TRUE(e.ok()) << e.status;
  EXPECT_NEAR(e.value, 5.008, 1e-12);  // round-off of a 256-point FFT
  EXPECT_EQ(e.a4, "ok");
  // Scale-free magnitudes: s = (1 + 0.6 * 0.5)/(1 + 0.36) and the magnitude term shrinks accordingly.
  o.unknown_amplitude = true;
  auto free = make_cost(o, tones({{2.0, 20, 0}, {1.0, 50, 0}}), kDt);
  const auto f = evaluate(*free, tones({{2.0, 21, 0}, {1.2, 48, 0}}));
  const double s = 1.3 / 1.36;
  EXPECT_NEAR(f.amplitude_scale, s, 1e-12);
  EXPECT_NEAR(f.value, 5 + 0.8 * (std::pow(s - 1, 2) + std::pow(0.6 * s - 0.5, 2)), 1e-12);
  // Explicit weights are used as given.
  o.unknown_amplitude = false;
  o.eps1 = 2.0;
  o.eps2 = 10.0;
  auto weighted = make_cost(o, tones({{2.0, 20, 0}, {1.0, 50, 0}}), kDt);
  EXPECT_NEAR(evaluate(*weighted, tones({{2.0, 21, 0}, {1.2, 48, 0}})).value, 2 * 5 + 10 * 0.01, 1e-12);
}

TEST(SpikeCost, ReportsAssumptionA4) {
  CostOptions o;
  o.name = "spike";
  o.spikes.count = 2;
  auto cost = make_cost(o, tones({{2.0, 20, 0}, {1.0, 50, 0}}), kDt);
  // A silent model has no local maxima at all: (A4) fails and the cost is undefined (infinite), not a crash.
  const auto silent = evaluate(*cost, std::vector<double>(kSamples, 0.0));
  EXPECT_FALSE(silent.ok());
  EXPECT_TRUE(std::isinf(silent.value));
  EXPECT_NE(silent.a4.find("(A4) violated"), std::string::npos);
  // Model spikes at 45 and 52: the first lies nearer to the data's 50 than to its partner 20: a jump, reported.
  const auto jumped = evaluate(*cost, tones({{2.0, 45, 0}, {1.0, 52, 0}}));
  EXPECT_TRUE(jumped.ok());
  EXPECT_TRUE(jumped.pairs[0].jumps);
  EXPECT_FALSE(jumped.pairs[1].jumps);
  EXPECT_NE(jumped.a4.find("jumps modes at spike(s) 1"), std::string::npos);
  // NaN in the model output: an undefined evaluation with its reason.
  std::vector<double> bad(kSamples, 0.0);
  bad[3] = std::nan("");
  EXPECT_EQ(evaluate(*cost, bad).status, "the model output is not finite");
  // Too few maxima in the data for the spikes requested: an input error at construction.
  o.spikes.count = 300;
  EXPECT_THROW(make_cost(o, tones({{2.0, 20, 0}}), kDt), InputError);
}

TEST(SpikeCosts, ThePapersCostIsAStaircaseAndTheSmoothOneIsNot) {
  // Model frequency swept across the bin boundary 30.5 at 0.01-bin steps, data a damped tone at 30.2 bins.
  // (3.5)'s frequency residual takes only integer values (property 1) and its value jumps where k^u changes bin
  // (property 2); the smooth cost's frequency residual follows the model frequency to within the 3-bin
  // estimator's bias (< 0.05 bin here, damped tone sigma T/(2 pi) = 0.08 bin, mirror-pole leakage ~1/60 bin).
  const auto z = tones({{1.0, 30.2, 0.5}});
  CostOptions paper;
  paper.name = "spike";
  paper.spikes.count = 1;
  CostOptions smooth = paper;
  smooth.name = "spike-smooth";
  auto j_f = make_cost(paper, z, kDt);
  auto j_s = make_cost(smooth, z, kDt);
  double previous_paper = 0, previous_smooth = 0, largest_smooth_step = 0, largest_paper_step = 0;
  for (int step = 0; step <= 40; ++step) {
    const double f = 30.3 + 0.01 * step;
    const auto y = tones({{1.0, f, 0.5}});
    const auto p = evaluate(*j_f, y);
    const auto s = evaluate(*j_s, y);
    ASSERT_TRUE(p.ok() && s.ok());
    const double frequency_residual = p.residuals(0);  // sqrt(eps1) (f_{k^u} - f_{k^z}) in bins
    EXPECT_NEAR(frequency_residual, std::round(frequency_residual), 1e-12);
    EXPECT_NEAR(s.residuals(0), f - 30.2, 0.05) << "f = " << f;
    if (step > 0) {
      largest_paper_step = std::max(largest_paper_step, std::abs(p.value - previous_paper));
      largest_smooth_step = std::max(largest_smooth_step, std::abs(s.value - previous_smooth));
    }
    previous_paper = p.value;
    previous_smooth = s.value;
  }
  // One step of 0.01 bin changes the smooth cost by O(0.01 * slope); the paper's frequency term jumps by a whole
  // bin^2 where k^u changes bin, partly offset (0.15 here) by the magnitude term's re-alignment on the new bin.
  EXPECT_GT(largest_paper_step, 0.5);
  EXPECT_LT(largest_smooth_step, 0.05);
}

TEST(SmoothSpikeCost, OutputJacobianEqualsCentralDifferencesOfItsResiduals) {
  // Two decaying tones: the model moves along dy (a shift of the first tone's frequency and the second's decay).
  // The residuals are smooth there (peak bins fixed), so central differences at h = 1e-5 agree with the chain rule
  // to O(h^2) ~ 1e-10 of the column's size; 1e-7 leaves room for round-off.
  const auto z = tones({{1.0, 20.3, 0.8}, {0.5, 47.6, 1.5}});
  const auto y = tones({{1.0, 20.45, 0.7}, {0.5, 47.4, 1.7}});
  std::vector<double> dy(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double t = i * kDt;
    dy[static_cast<std::size_t>(i)] =
        -2 * std::numbers::pi * t * std::exp(-0.7 * t) * std::sin(2 * std::numbers::pi * 20.45 * t) -
        0.5 * t * std::exp(-1.7 * t) * std::cos(2 * std::numbers::pi * 47.4 * t);
  }
  CostOptions o;
  o.name = kSpikeSmoothCost;
  o.spikes.count = 2;
  auto cost = make_cost(o, z, kDt);
  ASSERT_TRUE(cost->has_output_jacobian());
  const std::vector<std::complex<double>> none;
  ASSERT_TRUE(cost->evaluate(ModelResponse{y, none}).ok());
  const Eigen::MatrixXd j =
      cost->output_jacobian(ModelResponse{y, none}, Eigen::Map<const Eigen::VectorXd>(dy.data(), kSamples));
  const double h = 1e-5;
  std::vector<double> plus = y, minus = y;
  for (int i = 0; i < kSamples; ++i)
    plus[static_cast<std::size_t>(i)] += h * dy[static_cast<std::size_t>(i)],
        minus[static_cast<std::size_t>(i)] -= h * dy[static_cast<std::size_t>(i)];
  const Eigen::VectorXd differences =
      (cost->evaluate(ModelResponse{plus, none}).residuals - cost->evaluate(ModelResponse{minus, none}).residuals) /
      (2 * h);
  EXPECT_LT((differences - j.col(0)).cwiseAbs().maxCoeff(), 1e-7 * differences.cwiseAbs().maxCoeff());
  o.unknown_amplitude = true;  // the scale then depends on U: no Jacobian offered
  EXPECT_FALSE(make_cost(o, z, kDt)->has_output_jacobian());
}

TEST(SmoothSpikeCost, TakesModelPolesFromEigenvaluesPairedByFrequency) {
  // Data: a damped tone at 30.2 bins. Model eigenvalues: a decoy at 100 Hz listed first, and 30.2 Hz written
  // as its alias fs + 30.2 Hz above the sampling rate (fs = 256 Hz), which folds back onto 30.2 Hz. The nearest
  // aliased pole is taken and its decay rate compared directly; residuals are then the 3-bin bias on the data.
  const auto z = tones({{1.0, 30.2, 0.5}});
  CostOptions o;
  o.name = "spike-smooth";
  o.spikes.count = 1;
  o.model_poles = "eigenvalues";
  auto cost = make_cost(o, z, kDt);
  const double w = 2 * std::numbers::pi;
  const std::vector<std::complex<double>> poles{{-3.0, 100 * w}, {-0.5, (256 + 30.2) * w}};
  const auto y = tones({{1.0, 30.2, 0.5}});
  const auto e = cost->evaluate(ModelResponse{y, poles});
  ASSERT_TRUE(e.ok()) << e.status;
  EXPECT_NEAR(e.pairs[0].model_frequency_hz, 30.2, 1e-12);
  EXPECT_NEAR(e.pairs[0].model_decay_rate_1_s, 0.5, 1e-12);
  // 3-bin bias on this short record: < 0.05 bin in frequency and in sigma T/(2 pi).
  EXPECT_LT(std::abs(e.residuals(0)), 0.05);
  EXPECT_LT(std::abs(e.residuals(1)), 0.05);
  // Without eigenvalues the option cannot work: a status, not a crash.
  const std::vector<std::complex<double>> none;
  EXPECT_FALSE(cost->evaluate(ModelResponse{y, none}).ok());
}

TEST(SpikeCost, FrequencyWeightingsScaleEachSpikesFrequencyError) {
  // Data: undamped tones on bins 20 (amplitude 2) and 50 (amplitude 1); model: bins 22 and 55, both 10 % high, so
  // the paper's absolute residuals are 2 and 5 bins (eps1 = 1/df^2 = 1). Exact integer bins make every quantity
  // exact up to round-off: Z(k) = A Nbar / 2, the 3-bin decay rate 0, hence 1e-12.
  const auto z = tones({{2.0, 20, 0}, {1.0, 50, 0}});
  const auto y = tones({{2.0, 22, 0}, {1.0, 55, 0}});
  CostOptions o;
  o.name = kSpikeCost;
  o.spikes.count = 2;
  const auto residuals = [&](const std::string& weight) {
    o.frequency_weight = weight;
    auto cost = make_cost(o, z, kDt);
    const Evaluation e = evaluate(*cost, y);
    EXPECT_TRUE(e.ok()) << e.status;
    return std::pair(e.residuals(0), e.residuals(1));
  };
  const auto [a1, a2] = residuals(kAbsoluteWeight);
  EXPECT_NEAR(a1, 2.0, 1e-12);
  EXPECT_NEAR(a2, 5.0, 1e-12);
  // Relative: c_l ~ 1/f_l with mean square 1, so both 10 % errors cost the same, 0.1 / rms(1/20, 1/50) each.
  const auto [r1, r2] = residuals(kRelativeWeight);
  const double rms_inverse_f = std::sqrt((1.0 / 400 + 1.0 / 2500) / 2);
  EXPECT_NEAR(r1, 0.1 / rms_inverse_f, 1e-12);
  EXPECT_NEAR(r2, 0.1 / rms_inverse_f, 1e-12);
  // Inverse-variance: equal (zero) decay rates, so the bound is ~1/A and c_l ~ A_l = (2, 1), mean square 2.5.
  const auto [v1, v2] = residuals(kInverseVarianceWeight);
  EXPECT_NEAR(v1, 2.0 * 2 / std::sqrt(2.5), 1e-9);
  EXPECT_NEAR(v2, 1.0 * 5 / std::sqrt(2.5), 1e-9);
  // The weight factors (a study's variants) multiply eps1 and eps2: the frequency residuals by sqrt(eps1_factor),
  // the magnitude residuals by sqrt(eps2_factor), and nothing else.
  o.frequency_weight = kAbsoluteWeight;
  const auto all = [&](double f1, double f2) {
    o.eps1_factor = f1;
    o.eps2_factor = f2;
    auto cost = make_cost(o, z, kDt);
    return evaluate(*cost, y).residuals;
  };
  const Eigen::VectorXd base = all(1, 1), scaled = all(4, 9);
  ASSERT_EQ(base.size(), scaled.size());
  EXPECT_NEAR(scaled(0), 2 * base(0), 1e-12);
  EXPECT_NEAR(scaled(1), 2 * base(1), 1e-12);
  for (Eigen::Index i = 2; i < base.size(); ++i) EXPECT_NEAR(scaled(i), 3 * base(i), 1e-12 * (1 + std::abs(base(i))));
  o.eps1_factor = 0;
  EXPECT_EQ(*validation_error(o), "eps1_factor = 0: must be finite and > 0");
  o.eps1_factor = 1;
  o.frequency_weight = "hertz";
  EXPECT_EQ(*validation_error(o), "frequency_weight = 'hertz': must be one of absolute, relative, inverse-variance");
}

TEST(CostOptions, InvalidChoicesAreNamed) {
  CostOptions o;
  o.name = "frequency";
  EXPECT_EQ(*validation_error(o), "cost = 'frequency': must be one of time, spike, spike-smooth, freq-band, freq-ml, modal");
  o.name = "spike";
  o.eps1 = -1.0;
  EXPECT_EQ(*validation_error(o), "eps1 = -1: must be 0 or in [1e-100, 1e100]");
  EXPECT_THROW(make_cost(o, tones({{1, 20, 0}}), kDt), InputError);
  // Issue 30: a weight of 1e308 overflowed the cost to inf, and all weights 0 made the cost 0 everywhere (the fit
  // "converged" at its start).
  o.eps1 = 1e308;
  EXPECT_EQ(*validation_error(o), "eps1 = 1e+308: must be 0 or in [1e-100, 1e100]");
  o.eps1 = 0.0;
  o.eps2 = 0.0;
  EXPECT_EQ(*validation_error(o),
            "eps1 = eps2 = 0: every term of the spike cost would weigh nothing; at least one "
            "weight must be > 0");
  o.name = "spike-smooth";
  EXPECT_FALSE(validation_error(o)) << "eps3 (default) still weighs the decay rates";
  o.eps3 = 0.0;
  EXPECT_NE(validation_error(o)->find("eps1 = eps2 = eps3 = 0"), std::string::npos);
  // A weight that is zero in double precision is refused too: eps3 = 1e-300 (sqrt 1e-150 on its residuals) bypassed
  // the all-zero refusal and the fit "converged" 35 % off (the second pass's N372).
  o.eps3 = 1e-300;
  EXPECT_EQ(*validation_error(o), "eps3 = 1e-300: must be 0 or in [1e-100, 1e100]");
  o.eps3 = 0.0;
  o.name = "time";
  EXPECT_FALSE(validation_error(o)) << "the time cost has no such weights";
  CostOptions short_record;
  EXPECT_THROW(make_cost(short_record, std::vector<double>(5, 0.0), kDt), InputError);
}

}  // namespace
}  // namespace beamid::costs
