#include "core/errors.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace beamid {

std::string format_value(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

std::string one_line(const std::string& message) {
  std::string out;
  out.reserve(message.size());
  for (char c : message) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (c == '\t')
      out += "\\t";
    else if (u < 0x20 || u == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    } else {
      out += c;
    }
  }
  // A message quotes what a user gave, which can be a whole file's worth of text in one argument: the line keeps its
  // head (where, key) and its tail (the constraint) and says how much of the middle it cut.
  constexpr std::size_t kHead = 1000, kTail = 500;
  if (out.size() > kHead + kTail + 100)
    out = out.substr(0, kHead) + " ... [" + std::to_string(out.size() - kHead - kTail) + " characters cut] ... " +
          out.substr(out.size() - kTail);
  return out;
}

}  // namespace beamid
