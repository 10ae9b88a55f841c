// The command registry (commands.h): what each command is called, what it does in a line, and its flags.
#include <algorithm>
#include <limits>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "core/limits.h"
#include "io/provenance.h"

namespace beamid::apps {
namespace {

FlagSpec beam_flag() {
  return text_flag("beam", "preset (banks-aluminium, thick-steel) or a TOML file with a [beam] or [geometry] table",
                   true);
}
FlagSpec elements_flag(bool required) {
  return integer_flag("elements", "Galerkin order N (cubic B-spline elements)", core::kMinElements, core::kMaxElements,
                      required);
}

// The flags less one a command does not read (cost takes no --welch: it compares two records, it picks on neither).
std::vector<FlagSpec> without(std::vector<FlagSpec> flags, const std::string& name) {
  flags.erase(std::remove_if(flags.begin(), flags.end(), [&](const FlagSpec& f) { return f.name == name; }),
              flags.end());
  return flags;
}

std::vector<FlagSpec> joined(std::vector<FlagSpec> a, const std::vector<FlagSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// simulate's flags: the model and experiment, the integrator, the response's noise and the force column.
std::vector<FlagSpec> simulate_flags() {
  return joined(
      joined({beam_flag(), elements_flag(true)}, experiment_flag_specs()),
      {text_flag("integrator", "fast | cvode (default fast)"),
       number_flag("rtol", "CVODE relative tolerance (default 1e-10)"),
       number_flag("atol", "CVODE absolute tolerance (default: rtol times the state's natural size)"),
       integer_flag("max-order", "CVODE BDF order limit (default 5)", 1, 5),
       number_flag("noise-level",
                   "add white Gaussian noise of this many times the signal's RMS, e.g. 0.01 (default "
                   "0: none)"),
       text_flag("noise-model",
                 "the noise's colour: white | ar:a1,a2,... | power:alpha (1/f^alpha to "
                 "Nyquist), at --noise-level (default white)"),
       integer_flag("seed", "seed of the noise (default 1)", 0, std::numeric_limits<int>::max()),
       switch_flag("force-column", "also print the pulse's force at each sample, force_N (a hammer's force channel)"),
       number_flag("force-noise-level", "white noise on the force column, this many times its RMS (default 0)"),
       switch_flag("verbose", "say on stderr what ran, with the integrator statistics")});
}

std::vector<Command> make_commands() {
  std::vector<Command> c;
  c.push_back(
      {"modes",
       "natural frequencies and damping ratios (Galerkin or exact)",
       {beam_flag(), elements_flag(false), switch_flag("exact", "exact Timoshenko frequencies from the determinant"),
        switch_flag("undamped", "undamped Galerkin frequencies (damping_ratio 0)"),
        integer_flag("count", "number of modes (default: all underdamped Galerkin modes, 4 exact)", 1,
                     std::numeric_limits<int>::max())},
       {{"exact", "elements"}, {"exact", "undamped"}},
       run_modes});
  c.push_back(
      {"simulate", "sampled sensor signal of a pulse or pluck experiment, as CSV", simulate_flags(), {}, run_simulate});
  c.push_back({"system",
               "the Galerkin matrices M, C, K with the load, sensor and sampling of an experiment, as JSON",
               joined({beam_flag(), elements_flag(true)}, experiment_flag_specs()),
               {},
               run_system});
  c.push_back(
      {"spikes",
       "the DFT spikes of a record, with their 20 % supports and the peaks skipped as artefacts",
       joined(
           joined({text_flag("data", "record: CSV, LabVIEW .lvm, text table (.txt, .dat), .npy, .mat or UFF 58", true),
                   text_flag("detrend", "none | mean | linear: removed before the DFT (default linear)")},
                  spike_flags()),
           import_flags()),
       {},
       run_spikes});
  c.push_back(
      {"cost",
       "the time, spike, spike-smooth or freq-band cost of a prediction against data",
       joined(joined({text_flag("data",
                                "record of the data: CSV, LabVIEW .lvm, text table (.txt, .dat), .npy, .mat or UFF 58",
                                true),
                      text_flag("prediction",
                                "CSV record of the model prediction, same sampling (--start and --duration cut it as "
                                "they cut --data)",
                                true)},
                     without(cost_flags(true), "welch")),
              import_flags()),
       {},
       run_cost});
  c.push_back({"fit",
               "identify beam parameters from a record (NLopt or Ceres; direct, staged, continuation or hybrid)",
               fit_flags(),
               {},
               run_fit});
  c.push_back({"crb",
               "Cramer-Rao bound of chosen parameters for an experiment in white Gaussian noise",
               crb_flags(),
               {{"noise-sd", "noise-level"}},
               run_crb});
  c.push_back(
      {"design",
       "rank candidate experiments (sensor, force, pulse, sampling) by the Fisher information of chosen parameters",
       design_flags(),
       {{"noise-sd", "noise-level"}},
       run_design});
  c.push_back({"modal-id",
               "modal frequencies, damping ratios and amplitudes of a free-decay record (matrix pencil)",
               modal_id_flags(),
               {},
               run_modal_id});
  c.push_back({"verify",
               "forward-model verification tables (Galerkin vs exact, fast vs CVODE, modal truncation)",
               {text_flag("output", "folder for the CSV and Markdown tables", true)},
               {},
               run_verify});
  c.push_back({"report",
               "refresh the generated blocks of REPORT.md from results/",
               {text_flag("update", "the Markdown report whose generated blocks are refreshed", true),
                text_flag("results", "folder the block names are relative to (default results)")},
               {},
               run_report});
  c.push_back({"study",
               "run a study file (studies/*.toml): cases in parallel, resumable, tables in results/<study>/",
               study_flags(),
               {},
               run_study});
  c.push_back({"merge",
               "combine the results of a study's shards (--shard K/N) into the tables of one run",
               merge_flags(),
               {},
               run_merge});
  c.push_back({"real",
               "fit a measured free-decay record with each cost (studies/real-steel.toml)",
               real_flags(),
               {},
               run_real});
  return c;
}

}  // namespace

const std::vector<Command>& commands() {
  static const std::vector<Command> all = make_commands();
  return all;
}

std::string overview() {
  std::string s = "beamid " + io::version() + " (commit " + io::commit_label() +
                  "): identification of Timoshenko-beam parameters (Banks & Wang 1993)\n\n"
                  "usage: beamid COMMAND [flags]     (beamid COMMAND --help for its flags)\n";
  for (const Command& c : commands()) {
    std::string name = "  " + c.name;
    name.resize(13, ' ');
    s += name + c.summary + "\n";
  }
  return s;
}

}  // namespace beamid::apps
