// The tables of a finished study, written to results/<study>/ from the store alone (so a single run, a resumed run
// and merged shards give the same bytes). Every file but timings.csv is a pure function of the study file, the code
// and the seeds.
//   manifest.json          provenance: commit, dirty flag, compiler, library versions, study-file hash, seed, counts
//   provenance.csv         study, cases, commit (read by the plot scripts)
//   cases.csv              one row per case: its settings, status, termination, estimates, standard errors, errors
//   summary.csv / .md      per (pulse width, record, cost, method, start, N, noise) and parameter: mean relative bias,
//                          standard deviation, RMSE, median, success rate, median evaluations
//   convergence.csv / .md  the noise-free estimates against N, beside the Galerkin frequency error of each mode
//   spread.csv / .md       Monte-Carlo spread of the estimates against the median standard error the fits reported
//   modes.csv              success rate and errors against the number of modes in the data
//   bias_<K>.csv           RMSE and bias against N, one column pair per (cost, method, noise): for the plots
//   landscape/             slices and grids of every landscape cost (normalised), smoothness.csv / .md, multistart.csv
//   overlay.csv, spectrum.csv, spikes.csv   the fit overlay of one case per cost and the data spectrum with spikes
//   report.md              the study's generated block for REPORT.md (tables, computed claims, plot links)
//   timings.csv            wall-clock seconds of every unit (the only file that differs between runs)
#pragma once

#include <string>
#include <vector>

#include "study/plan.h"
#include "study/store.h"
#include "study/study_spec.h"

namespace beamid::study {

void write_tables(const StudySpec& spec, const Plan& plan, const Store& store, const std::vector<Record>& truths,
                  const std::string& output_dir);

// Smoothness of a sampled 1-D cost curve (exposed for tests).
struct SliceShape {
  int local_minima = 0;      // interior strict local minima, a plateau counting once
  double basin_lower = 0;    // relative offsets x/v - 1 of the monotone basin around the lowest point
  double basin_upper = 0;
  double total_variation_ratio = 0;  // sum |c_{j+1} - c_j| / (max - min): 1 for a monotone, 2 for a clean bowl
  double flat_share = 0;     // share of steps changing the cost by less than 1 % of the mean absolute step
};
SliceShape slice_shape(const std::vector<double>& x, const std::vector<double>& cost, double truth);

struct GridShape {
  int local_minima = 0;      // strict 8-neighbour minima
  double descent_share = 0;  // share of grid points whose steepest-descent walk on the grid ends at the lowest point
  double flat_share = 0;     // as for slices, over all row and column steps
};
GridShape grid_shape(const std::vector<double>& cost, int nx, int ny);

}  // namespace beamid::study
