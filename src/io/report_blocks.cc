#include "io/report_blocks.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include "core/errors.h"
#include "io/files.h"

namespace beamid::io {
namespace {

const std::string kBegin = "<!-- BEGIN GENERATED ";
const std::string kEnd = "<!-- END GENERATED ";
const std::string kClose = " -->";
const std::string kByteOrderMark = "\xEF\xBB\xBF";
const std::string kBeginWord = "<!-- BEGIN GENERATED", kEndWord = "<!-- END GENERATED";

// A line meant as a marker: without its blanks and in lower case it starts "<!--begingenerated" or
// "<!--endgenerated" ("<!--BEGIN GENERATED x-->", two spaces, lower case). Such a line that is no exact marker found
// no block, "0 generated block(s) refreshed" with exit 0, and pasted from a block's source it broke the next
// refresh (the twenty-fourth pass's adv56 P2, P5).
bool looks_like_marker(const std::string& line) {
  std::string squeezed;
  for (const char c : line)
    if (c != ' ' && c != '\t' && c != '\r') squeezed += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return squeezed.rfind("<!--begingenerated", 0) == 0 || squeezed.rfind("<!--endgenerated", 0) == 0;
}

// The block name if `line` is exactly a marker of the given kind.
bool marker(const std::string& line, const std::string& kind, std::string* name) {
  if (line.rfind(kind, 0) != 0 || line.size() < kind.size() + kClose.size() ||
      line.compare(line.size() - kClose.size(), kClose.size(), kClose) != 0)
    return false;
  *name = line.substr(kind.size(), line.size() - kind.size() - kClose.size());
  return !name->empty();
}

struct Block {
  std::string name;
  std::size_t begin_line, end_line;  // 0-based indices of the marker lines
};

std::vector<Block> scan(const std::vector<std::string>& lines, const std::string& source) {
  std::vector<Block> blocks;
  bool open = false;
  Block current{};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string name;
    // A UTF-8 byte-order mark before the first line's marker hid it (the second adversarial pass of 2026-11-28, P7).
    const std::string& line = i == 0 && lines[i].rfind(kByteOrderMark, 0) == 0 ? lines[i].substr(3) : lines[i];
    const std::string where = source + ":" + std::to_string(i + 1);
    // An indented marker was no marker, and the error blamed its partner's line, or nothing was said at all (the
    // twenty-third pass's P7); a marker without a name was blamed as "text beside it" (P6).
    const std::size_t text_start = line.find_first_not_of(" \t");
    const std::string text = text_start == std::string::npos ? "" : line.substr(text_start);
    const bool begin_word = text.rfind(kBeginWord, 0) == 0, end_word = text.rfind(kEndWord, 0) == 0;
    if ((begin_word || end_word) && text_start > 0)
      throw InputError(where + ": an indented GENERATED marker: a marker starts its line, with nothing before it");
    if (!begin_word && !end_word && looks_like_marker(text))
      throw InputError(where +
                       ": a misspelt GENERATED marker: a marker is exactly '<!-- BEGIN GENERATED name -->' or "
                       "'<!-- END GENERATED name -->' (single spaces, capitals)");
    if ((begin_word || end_word) && !marker(line, kBegin, &name) && !marker(line, kEnd, &name)) {
      const std::string rest = text.substr((begin_word ? kBeginWord : kEndWord).size());
      if (rest.find_first_not_of(" \t") == rest.find("-->") && rest.find("-->") + 3 == rest.size())
        throw InputError(where + ": a GENERATED marker without a block name: '<!-- BEGIN GENERATED name -->'");
      throw InputError(where +
                       ": a GENERATED marker with text beside it: a marker stands alone on its line, "
                       "'<!-- BEGIN GENERATED name -->' or '<!-- END GENERATED name -->'");
    }
    if (marker(line, kBegin, &name)) {
      if (open)
        throw InputError(source + ":" + std::to_string(i + 1) + ": BEGIN GENERATED " + name + " inside open block '" +
                         current.name + "' (opened at line " + std::to_string(current.begin_line + 1) + ")");
      open = true;
      current = {name, i, 0};
    } else if (marker(line, kEnd, &name)) {
      if (!open || name != current.name)
        throw InputError(source + ":" + std::to_string(i + 1) + ": END GENERATED " + name +
                         (open ? " does not close block '" + current.name + "'" : " without a BEGIN"));
      current.end_line = i;
      blocks.push_back(current);
      open = false;
    }
  }
  if (open)
    throw InputError(source + ":" + std::to_string(current.begin_line + 1) + ": block '" + current.name +
                     "' is never closed (END GENERATED " + current.name + ")");
  return blocks;
}

// Each line as the file holds it, its end ('\n', '\r\n' or none for an unterminated last line) included: lines
// outside the refreshed blocks are copied back byte for byte (the first line's end was given to every line, and a
// CR elsewhere was dropped: the twenty-second pass's P9).
std::vector<std::string> raw_lines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    const std::size_t next = end == std::string::npos ? text.size() : end + 1;
    lines.push_back(text.substr(start, next - start));
    start = next;
  }
  return lines;
}

