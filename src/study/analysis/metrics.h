// The numbers a study's tables and claims are made of, as pure functions of its results (results.h): statistics of
// relative errors per setting, landscape shapes, multi-start reach. Nothing here reads or writes a file.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "study/analysis/results.h"
#include "study/analysis/statistics.h"

namespace beamid::study {

// The settings that define a group of replicates.
struct GroupKey {
  double pulse_width_s;
  int samples;
  std::string cost, method, start;
  int elements;
  double noise;
  auto tie() const { return std::tie(pulse_width_s, samples, cost, method, start, elements, noise); }
  bool operator<(const GroupKey& o) const { return tie() < o.tie(); }
  bool operator==(const GroupKey& o) const { return tie() == o.tie(); }
};
GroupKey key_of(const Unit& unit);
using Groups = std::vector<std::pair<GroupKey, std::vector<const CaseRow*>>>;
// Groups in plan order of first appearance.
Groups group_cases(const std::vector<CaseRow>& cases);

struct SuccessCount {
  int successes = 0, cases = 0;
  double rate() const { return cases > 0 ? static_cast<double>(successes) / cases : -1.0; }
};
// Per cost, over the cases with noise <= max_noise.
std::map<std::string, SuccessCount> success_by_cost(const std::vector<CaseRow>& cases, double max_noise);

// Smoothness of a sampled 1-D cost curve.
struct SliceShape {
  int local_minima = 0;    // interior strict local minima, a plateau counting once
  double basin_lower = 0;  // relative offsets x/v - 1 of the monotone basin around the lowest point
  double basin_upper = 0;
  double total_variation_ratio = 0;  // sum |c_{j+1} - c_j| / (max - min): 1 for a monotone, 2 for a clean bowl
  double flat_share = 0;             // share of steps changing the cost by less than 1 % of the mean absolute step
};
SliceShape slice_shape(const std::vector<double>& x, const std::vector<double>& cost, double truth);

struct GridShape {
  int local_minima = 0;      // strict 8-neighbour minima
  double descent_share = 0;  // share of grid points whose steepest-descent walk on the grid ends at the lowest point
  double flat_share = 0;     // as for slices, over all row and column steps
};
GridShape grid_shape(const std::vector<double>& cost, int nx, int ny);

// Resolution of a slice or grid against the least-squares basin (start_distance.h, predict_basins): its step in
// relative frequency, max_k |d log f_k / d log q| x (step in log q) over the fitted modes (the widest of both axes for
// a grid), against the predicted basin min_k 1/(2 f_k T_eff,k) of its experiment. A sample spacing wider than a third
// of that basin cannot show the least-squares needle, so the monotone region around the lowest sample may be the bowl
// the needle sits in: its basin width is then reported as unresolved, not as a number. A damping axis moves no
// natural frequency (step 0): it has no least-squares needle to miss and counts as resolved.
struct Resolution {
  double frequency_step = std::numeric_limits<double>::quiet_NaN();
  double predicted_basin = std::numeric_limits<double>::quiet_NaN();
  bool resolved() const { return frequency_step <= predicted_basin / 3; }  // NaN (unknown): false
};
struct SliceRow {
  const LandscapeRow* row;
  int modes;  // in the data of the slice's experiment
  std::string cost, parameter;
  SliceShape shape;
  bool first_experiment;  // the experiment of the tables (grids, multi-starts, slices plots)
  bool first_setting;     // at the first N and noise level of [landscape] (the tables' setting)
  Resolution resolution;
};
struct GridRow {
  const LandscapeRow* row;
  std::string cost, a, b;
  GridShape shape;
  Resolution resolution;
  bool zoom;           // a fine grid around the truth (landscape.zoom_range_factor)
  bool first_setting;  // at the first N and noise level of [landscape]
};

// Local fits from the truth (start -1) and from random starts. The reference minimum of a cost is the lowest final
// cost over all its fits that did not fail, the truth start's included; a start "reaches" it when every estimate lies
// within the success tolerance of the reference's. The reach count is over the random starts only.
struct MultistartFit {
  const LandscapeRow* row;
  double cost_gap;  // final cost minus the reference's (NaN when either is missing)
  bool reached;
};
struct MultistartSummary {
  std::string cost;
  int reached = 0, started = 0;  // random starts
  double reference_cost;         // NaN when every fit failed
  int reference_start = 0;       // -1: the truth start
  std::vector<MultistartFit> fits;
};

struct LandscapeMetrics {
  std::vector<SliceRow> slices;  // every experiment, plan order
  std::vector<GridRow> grids;
  std::vector<MultistartSummary> multistarts;  // in the order of landscape.cost
};
LandscapeMetrics landscape_metrics(const StudyResults& results);
// Whether a landscape unit is at the first N and noise level of [landscape] (the setting of the tables and claims
// that compare costs: a comparison holds N and noise fixed).
bool first_setting(const StudySpec& spec, const Unit& u);

// Efficiency (outputs.efficiency): per group of noisy replicates and parameter, the fits that stayed at the global
// minimum (success: every estimate within the study's tolerances) summarised apart from those that left it, against
// the Cramér-Rao bound of the fitted model at the truth. Bias = mean relative error with its Monte-Carlo standard
// error sd / sqrt(n) (comparison.md section 4: a bias is claimed only beyond 2 MCSE); RMSE / bound = 1 for an
// efficient unbiased estimator, and above 1 by the estimator's excess variance and its bias (squared, added).
struct EfficiencyRow {
  GroupKey key;
  int modes = 0;  // in the data of the group's experiment (0 when unknown)
  std::string parameter;
  int stayed = 0, fits = 0;
  Stats errors;                                             // relative errors of the fits that stayed
  double mcse = std::numeric_limits<double>::quiet_NaN();   // errors.std / sqrt(stayed)
  double bound = std::numeric_limits<double>::quiet_NaN();  // relative sd bound (NaN when unavailable)
  bool significant_bias() const { return std::abs(errors.mean) > 2 * mcse; }  // NaN: false
  double efficiency() const { return errors.rmse / bound; }                   // RMSE / bound
};
// Rows for every noisy group with a bound unit (same pulse width, record length, N and noise), in group order.
std::vector<EfficiencyRow> efficiency_rows(const StudyResults& results, const Groups& groups);

// Bias decomposition (outputs.bias_decomposition): per group of noisy replicates and parameter, the relative error
// b0 of the noise-free fit of the same setting (the bias of the cost's minimum on these data), the mean error of the
// replicates that stayed at the minimum (success) with its Monte-Carlo standard error MCSE = sd / sqrt(stayed), and
// their difference, the noise-induced bias, with the same MCSE (b0 has none: it is one deterministic fit).
struct BiasRow {
  GroupKey key;
  std::string parameter;
  int stayed = 0, fits = 0;
  double noise_free = std::numeric_limits<double>::quiet_NaN();  // b0 (NaN when that fit failed or left the minimum)
  Stats errors;                                                  // of the replicates that stayed
  double mcse = std::numeric_limits<double>::quiet_NaN();
  double noise_induced() const { return errors.mean - noise_free; }
  bool significant_total() const { return std::abs(errors.mean) > 2 * mcse; }              // NaN: false
  bool significant_noise_induced() const { return std::abs(noise_induced()) > 2 * mcse; }  // NaN: false
};
// Rows for every noisy group whose noise-free twin (same settings, noise 0) is in the study, in group order.
std::vector<BiasRow> bias_rows(const StudyResults& results, const Groups& groups);

// Success and errors against the number of modes in the data, per (modes, pulse width, Nbar, cost, method).
struct ModeCell {
  int successes = 0, cases = 0;
  std::vector<double> errors;  // max |relative error| of each case
};
using ModeKey = std::tuple<int, double, int, std::string, std::string>;
std::map<ModeKey, ModeCell> mode_cells(const StudyResults& results);

}  // namespace beamid::study
