// report.md: a study's generated block for REPORT.md (what ran, the counts and computed claims, the Markdown tables
// already rendered, and links to the plots that plots/make_plots.sh makes from the tables).
#pragma once

#include <string>

#include "study/analysis/claims.h"
#include "study/analysis/results.h"
#include "study/tables/rendered.h"

namespace beamid::study {

// `tables` holds the rendered Markdown tables the block quotes (summary.md, convergence.md, ...).
std::string render_report_block(const StudyResults& results, const Findings& findings, const RenderedFiles& tables);

}  // namespace beamid::study