// A line without its end: a file written on Windows (CR LF) has its markers found as well (its markers ended in CR
// and no block was found, "0 generated block(s) refreshed": the tenth pass's RP_6).
std::string without_end(std::string line) {
  if (!line.empty() && line.back() == '\n') line.pop_back();
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines = raw_lines(text);
  for (std::string& line : lines) line = without_end(std::move(line));
  return lines;
}

// A refreshed block's lines end as its BEGIN marker's line does (CR LF in a Windows file).
std::string line_end(const std::string& raw_line) {
  return raw_line.size() >= 2 && raw_line.compare(raw_line.size() - 2, 2, "\r\n") == 0 ? "\r\n" : "\n";
}

}  // namespace

// Lines end in LF or CR LF: a CR alone (a classic Mac file) hid every marker, "0 generated block(s) refreshed" with
// exit 0, or made the whole file one block's name (the twenty-third pass's P2).
void check_line_ends(const std::string& text, const std::string& source) {
  for (std::size_t at = text.find('\r'); at != std::string::npos; at = text.find('\r', at + 1))
    if (at + 1 == text.size() || text[at + 1] != '\n')
      throw InputError(source + ":" + std::to_string(1 + std::count(text.begin(), text.begin() + at, '\n')) +
                       ": a carriage return (CR) alone ends or splits this line: lines end in LF or CR LF (convert "
                       "the file)");
}

std::size_t marker_line(const std::string& text) {
  std::size_t number = 0;
  for (const std::string& line : split_lines(text)) {
    ++number;
    if (looks_like_marker(line)) return number;
  }
  return 0;
}

std::filesystem::path block_source(const std::filesystem::path& results, const std::string& name,
                                   const std::string& source_name) {
  if (!stays_inside(name))
    throw InputError(source_name + ": block '" + name +
                     "': must be a relative name inside the --results folder (not absolute, no '..')");
  const std::filesystem::path path = results / (name + ".md");
  // The name stays inside, and so must the file it reaches: a symbolic link in results/ to a file outside it was
  // pasted into the report (the twentieth pass's P5). The folder itself may be a link (results -> /data/results).
  std::error_code ec;
  const std::filesystem::path base = std::filesystem::weakly_canonical(results, ec);
  const std::filesystem::path target = ec ? path : std::filesystem::weakly_canonical(path, ec);
  if (!ec) {
    const auto [b, t] = std::mismatch(base.begin(), base.end(), target.begin(), target.end());
    if (b != base.end())
      throw InputError(source_name + ": block '" + name + "': " + path.string() + " resolves to " + target.string() +
                       ", outside the --results folder (a symbolic link?): a block is read from inside it only");
  }
  return path;
}

std::vector<std::string> block_names(const std::string& text, const std::string& source_name) {
  std::vector<std::string> names;
  check_line_ends(text, source_name);
  for (const auto& b : scan(split_lines(text), source_name)) names.push_back(b.name);
  return names;
}

std::vector<std::size_t> block_lines(const std::string& text, const std::string& source_name) {
  std::vector<std::size_t> lines;
  check_line_ends(text, source_name);
  for (const auto& b : scan(split_lines(text), source_name)) lines.push_back(b.begin_line + 1);
  return lines;
}

std::string replace_blocks(const std::string& text, const std::map<std::string, std::string>& contents,
                           const std::string& source_name) {
  check_line_ends(text, source_name);
  const std::vector<std::string> raw = raw_lines(text);
  const std::vector<Block> blocks = scan(split_lines(text), source_name);
  std::string out;
  std::size_t next = 0;
  for (const auto& b : blocks) {
    for (; next <= b.begin_line; ++next) out += raw[next];
    auto it = contents.find(b.name);
    if (it == contents.end()) {
      for (; next < b.end_line; ++next) out += raw[next];
    } else {
      const std::string eol = line_end(raw[b.begin_line]);
      for (const std::string& line : split_lines(it->second)) out += line + eol;
      next = b.end_line;
    }
  }
  for (; next < raw.size(); ++next) out += raw[next];
  return out;
}

}  // namespace beamid::io
