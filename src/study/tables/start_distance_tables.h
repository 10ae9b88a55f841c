// The start-distance tables of a study (results/<study>/start_distance/ and start_distance.md), rendered from its
// results and start-distance metrics (start_distance.h):
//   start_distance/fits.csv     every fit: run, offset, direction, the start's exact frequency offset, reached
//   start_distance/curves.csv   per run and offset: reached / fits with the 95 % Wilson interval (the plotted curve)
//   start_distance/radius.csv   per run: the offset at which the share falls through 1/2, its interval, and the
//                               predicted least-squares basin 1/(2 f T)
//   start_distance.md           the report's table of the same
#pragma once

#include "study/analysis/results.h"
#include "study/analysis/start_distance.h"
#include "study/tables/rendered.h"

namespace beamid::study {

RenderedFiles render_start_distance(const StudyResults& results, const StartDistanceMetrics& metrics);

}  // namespace beamid::study
