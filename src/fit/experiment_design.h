// Experiment design from the Fisher information (issue 34 item 4): which sensor positions, force position, pulse
// width, record length and sampling interval make the beam parameters of interest best determined.
//
// Each candidate is an experiment with one or more sensors (channels with independent noise of one sd, each the
// output at its position). Its Fisher information in ln q is the sum over its channels,
//   F = sum_j W_j^T W_j / sigma_j^2,  W_j = the channel's sensitivities d y / d ln q, whitened for the noise model,
// (exact for a pulse: simulation/sensitivities.h; fit/cramer_rao.h), so that a channel's information is computed once
// and every set of K positions is a sum. The candidates are ranked by a criterion of the bound F^-1 (of ln q, so that
// each entry is a relative variance):
//   D   det(F^-1)^(1/2p), the geometric mean of the bound's semi-axes (D-optimal: the smallest confidence ellipsoid);
//   A   sqrt(trace(F^-1) / p), the root mean square relative sd (A-optimal);
//   KEY sqrt((F^-1)_kk), one parameter's relative sd (its bound alone; the others are estimated with it).
// A candidate whose F is singular (a sensor at a node, or too few channels for the parameters) is ranked last with its
// status, never dropped. The noise is either one absolute sd for every channel (a sensor's floor: what a placement
// cannot change) or a fraction of each channel's clean RMS (the studies' SNR).
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "model/beam_parameters.h"
#include "simulation/experiment.h"

namespace beamid::fit {

inline const std::string kDOptimal = "D";
inline const std::string kAOptimal = "A";

struct DesignCandidate {
  std::vector<double> sensors_x_m;  // one channel each
  double force_x_m = 0;
  double pulse_width_s = 0;
  double dt_s = 0;
  int samples = 0;
};

struct DesignOptions {
  model::BeamParameters beam;
  int elements = 16;
  std::vector<std::string> keys;  // the parameters of interest (estimated together)
  // The experiment every candidate shares (output, excitation "pulse", force amplitude); each candidate sets its
  // sensors, force position, pulse width, dt and samples.
  simulation::Experiment base;
  std::vector<double> sensor_positions_m;  // where a sensor may go
  int sensor_count = 1;                    // channels a candidate has: every set of this many positions
  std::vector<double> force_positions_m;   // each at least one value
  std::vector<double> pulse_widths_s;
  std::vector<double> dts_s;
  std::vector<int> samples;
  double noise_sd = 0;     // > 0: this sd on every channel; 0: noise_level
  double noise_level = 0;  // each channel's sd as this fraction of its clean RMS
  std::string noise_model = "white";
  std::string criterion = kDOptimal;  // D | A | one of keys
};

// The first violated constraint, or nothing: keys not empty and estimable, each list not empty, 1 <= sensor_count <=
// the positions, a criterion among D, A and the keys, exactly one of noise_sd and noise_level > 0, and at most
// kMaxDesignCandidates candidates (the positions' K-subsets times the other lists' product).
std::optional<std::string> validation_error(const DesignOptions& options);
constexpr long long kMaxDesignCandidates = 100000;

struct DesignRow {
  DesignCandidate candidate;
  double criterion = 0;         // as the options' criterion defines it (relative: 0.01 is 1 %); NaN when singular
  Eigen::VectorXd relative_sd;  // the bound on each key's relative sd (NaN when singular)
  std::string status = "ok";    // "ok", or why this candidate has no bound
};

// Every candidate, best first (ascending criterion; enumeration order among equals), those without a bound last.
// InputError for invalid options.
std::vector<DesignRow> rank_designs(const DesignOptions& options);

// The number of candidates the options describe (the positions' K-subsets times the other lists' sizes), saturated.
long long candidate_count(const DesignOptions& options);

}  // namespace beamid::fit
