// The landscape tables of a study (results/<study>/landscape/ and smoothness.md), rendered from its results and
// landscape metrics:
//   slice_<cost>_<K>.csv        cost along one parameter through the truth (ratio, value, cost, normalised cost)
//   grid_<cost>_<A>_<B>.dat     gnuplot pm3d blocks over two parameters (log10 of the normalised cost)
//   basin.csv                   slice shapes of every experiment, with the modes in its data
//   multistart.csv / .md        every local fit (the truth start first) with its cost gap to the reference minimum
//   smoothness.csv, ../smoothness.md   local minima, basin, TV / range, flat steps, grid descent share, reach
#pragma once

#include "study/analysis/metrics.h"
#include "study/analysis/results.h"
#include "study/tables/rendered.h"

namespace beamid::study {

RenderedFiles render_landscape(const StudyResults& results, const LandscapeMetrics& metrics);

}  // namespace beamid::study
