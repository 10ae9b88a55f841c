// The beamid command line: CLI11 subcommands built from the command registry (commands.h), generated --help, and
// every error as one line on `err`, "beamid: <command>: <what>: <constraint>", with exit status 2 for bad input
// (flags, files, values), 3 for a numerical failure and 1 for an internal error.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "apps/flags.h"

namespace beamid::apps {

// `args` as main receives them (args[0] is the program). Returns the exit status.
int run_command_line(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
// Parses the command line as run_command_line does, without running the command (0 when it would run; for the
// command-line fuzzer, which must not start the long computations a valid command line can ask for).
int check_command_line(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
// One command's flags parsed exactly as the command line parses them (`arguments`: what follows the command's name),
// for programs that call the commands' computations directly (the Python package): an InputError carries the message
// the command line would print after "beamid: ", e.g. "beamid fit: unknown flag --foo (fit --help lists them)".
Flags parse_flags(const std::string& command, const std::vector<std::string>& arguments);
// What `beamid <command> --help` prints (InputError for an unknown command).
std::string command_help(const std::string& command);

}  // namespace beamid::apps
