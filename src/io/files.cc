#include "io/files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

namespace {

// The "study_file" string of a manifest.json beamid wrote (io::json_string escapes '"' and '\\'), or "".
// The string value of a top-level `field` of a manifest.json ("" when absent).
std::string manifest_field(const std::filesystem::path& manifest, const std::string& field) {
  // Capped as every file read is: a 2 GB manifest.json was read whole into "out of memory", naming no file (the
  // twenty-second pass's P10); beamid's own are a few kB.
  const std::string text = read_file(manifest, "cannot read the output folder's manifest", std::uintmax_t{16} << 20);
  const std::string key = "\"" + field + "\": \"";
  auto at = text.find(key);
  if (at == std::string::npos) return "";
  std::string value;
  for (at += key.size(); at < text.size() && text[at] != '"'; ++at) {
    if (text[at] == '\\' && at + 1 < text.size()) ++at;
    value += text[at];
  }
  return value;
}

}  // namespace

std::string output_folder_problem(const std::filesystem::path& folder, const std::vector<std::string>& inputs,
                                  const std::string& study_file, const std::string& study_name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (std::string problem = dangling_link_problem(folder); !problem.empty()) return problem;
  if (!fs::exists(folder, ec)) return "";
  if (!fs::is_directory(folder, ec)) return "exists and is not a folder";
  const fs::path root = fs::weakly_canonical(folder, ec);
  if (ec) return "";
  // Inside by path, or by the folder itself among the input's parents (its device and inode): a bind mount of the
  // folder elsewhere passed the path check, and the study's table replaced the study file (the twenty-second pass's
  // P2).
  struct stat folder_stat {};
  const bool have_folder_stat = ::stat(folder.c_str(), &folder_stat) == 0;
  const auto under_folder = [&](const fs::path& file) {
    if (!have_folder_stat) return false;
    for (fs::path p = file.parent_path(); !p.empty(); p = p.parent_path()) {
      struct stat parent {};
      if (::stat(p.c_str(), &parent) == 0 && parent.st_dev == folder_stat.st_dev && parent.st_ino == folder_stat.st_ino)
        return true;
      if (p == p.parent_path()) break;
    }
    return false;
  };
  for (const std::string& input : inputs) {
    if (input.empty()) continue;
    const fs::path file = fs::weakly_canonical(input, ec);
    if (ec) continue;
    const auto [end, at] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
    if (end == root.end() || under_folder(file))
      return "holds the input " + input +
             " (an output folder holds what beamid writes, and an output there could replace an input of the same "
             "name): write into a new or empty folder";
  }
  // A table's name taken by a folder or a special file failed only when the tables were written, after every unit
  // had run (the thirteenth adversarial pass's problem 10: a folder named timings.csv; the fourteenth's P14: one in
  // landscape/), and a manifest.json that is a FIFO, a folder or a link to /dev/zero hung or failed the manifest's
  // read below (its P2, P3): every .csv, .md and .json outside store/ must be a regular file.
  // The same for anything that is neither a file nor a folder (a FIFO, a device, a link), any table-like name that is
  // a folder (.dat, .txt: the fifteenth pass's P6), the table subfolders as files, and the store's list of tables.
  const auto named = [&folder](const fs::path& path, const std::string& problem) {
    return "holds " + path.lexically_relative(folder).string() + ", which " + problem +
           ", where beamid writes a table or a folder of that name; remove it or write into a new or empty folder";
  };
  for (const char* sub : {"landscape", "start_distance"})
    if (fs::exists(fs::symlink_status(folder / sub, ec)) && !fs::is_directory(fs::symlink_status(folder / sub, ec)))
      return named(folder / sub, "is not a folder");
  if (const std::string problem = replaceable_output_problem(folder / "store" / "tables.txt"); !problem.empty())
    return named(folder / "store" / "tables.txt", problem);
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it.depth() == 0 && it->path().filename() == "store") {
      it.disable_recursion_pending();
      continue;
    }
    const fs::file_status status = it->symlink_status(ec);
    const std::string extension = it->path().extension().string();
    const bool table_name =
        extension == ".csv" || extension == ".md" || extension == ".json" || extension == ".dat" || extension == ".txt";
    if (fs::is_directory(status) ? table_name : !fs::is_regular_file(status))
      return named(it->path(), replaceable_output_problem(it->path()));
  }
  ec.clear();
  if (!study_file.empty() && fs::exists(folder / "manifest.json", ec)) {
    const std::string owner = manifest_field(folder / "manifest.json", "study_file");
    if (!owner.empty() && fs::exists(owner, ec) && !fs::equivalent(owner, study_file, ec) && !ec)
      return "holds the results of another study file, " + owner +
             " (its manifest.json), whose tables this run would replace: give this study its own [study] name, or "
             "its own --output";
  }
  if (!study_name.empty() && fs::exists(folder / "manifest.json", ec)) {
    const std::string owner = manifest_field(folder / "manifest.json", "study");
    if (!owner.empty() && owner != study_name)
      return "holds the results of another study, '" + owner +
             "' (its manifest.json), whose tables this run would replace: give this study its own --output";
  }
  // (A killed first write's temporary alone is beamid's own, not the user's: io::is_leftover_temporary.)
  bool users_files = false;
  for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
    if (!is_leftover_temporary(it->path())) users_files = true;
  if (!fs::exists(folder / "manifest.json", ec) && !fs::exists(folder / "store", ec) && users_files)
    return "holds files but no manifest.json or store/ (it is not an earlier output of beamid), which the tables "
           "could overwrite; write into a new or empty folder";
  return "";
}

