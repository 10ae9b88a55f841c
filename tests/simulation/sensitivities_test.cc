// Exact sensitivities of the modal closed form (simulation/sensitivities.h) against Ridders-extrapolated central
// differences of the simulator itself (fit/cramer_rao.h computes those, with their own error estimate), for every
// parameter but l, both presets and all three outputs.
#include "simulation/sensitivities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "fit/cramer_rao.h"

namespace beamid::simulation {
namespace {

const std::vector<std::string> kKeys = {"rho", "rho_r2", "kAG", "EI", "gamma", "cDI", "kAcs", "m", "c", "J_o"};

Experiment experiment_for(const std::string& preset, double length_m, const std::string& output) {
  Experiment e;  // a sin^2 pulse at 0.7 l, sensor at the tip; several samples inside the pulse
  e.dt_s = preset == "banks-aluminium" ? 1e-3 : 1e-4;
  e.samples = 1024;
  e.pulse_width_s = 6.5 * e.dt_s;
  e.force_x_m = 0.7 * length_m;
  e.output = output;
  return e;
}

TEST(Sensitivities, EqualExtrapolatedDifferencesOfTheSimulator) {
  // Tolerance per column: 1e-6 of the column's largest entry, or 10x the differences' own error estimate where that
  // is larger. The differences carry the simulator's round-off (~1e-9 of the signal for the thin beam) divided by
  // their steps; the closed form has only the eigen-decomposition's round-off.
  for (const std::string preset : {"banks-aluminium", "thick-steel"}) {
    const model::BeamParameters beam = model::preset(preset);
    const galerkin::SplineSpace space(6);
    const galerkin::BeamForms forms(space, beam.l);
    for (const std::string output : {"displacement", "velocity", "acceleration"}) {
      const Experiment e = experiment_for(preset, beam.l, output);
      const SensitivityTrace exact = simulate_with_sensitivities(forms, beam, e, kKeys);
      ASSERT_TRUE(exact.trace.ok()) << exact.trace.status;
      const Trace plain = simulate(forms, beam, e, {});
      EXPECT_EQ(exact.trace.y, plain.y) << "the output must be the simulator's own";
      // Ridders' differences of the simulator in ln q (fit::cramer_rao_bound's generic path).
      const fit::LogModel model = [&](const Eigen::VectorXd& log_q) {
        model::BeamParameters b = beam;
        for (std::size_t k = 0; k < kKeys.size(); ++k)
          b.*(model::find_parameter(kKeys[k])->member) = std::exp(log_q(static_cast<Eigen::Index>(k)));
        return simulate(forms, b, e, {}).y;
      };
      Eigen::VectorXd log_q(static_cast<Eigen::Index>(kKeys.size()));
      for (std::size_t k = 0; k < kKeys.size(); ++k)
        log_q(static_cast<Eigen::Index>(k)) = std::log(beam.*(model::find_parameter(kKeys[k])->member));
      const fit::CramerRaoBound numeric = fit::cramer_rao_bound(model, log_q, 1.0);
      ASSERT_EQ(numeric.method, "ridders");
      for (std::size_t k = 0; k < kKeys.size(); ++k) {
        const auto c = static_cast<Eigen::Index>(k);
        const double q = beam.*(model::find_parameter(kKeys[k])->member);
        const Eigen::VectorXd analytic = q * exact.dy_dq.col(c);  // d y / d ln q
        const Eigen::VectorXd differences = numeric.sensitivities.col(c);
        const double size = differences.cwiseAbs().maxCoeff();
        const double error = (analytic - differences).cwiseAbs().maxCoeff() / size;
        const double tolerance = std::max(1e-6, 10 * numeric.step_agreement);
        EXPECT_LT(error, tolerance) << preset << " " << output << " d y / d ln " << kKeys[k];
        if (error > 1e-8)
          std::printf("[ %s %s %s: %.1e (differences' own estimate %.1e) ]\n", preset.c_str(), output.c_str(),
                      kKeys[k].c_str(), error, numeric.step_agreement);
      }
    }
  }
}

TEST(Sensitivities, RefuseWhatHasNoClosedForm) {
  const model::BeamParameters beam = model::preset("banks-aluminium");
  const galerkin::SplineSpace space(4);
  const galerkin::BeamForms forms(space, beam.l);
  Experiment e;
  e.excitation = "pluck";
  EXPECT_THROW(simulate_with_sensitivities(forms, beam, e, {"EI"}), InputError);
  e.excitation = "pulse";
  e.force_x_m = 0.3;  // in metres: its place on the span moves with l, which the modal derivatives do not follow
  EXPECT_THROW(simulate_with_sensitivities(forms, beam, e, {"l"}), InputError);
  EXPECT_FALSE(has_exact_sensitivities(e, {"EI", "l"}));
  EXPECT_TRUE(has_exact_sensitivities(e, {"EI"}));
}

}  // namespace
}  // namespace beamid::simulation
