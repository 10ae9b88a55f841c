// REPORT.md generated blocks: only the text between matching markers changes.
#include "io/report_blocks.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.h"

namespace beamid::io {
namespace {

const std::string kReport =
    "# Report\nprose\n<!-- BEGIN GENERATED a/x -->\nold x\n<!-- END GENERATED a/x -->\nmiddle\n"
    "<!-- BEGIN GENERATED b -->\nold b\nold b2\n<!-- END GENERATED b -->\nend\n";

TEST(ReportBlocks, ReplacesOnlyNamedBlocks) {
  EXPECT_EQ(block_names(kReport, "R.md"), (std::vector<std::string>{"a/x", "b"}));
  // Each block's BEGIN line, 1-based, for errors that name it (the twenty-first pass's P9).
  EXPECT_EQ(block_lines(kReport, "R.md"), (std::vector<std::size_t>{3, 7}));
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

TEST(ReportBlocks, LinesOutsideTheRefreshedBlocksAreKeptByteForByte) {
  // The twenty-second pass's P9: the first line's end was given to every line, so a file with mixed ends lost its
  // CRs outside the blocks, and an unterminated last line gained a newline.
  const std::string mixed =
      "# Report\nprose\r\n<!-- BEGIN GENERATED b -->\r\nold\r\n<!-- END GENERATED b -->\nmiddle\r\nend";
  EXPECT_EQ(
      replace_blocks(mixed, {{"b", "new 1\nnew 2\n"}}, "R.md"),
      "# Report\nprose\r\n<!-- BEGIN GENERATED b -->\r\nnew 1\r\nnew 2\r\n<!-- END GENERATED b -->\nmiddle\r\nend");
  EXPECT_EQ(replace_blocks(mixed, {}, "R.md"), mixed);
}

TEST(ReportBlocks, AByteOrderMarkBeforeTheFirstMarkerIsKeptAndTheMarkerFound) {
  // An editor's UTF-8 byte-order mark hid a first-line marker: "END GENERATED a without a BEGIN" at line 3 (the
  // second adversarial pass of 2026-11-28, P7).
  const std::string bom = "\xEF\xBB\xBF<!-- BEGIN GENERATED a -->\nold\n<!-- END GENERATED a -->\n";
  EXPECT_EQ(block_names(bom, "R.md"), (std::vector<std::string>{"a"}));
  EXPECT_EQ(replace_blocks(bom, {{"a", "new\n"}}, "R.md"),
            "\xEF\xBB\xBF<!-- BEGIN GENERATED a -->\nnew\n<!-- END GENERATED a -->\n");
}

TEST(ReportBlocks, MalformedMarkersAreLocatedErrors) {
  // A marker with text beside it is no marker, and said so at its line.
  try {
    block_names("x\n<!-- BEGIN GENERATED a --> junk\n<!-- END GENERATED a -->\n", "R.md");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("R.md:2: a GENERATED marker with text beside it", 0), 0u) << e.what();
  }
  EXPECT_THROW(block_names("<!-- BEGIN GENERATED a -->\n", "R.md"), InputError);
  try {
    block_names("x\n<!-- BEGIN GENERATED a -->\n<!-- END GENERATED b -->\n", "R.md");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "R.md:3: END GENERATED b does not close block 'a'");
  }
  // The twenty-third pass's P6, P7, P2: a marker without a name, an indented marker (no marker, and the error named
  // its partner's line, or nothing was said), and CR-only line ends (no block found, exit 0) are each named at their
  // line.
  const auto error_of = [](const std::string& text) {
    try {
      block_names(text, "R.md");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("x\n<!-- BEGIN GENERATED  -->\n"),
            "R.md:2: a GENERATED marker without a block name: '<!-- BEGIN GENERATED name -->'");
  EXPECT_EQ(error_of("<!-- END GENERATED -->\n"),
            "R.md:1: a GENERATED marker without a block name: '<!-- BEGIN GENERATED name -->'");
  EXPECT_EQ(error_of("  <!-- BEGIN GENERATED a -->\nold\n<!-- END GENERATED a -->\n"),
            "R.md:1: an indented GENERATED marker: a marker starts its line, with nothing before it");
  EXPECT_EQ(error_of("<!-- BEGIN GENERATED a -->\nold\n\t<!-- END GENERATED a -->\n"),
            "R.md:3: an indented GENERATED marker: a marker starts its line, with nothing before it");
  EXPECT_EQ(error_of("# Report\r<!-- BEGIN GENERATED a -->\rold\r<!-- END GENERATED a -->\r"),
            "R.md:1: a carriage return (CR) alone ends or splits this line: lines end in LF or CR LF (convert the "
            "file)");
  EXPECT_EQ(error_of("# Report\r\nok\r\nbad\rline\r\n"),
            "R.md:3: a carriage return (CR) alone ends or splits this line: lines end in LF or CR LF (convert the "
            "file)");
  EXPECT_THROW(replace_blocks("a\rb\n", {}, "R.md"), InputError);
  // A line meant as a marker but misspelt found no block, "0 refreshed" with exit 0 (the twenty-fourth pass's adv56
  // P5); in a block's source it broke the next refresh (P2): each is named at its line.
  for (const std::string misspelt : {"<!--BEGIN GENERATED x-->", "<!-- begin generated x -->",
                                     "<!--  END  GENERATED x -->", "<!-- BEGIN  GENERATED x -->"})
    EXPECT_EQ(error_of("x\n" + misspelt + "\n").rfind("R.md:2: a ", 0), 0u) << misspelt << ": " << error_of(misspelt);
  // And the misspellings the twenty-fifth pass found ignored (adv58 P3); a name with a blank at an end is no name.
  for (const std::string misspelt :
       {"<!-- BEGIN GENERATD x -->", "<!-- BEGIN-GENERATED x -->", "<!---BEGIN_GENERATED x -->",
        "<!--\xC2\xA0"
        "BEGIN GENERATED x -->",
        "<!-- BEGIN GENERATED  x -->", "<!-- END GENERATED x  -->", "<!-- GENERATED BEGIN x -->"})
    EXPECT_EQ(error_of("x\n" + misspelt + "\n").rfind("R.md:2: a ", 0), 0u) << misspelt << ": " << error_of(misspelt);
  EXPECT_EQ(error_of("<!-- a comment about what is generated -->\n"), "no error");
  EXPECT_EQ(error_of("<!-- Endpoint generation notes -->\n<!-- endnote: generated by pandoc -->\n"), "no error");
  EXPECT_EQ(marker_line("| a |\n|---|\n<!-- END GENERATED\tx -->\n"), 3u);
  EXPECT_EQ(marker_line("| a |\n<!-- a comment -->\n"), 0u);
}

}  // namespace
}  // namespace beamid::io

