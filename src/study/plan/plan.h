// The work of a study as a list of independent units, each with a stable identity:
//   truth       one clean synthetic record per pulse width (the exact modal closed form at N_truth, the longest
//               record of the sweep; the first is also integrated with CVODE as an independent cross-check);
//   case        one fit: the Cartesian product of the sweep (N, cost, noise, replicate, method, start, pulse width,
//               record length); a noise-free case is run once (replicate 0), since its replicates would be identical;
//   slice/grid  a cost evaluated along one parameter axis, or on a grid of two, through the truth (landscape), for
//               every fitted N and noise level of [landscape] (noisy records: the sweep's replicate 0 draw);
//   multistart  one local fit of the landscape cost from a random start in the bounds, or from the truth (index -1);
//   frequencies the Galerkin frequencies of the truth beam at one N of the sweep, and the exact ones;
//   bound       the Cramér-Rao bound of the model at one N for one experiment and noise level (outputs.efficiency);
//   start       one fit of the start-distance curves (study_spec.h): a run (cost and method) from a start at a
//               frequency offset in one random direction (index), or from the truth (index -1, offset 0).
// A unit's id is the FNV-1a hash of its canonical text (every setting that affects its result, written out), so
// adding a unit changes no other id, and its seed derives from (study seed, id), not from its position. The noise
// realisation of a case derives from (study seed, truth, noise level, replicate) only, so every cost, N and method
// sees the same noisy record (common random numbers: paired comparisons between costs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "study/spec/study_spec.h"

namespace beamid::study {

// The kinds of unit (above). A kind's name (unit_kind_name) is how the store, the timings and a unit's canonical
// text spell it, so it never changes.
enum class UnitKind { Truth, Case, Slice, Grid, Multistart, Frequencies, Start, Bound };
const std::string& unit_kind_name(UnitKind kind);

struct Unit {
  UnitKind kind = UnitKind::Case;
  std::string id;         // 16 hex digits
  std::string canonical;  // "key=value;..." of everything that determines the result
  std::uint64_t seed = 0;
  // The settings (those that apply to the kind).
  int truth = 0;  // index of the truth unit this one reads
  double pulse_width_s = 0;
  int samples = 0;
  int elements = 0;
  std::string cost;
  double noise = 0;
  int replicate = 0;
  std::string method;
  std::string start;
  std::vector<std::string> parameters;  // slice: 1, grid: 2
  int index = 0;                        // multistart, start: which random start or direction (-1: the truth)
  double offset = 0;                    // start: the relative frequency offset of the start
  double range_factor = 0;              // slice, grid: the axes span [v/F, v F] around the true value v
  int points = 0;                       // slice, grid: points per axis
  bool zoom = false;                    // grid: one of the fine grids around the truth (landscape.zoom_range_factor)
  bool overlay = false;                 // case: also compute the fit overlay and spectra (one case per cost)
  bool cvode_check = false;             // truth: also integrate with CVODE and record the agreement (first truth)
  std::uint64_t noise_seed = 0;
};

struct Plan {
  std::vector<Unit> truths;  // run first: every other unit needs one
  std::vector<Unit> units;   // cases, then landscape units, in sweep order
};

Plan make_plan(const StudySpec& spec);

// The shard of `units` that worker k of n (1 <= k <= n) runs: every n-th unit from the (k-1)-th, by position in
// the plan (whose order depends only on the study file). Truths are needed by all shards and are not split.
std::vector<const Unit*> shard(const std::vector<Unit>& units, int k, int n);

}  // namespace beamid::study
