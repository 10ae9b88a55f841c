#include "study/run/estimate.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "core/limits.h"
#include "io/resources.h"
#include "study/analysis/statistics.h"

namespace beamid::study {
namespace {

using GroupKey = std::tuple<std::string, std::string, int>;  // kind, cost, elements

struct Timings {
  std::map<std::string, double> by_id;
  std::map<GroupKey, std::vector<double>> by_group;
  std::map<std::string, std::vector<double>> by_kind;
};

// unit_id,kind,cost,elements,noise,wall_time_s (study/tables/case_tables.cc).
Timings read_timings(const std::string& path) {
  Timings t;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line.rfind("unit_id,kind,cost,elements,noise,wall_time_s", 0) != 0) return t;
  while (std::getline(in, line)) {
    std::vector<std::string> field;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) field.push_back(cell);
    if (field.size() != 6) continue;
    char* end = nullptr;
    const double seconds = std::strtod(field[5].c_str(), &end);
    if (end == field[5].c_str() || !(seconds >= 0) || seconds > 1e7) continue;
    const int elements = field[3].empty() ? 0 : std::atoi(field[3].c_str());
    t.by_id[field[0]] = seconds;
    t.by_group[{field[1], field[2], elements}].push_back(seconds);
    t.by_kind[field[1]].push_back(seconds);
  }
  return t;
}

// A unit's key as timings.csv writes it: a bound unit's cost and a truth's N are written empty.
GroupKey key_of(const Unit& u) {
  const std::string& kind = unit_kind_name(u.kind);
  if (u.kind == UnitKind::Truth) return {kind, "", 0};
  return {kind, u.kind == UnitKind::Bound || u.kind == UnitKind::Frequencies ? "" : u.cost, u.elements};
}

std::string label_of(const GroupKey& key) {
  const auto& [kind, cost, elements] = key;
  std::string label = kind;
  if (!cost.empty()) label += " " + cost;
  if (elements > 0) label += " N = " + std::to_string(elements);
  return label;
}

// An untimed unit's seconds: kSecondsPerUntimedUnit, or its model evaluations' cost where that is more (estimate.h).
double untimed_seconds(const Unit& u, int truth_elements) {
  const bool truth = u.kind == UnitKind::Truth;
  const double evaluation = core::seconds_per_evaluation(truth ? truth_elements : u.elements);
  return std::max(kSecondsPerUntimedUnit, (truth ? kTruthEvaluations : kFitEvaluations) * evaluation);
}

}  // namespace

PlanEstimate estimate_plan(const std::vector<const Unit*>& units, const std::string& timings_path, int truth_elements) {
  const Timings t = read_timings(timings_path);
  std::map<GroupKey, double> group_median;
  for (const auto& [key, times] : t.by_group) group_median[key] = median(times);
  std::map<std::string, double> kind_median;
  for (const auto& [kind, times] : t.by_kind) kind_median[kind] = median(times);
  PlanEstimate e;
  std::map<GroupKey, PlanEstimate::Group> groups;
  for (const Unit* u : units) {
    const GroupKey key = key_of(*u);
    double seconds = untimed_seconds(*u, truth_elements);
    if (const auto id = t.by_id.find(u->id); id != t.by_id.end()) {
      seconds = id->second;
      ++e.by_id;
    } else if (const auto g = group_median.find(key); g != group_median.end()) {
      seconds = g->second;
      ++e.by_median;
    } else if (const auto k = kind_median.find(std::get<0>(key)); k != kind_median.end()) {
      seconds = k->second;
      ++e.by_median;
    } else {
      ++e.untimed;
    }
    ++e.units;
    e.compute_s += seconds;
    PlanEstimate::Group& group = groups[key];
    group.label = label_of(key);
    ++group.units;
    group.compute_s += seconds;
  }
  for (auto& [key, group] : groups) e.groups.push_back(group);
  std::stable_sort(e.groups.begin(), e.groups.end(),
                   [](const auto& a, const auto& b) { return a.compute_s > b.compute_s; });
  return e;
}

std::string plan_text(const PlanEstimate& e, int jobs, const std::string& timings_path) {
  std::ostringstream out;
  out << "plan: " << e.units << " unit(s) to run, about " << io::seconds_text(e.compute_s)
      << " of compute: " << io::seconds_text(e.compute_s / std::max(1, jobs)) << " wall on " << jobs << " thread(s)";
  if (e.compute_s / std::max(1, jobs) > 1800)
    out << ", " << io::seconds_text(e.compute_s / (4.0 * std::max(1, jobs))) << " as --shard K/4 on 4 such nodes";
  out << " (";
  if (e.by_id + e.by_median > 0)
    out << e.by_id << " timed by their own id and " << e.by_median << " at their kind's median in " << timings_path;
  if (e.untimed > 0)
    out << (e.by_id + e.by_median > 0 ? "; " : "") << e.untimed << " never timed, counted at " << kSecondsPerUntimedUnit
        << " s each, or their model evaluations' cost at their N where more";
  out << ")";
  if (!e.groups.empty()) {
    out << "; the most: ";
    for (std::size_t i = 0; i < std::min<std::size_t>(3, e.groups.size()); ++i)
      out << (i ? ", " : "") << e.groups[i].units << " x " << e.groups[i].label << " ("
          << io::seconds_text(e.groups[i].compute_s) << ")";
  }
  return out.str();
}

}  // namespace beamid::study
