// beamid: command-line entry point (apps/cli.h): the subcommands of apps/commands.h; any error is one line on
// stderr ("beamid: ...") and a non-zero exit status (2 for bad input, 3 for a numerical failure, 1 when the results
// could not be written: standard output full, closed or on a failing device).
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "apps/cli.h"
#include "core/allocator.h"
#include "io/files.h"
#include "io/standard_streams.h"

int main(int argc, char** argv) {
  beamid::core::keep_freed_memory();    // core/allocator.h
  beamid::io::guard_standard_output();  // no input is read from the file the results go to (io/files.h)
  beamid::io::RecordingOutput output;   // io/standard_streams.h
  beamid::io::DiagnosticOutput diagnostics;
  std::streambuf* const original = std::cout.rdbuf(&output);
  std::streambuf* const original_error = std::cerr.rdbuf(&diagnostics);
  int status = beamid::apps::run_command_line(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
  // A write to stdout that failed (a full disk, /dev/full) leaves the results incomplete: the run has failed, whatever
  // the command returned.
  std::cout.flush();
  if (!std::cout || output.error() != 0) {
    // Named with the command, as every other error is ("beamid modes: ...": the seventh pass's O07): the first
    // argument that is no flag.
    std::string command;
    for (int i = 1; i < argc && command.empty(); ++i)
      if (argv[i][0] != '-') command = argv[i];
    std::cerr << "beamid" << (command.empty() ? "" : " " + command) << ": standard output: cannot write the results: "
              << (output.error() != 0 ? std::strerror(output.error()) : "the write failed") << "\n";
    status = 1;
  }
  std::cout.rdbuf(original);
  std::cerr.rdbuf(original_error);
  return status;
}
