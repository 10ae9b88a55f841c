// Output files (issue 30): a failed write names the OS's reason and leaves neither a temporary nor a partial file; a
// path that exists and is not a regular file (a pipe, a link, a folder) is never replaced; an output folder that
// holds the user's files or an input is refused.
#include "io/files.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"

namespace beamid::io {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("beamid-files-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

TEST(WriteFileAtomic, AFailedWriteNamesTheReasonAndLeavesNothingBehind) {
  const fs::path dir = scratch("failed");
  // A name the system refuses: the open fails with the OS's own reason, and nothing is left under either name. The
  // machine's failure, not the input's: programs exit 1 for it, not 2 (the twentieth pass's P3).
  const fs::path long_name = dir / (std::string(300, 'x') + ".csv");
  const std::string m = message_of([&] { write_file_atomic(long_name, "x\n"); });
  EXPECT_NE(m.find(": cannot write (File name too long)"), std::string::npos) << m;
  EXPECT_THROW(write_file_atomic(long_name, "x\n"), OutputError);
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(WriteFileAtomic, ItsTemporaryIsANameOfItsOwnAndTouchesNoUsersFile) {
  // "<path>.tmp" was a user's name too: a link planted there made the write replace the file it led to (the
  // twenty-first pass's P1), a folder there failed it, a user's REPORT.md.tmp was deleted (the twenty-second pass's
  // P8), and a 252-255 byte name could not be written (its P13). The temporary is ".beamid-<pid>-<n>.tmp": every such
  // file of the user's is left as it was, the output is a regular file of its own, and no temporary is left.
  const fs::path dir = scratch("temporary");
  std::ofstream(dir / "victim.txt") << "precious\n";
  fs::create_symlink(dir / "victim.txt", dir / "out.md.tmp");
  fs::create_directories(dir / "t.csv.tmp" / "x");
  std::ofstream(dir / "a.csv.tmp") << "mine";
  write_file_atomic(dir / "out.md", "report\n");
  write_file_atomic(dir / "t.csv", "t\n");
  write_file_atomic(dir / "a.csv", "a\n");
  const std::string long_name(255, 'n');
  write_file_atomic(dir / long_name, "long\n");
  std::string line;
  std::getline(std::ifstream(dir / "victim.txt"), line);
  EXPECT_EQ(line, "precious");
  std::getline(std::ifstream(dir / "a.csv.tmp"), line);
  EXPECT_EQ(line, "mine");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "out.md.tmp")));
  EXPECT_TRUE(fs::is_directory(dir / "t.csv.tmp" / "x"));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "out.md")));
  for (const char* name : {"t.csv", "a.csv"}) {
    std::getline(std::ifstream(dir / name), line);
    EXPECT_EQ(line, std::string(1, name[0]));
  }
  std::getline(std::ifstream(dir / long_name), line);
  EXPECT_EQ(line, "long");
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_FALSE(is_leftover_temporary(entry.path())) << entry.path();
  EXPECT_TRUE(is_leftover_temporary(dir / ".beamid-12-3.tmp"));
  EXPECT_FALSE(is_leftover_temporary(dir / "out.md.tmp"));
  fs::remove_all(dir);
}

TEST(OutputFolder, PartialFilesOfKilledRunsAreRemovedWhenTheirWriterIsGone) {
  // The twenty-eighth pass's adv64 P1 and the twenty-ninth's adv66 P2, P3: a killed merge left
  // ".beamid-<pid>-<n>.tmp" in store/ and landscape/, and no later run removed them; then a user's
  // ".beamid-notes.tmp" was removed as one. Removed: the pattern exactly, its process gone (pid 99999999 is above any
  // Linux pid_max, 2^22), unwritten for a minute, in the folder or one level down. Kept: a live writer's (this test),
  // one written a moment ago (a writer on another machine), names beamid never writes, two levels down.
  const fs::path dir = scratch("leftovers");
  fs::create_directories(dir / "store" / "damaged");
  const auto write = [&](const fs::path& path, bool old) {
    std::ofstream(path) << "partial record";
    if (old) fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::minutes(5));
  };
  const std::string mine = ".beamid-" + std::to_string(::getpid()) + "-4.tmp";
  for (const fs::path& p : {dir / ".beamid-99999999-3.tmp", dir / "store" / ".beamid-99999999-7.tmp", dir / mine,
                            dir / ".beamid-notes.tmp", dir / ".beamid-0-1.tmp", dir / ".beamid--5-1.tmp",
                            dir / "u1.tmp", dir / "store" / "damaged" / ".beamid-99999999-8.tmp"})
    write(p, true);
  write(dir / ".beamid-99999999-5.tmp", false);
  EXPECT_EQ(remove_leftovers_of_output(dir),
            dir.string() + ": removed 2 partial file(s) that killed runs left behind (28 bytes)");
  EXPECT_FALSE(fs::exists(dir / ".beamid-99999999-3.tmp"));
  EXPECT_FALSE(fs::exists(dir / "store" / ".beamid-99999999-7.tmp"));
  for (const fs::path& kept :
       {dir / mine, dir / ".beamid-notes.tmp", dir / ".beamid-0-1.tmp", dir / ".beamid--5-1.tmp", dir / "u1.tmp",
        dir / "store" / "damaged" / ".beamid-99999999-8.tmp", dir / ".beamid-99999999-5.tmp"})
    EXPECT_TRUE(fs::exists(kept)) << kept;
  EXPECT_EQ(remove_leftovers_of_output(dir), "");
  EXPECT_TRUE(is_leftover_temporary(".beamid-12-0.tmp"));
  EXPECT_FALSE(is_leftover_temporary(".beamid-00-0.tmp"));
  fs::remove_all(dir);
}

