// What every layer uses: stable hashes and seeds, one-line errors, name registries that refuse unknown names.
#include <gtest/gtest.h>

#include <cstdint>
#include <new>

#include "core/errors.h"
#include "core/hash.h"
#include "core/names.h"
#include "core/scratch.h"

namespace beamid::core {
namespace {

// The pencil's Hankel buffer: reused while large enough (the point of it), grown when not, aligned for Eigen's
// vectorised access (and on a 2 MB huge-page boundary), writable over its whole capacity, and returned by release().
TEST(ScratchBuffer, ReusesGrowsAlignsAndReleases) {
  ScratchBuffer buffer;
  EXPECT_EQ(buffer.capacity(), 0u);
  double* first = buffer.reserve(1000);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(first) % (std::uintptr_t{2} << 20), 0u);
  for (std::size_t i = 0; i < 1000; ++i) first[i] = static_cast<double>(i);
  EXPECT_EQ(buffer.reserve(10), first);  // smaller: the same block, contents kept
  EXPECT_EQ(first[999], 999.0);
  const std::size_t large = std::size_t{3} << 20;  // 24 MB
  double* grown = buffer.reserve(large);
  EXPECT_EQ(buffer.capacity(), large);
  grown[0] = 1, grown[large - 1] = 2;
  EXPECT_EQ(grown[0] + grown[large - 1], 3.0);
  buffer.release();
  EXPECT_EQ(buffer.capacity(), 0u);
  EXPECT_THROW(buffer.reserve(SIZE_MAX / 4), std::bad_alloc);
}

TEST(Hash, SeedsAreMixedAndNamedStreamsDiffer) {
  EXPECT_NE(mix64(1), mix64(2));
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);   // the FNV-1a offset basis
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);  // published FNV-1a test vector
  EXPECT_NE(derive_seed(1, "noise"), derive_seed(1, "start"));
  EXPECT_EQ(derive_seed(5, "x"), derive_seed(5, "x"));
}

TEST(NameSet, RequireReturnsANameAndRefusesAnythingElseListingTheNames) {
  const NameSet set({{"time", "least squares"}, {"spike", "(3.5)"}});
  EXPECT_EQ(set.require("cost", "spike"), "spike");
  try {
    set.require("cost", "spikes");
    FAIL() << "an unknown name was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "cost = 'spikes': must be one of time, spike");
  }
  EXPECT_EQ(set.alternatives(), "time | spike");
}

TEST(Errors, MessagesAreOneLineAndNumbersRoundTrip) {
  EXPECT_STREQ(InputError("a\nb\tc\x01").what(), "a\\nb\\tc\\x01");
  EXPECT_EQ(format_value(0.491), "0.491");
  EXPECT_EQ(format_value(1e-300), "1e-300");
  EXPECT_EQ(format_value(-std::numeric_limits<double>::infinity()), "-inf");
  // A 120 KB value quoted in a message: the line keeps where (head) and the constraint (tail).
  const std::string message = "beamid fit: --estimate = '" + std::string(120000, 'x') + "': must be a list of keys";
  const std::string line = InputError(message).what();
  EXPECT_LT(line.size(), 1700u);
  EXPECT_EQ(line.rfind("beamid fit: --estimate = 'xxx", 0), 0u);
  EXPECT_NE(line.find("bytes cut"), std::string::npos);
  EXPECT_EQ(line.substr(line.size() - 25), "': must be a list of keys");
  // Two-byte characters (U+00E9) throughout: no cut falls inside one, so the line is valid UTF-8.
  std::string accents;
  for (int i = 0; i < 3000; ++i) accents += "\xc3\xa9";
  const std::string cut = InputError("--estimate = '" + accents + "'").what();
  int continuation_run = 0;
  for (std::size_t i = 0; i < cut.size(); ++i) {
    const auto u = static_cast<unsigned char>(cut[i]);
    if ((u & 0xC0) == 0x80) {
      ASSERT_GT(i, 0u);
      ASSERT_EQ(static_cast<unsigned char>(cut[i - 1]), 0xC3) << "a continuation byte without its lead, at " << i;
      ++continuation_run;
    } else if (u == 0xC3) {
      ASSERT_LT(i + 1, cut.size());
      ASSERT_EQ(static_cast<unsigned char>(cut[i + 1]) & 0xC0, 0x80)
          << "a lead byte without its continuation, at " << i;
    }
  }
  EXPECT_GT(continuation_run, 0);
}

}  // namespace
}  // namespace beamid::core
