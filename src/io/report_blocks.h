// Generated blocks in REPORT.md. A block is delimited by
//   <!-- BEGIN GENERATED name -->
//   ...
//   <!-- END GENERATED name -->
// and `name` is the path, relative to a results folder and without ".md", of the Markdown file that fills it
// (e.g. "verification/frequencies" <- results/verification/frequencies.md). Only the text between the markers is
// rewritten; everything people wrote around them stays as it is.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace beamid::io {

// Names of the blocks in `text`, in order. InputError (naming source:line) for an unmatched or mismatched marker.
std::vector<std::string> block_names(const std::string& text, const std::string& source_name);

// The 1-based line of each block's BEGIN marker in `text`, in the order of block_names (so that an error about a
// block names the report's line).
std::vector<std::size_t> block_lines(const std::string& text, const std::string& source_name);

// The file that fills block `name`: results/<name>.md. InputError naming the report (source_name) and the block when
// the name would leave the results folder (empty, absolute, or through '..').
std::filesystem::path block_source(const std::filesystem::path& results, const std::string& name,
                                   const std::string& source_name);

// InputError naming source's line when a carriage return (CR) is not followed by LF: lines end in LF or CR LF, in a
// report and in a block's source alike.
void check_line_ends(const std::string& text, const std::string& source);

// The 1-based number of text's first line that is, or is meant as, a GENERATED marker (blanks and case aside), 0 when
// none: a block's source must hold none, or the next refresh breaks.
std::size_t marker_line(const std::string& text);

// `text` with the content of each named block replaced by contents.at(name) (blocks not in `contents` are kept).
std::string replace_blocks(const std::string& text, const std::map<std::string, std::string>& contents,
                           const std::string& source_name);

}  // namespace beamid::io
