// beamid study and beamid merge: run a study file, or combine the stores of its shards into the tables of one run.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "io/arguments.h"
#include "model/errors.h"
#include "study/real_study.h"
#include "study/runner.h"
#include "study/store.h"
#include "io/provenance.h"

namespace beamid::apps {
namespace {

// The study file is the first argument (positional); the rest are flags.
std::pair<std::string, Args> split_study_file(const Args& args) {
  if (args.empty() || args[0].rfind("--", 0) == 0) return {"", args};
  return {args[0], Args(args.begin() + 1, args.end())};
}

std::string default_output(const study::StudySpec& spec) { return "results/" + spec.name; }

}  // namespace

int run_study(const Args& all, std::ostream& out) {
  auto [file, args] = split_study_file(all);
  const io::Arguments a("study", args,
                        {kHelpFlag,
                         {"jobs", true, "threads (default 0: all cores); the tables do not depend on it"},
                         {"output", true, "results folder (default results/<study name>)"},
                         {"shard", true, "K/N: run only every N-th unit from the K-th (combine with beamid merge)"}});
  if (wants_help(a, out, "STUDY.toml [--jobs J] [--output DIR] [--shard K/N]")) return 0;
  if (file.empty()) throw InputError("beamid study: missing the study file: beamid study STUDY.toml [flags]");
  const study::StudySpec spec = study::load_study(file);
  study::RunOptions o;
  o.output_dir = a.text_or("output", default_output(spec));
  o.jobs = a.optional_integer("jobs").value_or(0);
  if (a.has("shard")) {
    const std::string s = a.text("shard");
    const auto slash = s.find('/');
    int k = 0, n = 0;
    try {
      if (slash == std::string::npos) throw std::invalid_argument("no slash");
      std::size_t p1 = 0, p2 = 0;
      k = std::stoi(s.substr(0, slash), &p1);
      n = std::stoi(s.substr(slash + 1), &p2);
      if (p1 != slash || p2 != s.size() - slash - 1) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw InputError("beamid study: --shard = '" + s + "': must be K/N with integers 1 <= K <= N");
    }
    o.shard_index = k;
    o.shard_count = n;
  }
  if (auto e = study::validation_error(o)) throw InputError("beamid study: --" + *e);
  const study::RunSummary summary = study::run_study(spec, o, std::cerr, isatty(STDERR_FILENO) != 0);
  out << "study,units,computed,reused,failed_cases,tables\n"
      << spec.name << "," << summary.units << "," << summary.computed << "," << summary.reused << ","
      << summary.failed << "," << (summary.tables ? "written" : "pending") << "\n";
  return 0;
}

int run_merge(const Args& all, std::ostream& out) {
  auto [file, args] = split_study_file(all);
  const io::Arguments a("merge", args,
                        {kHelpFlag,
                         {"output", true, "results folder of the merged study (default results/<study name>)"},
                         {"shards", true, "comma-separated results folders of the shard runs"}});
  if (wants_help(a, out, "STUDY.toml --shards DIR1,DIR2,... [--output DIR]")) return 0;
  if (file.empty()) throw InputError("beamid merge: missing the study file: beamid merge STUDY.toml --shards ...");
  const study::StudySpec spec = study::load_study(file);
  const std::string output = a.text_or("output", default_output(spec));
  const study::Store store(output + "/store", io::commit_label());
  std::stringstream list(a.text("shards"));
  std::string dir;
  int records = 0;
  while (std::getline(list, dir, ',')) {
    if (dir.empty()) continue;
    if (!std::filesystem::is_directory(dir + "/store"))
      throw InputError("beamid merge: --shards: '" + dir + "' has no store/ folder: must be the --output of a shard run");
    if (std::filesystem::equivalent(dir + "/store", output + "/store")) continue;
    records += store.absorb(dir + "/store");
  }
  study::write_tables_from_store(spec, output);
  out << "study,records_merged,output\n" << spec.name << "," << records << "," << output << "\n";
  return 0;
}

int run_real(const Args& all, std::ostream& out) {
  auto [file, args] = split_study_file(all);
  const io::Arguments a("real", args,
                        {kHelpFlag, {"output", true, "results folder (default results/<study name>)"}});
  if (wants_help(a, out, "STUDY.toml [--output DIR]")) return 0;
  if (file.empty()) throw InputError("beamid real: missing the study file: beamid real STUDY.toml [--output DIR]");
  const study::RealStudySpec spec = study::load_real_study(file);
  const std::string output = a.text_or("output", "results/" + spec.name);
  const int failed = study::run_real_study(spec, output, std::cerr);
  out << "study,fits,failed,output\n" << spec.name << "," << spec.costs.size() << "," << failed << "," << output << "\n";
  return failed > 0 ? 3 : 0;
}

}  // namespace beamid::apps
