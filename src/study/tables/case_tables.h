// The tables of a study's fits, rendered from its results (results.h, metrics.h); each function renders one table
// (CSV and, where it is read by people, Markdown) and computes nothing the store does not hold.
//   cases.csv, timings.csv  one row per case (settings, status, estimates, standard errors, errors); wall-clock
//                           seconds of every unit (the only file that differs between runs)
//   summary.csv / .md       per setting and parameter: mean relative bias, sd, RMSE, median, success, evaluations
//   bias_<K>.csv            RMSE and sd against N, a column pair per (cost, method, start, noise): for the plots
//   convergence.csv / .md   the noise-free estimates against N, beside galerkin_frequencies.csv
//   spread.csv / .md        Monte-Carlo spread of the estimates against the median standard error the fits report
//   modes.csv               success rate and errors against the number of modes in the data
#pragma once

#include "study/analysis/metrics.h"
#include "study/analysis/results.h"
#include "study/tables/rendered.h"

namespace beamid::study {

RenderedFiles render_cases(const StudyResults& results);
RenderedFiles render_summary(const StudyResults& results, const Groups& groups);
RenderedFiles render_bias(const StudyResults& results, const Groups& groups);
RenderedFiles render_convergence(const StudyResults& results, const Groups& groups);
RenderedFiles render_spread(const StudyResults& results, const Groups& groups);
// efficiency.csv and efficiency.md (RMSE against the Cramér-Rao bound; nothing without outputs.efficiency).
RenderedFiles render_efficiency(const std::vector<EfficiencyRow>& rows);
// bias_decomposition.csv and .md (the noise-free bias, the noisy mean and their difference; nothing without
// outputs.bias_decomposition).
RenderedFiles render_bias_decomposition(const std::vector<BiasRow>& rows, bool control);
RenderedFiles render_modes(const StudyResults& results);

}  // namespace beamid::study
