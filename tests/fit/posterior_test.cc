// The posterior of a beam fit (issue 34 item 2): near a well-determined least-squares minimum it is the Gaussian the
// formal covariance describes, its two evidences agree, and the costs without a likelihood are refused.
#include "fit/posterior.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "same_model_record.h"
#include "signal/noise.h"

namespace beamid::fit {
namespace {

// banks-aluminium's pulse test at N = 4 (1024 samples: a few hundred microseconds an evaluation), EI and rho
// estimated by least squares from the truth's values, on a record with 0.1 % white noise.
struct Case {
  FitOptions options;
  std::vector<Record> records;
};
Case pulse_case(const std::string& cost) {
  const model::BeamParameters truth = model::preset("banks-aluminium");
  Case c;
  c.options.elements = 4;
  c.options.experiment.pulse_width_s = 0.004;
  c.options.experiment.samples = 1024;
  c.options.cost.name = cost;
  c.options.optimizer.method = default_optimizer(cost);
  c.options.start = truth;
  for (const std::string key : {"EI", "rho"}) {
    const double v = model::parameter_value(truth, key);
    c.options.estimate.push_back({key, v / 2, v * 2});
  }
  Record r;
  r.name = "record1";
  r.start = truth;
  r.experiment = c.options.experiment;
  r.data = signal::add_noise(same_model_record(truth, c.options.experiment, 4), 1e-3, 12);
  c.records = {r};
  return c;
}

TEST(Posterior, NearAWellDeterminedMinimumItIsTheFormalGaussianAndItsEvidencesAgree) {
  const Case c = pulse_case("time");
  const FitResult best = fit(c.options, c.records);
  ASSERT_EQ(best.status, "converged") << best.termination;
  PosteriorOptions o;
  o.sampler.steps = 2000, o.sampler.warmup = 300, o.threads = 2;
  const Posterior p = posterior(c.options, c.records, best, o);
  ASSERT_TRUE(p.converged()) << p.status;
  ASSERT_EQ(p.parameters.size(), 2u);
  for (const PosteriorParameter& q : p.parameters) {
    // With 0.1 % noise the cost is quadratic over several standard errors (profile_test: the profile interval is the
    // formal one to 2 %), so the posterior is the Gaussian of the formal covariance, its sd the formal SE times
    // sqrt(m / (m - p)) = 1.001 (the noise level integrated out). Monte-Carlo error: the sd's relative error is
    // 1 / sqrt(2 ESS) < 0.036 at ESS >= 400, the mean's SE / sqrt(ESS) < 0.05 SE: 4.5 of each asked.
    const double mcse = 1 / std::sqrt(q.effective_samples);
    EXPECT_NEAR(q.sd / q.standard_error, 1.0, 4.5 * mcse / std::sqrt(2.0) + 0.01) << q.key;
    EXPECT_NEAR((q.mean - q.estimate) / q.standard_error, 0.0, 4.5 * mcse + 0.02) << q.key;
    // The 95 % credible interval is estimate +- 1.96 SE, to a tail quantile's Monte-Carlo error (2.7 SE / sqrt(ESS)).
    EXPECT_NEAR((q.upper95 - q.estimate) / q.standard_error, 1.96, 4.5 * 2.7 * mcse + 0.02) << q.key;
    EXPECT_NEAR((q.estimate - q.lower95) / q.standard_error, 1.96, 4.5 * 2.7 * mcse + 0.02) << q.key;
    EXPECT_LT(q.rhat, kMaxRhat) << q.key;
  }
  // The correlation of EI and rho (a frequency fixes EI / rho: near +1) as the fit's.
  EXPECT_NEAR(p.correlation(0, 1), best.correlation(0, 1), 0.02);
  // The two evidences of a Gaussian posterior agree: Laplace's is exact for it, the sampled one within its standard
  // error (4.5 of them asked, and 0.02 for the posterior's departure from the Gaussian).
  ASSERT_TRUE(std::isfinite(p.log_evidence_laplace)) << p.evidence_note;
  ASSERT_TRUE(std::isfinite(p.log_evidence_sampled)) << p.evidence_note;
  EXPECT_GT(p.log_evidence_sampled_se, 0);
  EXPECT_NEAR(p.log_evidence_sampled, p.log_evidence_laplace, 4.5 * p.log_evidence_sampled_se + 0.02);
  EXPECT_NE(p.line(0).find("EI: mean "), std::string::npos) << p.line(0);
}

TEST(Posterior, ACostWithoutALikelihoodIsRefused) {
  const Case c = pulse_case("spike-smooth");
  const FitResult best = fit(c.options, c.records);
  try {
    posterior(c.options, c.records, best, PosteriorOptions{});
    ADD_FAILURE() << "the spike-smooth cost was sampled";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("posterior: the cost 'spike-smooth' is no likelihood"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace beamid::fit
