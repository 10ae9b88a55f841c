// The Cramér-Rao bound: the smallest covariance any unbiased estimator of the parameters can have, the yardstick
// against which the costs' precision is measured (../shared/docs/comparison.md section 3).
//
// Samples z_i = y_i(q) + e_i with e_i independent N(0, sigma^2) and a known input. With the relative sensitivities
//   J_ik = d y_i / d ln q_k,
// the Fisher information is F = J^T J / sigma^2 and cov(ln q_hat) >= F^-1: the relative standard deviation of q_k is
// at least sqrt((F^-1)_kk). Least squares on the samples is the maximum-likelihood estimator for this noise and
// reaches the bound at high SNR (from inside its basin); the spike costs use the same data, so RMSE / bound is their
// efficiency.
//
// Sensitivities: central differences in ln q at steps h0, h0/2, h0/4, ... extrapolated to zero step by Ridders'
// method, whose error estimate (how well neighbouring extrapolations agree) is reported as the sensitivities' own
// accuracy check (comparison.md: "check two steps agree to a few digits"). A fixed step cannot serve every record:
// a step h in ln EI shifts the phase of a mode of frequency omega by about h omega t / 2, which over a 4 s record of
// an 80 Hz mode is a radian at h = 1e-3, while at h = 1e-6 round-off in the model output dominates. F^-1 is formed
// from the singular value decomposition of J (V S^-2 V^T), not by inverting J^T J, so its conditioning is J's.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "model/beam_parameters.h"
#include "signal/noise.h"
#include "signal/sensor_filter.h"
#include "simulation/experiment.h"
#include "simulation/simulator.h"

namespace beamid::fit {

struct SensitivityOptions {
  double log_step = 1e-2;  // the first (largest) step h0 in ln q of Ridders' sequence h0 / 2^i, i < 12
};

struct CramerRaoBound {
  std::vector<std::string> keys;   // parameter names, in the order of the vectors below
  Eigen::VectorXd values;          // q at which the bound holds
  double noise_sd = 0;             // sigma, in the units of the samples
  Eigen::MatrixXd sensitivities;   // J: samples x parameters, d y_i / d ln q_k
  Eigen::MatrixXd covariance;      // F^-1 = sigma^2 (J^T J)^-1, of ln q (empty when F is singular)
  Eigen::VectorXd relative_sd;     // sqrt(diag F^-1): the bound on sd(q_hat_k) / q_k (NaN when F is singular)
  Eigen::VectorXd sd;              // relative_sd * values: the bound on sd(q_hat_k) in q's units
  std::string method = "ridders";  // "exact" (simulation/sensitivities.h) or "ridders" (extrapolated differences)
  double step_agreement = 0;       // ridders: max over the columns of Ridders' error estimate / max |J_k|
  double rcond = 0;                // reciprocal condition number of J (smallest / largest singular value)
  std::string status = "ok";       // "ok" or why the bound is not available (singular Fisher information, ...)
  // When F is singular: the unit direction in ln q that the output does not determine (V's last column), so that the
  // caller can name the combination (the twenty-second pass's P7: "some combination" named none).
  Eigen::VectorXd null_direction;
  int null_dimension = 0;  // how many directions (singular values within 1e-12 of the largest): one is named

  std::string noise_model = "white";  // the noise's colour (signal/noise.h); noise_sd is its process sd
};

// The samples of a model as a function of ln q (throws NumericalError when it cannot be evaluated).
using LogModel = std::function<std::vector<double>(const Eigen::VectorXd& log_q)>;

// The bound for any model of sampled data. InputError unless noise_sd > 0 and finite, log_q finite.
CramerRaoBound cramer_rao_bound(const LogModel& model, const Eigen::VectorXd& log_q, double noise_sd,
                                const SensitivityOptions& options = {});

// The bound for the beam parameters `keys` (each > 0 in `beam`, not l) of the output of `experiment` from the
// Galerkin model of order `elements` with the given simulator: with the exact sensitivities of the modal closed form
// for a pulse and the fast integrator, else with Ridders' differences of the simulator. InputError for a bad key or
// a parameter that is 0. With a sensor filter (a cut-off > 0), the bound of the record as that sensor delivers it
// (fit/sensed_output.h: the sensitivities filtered and decimated, exactly: through the closed form for a pulse).
CramerRaoBound beam_cramer_rao_bound(const model::BeamParameters& beam, int elements,
                                     const simulation::Experiment& experiment, const std::vector<std::string>& keys,
                                     double noise_sd, const simulation::SimulatorOptions& simulator = {},
                                     const SensitivityOptions& options = {}, const signal::SensorFilter& sensor = {});

// The bound in coloured noise of process sd b.noise_sd (issue 33): F = W^T W / sigma^2 with W the sensitivities
// whitened for the model (signal::whiten: X^T R^-1 X, R the noise's correlation matrix; time-domain for an AR process,
// per DFT bin for power-law noise, whose noise-free offset bin carries no information). b.sensitivities stay J itself.
// White: b unchanged.
CramerRaoBound coloured_bound(const CramerRaoBound& b, const signal::NoiseModel& model);

}  // namespace beamid::fit