TEST(OutputFolder, TheCheckRemovesTheFolderItMadeButNotTheParentsOthersShare) {
  // Shards of a Slurm array start together: one shard's check removed an empty results/ that another shard had just
  // made, and that shard's mkdir of results/smoke-shard-2 failed (ENOENT, exit 2; CI of 2026-11-29). The asked folder
  // is removed again (a refused command leaves no empty output behind); its parents stay.
  const fs::path dir = scratch("parents");
  const fs::path folder = dir / "results" / "smoke-shard-1";
  EXPECT_EQ(unwritable_folder_problem(folder), "");
  EXPECT_FALSE(fs::exists(folder));
  EXPECT_TRUE(fs::is_directory(dir / "results"));
  // Many checks of sibling folders at once, each making its own folder in the shared parent: none is refused.
  fs::remove_all(dir / "results");
  std::vector<std::string> problems(8);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < problems.size(); ++k)
    threads.emplace_back([&, k] {
      const fs::path mine = dir / "results" / ("shard-" + std::to_string(k));
      try {
        for (int round = 0; round < 50 && problems[k].empty(); ++round) {
          problems[k] = unwritable_folder_problem(mine);
          if (problems[k].empty()) make_folder(mine), fs::remove(mine);
        }
      } catch (const InputError& error) {
        problems[k] = error.what();
      }
    });
  for (std::thread& t : threads) t.join();
  for (const std::string& problem : problems) EXPECT_EQ(problem, "");
  fs::remove_all(dir);
}

TEST(OutputFolder, ALinkThatLeadsNowhereIsNamedAndKept) {
  // Taken for a missing folder, a dangling link was "created" (File exists) and then removed (the twenty-first
  // pass's P3).
  const fs::path dir = scratch("dangling");
  fs::create_symlink(dir / "not-mounted" / "results", dir / "out");
  fs::create_symlink(dir / "loop", dir / "loop");
  for (const fs::path& folder : {dir / "out", dir / "out" / "sub", dir / "loop"}) {
    const std::string problem = unwritable_folder_problem(folder);
    EXPECT_NE(problem.find("is a symbolic link to"), std::string::npos) << problem;
    EXPECT_NE(problem.find("which does not exist or leads in a loop"), std::string::npos) << problem;
    EXPECT_EQ(output_folder_problem(folder, {}), problem);
  }
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "out")));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "loop")));
  EXPECT_EQ(dangling_link_problem(dir / "new"), "");
  fs::remove_all(dir);
}

TEST(ReadFile, AFileLargerThanItsKindMayBeIsRefusedBeforeItIsRead) {
  // A 1 GB block source ended in std::bad_alloc under a 3 GB limit (the twenty-first pass's P4); the cap is the
  // caller's, and a file at it is read whole.
  const fs::path dir = scratch("sizes");
  std::ofstream(dir / "f.md") << std::string(1000, 'a');
  EXPECT_EQ(read_file(dir / "f.md", "cannot read", 1000).size(), 1000u);
  const std::string m = message_of([&] { read_file(dir / "f.md", "cannot read", 999); });
  EXPECT_NE(m.find("f.md: 1000 bytes: more than the 999 bytes"), std::string::npos) << m;
  fs::remove_all(dir);
}

