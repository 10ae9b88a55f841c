// beamid: command-line entry point (apps/cli.h): the subcommands of apps/commands.h; any error is one line on
// stderr ("beamid: ...") and a non-zero exit status (2 for bad input, 3 for a numerical failure, 1 when the results
// could not be written: standard output full, closed or on a failing device).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <streambuf>
#include <string>
#include <vector>

#include "apps/cli.h"
#include "core/allocator.h"
#include "io/files.h"

namespace {

// Standard output through write(2) with a buffer of its own, keeping the errno of the first write that failed: read
// after the run, errno itself may be that of any later call (a strtod's ERANGE was reported as the reason a full
// disk refused the results).
class RecordingOutput : public std::streambuf {
 public:
  RecordingOutput() { setp(buffer_, buffer_ + sizeof buffer_); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* at = pbase();
    while (at < pptr()) {
      const ssize_t written = ::write(STDOUT_FILENO, at, static_cast<std::size_t>(pptr() - at));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) {
        if (error_ == 0) error_ = written < 0 ? errno : EIO;
        setp(buffer_, buffer_ + sizeof buffer_);  // the rest is lost: the run has failed
        return false;
      }
      at += written;
    }
    setp(buffer_, buffer_ + sizeof buffer_);
    return true;
  }
  char buffer_[1 << 16];
  int error_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  beamid::core::keep_freed_memory();    // core/allocator.h
  beamid::io::guard_standard_output();  // no input is read from the file the results go to (io/files.h)
  RecordingOutput output;
  std::streambuf* const original = std::cout.rdbuf(&output);
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
  return status;
}
