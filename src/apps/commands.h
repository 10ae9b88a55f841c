// The beamid commands: one registry (name, summary, flags, the function that runs it) from which the command line
// (cli.h) builds its subcommands, its --help and the list of commands an unknown name is answered with. Each
// function writes its result to `out` and throws InputError / NumericalError with a one-line message on failure.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "apps/flags.h"

namespace beamid::apps {

struct Command {
  std::string name;
  std::string summary;  // one line for the overview
  std::vector<FlagSpec> flags;
  std::vector<std::pair<std::string, std::string>> excludes;  // flags that may not be given together
  std::function<int(const Flags&, std::ostream&)> run;
};

// Every command, in the order of the overview.
const std::vector<Command>& commands();
// The overview printed by "beamid --help" (and by "beamid" alone).
std::string overview();

// beamid modes --beam B (--elements N [--undamped] | --exact) [--count K]: mode,frequency_hz[,damping_ratio]
int run_modes(const Flags& flags, std::ostream& out);
// beamid simulate --beam B --elements N [experiment flags] [--integrator fast|cvode]: t_s,<output>
int run_simulate(const Flags& flags, std::ostream& out);
// beamid system --beam B --elements N [experiment flags]: M, C, K, load, sensor and sampling as JSON
int run_system(const Flags& flags, std::ostream& out);
// beamid spikes --data FILE --spikes NM: spike,bin,frequency_hz,magnitude,n_left,n_right
int run_spikes(const Flags& flags, std::ostream& out);
// beamid cost --data FILE --prediction FILE --cost NAME: the cost value
int run_cost(const Flags& flags, std::ostream& out);
// beamid fit --data FILE --beam B --elements N --estimate KEYS --cost NAME:
// parameter,estimate,standard_error,...,status; exit 3 when the fit failed
int run_fit(const Flags& flags, std::ostream& out);
// beamid crb --beam B --elements N --estimate KEYS (--noise-sd S | --noise-level L) [experiment flags]:
// parameter,value,crb_sd,crb_relative_sd (the Cramér-Rao bound, fit/cramer_rao.h)
int run_crb(const Flags& flags, std::ostream& out);
// beamid design --beam B --elements N --estimate KEYS (--noise-sd S | --noise-level L) --sensor-x LIST [--sensors K]
// [--force-x LIST] [--pulse-width LIST] [--dt LIST] [--samples LIST] [--criterion D|A|KEY]: every candidate, best
// first: rank,sensors_x_m,force_x_m,pulse_width_s,dt_s,samples,criterion,relative_sd_<key>...,status
// (fit/experiment_design.h)
int run_design(const Flags& flags, std::ostream& out);
// beamid modal-id --data FILE [--modes K] [--order M] [--min-frequency F] [--max-frequency F]:
// mode,frequency_hz,damping_ratio,amplitude,phase_rad (matrix pencil, signal/matrix_pencil.h)
int run_modal_id(const Flags& flags, std::ostream& out);
// beamid verify --output DIR: forward-model verification tables (see verification.h)
int run_verify(const Flags& flags, std::ostream& out);
// beamid report --update REPORT.md [--results DIR]: refresh the generated blocks
int run_report(const Flags& flags, std::ostream& out);
// beamid study STUDY.toml [--jobs J] [--output DIR] [--shard K/N]: run a study (tables in results/<study>/)
int run_study(const Flags& flags, std::ostream& out);
// beamid merge STUDY.toml --shards DIR1,DIR2 [--output DIR]: combine shard runs into the tables of one run
int run_merge(const Flags& flags, std::ostream& out);
// beamid real STUDY.toml [--output DIR]: fit a measured free-decay record with each cost (study/real/real_study.h)
int run_real(const Flags& flags, std::ostream& out);

// The flags of the commands that share them.
std::vector<FlagSpec> spike_flags();
std::vector<FlagSpec> import_flags();
std::vector<FlagSpec> cost_flags(bool required);
std::vector<FlagSpec> fit_flags();
std::vector<FlagSpec> crb_flags();
std::vector<FlagSpec> design_flags();
std::vector<FlagSpec> modal_id_flags();
std::vector<FlagSpec> study_flags();
std::vector<FlagSpec> merge_flags();
std::vector<FlagSpec> real_flags();

}  // namespace beamid::apps
