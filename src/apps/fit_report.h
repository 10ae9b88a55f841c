// The Markdown report of one fit (beamid fit --report FILE.md): what ran, the estimates with standard errors and
// correlations (formal, assuming independent Gaussian noise), cost, evaluations, stages and termination, the spike
// table with the (A4) check, and the data and model spectra side by side around each spike. The full spectra go to
// FILE.spectra.csv beside it (bin, frequency, |Z|, |U|) for plotting.
#pragma once

#include <string>

#include "fit/identification.h"
#include "io/time_series.h"

namespace beamid::apps {

struct FitReportInput {
  const fit::FitOptions& options;
  const fit::FitResult& result;
  const io::TimeSeries& data;
  const std::string& beam_name;
  const std::vector<std::string>& arguments;
};

// InputError when the file cannot be written.
void write_fit_report(const std::string& path, const FitReportInput& input);

}  // namespace beamid::apps
