// The beamid subcommands. Each takes the arguments after its name, writes its result to `out`, and throws
// InputError / NumericalError with a one-line message on failure (beamid_main.cc prints it and exits non-zero).
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace beamid::apps {

using Args = std::vector<std::string>;

// beamid modes --beam <preset|file.toml> (--elements N [--undamped] | --exact) [--count K]
int run_modes(const Args& args, std::ostream& out);
// beamid simulate --beam B --elements N [experiment flags] [--integrator fast|cvode] [--rtol R --atol A]
int run_simulate(const Args& args, std::ostream& out);
// beamid spikes --data FILE.csv --spikes NM [--window NAME]: CSV spike,bin,frequency_hz,magnitude,n_left,n_right
int run_spikes(const Args& args, std::ostream& out);
// beamid cost --data FILE.csv --prediction FILE.csv --cost time|spike|spike-smooth --spikes NM [--eps1 X --eps2 Y]
int run_cost(const Args& args, std::ostream& out);
// beamid fit --data FILE.csv --beam B --elements N --estimate KEYS --cost NAME [...]: CSV
// parameter,estimate,standard_error,start,lower,upper; exit 3 when the fit failed
int run_fit(const Args& args, std::ostream& out);
// beamid verify --output DIR: forward-model verification tables (see verification.h)
int run_verify(const Args& args, std::ostream& out);
// beamid report --update REPORT.md [--results DIR]: refresh the generated blocks
int run_report(const Args& args, std::ostream& out);

// beamid study STUDY.toml [--jobs J] [--output DIR] [--shard K/N]: run a study (tables in results/<study>/)
int run_study(const Args& args, std::ostream& out);
// beamid merge STUDY.toml --shards DIR1,DIR2 [--output DIR]: combine shard runs into the tables of one run
int run_merge(const Args& args, std::ostream& out);

// beamid real STUDY.toml [--output DIR]: fit a measured free-decay record with each cost (study/real_study.h)
int run_real(const Args& args, std::ostream& out);

// The overview printed by "beamid --help".
std::string overview();

}  // namespace beamid::apps
