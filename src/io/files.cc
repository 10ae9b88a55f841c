#include "io/files.h"

#include <fstream>
#include <iterator>

#include "core/errors.h"
#include "io/resources.h"

namespace beamid::io {

void make_folder(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) throw InputError(path.string() + ": cannot create folder (" + ec.message() + ")");
}

bool is_existing_file(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && !ec;
}

bool is_existing_folder(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) && !ec;
}

void write_file_atomic(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) make_folder(path.parent_path());
  const std::filesystem::path temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw InputError(temporary.string() + ": cannot write");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) throw InputError(path.string() + ": cannot write (" + ec.message() + ")");
}

std::string read_file(const std::filesystem::path& path, const std::string& cannot_read, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  const std::string where = path.string() + ": ";
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!ec && fs::is_directory(status)) throw InputError(where + cannot_read + " (is a folder)");
  if (!ec && fs::exists(status) && !fs::is_regular_file(status))
    throw InputError(where + cannot_read + " (not a regular file)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw InputError(where + std::to_string(size) + " bytes: more than the " +
                     bytes_text(static_cast<double>(max_bytes)) + " such a file may have here");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where + cannot_read);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace beamid::io
