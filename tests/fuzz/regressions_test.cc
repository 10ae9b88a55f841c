// Every input in tests/fuzz/corpus/<target>/ (the seeds `make fuzz` starts from, and every input that once crashed
// a reader, kept as a regression) through its fuzz target: each must end in a value or a one-line error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz_targets.h"

namespace beamid::fuzz {
namespace {
namespace fs = std::filesystem;

TEST(FuzzRegressions, EveryCorpusInputEndsInAValueOrAOneLineError) {
  int inputs = 0;
  for (const Target& t : targets()) {
    const fs::path dir = fs::path(BEAMID_SOURCE_DIR) / "tests/fuzz/corpus" / t.name;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    for (const auto& entry : fs::directory_iterator(dir)) {
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      EXPECT_NO_THROW(t.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()))
          << t.name << ": " << entry.path();
      ++inputs;
    }
  }
  EXPECT_GE(inputs, 10);  // seeds for every target at least
}

}  // namespace
}  // namespace beamid::fuzz