TEST(WriteFileAtomic, AReplacedFileKeepsItsPermissionsAndAReadOnlyOneIsKept) {
  // A private report stays private (it was rewritten as 0644, world-readable); a read-only one is not replaced.
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(testing::TempDir()) / "beamid_perms";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file_atomic(dir / "private.md", "one\n");
  fs::permissions(dir / "private.md", fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
  write_file_atomic(dir / "private.md", "two\n");
  EXPECT_EQ(fs::status(dir / "private.md").permissions(), fs::perms::owner_read | fs::perms::owner_write);
  fs::permissions(dir / "private.md", fs::perms::owner_read, fs::perm_options::replace);
  const std::string m = message_of([&] { write_file_atomic(dir / "private.md", "three\n"); });
  EXPECT_NE(m.find("private.md: is read-only"), std::string::npos) << m;
  fs::permissions(dir / "private.md", fs::perms::owner_all, fs::perm_options::replace);
  fs::remove_all(dir);
}

TEST(WriteFileAtomic, NeverReplacesAPipeALinkOrAFolder) {
  const fs::path dir = scratch("special");
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  { std::ofstream(dir / "target") << "kept"; }
  fs::create_symlink(dir / "target", dir / "link");
  fs::create_directory(dir / "folder");
  for (const std::string name : {"pipe", "link", "folder"}) {
    const std::string m = message_of([&] { write_file_atomic(dir / name, "x\n"); });
    EXPECT_NE(m.find("an output replaces only a regular file"), std::string::npos) << name << ": " << m;
  }
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(dir / "pipe")));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link")));
  write_file_atomic(dir / "target", "new\n");  // a regular file is replaced
  std::ifstream in(dir / "target");
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "new");
  fs::remove_all(dir);
}

TEST(OutputFolder, RefusesAFolderOfTheUsersFilesOrOneThatHoldsAnInput) {
  const fs::path dir = scratch("folders");
  EXPECT_EQ(output_folder_problem(dir / "new", {}), "");  // a new folder
  EXPECT_EQ(output_folder_problem(dir, {}), "");          // an empty one
  { std::ofstream(dir / "cases.csv") << "my notes"; }
  EXPECT_NE(output_folder_problem(dir, {}).find("no manifest.json or store/"), std::string::npos);
  { std::ofstream(dir / "manifest.json") << "{}"; }
  EXPECT_EQ(output_folder_problem(dir, {}), "");  // an earlier output of beamid
  { std::ofstream(dir / "study.toml") << ""; }
  EXPECT_NE(output_folder_problem(dir, {(dir / "study.toml").string()}).find("holds the input"), std::string::npos);
  EXPECT_EQ(output_folder_problem(dir, {(dir.parent_path() / "elsewhere.toml").string()}), "");
  EXPECT_NE(output_folder_problem(dir / "cases.csv", {}).find("not a folder"), std::string::npos);
  // Another study's results: refused by the manifest's study name, whether or not its study file (relative to the
  // folder the run started in) can be found from here (the twelfth pass's P1).
  {
    std::ofstream(dir / "manifest.json") << "{\n  \"study\": \"paper\",\n  \"study_file\": \"nowhere/paper.toml\"\n}\n";
  }
  EXPECT_NE(output_folder_problem(dir, {}, "real.toml", "real-steel").find("another study, 'paper'"),
            std::string::npos);
  EXPECT_EQ(output_folder_problem(dir, {}, "paper.toml", "paper"), "");
  fs::remove_all(dir);
}

TEST(Files, AStoreIsClaimedByOneStudyFile) {
  // The seventh pass's S69 and S73: two study files of one [study] name, run at overlapping times or from another
  // working folder, each took the other's finished units for damaged ones. The first run claims the store; the same
  // file (by path, or a copy of the same text elsewhere) is let in, another file is refused naming the owner, and a
  // claim whose file is gone (renamed) is taken over.
  const fs::path dir = scratch("claim");
  const fs::path store = dir / "results" / "store";
  const auto write = [&](const fs::path& p, const std::string& text) { std::ofstream(p) << text; };
  write(dir / "a.toml", "seed = 1\n");
  write(dir / "b.toml", "seed = 2\n");
  fs::create_directories(dir / "elsewhere");
  write(dir / "elsewhere" / "a.toml", "seed = 1\n");
  EXPECT_EQ(claim_store(store, (dir / "a.toml").string()), "");
  EXPECT_TRUE(fs::exists(store / "claim"));
  EXPECT_EQ(claim_store(store, (dir / "a.toml").string()), "");
  EXPECT_EQ(claim_store(store, (dir / "elsewhere" / "a.toml").string()), "");
  const std::string refused = claim_store(store, (dir / "b.toml").string());
  EXPECT_NE(refused.find("holds the units of another study file, " + fs::weakly_canonical(dir / "a.toml").string()),
            std::string::npos)
      << refused;
  fs::remove(dir / "a.toml");
  EXPECT_EQ(claim_store(store, (dir / "b.toml").string()), "");
  EXPECT_NE(claim_store(store, (dir / "elsewhere" / "a.toml").string()), "");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace beamid::io
