// Forward-model verification, written as tables for REPORT.md (make verify):
//   frequencies.{csv,md}:   undamped Galerkin frequencies of both presets for N = 2..32 against the exact
//                           Timoshenko determinant, relative error per mode (Rayleigh-Ritz: >= 0, non-increasing);
//   fast_vs_cvode.{csv,md}: the exact modal propagator against CVODE BDF at decreasing rtol, for all three outputs,
//                           max |fast - cvode| / max |y|, with CVODE's step counts;
//   model_reduction.{csv,md}: modal truncation at the widest gap of the undamped spectrum, plain and with the discarded
//                           modes as uncoupled oscillators, against the exact response (simulation/modal_truncation.h).
// Deterministic content only (no timings), so a rerun leaves the files byte-identical.
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace beamid::apps {

void write_verification(const std::string& folder, std::ostream& log);
// The files write_verification writes, each with the text it starts with: its folder may hold these, as verify wrote
// them, and nothing else (a user's own frequencies.csv is not replaced).
const std::vector<std::pair<std::string, std::string>>& verification_files();

}  // namespace beamid::apps
