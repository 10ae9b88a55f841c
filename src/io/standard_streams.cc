// Standard streams over write(2): see standard_streams.h.
#include "io/standard_streams.h"

#include <cerrno>

namespace beamid::io {

RecordingOutput::RecordingOutput(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }

RecordingOutput::int_type RecordingOutput::overflow(int_type c) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int RecordingOutput::sync() { return drain() ? 0 : -1; }

// The errno is kept at the failing write: read after the run, errno itself may be that of any later call (a
// strtod's ERANGE was reported as the reason a full disk refused the results).
bool RecordingOutput::drain() {
  const char* at = pbase();
  while (at < pptr()) {
    const ssize_t written = ::write(fd_, at, static_cast<std::size_t>(pptr() - at));
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

DiagnosticOutput::int_type DiagnosticOutput::overflow(int_type c) {
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    const char byte = traits_type::to_char_type(c);
    write_all(&byte, 1);
  }
  return traits_type::not_eof(c);
}

std::streamsize DiagnosticOutput::xsputn(const char* text, std::streamsize n) {
  write_all(text, static_cast<std::size_t>(n));
  return n;  // as written, whatever became of it
}

void DiagnosticOutput::write_all(const char* at, std::size_t n) const {
  while (n > 0) {
    const ssize_t written = ::write(fd_, at, n);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return;
    at += written;
    n -= static_cast<std::size_t>(written);
  }
}

}  // namespace beamid::io
