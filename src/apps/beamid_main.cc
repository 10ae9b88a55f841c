// beamid: command-line entry point (apps/cli.h): the subcommands of apps/commands.h; any error is one line on
// stderr ("beamid: ...") and a non-zero exit status (2 for bad input, 3 for a numerical failure).
#include <iostream>
#include <string>
#include <vector>

#include "apps/cli.h"

int main(int argc, char** argv) {
  return beamid::apps::run_command_line(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
}
