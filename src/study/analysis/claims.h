// What a study's data say, as data: counts (facts, "time succeeds in 0/252 fits") and computed claims (a statement
// and whether the data support it, "[true] spike-smooth succeeds at least as often as time in every setting
// (12/12 settings)"). Each carries its evidence (k of n); none is a literal: a claim holds or fails by its numbers.
#pragma once

#include <string>
#include <vector>

#include "study/analysis/metrics.h"
#include "study/analysis/results.h"
#include "study/analysis/start_distance.h"

namespace beamid::study {

struct Claim {
  bool holds = false;
  std::string text;          // ends with its evidence, e.g. "(5/6 settings)"
  int count = 0, total = 0;  // k of n for a k-of-n claim; -1 for a comparison of two rates (both in the text)
};

struct Count {
  std::string text;  // "time succeeds in 0/252 fits with noise <= 1 %"
  int count = 0, total = 0;
};

struct Findings {
  std::vector<Count> counts;
  std::vector<Claim> claims;
};

Findings study_findings(const StudyResults& results, const Groups& groups, const LandscapeMetrics& landscape,
                        const StartDistanceMetrics& start_distance);

}  // namespace beamid::study