std::string dangling_link_problem(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::path p = folder; !p.empty(); p = p.parent_path()) {
    if (fs::is_symlink(fs::symlink_status(p, ec)) && !fs::exists(p, ec)) {
      const fs::path target = fs::read_symlink(p, ec);
      return p.string() + ": is a symbolic link to " + target.string() +
             ", which does not exist or leads in a loop: create its target, or give another folder";
    }
    if (p == p.parent_path()) break;
  }
  return "";
}

std::string unwritable_folder_problem(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  // The asked folder, when this check creates it, is removed again (when still empty): a command that then fails on
  // its inputs leaves no empty output folder behind. The parents it creates stay: another process may be making
  // its own folder in them. Removing an empty results/ raced the shards of a Slurm job array started together: one
  // shard's check removed results/ between another's mkdir of results/ and of results/smoke-shard-2 (ENOENT, exit 2).
  std::error_code ec;
  if (std::string problem = dangling_link_problem(folder); !problem.empty()) return problem;
  const bool creates_it = !fs::exists(fs::symlink_status(folder, ec));
  struct Cleanup {
    const fs::path& folder;
    bool created;
    ~Cleanup() {
      std::error_code e;
      if (created) fs::remove(folder, e);
    }
  } cleanup{folder, creates_it};
  try {
    make_folder(folder);
  } catch (const InputError& error) {
    return error.what();
  }
  // access(W_OK) says yes to root everywhere, /proc included: a file is created (exclusively, under a name no output
  // has) and removed.
  const std::filesystem::path probe = folder / (".beamid-write-probe-" + std::to_string(::getpid()));
  errno = 0;
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) return folder.string() + ": cannot write in it (" + std::strerror(errno) + ")";
  ::close(fd);
  fs::remove(probe, ec);
  return "";
}

std::string study_name_problem(const std::string& name) {
  if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") != std::string::npos)
    return "must be a non-empty word of a-z, 0-9, '-', '_' (it names results/<name>/)";
  return "";
}

namespace {

std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

std::string claim_store(const std::filesystem::path& store, const std::string& study_file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path mine = fs::weakly_canonical(study_file, ec);
  if (ec) return "";
  make_folder(store);
  const fs::path claim = store / "claim";
  for (int attempt = 0; attempt < 2; ++attempt) {
    // "x": created only if absent (C11 fopen exclusive mode), so that one of two runs starting together wins.
    if (std::FILE* f = std::fopen(claim.c_str(), "wx")) {
      const std::string line = mine.string() + "\n";
      const bool ok = std::fwrite(line.data(), 1, line.size(), f) == line.size();
      if (std::fclose(f) != 0 || !ok)
        throw OutputError(claim.string() + ": cannot write (" + std::strerror(errno) + ")");
      return "";
    }
    // Not a regular file (a folder of that name switched the guard off: the fourteenth pass's P10): said.
    if (const std::string problem = replaceable_output_problem(claim); !problem.empty())
      return claim.string() + " " + problem + ", where the file that guards the store against another study file " +
             "goes: remove it";
    if (!fs::is_regular_file(claim, ec)) return "";  // vanished meanwhile: the store's own checks say so
    std::string owner = text_of(claim);
    while (!owner.empty() && (owner.back() == '\n' || owner.back() == '\r')) owner.pop_back();
    if (owner == mine.string()) return "";
    if (fs::exists(owner, ec) && !ec) {
      if (text_of(owner) == text_of(mine)) return "";
      return "holds the units of another study file, " + owner + " (" + claim.string() +
             "), which may be running now; this run would take its units for damaged ones: give this study its own "
             "[study] name, or its own --output";
    }
    fs::remove(claim, ec);  // its study file is gone (renamed): taken over
  }
  return "";
}

bool stays_inside(const std::filesystem::path& relative) {
  if (relative.empty() || relative.is_absolute()) return false;
  for (const auto& part : relative)
    if (part == "..") return false;
  return true;
}

bool is_existing_file(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && !ec;
}

bool is_existing_folder(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) && !ec;
}

