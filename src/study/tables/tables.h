// The tables of a finished study, written to results/<study>/ from the store alone (so a single run, a resumed run
// and merged shards give the same bytes). Every file but timings.csv is a pure function of the study file, the code
// and the seeds. The steps are apart: load the results (results.h), compute the metrics (metrics.h) and findings
// (claims.h), render each table (case_tables.h, landscape_tables.h, overlay.h, report_block.h, manifest.h), then
// write every rendered file atomically.
//   manifest.json, provenance.csv   what ran (manifest.h)
//   cases.csv ... modes.csv         the fits (case_tables.h)
//   landscape/, smoothness.md       cost landscapes (landscape_tables.h)
//   overlay.csv, spectrum.csv, spikes.csv   one fit per cost in time and frequency (overlay.h)
//   report.md                       the study's generated block for REPORT.md (report_block.h)
//   timings.csv                     wall-clock seconds of every unit (the only file that differs between runs)
#pragma once

#include <ostream>
#include <string>

#include "study/analysis/results.h"
#include "study/plan/plan.h"
#include "study/run/store.h"
#include "study/spec/study_spec.h"
#include "study/tables/rendered.h"

namespace beamid::study {

// Every table of the study, rendered (no file is touched).
RenderedFiles render_tables(const StudyResults& results);

// Loads the results from the store (InputError when a unit is missing), renders and writes every table.
// `log` hears what is not done (a list of earlier tables that fails its check).
void write_tables(const StudySpec& spec, const Plan& plan, const Store& store, const std::string& output_dir,
                  std::ostream& log);

}  // namespace beamid::study
