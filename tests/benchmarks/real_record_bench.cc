// Real-record fits as a user waits for them (make bench; issue 32's targets: one record's fit <= 1 s, a joint fit of
// four records <= 10 s): each iteration runs the beamid program itself, a fresh process as a user's command is, so
// that the process-wide caches (the matrix pencil's Hankel basis) start empty and reading the record counts.
//   RealRecordFit/modal, /spike_smooth: README's fit of the steel cantilever's free decay (ARTS-Lab, CC BY-SA 4.0:
//     studies/data/arts-steel-cantilever/), 8 s at 1,652 Hz, N = 16, EI, cDI and gamma, with its report.
//   JointRealFit: tests/benchmarks/joint_real_fit.toml, four UnB records, one EI, a cDI each, the route from nominal
//     starts (modal from 8 starts, then spike-smooth), `beamid real`.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace {

// Runs the program with `args`, its output to /dev/null; false (with the reason in `why`) when it did not exit 0.
bool run_program(const std::vector<std::string>& args, std::string& why) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(BEAMID_PROGRAM));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, BEAMID_PROGRAM, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    why = std::string("cannot start ") + BEAMID_PROGRAM;
    return false;
  }
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    why = std::string(BEAMID_PROGRAM) + " " + args.front() + " failed (run it by hand to see why)";
    return false;
  }
  return true;
}

// A fresh scratch folder for one benchmark's outputs, removed afterwards.
struct Scratch {
  std::filesystem::path path;
  explicit Scratch(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("beamid-bench-" + name + "-" + std::to_string(getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Scratch() { std::filesystem::remove_all(path); }
};

void BM_RealRecordFit(benchmark::State& state, const std::string& cost) {
  const std::string arts = std::string(BEAMID_SOURCE_DIR) + "/studies/data/arts-steel-cantilever";
  const Scratch scratch("real-" + cost);
  const std::vector<std::string> args = {"fit",
                                         "--data",
                                         arts + "/timeseries_data.lvm",
                                         "--start",
                                         "1.2",
                                         "--duration",
                                         "8",
                                         "--beam",
                                         arts + "/steel_cantilever.toml",
                                         "--elements",
                                         "16",
                                         "--estimate",
                                         "EI,cDI,gamma",
                                         "--bounds",
                                         "EI=50:200,cDI=1e-5:1e-2,gamma=0.001:5",
                                         "--excitation",
                                         "free-decay",
                                         "--cost",
                                         cost,
                                         "--spike-frequencies",
                                         "6.62,41.38,116.9,229.8,380.5",
                                         "--report",
                                         (scratch.path / "steel.md").string()};
  std::string why;
  for (auto _ : state)
    if (!run_program(args, why)) state.SkipWithError(why.c_str());
}
BENCHMARK_CAPTURE(BM_RealRecordFit, modal, std::string("modal"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_RealRecordFit, spike_smooth, std::string("spike-smooth"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_JointRealFit(benchmark::State& state) {
  const Scratch scratch("joint");
  int run = 0;
  std::string why;
  for (auto _ : state) {
    const std::string output = (scratch.path / std::to_string(run++)).string();  // `real` writes a new folder
    if (!run_program(
            {"real", std::string(BEAMID_SOURCE_DIR) + "/tests/benchmarks/joint_real_fit.toml", "--output", output},
            why))
      state.SkipWithError(why.c_str());
  }
}
BENCHMARK(BM_JointRealFit)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