std::string replaceable_output_problem(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (ec || !fs::exists(status)) return "";
  if (fs::is_directory(status)) return "is a folder";
  if (fs::is_symlink(status)) return "is a symbolic link (an output is written as a new file, which would replace it)";
  if (!fs::is_regular_file(status)) return "is not a regular file (a device, pipe or socket)";
  return "";
}

bool is_leftover_temporary(const std::filesystem::path& path) {
  // ".beamid-<pid>-<n>.tmp" exactly, pid and n decimal digits, pid positive: a user's ".beamid-notes.tmp" is no
  // temporary of beamid's (the twenty-ninth pass's adv66 P3 had it removed).
  const std::string name = path.filename().string();
  const std::string prefix = kTemporaryPrefix, suffix = ".tmp";
  if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string middle = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  const auto dash = middle.find('-');
  const auto digits = [](const std::string& t) {
    return !t.empty() && std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
  };
  return dash != std::string::npos && digits(middle.substr(0, dash)) && digits(middle.substr(dash + 1)) &&
         middle.find_first_not_of('0', 0) < dash;
}

RemovedTemporaries remove_leftover_temporaries(const std::filesystem::path& folder, double min_age_s, int depth) {
  namespace fs = std::filesystem;
  RemovedTemporaries removed;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const fs::path& path = it->path();
    std::error_code entry_ec;
    if (depth > 0 && !it->is_symlink(entry_ec) && it->is_directory(entry_ec)) {
      const RemovedTemporaries below = remove_leftover_temporaries(path, min_age_s, depth - 1);
      removed.files += below.files, removed.bytes += below.bytes;
      continue;
    }
    if (!is_leftover_temporary(path) || it->is_symlink(entry_ec) || !it->is_regular_file(entry_ec)) continue;
    // ".beamid-<pid>-<n>.tmp": a process that still runs (or that this user may not signal) may still be writing.
    const std::string name = path.filename().string();
    const std::size_t digits = std::string(kTemporaryPrefix).size();
    const long pid = std::strtol(name.c_str() + digits, nullptr, 10);
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    const auto written = fs::last_write_time(path, entry_ec);
    if (entry_ec || std::chrono::duration<double>(now - written).count() < min_age_s) continue;
    const std::uintmax_t size = fs::file_size(path, entry_ec);
    if (fs::remove(path, entry_ec) && !entry_ec) ++removed.files, removed.bytes += size;
  }
  return removed;
}

std::string remove_leftovers_of_output(const std::filesystem::path& folder) {
  const RemovedTemporaries removed = remove_leftover_temporaries(folder, 60, 1);
  if (removed.files == 0) return "";
  return folder.string() + ": removed " + std::to_string(removed.files) +
         " partial file(s) that killed runs left behind (" + std::to_string(removed.bytes) + " bytes)";
}

namespace {

// The OS's reason for the last failed call, or a generic one.
std::string os_reason(int error) { return error != 0 ? std::strerror(error) : "an unknown reason"; }

// The temporary of write_file_atomic: "<folder>/.beamid-<pid>-<n>.tmp", a name of beamid's own beside the output,
// created exclusively and never through a link. "<path>.tmp" was a user's name too: a link planted there made every
// write replace the file it led to (the twenty-first pass's P1), a folder there failed the write, and a user's
// REPORT.md.tmp was deleted (the twenty-second pass's P8); it made a 252-255 byte name unwritable (P13), and two
// processes writing one output removed each other's (P14). A leftover of a killed run is a hidden file of that
// pattern (is_leftover_temporary).
int create_temporary(const std::filesystem::path& output, std::filesystem::path& temporary) {
  static std::atomic<long> sequence{0};
  for (int attempt = 0; attempt < 8; ++attempt) {
    temporary = output.parent_path() / (std::string(kTemporaryPrefix) + std::to_string(::getpid()) + "-" +
                                        std::to_string(++sequence) + ".tmp");
    errno = 0;
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST) break;  // a leftover of another process of this pid: the next number
  }
  throw OutputError(output.string() + ": cannot write (" + os_reason(errno) + ")");
}

}  // namespace