namespace beamid::io {
namespace {

// A block's file is read from inside the results folder only: its name may not leave it ('..', absolute), and
// neither may a symbolic link it reaches (a link res/lnk.md -> ../secret.md was pasted into the report: the twentieth
// pass's P5). A link within the folder, or the folder itself a link, is fine.
TEST(ReportBlocks, ABlocksFileOutsideTheResultsFolderIsRefused) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(testing::TempDir()) / "beamid_blocks";
  fs::remove_all(dir);
  fs::create_directories(dir / "res" / "study");
  std::ofstream(dir / "secret.md") << "secret\n";
  std::ofstream(dir / "res" / "study" / "table.md") << "table\n";
  fs::create_symlink("../secret.md", dir / "res" / "lnk.md");
  fs::create_symlink("study/table.md", dir / "res" / "inner.md");
  fs::create_directory_symlink("res", dir / "linked");
  EXPECT_THROW(block_source(dir / "res", "../secret", "REPORT.md"), InputError);
  try {
    block_source(dir / "res", "lnk", "REPORT.md");
    ADD_FAILURE() << "a link out of the folder was followed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the --results folder"), std::string::npos) << e.what();
  }
  EXPECT_EQ(block_source(dir / "res", "inner", "REPORT.md"), dir / "res" / "inner.md");
  EXPECT_EQ(block_source(dir / "linked", "study/table", "REPORT.md"), dir / "linked" / "study/table.md");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace beamid::io
