// beamid: command-line entry point (apps/cli.h): the subcommands of apps/commands.h; any error is one line on
// stderr ("beamid: ...") and a non-zero exit status (2 for bad input, 3 for a numerical failure, 1 when the results
// could not be written: standard output full, closed or on a failing device).
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "apps/cli.h"

int main(int argc, char** argv) {
  const int status = beamid::apps::run_command_line(std::vector<std::string>(argv, argv + argc), std::cout, std::cerr);
  // A write to stdout that failed (a full disk, /dev/full) leaves the stream failed; the results are incomplete, so
  // the run has failed whatever the command returned. The reason is errno: that of the final flush when it is the
  // write that failed, else (usually) that of the earlier failed write.
  if (std::cout) errno = 0;
  std::cout.flush();
  if (!std::cout) {
    const int error = errno;
    std::cerr << "beamid: standard output: cannot write the results: "
              << (error != 0 ? std::strerror(error) : "the write failed") << "\n";
    return 1;
  }
  return status;
}
