// The process's standard output and error as stream buffers over write(2): the results' stream keeps the first
// failure's errno (so a full disk is reported as such), and the diagnostics' stream never fails (so one lost message
// does not silence the rest). apps/beamid_main.cc installs both.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <streambuf>

namespace beamid::io {

// Buffered writes to `fd`; error() is the errno of the first write that failed (0 if none). A failed write's buffer
// is dropped: the results are incomplete, and the caller fails the run when error() is set.
class RecordingOutput : public std::streambuf {
 public:
  explicit RecordingOutput(int fd = STDOUT_FILENO);
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  bool drain();
  int fd_;
  char buffer_[1 << 16];
  int error_ = 0;
};

// Unbuffered writes to `fd` that always report success: a message that cannot be written is lost alone (std::cerr
// kept a failed write's badbit, and every later message, the run's final error included, was silently dropped: the
// twenty-second pass's P12).
class DiagnosticOutput : public std::streambuf {
 public:
  explicit DiagnosticOutput(int fd = STDERR_FILENO) : fd_(fd) {}

 protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* text, std::streamsize n) override;

 private:
  void write_all(const char* at, std::size_t n) const;
  int fd_;
};

}  // namespace beamid::io
