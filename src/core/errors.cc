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

std::string format_rounded(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
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
  // The cuts fall on character boundaries (never inside a UTF-8 sequence, whose continuation bytes are 10xxxxxx), so
  // the line stays valid text (Python decodes it).
  constexpr std::size_t kHead = 1000, kTail = 500;
  if (out.size() > kHead + kTail + 100) {
    const auto continuation = [&out](std::size_t i) { return (static_cast<unsigned char>(out[i]) & 0xC0) == 0x80; };
    std::size_t head = kHead, tail = out.size() - kTail;
    while (head > 0 && continuation(head)) --head;
    while (tail < out.size() && continuation(tail)) ++tail;
    out = out.substr(0, head) + " ... [" + std::to_string(tail - head) + " bytes cut] ... " + out.substr(tail);
  }
  return out;
}

}  // namespace beamid
