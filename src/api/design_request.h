// beamid design (issue 34 item 4): the candidate experiments a user admits (sensor positions and count, force
// positions, pulse widths, sampling intervals and record lengths, each a list or a range), ranked by a criterion of the
// Fisher information of the parameters of interest (fit/experiment_design.h).
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "api/model_requests.h"
#include "fit/experiment_design.h"

namespace beamid::api {

struct DesignRequest {
  // --beam, --elements, and the experiment every candidate shares: --output, --force-amplitude (a pulse's).
  ModelRunRequest run = ModelRunRequest::labelled("beamid design");
  std::vector<std::string> estimate;       // --estimate: the parameters of interest (required)
  std::optional<double> noise_sd;          // --noise-sd: on every channel, in the output's unit
  std::optional<double> noise_level;       // --noise-level: each channel's sd as a fraction of its clean RMS
  std::optional<std::string> noise_model;  // --noise-model (default white)
  std::optional<std::string> criterion;    // --criterion D | A | KEY (default D)
  std::optional<int> sensors;              // --sensors K: channels a candidate has (default 1)
  // The choices, each item a number or a range START:STOP:COUNT (COUNT values from START to STOP): --sensor-x
  // (default: the tip), --force-x (default: the tip), --pulse-width (default 0.01), --dt (default 1e-3), --samples
  // (default 4096).
  std::vector<std::string> sensor_x, force_x, pulse_width, dt, samples;
};

struct DesignResult {
  ModelRun run;
  fit::DesignOptions options;
  std::vector<fit::DesignRow> rows;  // best first
};

// Validates (one-line errors naming the flag, value and constraint), ranks and returns every candidate.
DesignResult compute_design(const DesignRequest& request, std::ostream& warnings);

// A list of choices as the flags give them: each item a number or START:STOP:COUNT (2 <= COUNT <= 1000).
std::vector<double> design_choices(const Caller& caller, const std::string& flag,
                                   const std::vector<std::string>& items);

}  // namespace beamid::api
