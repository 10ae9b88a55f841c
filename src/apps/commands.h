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
// beamid verify --output DIR: forward-model verification tables (see verification.h)
int run_verify(const Args& args, std::ostream& out);
// beamid report --update REPORT.md [--results DIR]: refresh the generated blocks
int run_report(const Args& args, std::ostream& out);

// The overview printed by "beamid --help".
std::string overview();

}  // namespace beamid::apps
