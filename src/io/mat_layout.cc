#include "io/mat_layout.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "core/limits.h"
#include "io/resources.h"

namespace beamid::io {
namespace {

// Data types (miINT8 = 1 ... miUTF32 = 18) and their sizes in bytes; 0 where a type has no fixed size.
constexpr std::uint32_t kMatrix = 14, kCompressed = 15;
std::size_t type_size(std::uint32_t type) {
  switch (type) {
    case 1:
    case 2:
    case 16:
      return 1;  // miINT8, miUINT8, miUTF8
    case 3:
    case 4:
    case 17:
      return 2;  // miINT16, miUINT16, miUTF16
    case 5:
    case 6:
    case 7:
    case 18:
      return 4;  // miINT32, miUINT32, miSINGLE, miUTF32
    case 9:
    case 12:
    case 13:
      return 8;  // miDOUBLE, miINT64, miUINT64
    default:
      return 0;
  }
}

// An inflated element may be at most this large: the largest record a command reads (kMaxSamples doubles).
constexpr std::size_t kMaxInflatedBytes = static_cast<std::size_t>(core::kMaxSamples) * 8;
// Structs and cells nest arrays in arrays; a file that nests deeper than this is refused rather than recursed into.
constexpr int kMaxDepth = 32;

// One data element: its type, the byte count it declares, where its data starts and where the next element starts.
struct Element {
  std::uint32_t type = 0, count = 0;
  std::size_t data = 0, next = 0;
};

class Layout {
 public:
  Layout(const std::string& where, bool little_endian) : where_(where), little_(little_endian) {}

  // The elements of `bytes` from `at` on; `base` is the offset of `bytes` in the file (for messages), and `inflated`
  // says that these bytes came out of a compressed element at `base`.
  void top_level(const std::string& bytes, std::size_t at, std::size_t base, bool inflated) {
    while (at + 8 <= bytes.size()) {
      if (!inflated) ++variable_, name_.clear();
      const Element e = element(bytes, at, bytes.size(), base, "a top-level element");
      if (e.type == kMatrix) {
        matrix(bytes, e, base, 0);
      } else if (e.type == kCompressed && !inflated) {
        top_level(inflate(bytes, e, base), 0, base + at, true);
      } else {
        return;  // another kind of element: libmatio judges the rest
      }
      at = e.next;
    }
  }

