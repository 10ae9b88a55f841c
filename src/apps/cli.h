// The beamid command line: CLI11 subcommands built from the command registry (commands.h), generated --help, and
// every error as one line on `err`, "beamid: <command>: <what>: <constraint>", with exit status 2 for bad input
// (flags, files, values), 3 for a numerical failure and 1 for an internal error.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace beamid::apps {

// `args` as main receives them (args[0] is the program). Returns the exit status.
int run_command_line(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
// Parses the command line as run_command_line does, without running the command (0 when it would run; for the
// command-line fuzzer, which must not start the long computations a valid command line can ask for).
int check_command_line(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace beamid::apps
