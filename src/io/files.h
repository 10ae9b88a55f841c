// Writing files so that a reader never sees half of one: the text goes to "<path>.tmp", which is then renamed over
// the path (atomic on POSIX file systems). Folders are created as needed. InputError naming the path when the file
// cannot be written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace beamid::io {

void write_file_atomic(const std::filesystem::path& path, const std::string& text);

// Creates a folder and its parents; InputError "path: cannot create folder (<reason>)" when the path is too long,
// is a file, or is not writable.
void make_folder(const std::filesystem::path& path);

// Whether a path names an existing regular file / folder. Never throws: a path the system refuses (too long,
// unreadable parent) is reported as absent, so that the caller's one-line error names it.
bool is_existing_file(const std::filesystem::path& path);
bool is_existing_folder(const std::filesystem::path& path);

// The whole file, for every reader of user files (records, TOML files, study records). Refused before anything
// is read, each an InputError: a missing or unreadable path ("path: <cannot_read>"), a folder or a device
// ("path: <cannot_read> (is a folder)", "... (not a regular file)": /dev/zero is never read), and a file larger than
// max_bytes.
std::string read_file(const std::filesystem::path& path, const std::string& cannot_read,
                      std::uintmax_t max_bytes = std::uintmax_t{1} << 30);

}  // namespace beamid::io
