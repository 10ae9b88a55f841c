// beamid study and beamid merge: run a study file, or combine the stores of its shards into the tables of one run.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "core/errors.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/resources.h"
#include "study/plan/plan.h"
#include "study/real/real_study.h"
#include "study/run/record_schema.h"
#include "study/run/runner.h"
#include "study/run/store.h"

namespace beamid::apps {
namespace {

std::string default_output(const study::StudySpec& spec) { return "results/" + spec.name; }

}  // namespace

std::vector<FlagSpec> study_flags() {
  return {positional("STUDY.toml", "the study file (studies/*.toml)"),
          integer_flag("jobs", "threads (default 0: all cores); the tables do not depend on it", 0, 4096),
          text_flag("output", "results folder (default results/<study name>)"),
          text_flag("shard", "K/N: run only every N-th unit from the K-th (combine with beamid merge)")};
}

int run_study(const Flags& a, std::ostream& out) {
  const study::StudySpec spec = study::load_study(a.text("STUDY.toml"));
  study::RunOptions o;
  o.output_dir = a.text_or("output", default_output(spec));
  o.jobs = a.optional_integer("jobs").value_or(0);
  if (a.has("shard")) {
    // K and N in decimal digits alone: " 1/2" and "1/+2" were taken and "1/2 " refused, and an N too large for an
    // int was said not to be an integer (the twenty-eighth pass's adv64 P5).
    const std::string s = a.text("shard");
    const auto slash = s.find('/');
    const auto digits = [](const std::string& t) {
      return !t.empty() && std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    };
    if (slash == std::string::npos || !digits(s.substr(0, slash)) || !digits(s.substr(slash + 1)))
      a.require(false, "shard", "must be K/N with integers 1 <= K <= N (digits only)");
    constexpr double kMostShards = 1e6;  // a shard per unit at most; a plan holds far fewer units than this
    const double k = std::stod(s.substr(0, slash)), n = std::stod(s.substr(slash + 1));
    if (n > kMostShards) a.require(false, "shard", "N must be at most 1000000");
    // Named as given: a K above 1e6 was shown clamped, "--shard = 1000001/1000000" (the twenty-ninth pass's adv66 P4).
    if (k < 1 || k > n) a.require(false, "shard", "must be K/N with 1 <= K <= N");
    o.shard_index = static_cast<int>(k);
    o.shard_count = static_cast<int>(n);
  }
  if (auto e = study::validation_error(o)) throw InputError("beamid study: --" + *e);
  const study::RunSummary summary = study::run_study(spec, o, std::cerr, isatty(STDERR_FILENO) != 0);
  out << "study,units,computed,reused,failed_cases,tables\n"
      << spec.name << "," << summary.units << "," << summary.computed << "," << summary.reused << "," << summary.failed
      << "," << (summary.tables ? "written" : "pending") << "\n";
  std::cerr << "beamid study " << spec.name << ": peak memory (resident) " << io::bytes_text(io::peak_resident_bytes())
            << "\n";
  return 0;
}

std::vector<FlagSpec> merge_flags() {
  return {positional("STUDY.toml", "the study file the shards ran"),
          text_flag("shards", "comma-separated results folders of the shard runs", true),
          text_flag("output", "results folder of the merged study (default results/<study name>)")};
}

int run_merge(const Flags& a, std::ostream& out) {
  const study::StudySpec spec = study::load_study(a.text("STUDY.toml"));
  const std::string output = a.text_or("output", default_output(spec));
  std::string problem = io::output_folder_problem(output, {spec.path, spec.truth.beam_path}, spec.path, spec.name);
  // A merge refused midway (units missing, a foreign shard) removes what it created: the folder, or in a folder that
  // existed the store. The shards still hold every record (it left a store of copies and no tables: the fourteenth
  // pass's P11, the fifteenth's P7).
  std::error_code exists_ec;
  struct RemoveUnlessKept {
    std::string folder;
    bool keep;
    ~RemoveUnlessKept() {
      std::error_code ec;
      if (!keep) std::filesystem::remove_all(folder, ec);
    }
  } created{std::filesystem::exists(std::filesystem::symlink_status(output, exists_ec)) ? output + "/store" : output,
            std::filesystem::exists(std::filesystem::symlink_status(output + "/store", exists_ec))};
  if (problem.empty()) problem = io::claim_store(output + "/store", spec.path);
  if (!problem.empty()) {
    if (a.has("output")) a.require(false, "output", problem);
    // No --output given: name the default folder, not an empty flag (the seventh pass's S70).
    throw InputError("beamid merge: " + output + " (the default --output, results/<study name>): " + problem);
  }
  const study::Store store(output + "/store", io::commit_label());
  if (const std::string removed = io::remove_leftovers_of_output(output); !removed.empty())
    std::cerr << "beamid merge: " << removed << "\n";
  // The unit ids of this study file: a shard's record of any other unit is left behind and named (shards run from
  // another study file of the same name said only "N units are missing").
  const study::Plan plan = study::make_plan(spec);
  std::map<std::string, const study::Unit*> units_by_id;
  for (const auto* units : {&plan.truths, &plan.units})
    for (const study::Unit& u : *units) units_by_id[u.id] = &u;
  int shard_units = 0;  // of the shard being absorbed: its accepted records other than truths
  const study::Store::Belongs belongs = [&](const std::string& id, const study::Record& record) -> std::string {
    const auto unit = units_by_id.find(id);
    if (unit == units_by_id.end())
      return "no unit of this study file (a shard of another study file, or of another version of this one)";
    const std::string why = study::schema_violation(record, *unit->second, spec.fit.estimate);
    if (why.empty() && unit->second->kind != study::UnitKind::Truth) ++shard_units;
    return why.empty() ? why : "not this study's unit: " + why;
  };
  // getline drops an empty last item: a comma at the end was accepted, against this very rule (the twenty-third
  // pass's P4).
  const std::string shards = a.text("shards");
  if (!shards.empty() && shards.back() == ',')
    a.require(false, "shards", "names an empty folder (two commas together, or a comma at an end)");
  std::stringstream list(shards);
  std::string dir;
  int records = 0, left_behind = 0;
  std::vector<std::string> seen;
  while (std::getline(list, dir, ',')) {
    // An empty name between two commas is a typo, not a shard to skip (the third pass's P397).
    if (dir.empty()) a.require(false, "shards", "names an empty folder (two commas together, or a comma at an end)");
    if (!io::is_existing_folder(dir + "/store"))
      throw InputError("beamid merge: --shards: '" + dir +
                       "' has no store/ folder: must be the --output of a shard run");
    // A shard is an input: the merged output is a folder of its own (a merge into a shard's folder filled that
    // shard's store with the others' records and wrote tables into it), and a shard is named once.
    std::error_code same_ec;
    if (std::filesystem::equivalent(dir, output, same_ec))
      a.require(false, "output", "is the shard folder '" + dir + "', an input of the merge: choose another folder");
    for (const std::string& earlier : seen)
      if (std::filesystem::equivalent(dir, earlier, same_ec))
        a.require(
            false, "shards",
            "names the folder '" + dir + "' twice" + (earlier == dir ? std::string() : " (as '" + earlier + "')"));
    seen.push_back(dir);
    shard_units = 0;
    const study::Store::Absorbed absorbed = store.absorb(dir + "/store", belongs);
    records += absorbed.copied;
    // Only truths (which do not depend on the sweep or the seed) and foreign records: the shard ran another study.
    if (shard_units == 0 && absorbed.foreign > 0)
      a.require(false, "shards",
                "'" + dir + "' holds " + std::to_string(absorbed.foreign) + " record(s) of no unit of " + spec.path +
                    " (and no case of it): it is a shard of another study file, or of another version of this one");
    // A shard of another study holds thousands: the first ten named, the rest counted (the adversarial pass's P8).
    constexpr std::size_t kNamed = 10;
    for (std::size_t i = 0; i < absorbed.left_behind.size() && i < kNamed; ++i)
      std::cerr << "beamid merge: left behind: " << absorbed.left_behind[i] << "\n";
    if (absorbed.left_behind.size() > kNamed)
      std::cerr << "beamid merge: left behind: " << absorbed.left_behind.size() - kNamed << " more record(s) of " << dir
                << "/store\n";
    left_behind += static_cast<int>(absorbed.left_behind.size());
  }
  try {
    study::write_tables_from_store(spec, output);
  } catch (const InputError& e) {
    // The units the damaged shard records held are the missing ones: said beside the count.
    if (left_behind == 0) throw;
    throw InputError(std::string(e.what()) + " (" + std::to_string(left_behind) +
                     " shard record(s) were left behind, damaged or of no unit of this study: listed above; rerun "
                     "their shards)");
  }
  created.keep = true;
  out << "study,records_merged,output\n" << spec.name << "," << records << "," << output << "\n";
  return 0;
}

std::vector<FlagSpec> real_flags() {
  return {positional("STUDY.toml", "the real-record study file (studies/real-*.toml)"),
          text_flag("output", "results folder (default results/<study name>)")};
}

int run_real(const Flags& a, std::ostream& out) {
  const study::RealStudySpec spec = study::load_real_study(a.text("STUDY.toml"));
  const std::string output = a.text_or("output", "results/" + spec.name);
  const int failed = study::run_real_study(spec, output, std::cerr);
  out << "study,fits,failed,output\n"
      << spec.name << "," << spec.costs.size() * spec.candidates.size() << "," << failed << "," << output << "\n";
  return failed > 0 ? 3 : 0;
}

}  // namespace beamid::apps
