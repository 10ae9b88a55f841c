// Writing files so that a reader never sees half of one: the text goes to a temporary of beamid's own beside it
// (".beamid-<pid>-<n>.tmp", created exclusively, never through a link), which is then renamed over the path (atomic
// on POSIX file systems). Folders are created as needed.
// InputError "path: cannot write (<the OS's reason>)" when the file cannot be written, with the temporary removed;
// refused before anything is written when the path exists and is not a regular file (replaceable_output_problem).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace beamid::io {

void write_file_atomic(const std::filesystem::path& path, const std::string& text);

// The prefix of write_file_atomic's temporaries (".beamid-<pid>-<n>.tmp" beside the output), and whether a path is
// one: the leftover of a killed write, which a folder check takes for beamid's own and may remove.
inline constexpr const char* kTemporaryPrefix = ".beamid-";
bool is_leftover_temporary(const std::filesystem::path& path);
// Removes the leftover temporaries in `folder`, and in its folders `depth` levels down (not through links), whose
// writing process no longer runs on this machine and which have not been written for `min_age_s` seconds (a live
// writer on another machine sharing the folder keeps its file fresh), and returns how many it removed and their bytes.
// A killed merge or study left partial records in a store, and tables in landscape/, that no later run removed (the
// twenty-eighth pass's adv64 P1, the twenty-ninth's adv66 P2).
struct RemovedTemporaries {
  int files = 0;
  std::uintmax_t bytes = 0;
};
RemovedTemporaries remove_leftover_temporaries(const std::filesystem::path& folder, double min_age_s = 60,
                                               int depth = 0);
// remove_leftover_temporaries of an output folder and the folders in it (store/, landscape/, ...), with the line a
// command prints when it removed any ("<folder>: removed N partial file(s) that killed runs left behind (B bytes)"),
// else "".
std::string remove_leftovers_of_output(const std::filesystem::path& folder);

// Why an existing path cannot be an output ("is a folder", "is a symbolic link ...", "is not a regular file ..."), or
// "" when it does not exist or is a regular file.
std::string replaceable_output_problem(const std::filesystem::path& path);

// Why `folder` cannot take a command's output files (tables, reports), or "" when it can: it exists and is not a
// folder; it holds files but is not an earlier output of beamid (no manifest.json, no store/), so that files of the
// user's could be overwritten by the tables' names; or one of `inputs` (the command's input files) lies inside it,
// where a table of the same name would replace it.
// With `study_file`, also a folder whose manifest.json names another study file that still exists: two study files of
// one [study] name wrote into one results/<name>, each replacing the other's tables and recomputing its units (the
// sixth pass's S420). With `study_name`, also a folder whose manifest.json names another study: the file check
// resolves the manifest's (relative) study file from the current folder, and run from elsewhere it passed, so that
// `beamid real` replaced another study's tables (the twelfth pass's P1).
std::string output_folder_problem(const std::filesystem::path& folder, const std::vector<std::string>& inputs,
                                  const std::string& study_file = "", const std::string& study_name = "");

// Why `folder` cannot be created: it, or a folder above it, is a symbolic link that leads nowhere (dangling, or a
// loop); "" otherwise. Such a link was taken for a missing folder, "created" (EEXIST: "File exists") and then removed
// as one that had been made (the twenty-first pass's P3). unwritable_folder_problem and output_folder_problem say it.
std::string dangling_link_problem(const std::filesystem::path& folder);

// Why nothing can be written in `folder`, or "": it is created (with its parents) if missing, and a probe file is
// created and removed in it. Checked before a command computes, so that an unwritable output costs no compute (a
// `real --output /proc/rs` fitted its records first).
std::string unwritable_folder_problem(const std::filesystem::path& folder);

// The constraint a study's [study] name breaks, or "": it names results/<name>/, so it must be a non-empty word of
// a-z, 0-9, '-', '_' (a real study's name "../victim" wrote its tables outside results/: the twelfth pass's P2).
std::string study_name_problem(const std::string& name);

// Claims a study's store folder for its study file when a run starts, before any unit runs: the file `claim` in it
// holds the study file's absolute path, created exclusively (two runs that start together do not both claim it).
// Returns "" when the folder is free or already this study file's (the same path, or a file of the same text: a copy
// run from another folder or node); else why not: "holds the units of another study file, PATH, ...". A claim whose
// file no longer exists (renamed) is taken over. Two study files of one [study] name that ran at overlapping times
// each moved the other's finished units aside as damaged and ended without tables (the seventh pass's S69), and a
// manifest's relative study_file did not resolve from another working folder (S73).
std::string claim_store(const std::filesystem::path& store, const std::string& study_file);

// Whether a relative path stays inside the folder it is joined to: not empty, not absolute, and no ".." part. For
// names that come from files (a report's block names, the list of tables a study wrote), which must not reach out.
bool stays_inside(const std::filesystem::path& relative);

// Creates a folder and its parents; InputError "path: cannot create folder (<reason>)" when the path is too long,
// is a file, or is not writable.
void make_folder(const std::filesystem::path& path);

// Whether a path names an existing regular file / folder. Never throws: a path the system refuses (too long,
// unreadable parent) is reported as absent, so that the caller's one-line error names it.
bool is_existing_file(const std::filesystem::path& path);
bool is_existing_folder(const std::filesystem::path& path);

// The command line's standard output, when it is a regular file, is guarded from then on: every user file read_file
// and read_file_head open is refused (InputError) when it is that same file. "beamid modes --beam b.toml >> b.toml"
// appended to its own input (the twenty-first pass's P6), as did every command that prints to standard output. The
// command line calls it once, before a command runs; the Python binding, which prints nothing, does not.
void guard_standard_output();

// The whole file, for every reader of user files (records, TOML files, study records). Refused before anything
// is read, each an InputError: a missing or unreadable path ("path: <cannot_read> (No such file or directory)", the
// system's reason), a folder or a device ("path: <cannot_read> (is a folder)", "... (not a regular file)": /dev/zero is
// never read), and a file larger than max_bytes.
std::string read_file(const std::filesystem::path& path, const std::string& cannot_read,
                      std::uintmax_t max_bytes = std::uintmax_t{1} << 30);
// Its first `bytes` bytes (all of a shorter file), with the same refusals but the size's: for a look at a file's kind
// before the whole of it is read.
std::string read_file_head(const std::filesystem::path& path, const std::string& cannot_read, std::size_t bytes);

}  // namespace beamid::io