void write_file_atomic(const std::filesystem::path& path, const std::string& text) {
  // A NUL ends the name the system sees ("a\0b.md" wrote "a"): refused (the twenty-first pass's P7).
  if (path.native().find('\0') != std::string::npos)
    throw InputError(path.string().substr(0, path.native().find('\0')) +
                     "...: the output's name holds a NUL character, which no file name may hold");
  // An output only replaces a regular file: a device (/dev/null), a pipe or a link given as an output path would be
  // replaced by a plain file (as root, /dev/null itself).
  if (const std::string problem = replaceable_output_problem(path); !problem.empty())
    throw InputError(path.string() + ": " + problem + ": an output replaces only a regular file; choose another path");
  std::error_code ec;
  // A file its owner made read-only is not replaced behind their back (a rename would, whatever its mode).
  const std::filesystem::file_status existing = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::is_regular_file(existing) &&
      (existing.permissions() & std::filesystem::perms::owner_write) == std::filesystem::perms::none)
    throw InputError(path.string() + ": is read-only: make it writable to replace it, or choose another path");
  if (path.has_parent_path()) make_folder(path.parent_path());
  std::filesystem::path temporary;
  const int fd = create_temporary(path, temporary);
  // A failed or short write (a full disk, a read-only folder, a quota) names the OS's reason and leaves neither the
  // temporary nor a partial file under the final name.
  const auto fail = [&](int error) {
    std::filesystem::remove(temporary, ec);
    throw OutputError(path.string() + ": cannot write (" + os_reason(error) + ")");
  };
  for (std::size_t written = 0; written < text.size();) {
    errno = 0;
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;
      ::close(fd);
      fail(error);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) fail(errno);
  // The file it replaces keeps its permissions: a private (0600) or read-only report was rewritten as 0644, i.e.
  // made world-readable (the second adversarial pass's N528-N530).
  if (std::filesystem::is_regular_file(existing)) {
    std::filesystem::permissions(temporary, existing.permissions(), std::filesystem::perm_options::replace, ec);
    if (ec) fail(ec.value());
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(temporary, ec);
    throw OutputError(path.string() + ": cannot write (" + reason + ")");
  }
}

namespace {

// guard_standard_output's file: its device and inode, once set.
struct GuardedOutput {
  bool set = false;
  dev_t device = 0;
  ino_t inode = 0;
};
GuardedOutput& guarded_output() {
  static GuardedOutput guarded;
  return guarded;
}

}  // namespace

void guard_standard_output() {
  struct stat out {};
  if (::fstat(STDOUT_FILENO, &out) == 0 && S_ISREG(out.st_mode))
    guarded_output() = GuardedOutput{true, out.st_dev, out.st_ino};
}

namespace {

// The file opened for reading after the refusals read_file lists but the size's.
std::ifstream open_user_file(const std::filesystem::path& path, const std::string& cannot_read) {
  namespace fs = std::filesystem;
  const std::string where = path.string() + ": ";
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!ec && fs::is_directory(status)) throw InputError(where + cannot_read + " (is a folder)");
  if (!ec && fs::exists(status) && !fs::is_regular_file(status))
    throw InputError(where + cannot_read + " (not a regular file)");
  struct stat file {};
  if (const GuardedOutput& g = guarded_output();
      g.set && ::stat(path.c_str(), &file) == 0 && file.st_dev == g.device && file.st_ino == g.inode)
    throw InputError(where +
                     "is also the standard output (the shell's > or >>), which the results would overwrite "
                     "or append to: an output never replaces an input; send the output elsewhere");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where + cannot_read + (errno ? " (" + std::string(std::strerror(errno)) + ")" : ""));
  return in;
}

}  // namespace

std::string read_file(const std::filesystem::path& path, const std::string& cannot_read, std::uintmax_t max_bytes) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > max_bytes)
    // Both sizes exact: rounded, a 1,073,741,952-byte file read "more than the 1.1 GB" (the twentieth pass's P11).
    throw InputError(path.string() + ": " + std::to_string(size) + " bytes: more than the " +
                     std::to_string(max_bytes) + " bytes (" + bytes_text(static_cast<double>(max_bytes)) +
                     ") such a file may have here");
  std::ifstream in = open_user_file(path, cannot_read);
  // Read at its size in one piece (an iterator's growth by doubling took twice the file's size at its peak), and to
  // its end, never past max_bytes, should it have grown since.
  std::string text;
  if (!ec) text.reserve(static_cast<std::size_t>(std::min(size, max_bytes)));
  std::array<char, 1 << 16> chunk{};
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw InputError(path.string() + ": more than the " + std::to_string(max_bytes) + " bytes (" +
                       bytes_text(static_cast<double>(max_bytes)) + ") such a file may have here");
  }
  return text;
}

std::string read_file_head(const std::filesystem::path& path, const std::string& cannot_read, std::size_t bytes) {
  std::ifstream in = open_user_file(path, cannot_read);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(bytes));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

}  // namespace beamid::io
