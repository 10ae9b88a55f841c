#include "study/real/real_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "config/beam_file.h"
#include "config/document.h"
#include "core/errors.h"
#include "core/limits.h"
#include "costs/cost.h"
#include "io/files.h"
#include "io/text.h"
#include "io/time_series.h"
#include "signal/noise.h"

namespace beamid::study {
namespace fs = std::filesystem;
namespace {

using config::Table;

}  // namespace

namespace {

// fit.bounds or a candidate's: a table KEY = [lower, upper] over keys in `estimated` (any key when it is empty).
std::map<std::string, std::pair<double, double>> read_bounds(Table& r, const std::string& path,
                                                             const std::string& prefix,
                                                             const std::vector<std::string>& estimated) {
  std::map<std::string, std::pair<double, double>> bounds;
  auto table = r.table("bounds");
  if (!table) return bounds;
  for (const auto& [k, value] : table->entries()) {
    const std::vector<config::Node> a = value.elements();
    const auto line = path + ":" + std::to_string(value.line()) + ": " + prefix + "bounds." + k;
    if (!estimated.empty() && std::find(estimated.begin(), estimated.end(), k) == estimated.end())
      throw InputError(line + ": '" + k + "' is not estimated (estimate or per_record)");
    if (!value.is_array() || a.size() != 2 || !a[0].is_number() || !a[1].is_number())
      throw InputError(line + " = " + value.text() + ": must be [lower, upper]");
    const double lo = *a[0].number(), hi = *a[1].number();
    if (!(lo >= 0 && hi > lo))
      throw InputError(line + " = [" + format_value(lo) + ", " + format_value(hi) + "]: must have 0 <= lower < upper");
    bounds[k] = {lo, hi};
  }
  return bounds;
}

std::vector<std::string> parameter_keys() {
  std::vector<std::string> keys;
  for (const auto& info : model::parameter_table()) keys.emplace_back(info.key);
  return keys;
}

// Estimated keys: the lumped ones and those of a clamp spring or an attachment (checked against the beams later).
std::vector<std::string> estimated_keys(Table& r, const std::string& key) {
  if (!r.has(key)) return {};
  std::vector<std::string> keys = r.strings(key, false, {});
  const std::vector<std::string> lumped = parameter_keys();
  for (const std::string& k : keys)
    if (std::find(lumped.begin(), lumped.end(), k) == lumped.end() && k.rfind("support.", 0) != 0 &&
        !model::attachment_field(k))
      r.fail(
          key, "'" + k + "'",
          "must name beam parameters (" + Table::join(lumped) + ", support.k_theta, support.k_w, attachmentK.m/J/x)");
  return keys;
}

// fixed = { "record name" = ["cDI", ...] }: per-record keys that these records keep at their nominal value (a record
// left out of one parameter: a decay too short to measure its damping, say). Keys must be per_record ones, records
// the study's; nothing when absent.
std::map<int, std::vector<std::string>> read_fixed(Table& r, const std::vector<RealRecordSpec>& records,
                                                   const std::vector<std::string>& per_record) {
  std::map<int, std::vector<std::string>> fixed;
  std::optional<Table> t = r.table("fixed");
  if (!t) return fixed;
  for (const auto& [key, node] : t->entries()) {
    const std::string name = key;  // Clang 14 does not capture a structured binding in a lambda
    const auto found =
        std::find_if(records.begin(), records.end(), [&](const RealRecordSpec& record) { return record.name == name; });
    if (found == records.end()) t->fail(name, node.text(), "must be keyed by the name of a [[record]] of the study");
    if (per_record.empty()) t->fail(name, node.text(), "fixes per_record keys; this model has none");
    fixed[static_cast<int>(found - records.begin())] = t->strings(name, true, per_record);
  }
  return fixed;
}

// A record's or candidate's name labels table rows: a quote or a control character in it broke the CSV tables' rows
// and every message about it (the second adversarial pass of 2026-11-28, P1; a comma is quoted). Nothing, or the
// constraint.
std::string label_problem(const std::string& name) {
  if (name.find_first_not_of(" \t") == std::string::npos) return "must be a non-empty name (it labels table rows)";
  for (const char c : name)
    if (c == '"' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return "must hold no quote or control character (it labels the rows of CSV tables)";
  return "";
}
// The name as an error shows it on one line: control characters as '?'.
std::string printable(std::string name) {
  for (char& c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return "'" + name + "'";
}

RealRecordSpec read_record(Table r, const std::string& default_name,
                           const std::function<std::string(const std::string&)>& relative) {
  const auto positive = [](double v) { return v > 0; };
  RealRecordSpec s;
  s.name = r.string("name", default_name);
  if (const std::string problem = label_problem(s.name); !problem.empty()) r.fail("name", printable(s.name), problem);
  s.file = relative(r.string("file", std::nullopt));
  if (!io::is_existing_file(s.file)) r.fail("file", "'" + s.file + "'", "must be an existing record file");
  s.channel = r.string("channel", "");
  s.units = r.string("units", s.units, {"auto", "g", "as-is"});
  if (r.has("start_s"))
    s.start_s = r.number(
        "start_s", std::nullopt, [](double v) { return v >= 0 && std::isfinite(v); }, "must be finite and >= 0");
  if (r.has("duration_s"))
    s.duration_s = r.number(
        "duration_s", std::nullopt, [](double v) { return v > 0 && std::isfinite(v); }, "must be finite and > 0");
  s.resample = r.boolean("resample", false);
  s.peaks_hz = r.numbers("peaks_hz", positive, "must be > 0 (Hz)");
  if (s.peaks_hz.empty()) r.fail("peaks_hz", "[]", "must list the measured peak frequencies of the modes to fit");
  std::sort(s.peaks_hz.begin(), s.peaks_hz.end());
  if (r.has("beam")) {
    s.beam_file = relative(r.string("beam", std::nullopt));
    if (!io::is_existing_file(s.beam_file)) r.fail("beam", "'" + s.beam_file + "'", "must be an existing beam file");
  }
  if (r.has("sample_rate_hz"))
    s.sample_rate_hz = r.number("sample_rate_hz", std::nullopt, positive, "must be > 0 (Hz)");
  if (r.has("resample_rate_hz"))
    s.resample_rate_hz = r.number("resample_rate_hz", std::nullopt, positive, "must be > 0 (Hz)");
  s.variable = r.string("variable", "");
  s.time_variable = r.string("time_variable", "");
  if (r.has("time_channel")) s.time_channel = std::to_string(r.integer("time_channel", std::nullopt, 1, 1 << 20));
  const std::vector<std::string> keys = {
      "name", "file",           "channel",          "units",    "start_s",       "duration_s",  "resample", "peaks_hz",
      "beam", "sample_rate_hz", "resample_rate_hz", "variable", "time_variable", "time_channel"};
  r.finish(keys);
  s.where[""] = r.where();
  for (const std::string& key : keys)
    if (r.has(key)) s.where[key] = r.where(key);
  return s;
}

using Relative = std::function<std::string(const std::string&)>;

// [record] or [[record]]: one record, or up to kMaxRecords of them (record1, record2, ...).
void read_records(const config::Document& document, const Relative& relative, RealStudySpec& s) {
  Table root = document.root();
  const std::optional<config::Node> node = root.get("record");
  if (!node) document.required("record");  // the error for a missing [record]
  if (node->is_array()) {
    const std::vector<config::Node> items = node->elements();
    if (items.size() > static_cast<std::size_t>(core::kMaxRecords))
      root.fail("record", "[" + std::to_string(items.size()) + " tables]",
                "must hold at most " + std::to_string(core::kMaxRecords) + " records");
    for (std::size_t k = 0; k < items.size(); ++k) {
      const std::string name = "record" + std::to_string(k + 1);
      Table t = items[k].table(name + ".", "record");
      s.records.push_back(read_record(t, name, relative));
      // Records are named in candidates' `records` and in the tables: two of one name were accepted (the fifth
      // pass's R437).
      for (std::size_t j = 0; j + 1 < s.records.size(); ++j)
        if (s.records[j].name == s.records.back().name)
          t.fail("name", "'" + s.records.back().name + "'", "must differ from every other record's");
    }
  } else {
    s.records.push_back(read_record(document.required("record"), "record1", relative));
  }
}

// The k-th [[candidate]] (0-based): [fit]'s choices (`given`) with the candidate's own beam, values, records,
// estimated keys and bounds.
CandidateSpec read_candidate(const config::Node& item, std::size_t k, const CandidateSpec& given,
                             const RealStudySpec& s, const std::string& path, const Relative& relative) {
  const std::string prefix = "candidate" + std::to_string(k + 1) + ".";
  Table r = item.table(prefix, "candidate");
  CandidateSpec c = given;
  c.name = r.string("name", std::nullopt);
  // It names the candidate's rows in every table (an empty one was accepted: the fourth pass's Q440).
  if (const std::string problem = label_problem(c.name); !problem.empty()) r.fail("name", printable(c.name), problem);
  for (const CandidateSpec& other : s.candidates)
    if (other.name == c.name) r.fail("name", "'" + c.name + "'", "must differ from every other candidate's");
  if (r.has("beam")) {
    c.beam_file = relative(r.string("beam", std::nullopt));
    if (!io::is_existing_file(c.beam_file)) r.fail("beam", "'" + c.beam_file + "'", "must be an existing beam file");
  }
  if (auto values = r.table("values"))
    for (const auto& [key, value] : values->entries()) {
      if (!value.is_number())
        throw InputError(path + ":" + std::to_string(value.line()) + ": " + prefix + "values." + key + " = " +
                         value.text() + ": must be a number");
      c.values.emplace_back(key, *value.number());
    }
  if (r.has("records"))
    for (const std::string& name : r.strings("records", false, {})) {
      const auto found = std::find_if(s.records.begin(), s.records.end(),
                                      [&](const RealRecordSpec& record) { return record.name == name; });
      if (found == s.records.end()) r.fail("records", "'" + name + "'", "must name a [[record]] of the study");
      c.records.push_back(static_cast<int>(found - s.records.begin()));
    }
  if (r.has("estimate")) c.estimate = estimated_keys(r, "estimate");
  if (r.has("per_record")) c.per_record = estimated_keys(r, "per_record");
  if (c.estimate.empty() && c.per_record.empty())
    r.fail("estimate", "[]", "must name the parameters to estimate (here or in [fit])");
  // A key both shared and per record failed every fit at run time, exit 3 (the fifth pass's R428).
  for (const std::string& key : c.per_record)
    if (std::find(c.estimate.begin(), c.estimate.end(), key) != c.estimate.end())
      r.fail("per_record", "'" + key + "'", "is also in estimate: a key is shared or per record, not both");
  std::vector<std::string> all = c.estimate;
  all.insert(all.end(), c.per_record.begin(), c.per_record.end());
  for (auto it = c.bounds.begin(); it != c.bounds.end();)  // [fit]'s bounds of keys this candidate does not fit
    it = std::find(all.begin(), all.end(), it->first) == all.end() ? c.bounds.erase(it) : std::next(it);
  for (const auto& [key, b] : read_bounds(r, path, prefix, all)) c.bounds[key] = b;
  if (r.has("fixed")) {
    c.fixed = read_fixed(r, s.records, c.per_record);
  } else {  // [fit]'s, where they still apply: keys this candidate estimates per record, records it fits
    std::map<int, std::vector<std::string>> kept;
    for (const auto& [record, keys] : c.fixed)
      if (c.records.empty() || std::find(c.records.begin(), c.records.end(), record) != c.records.end())
        for (const std::string& key : keys)
          if (std::find(c.per_record.begin(), c.per_record.end(), key) != c.per_record.end())
            kept[record].push_back(key);
    c.fixed = kept;
  }
  for (const auto& [record, keys] : c.fixed)
    if (!c.records.empty() && std::find(c.records.begin(), c.records.end(), record) == c.records.end())
      r.fail("fixed", "'" + s.records[static_cast<std::size_t>(record)].name + "'",
             "is no record of this candidate (its records)");
  // A value set for an estimated key is its start, which must lie inside its bounds (one outside ran, and every fit
  // of the candidate failed: the fourth pass's Q429, Q435, Q437).
  for (const auto& [key, value] : c.values) {
    const auto b = c.bounds.find(key);
    if (b != c.bounds.end() && !(value >= b->second.first && value <= b->second.second))
      r.fail("values", key + " = " + format_value(value),
             "is the start of an estimated key: must lie in its bounds [" + format_value(b->second.first) + ", " +
                 format_value(b->second.second) + "]");
  }
  r.finish({"name", "beam", "values", "estimate", "per_record", "bounds", "records", "fixed"});
  return c;
}

// A bound in [fit] of a key that no candidate estimates is a mistake, refused with the line of [fit].bounds.
void check_bounds_used(const CandidateSpec& given, const RealStudySpec& s,
                       const std::function<std::string(const std::string&)>& fit_bounds_line) {
  for (const auto& [key, bounds] : given.bounds) {
    bool used = false;
    for (const CandidateSpec& c : s.candidates)
      for (const auto& lists : {c.estimate, c.per_record})
        used = used || std::find(lists.begin(), lists.end(), key) != lists.end();
    if (!used) throw InputError(fit_bounds_line(key) + ": '" + key + "' is estimated by no model of the study");
  }
}

// Every beam is read before anything runs, and every candidate's beams must have what it sets and estimates.
void check_beams(const RealStudySpec& s, const std::string& path) {
  for (const CandidateSpec& c : s.candidates)
    for (const int index : c.records) {
      const RealRecordSpec& record = s.records[static_cast<std::size_t>(index)];
      const std::string where = path + ": candidate '" + c.name + "', record '" + record.name + "': ";
      model::BeamParameters beam = config::load_beam_toml(!c.beam_file.empty()        ? c.beam_file
                                                          : !record.beam_file.empty() ? record.beam_file
                                                                                      : s.beam_file);
      try {
        for (const auto& [key, value] : c.values) model::set_nominal_value(beam, key, value);
        // the bounds the beam file's own values met (a 1e9 kg tip set here failed its fit with no reason)
        if (auto error = model::rig_implausibility(beam)) throw InputError("values: " + *error);
        for (const auto& lists : {c.estimate, c.per_record})
          for (const std::string& key : lists) {
            // An estimated key's start, the beam's value, must lie in its bounds: one outside was found at fit time,
            // each fit of the candidate a failed row and exit 3 (the second adversarial pass of 2026-11-28, P6).
            const double start = model::parameter_value(beam, key);
            const auto b = c.bounds.find(key);
            if (b != c.bounds.end() && !(start >= b->second.first && start <= b->second.second))
              throw InputError("the start of " + key + ", " + format_value(start) +
                               " (the beam's value), lies outside its bounds [" + format_value(b->second.first) + ", " +
                               format_value(b->second.second) + "]: set it with values or widen the bounds");
          }
      } catch (const InputError& error) {
        throw InputError(where + error.what());
      }
    }
}

}  // namespace

RealStudySpec load_real_study(const std::string& path) {
  const config::Document document = config::Document::load(path, "cannot read the study file");
  document.root().only_tables({"study", "record", "beam", "fit", "candidate"});
  const fs::path dir = fs::path(path).parent_path();
  const Relative relative = [&](const std::string& f) { return fs::path(f).is_absolute() ? f : (dir / f).string(); };
  RealStudySpec s;
  s.path = path;
  s.file_hash = io::hex64(core::fnv1a64(document.text()));
  {
    Table r = document.required("study");
    s.name = r.string("name", std::nullopt);
    if (const std::string problem = io::study_name_problem(s.name); !problem.empty())
      r.fail("name", "'" + s.name + "'", problem);
    s.question = r.string("question", std::nullopt);
    r.finish({"name", "question"});
  }
  read_records(document, relative, s);
  {
    Table r = document.required("beam");
    s.beam_file = relative(r.string("file", std::nullopt));
    // Checked here even when every record has its own beam (a missing file was accepted in silence: R438).
    if (!io::is_existing_file(s.beam_file)) r.fail("file", "'" + s.beam_file + "'", "must be an existing beam file");
    r.finish({"file"});
  }
  CandidateSpec given;
  std::function<std::string(const std::string&)> fit_bounds_line;
  {
    Table r = document.required("fit");
    s.elements = r.integer("elements", s.elements, core::kMinElements, core::kMaxElements);
    given.estimate = estimated_keys(r, "estimate");
    given.per_record = estimated_keys(r, "per_record");
    if (given.estimate.empty() && given.per_record.empty() && !document.root().has("candidate"))
      r.fail("estimate", "[]", "must name the parameters to estimate (or per_record, or [[candidate]]s)");
    // As in a candidate: a key both shared and per record failed every fit at run time, exit 3, also when [fit] is
    // the one model (the sixth pass's S460).
    for (const std::string& key : given.per_record)
      if (std::find(given.estimate.begin(), given.estimate.end(), key) != given.estimate.end())
        r.fail("per_record", "'" + key + "'", "is also in estimate: a key is shared or per record, not both");
    s.costs = r.strings("costs", true, costs::cost_names().names());
    s.max_evaluations = r.integer("max_evaluations", s.max_evaluations, 10, core::kMaxEvaluations);
    s.frequency_weight = r.string("frequency_weight", s.frequency_weight, costs::frequency_weight_names().names());
    s.mode_weight = r.string("mode_weight", s.mode_weight, costs::mode_weight_names().names());
    // Read by the modal cost only: given without it, it would weigh nothing (the eighth pass's RQ04).
    if (r.has("mode_weight") && std::find(s.costs.begin(), s.costs.end(), costs::kModalCost) == s.costs.end())
      r.fail("mode_weight", "'" + s.mode_weight + "'", "is read by the modal cost; fit.costs holds no modal cost");
    s.windows = r.integer("windows", 0, 0, 64);
    if (s.windows == 1) r.fail("windows", "1", "must be 0 (none) or >= 2");
    s.starts = r.integer("starts", s.starts, 1, core::kMaxStarts);
    s.seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, 1 << 30));
    if (r.has("seed") && s.starts == 1) r.fail("seed", std::to_string(s.seed), "seeds fit.starts > 1; starts is 1");
    s.start_from = r.string("start_from", "");
    if (!s.start_from.empty() && (s.costs.size() < 2 || s.start_from != s.costs.front()))
      r.fail("start_from", "'" + s.start_from + "'",
             "must be the first of fit.costs ('" + s.costs.front() +
                 "'), with other costs after it to start from its "
                 "estimate");
    // Bounds of any key a candidate may estimate; one that no model estimates is refused below.
    given.bounds = read_bounds(r, path, "fit.", {});
    given.fixed = read_fixed(r, s.records, given.per_record);
    fit_bounds_line = [r](const std::string& key) { return r.where("bounds") + ": fit.bounds." + key; };
    r.finish({"elements", "estimate", "per_record", "costs", "max_evaluations", "frequency_weight", "mode_weight",
              "bounds", "windows", "starts", "seed", "start_from", "fixed"});
  }
  if (const auto items = document.root().array("candidate", false)) {
    for (std::size_t k = 0; k < items->size(); ++k) {
      s.candidates.push_back(read_candidate((*items)[k], k, given, s, path, relative));
    }
  } else {
    s.candidates.push_back(given);
  }
  for (CandidateSpec& c : s.candidates)
    if (c.records.empty())
      for (std::size_t k = 0; k < s.records.size(); ++k) c.records.push_back(static_cast<int>(k));
  check_bounds_used(given, s, fit_bounds_line);
  check_beams(s, path);
  return s;
}

int run_real_study(const RealStudySpec& spec, const std::string& output_dir, std::ostream& log) {
  std::vector<std::string> inputs = {spec.path, spec.beam_file};
  for (const RealRecordSpec& r : spec.records) inputs.insert(inputs.end(), {r.file, r.beam_file});
  for (const CandidateSpec& c : spec.candidates) inputs.push_back(c.beam_file);
  if (const std::string problem = io::output_folder_problem(output_dir, inputs, spec.path, spec.name); !problem.empty())
    throw InputError("beamid real: --output " + output_dir + ": " + problem);
  if (const std::string problem = io::unwritable_folder_problem(output_dir); !problem.empty())
    throw InputError("beamid real: --output " + output_dir + ": " + problem);
  const RealResults results = compute_real_study(spec, log);
  for (const Rendered& f : render_real_study(spec, results))
    io::write_file_atomic(std::filesystem::path(output_dir) / f.path, f.text);
  log << "tables written to " << output_dir << "\n";
  int failed = 0;
  for (const RealFit& f : results.fits) failed += f.status.rfind("failed", 0) == 0 ? 1 : 0;
  return failed;
}

}  // namespace beamid::study