 private:
  std::uint32_t word(const std::string& b, std::size_t at) const {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) {
      const auto byte = static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]));
      v |= byte << (8 * (little_ ? i : 3 - i));
    }
    return v;
  }

  [[noreturn]] void corrupt(std::size_t at, const std::string& what) const {
    throw InputError(where_ + "byte " + std::to_string(at) + ": variable " + std::to_string(variable_) +
                     (name_.empty() ? "" : " ('" + name_ + "')") + " " + what + ": the file is truncated or corrupt");
  }

  // The element at `at`, which must end by `end`: an 8-byte tag (type, byte count) and its data padded to 8 bytes,
  // or a small element (byte count in the tag's upper half, up to 4 bytes of data in its second word).
  Element element(const std::string& b, std::size_t at, std::size_t end, std::size_t base, const char* what) const {
    if (at + 8 > end) corrupt(base + at, std::string("has no room for ") + what);
    Element e;
    const std::uint32_t first = word(b, at);
    if (first >> 16 != 0) {
      e.type = first & 0xffff, e.count = first >> 16, e.data = at + 4, e.next = at + 8;
      if (e.count > 4) corrupt(base + at, "has a small element of " + std::to_string(e.count) + " bytes (at most 4)");
      return e;
    }
    e.type = first, e.count = word(b, at + 4), e.data = at + 8;
    const std::size_t left = end - e.data;
    if (e.count > left)
      corrupt(base + at, "declares " + std::to_string(e.count) + " bytes of data, but " +
                             (end == b.size() && base == 0 ? "the file" : "its container") + " ends " +
                             std::to_string(left) + " bytes later");
    e.next = e.type == kCompressed ? e.data + e.count : e.data + (e.count + 7) / 8 * 8;
    e.next = std::min(e.next, end);
    return e;
  }

  // An miMATRIX: array flags, dimensions, name, then by class the data (numeric, char), the fields (struct) or the
  // cells (cell); other classes (sparse, objects) are left to libmatio.
  void matrix(const std::string& b, const Element& m, std::size_t base, int depth) {
    if (depth > kMaxDepth) corrupt(base + m.data, "nests arrays more than " + std::to_string(kMaxDepth) + " deep");
    const std::size_t end = m.data + m.count;
    if (m.count == 0) return;  // an empty array (a struct field with no value)
    const Element flags = element(b, m.data, end, base, "its array flags");
    if (flags.count < 8) corrupt(base + m.data, "has array flags of " + std::to_string(flags.count) + " bytes");
    const std::uint32_t flag_word = word(b, flags.data);
    const std::uint32_t cls = flag_word & 0xff;
    const bool complex = (flag_word & 0x800) != 0;
    const Element dims = element(b, flags.next, end, base, "its dimensions");
    if (dims.count % 4 != 0 || dims.count < 8)
      corrupt(base + flags.next, "has a dimensions element of " + std::to_string(dims.count) + " bytes");
    // The number of values, saturated: anything above 2^62 is refused by the comparison below anyway.
    std::uint64_t values = 1;
    for (std::size_t d = 0; d < dims.count / 4; ++d) {
      const std::uint64_t n = word(b, dims.data + 4 * d);
      values = n == 0 ? 0 : values > (std::uint64_t{1} << 62) / n ? (std::uint64_t{1} << 62) : values * n;
    }
    const Element name = element(b, dims.next, end, base, "its name");
    if (depth == 0 && name.type == 1 && name.count <= 64) name_ = b.substr(name.data, name.count);  // miINT8
    std::size_t at = name.next;
    // Numeric (double ... uint64); not char, whose UTF-8 or UTF-16 bytes need not be one code unit per character.
    if (cls >= 6 && cls <= 15) {
      for (const char* part : {"real", "imaginary"}) {
        if (part[0] == 'i' && !complex) break;
        const Element data = element(b, at, end, base, "its data");
        const std::size_t size = type_size(data.type);
        if (size == 0)
          corrupt(base + at, "stores its " + std::string(part) + " part as type " + std::to_string(data.type));
        if (values * size != data.count)
          corrupt(base + at, "declares " + std::to_string(values) + " values (its dimensions) but its " + part +
                                 " part holds " + std::to_string(data.count) + " bytes of " + std::to_string(size) +
                                 "-byte values (" + std::to_string(data.count / size) + ")");
        at = data.next;
      }
    } else if (cls == 2) {  // struct: field-name length, the names, then values x fields arrays
      const Element length = element(b, at, end, base, "its field-name length");
      const std::uint32_t name_length = length.count >= 4 ? word(b, length.data) : 0;
      const Element names = element(b, length.next, end, base, "its field names");
      const std::uint64_t fields = name_length ? names.count / name_length : 0;
      at = names.next;
      for (std::uint64_t k = 0; k < values * fields && at < end; ++k) {
        const Element field = element(b, at, end, base, "a field");
        if (field.type != kMatrix) corrupt(base + at, "has a field of type " + std::to_string(field.type));
        matrix(b, field, base, depth + 1);
        at = field.next;
      }
    } else if (cls == 1) {  // cell: one array per value
      for (std::uint64_t k = 0; k < values && at < end; ++k) {
        const Element cell = element(b, at, end, base, "a cell");
        if (cell.type != kMatrix) corrupt(base + at, "has a cell of type " + std::to_string(cell.type));
        matrix(b, cell, base, depth + 1);
        at = cell.next;
      }
    }
  }

  // The inflated bytes of an miCOMPRESSED element (zlib), at most kMaxInflatedBytes and within the machine's memory.
  std::string inflate(const std::string& b, const Element& e, std::size_t base) const {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) corrupt(base + e.data, "cannot be inflated (zlib)");
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(b.data() + e.data));
    z.avail_in = e.count;
    std::string out;
    int rc = Z_OK;
    for (;;) {
      const std::size_t have = out.size();
      if (have >= kMaxInflatedBytes) {
        inflateEnd(&z);
        corrupt(base + e.data, "inflates to more than " + std::to_string(kMaxInflatedBytes) + " bytes");
      }
      const std::size_t chunk = std::min(std::max<std::size_t>(have, 1 << 16), kMaxInflatedBytes - have);
      if (have + chunk > (std::size_t{1} << 28))
        check_memory(where_ + "an inflated variable", double(have + chunk), std::cerr);
      out.resize(have + chunk);
      z.next_out = reinterpret_cast<Bytef*>(out.data() + have);
      z.avail_out = static_cast<uInt>(chunk);
      rc = ::inflate(&z, Z_NO_FLUSH);
      out.resize(have + (chunk - z.avail_out));
      if (rc == Z_STREAM_END) break;
      if (rc == Z_OK || (rc == Z_BUF_ERROR && z.avail_out == 0)) continue;
      break;  // a stream error, or input that ends before the stream does
    }
    inflateEnd(&z);
    if (rc != Z_STREAM_END)
      corrupt(base + e.data, "has a compressed element that does not inflate (zlib " + std::to_string(rc) + ")");
    return out;
  }

  std::string where_;
  bool little_;
  int variable_ = 0;  // the top-level variable being checked, from 1
  std::string name_;  // its name, once read
};

}  // namespace

void check_v5_layout(const std::string& where, const std::string& bytes, bool little_endian) {
  Layout(where, little_endian).top_level(bytes, 128, 0, false);
}

}  // namespace beamid::io
