// The standard streams over write(2): the results' stream names its failure, the diagnostics' stream survives one.
#include "io/standard_streams.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

namespace beamid::io {
namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(StandardStreams, ADiagnosticThatCannotBeWrittenDoesNotSilenceTheNext) {
  // The twenty-second pass's P12: std::cerr kept a failed write's badbit, and the run's final error was dropped.
  // The stream writes to one descriptor, first /dev/full (every write fails with ENOSPC), then a file.
  const int fd = ::open("/dev/full", O_WRONLY);
  ASSERT_GE(fd, 0);
  DiagnosticOutput buffer(fd);
  std::ostream diagnostics(&buffer);
  diagnostics << "beamid: a note nobody can read\n";
  EXPECT_TRUE(diagnostics.good());
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "beamid_standard_streams_test.txt";
  const int target = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(target, 0);
  ASSERT_EQ(::dup2(target, fd), fd);
  ::close(target);
  diagnostics << "beamid: the final error" << '\n';
  EXPECT_TRUE(diagnostics.good());
  EXPECT_EQ(read_all(file), "beamid: the final error\n");
  ::close(fd);
  std::filesystem::remove(file);
}

TEST(StandardStreams, TheResultsStreamKeepsTheFirstFailuresReason) {
  // A full disk is reported as such (ENOSPC), whatever errno later calls leave behind.
  const int fd = ::open("/dev/full", O_WRONLY);
  ASSERT_GE(fd, 0);
  RecordingOutput buffer(fd);
  std::ostream results(&buffer);
  results << "EI_Nm2 = 1.0\n" << std::flush;
  errno = ERANGE;
  results << "rho_kgm = 2.0\n" << std::flush;
  EXPECT_EQ(buffer.error(), ENOSPC);
  ::close(fd);
}

}  // namespace
}  // namespace beamid::io
