#include "io/report_blocks.h"

#include <algorithm>
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
    if ((line.rfind(kBegin, 0) == 0 || line.rfind(kEnd, 0) == 0) && !marker(line, kBegin, &name) &&
        !marker(line, kEnd, &name))
      throw InputError(source + ":" + std::to_string(i + 1) +
                       ": a GENERATED marker with text beside it: a marker stands alone on its line, "
                       "'<!-- BEGIN GENERATED name -->' or '<!-- END GENERATED name -->'");
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
  for (const auto& b : scan(split_lines(text), source_name)) names.push_back(b.name);
  return names;
}

std::vector<std::size_t> block_lines(const std::string& text, const std::string& source_name) {
  std::vector<std::size_t> lines;
  for (const auto& b : scan(split_lines(text), source_name)) lines.push_back(b.begin_line + 1);
  return lines;
}

std::string replace_blocks(const std::string& text, const std::map<std::string, std::string>& contents,
                           const std::string& source_name) {
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
