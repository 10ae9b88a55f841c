// REPORT.md generated blocks: only the text between matching markers changes.
#include "io/report_blocks.h"

#include <gtest/gtest.h>

#include "core/errors.h"

namespace beamid::io {
namespace {

const std::string kReport =
    "# Report\nprose\n<!-- BEGIN GENERATED a/x -->\nold x\n<!-- END GENERATED a/x -->\nmiddle\n"
    "<!-- BEGIN GENERATED b -->\nold b\nold b2\n<!-- END GENERATED b -->\nend\n";

TEST(ReportBlocks, ReplacesOnlyNamedBlocks) {
  EXPECT_EQ(block_names(kReport, "R.md"), (std::vector<std::string>{"a/x", "b"}));
  const std::string out = replace_blocks(kReport, {{"b", "new b\n"}}, "R.md");
  EXPECT_EQ(out,
            "# Report\nprose\n<!-- BEGIN GENERATED a/x -->\nold x\n<!-- END GENERATED a/x -->\nmiddle\n"
            "<!-- BEGIN GENERATED b -->\nnew b\n<!-- END GENERATED b -->\nend\n");
  // Idempotent: applying the same content again changes nothing.
  EXPECT_EQ(replace_blocks(out, {{"b", "new b\n"}}, "R.md"), out);
  EXPECT_EQ(replace_blocks(kReport, {}, "R.md"), kReport);
}

TEST(ReportBlocks, AFileWithWindowsLineEndsIsUpdatedAndKeepsThem) {
  // The tenth pass's RP_6: markers ending in CR were no markers, and nothing was refreshed without a word.
  std::string crlf;
  for (char c : kReport) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(block_names(crlf, "R.md"), (std::vector<std::string>{"a/x", "b"}));
  EXPECT_EQ(replace_blocks(crlf, {{"b", "new b\n"}}, "R.md"),
            "# Report\r\nprose\r\n<!-- BEGIN GENERATED a/x -->\r\nold x\r\n<!-- END GENERATED a/x -->\r\nmiddle\r\n"
            "<!-- BEGIN GENERATED b -->\r\nnew b\r\n<!-- END GENERATED b -->\r\nend\r\n");
}

TEST(ReportBlocks, MalformedMarkersAreLocatedErrors) {
  EXPECT_THROW(block_names("<!-- BEGIN GENERATED a -->\n", "R.md"), InputError);
  try {
    block_names("x\n<!-- BEGIN GENERATED a -->\n<!-- END GENERATED b -->\n", "R.md");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "R.md:3: END GENERATED b does not close block 'a'");
  }
}

}  // namespace
}  // namespace beamid::io
