#include "study/run/runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <thread>
#include <tuple>
#include <unordered_set>

#include "core/errors.h"
#include "core/limits.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/resources.h"
#include "study/plan/plan.h"
#include "study/run/estimate.h"
#include "study/run/execute.h"
#include "study/run/record_schema.h"
#include "study/run/store.h"
#include "study/tables/tables.h"

namespace beamid::study {
namespace {

std::string duration_text(double s) {
  char buf[32];
  if (s < 90)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400)
    std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

class Progress {
 public:
  Progress(std::ostream& log, bool terminal, std::string what, int total)
      : log_(log), terminal_(terminal), what_(std::move(what)), total_(total), t0_(std::chrono::steady_clock::now()) {}
  void tick(bool failed) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    failed_ += failed ? 1 : 0;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const double eta = done_ > 0 ? elapsed / done_ * (total_ - done_) : 0;
    const int percent = total_ > 0 ? 100 * done_ / total_ : 100;
    if (terminal_) {
      const int width = 30, filled = total_ > 0 ? width * done_ / total_ : width;
      log_ << "\r" << what_ << " [" << std::string(static_cast<std::size_t>(filled), '#')
           << std::string(static_cast<std::size_t>(width - filled), '.') << "] " << done_ << "/" << total_ << ", "
           << failed_ << " failed, " << duration_text(elapsed) << " elapsed, ETA " << duration_text(eta) << "   "
           << std::flush;
      if (done_ == total_) log_ << "\n";
    } else if (done_ == total_ || percent >= next_percent_ || elapsed >= next_time_) {
      log_ << what_ << ": " << done_ << "/" << total_ << " (" << percent << " %), " << failed_ << " failed, "
           << duration_text(elapsed) << " elapsed, ETA " << duration_text(eta) << "\n"
           << std::flush;
      next_percent_ = percent + 10;
      next_time_ = elapsed + 30;
    }
  }

 private:
  std::ostream& log_;
  bool terminal_;
  std::string what_;
  int total_, done_ = 0, failed_ = 0, next_percent_ = 10;
  double next_time_ = 30;
  std::chrono::steady_clock::time_point t0_;
  std::mutex mutex_;
};

// Runs `work(i)` for i in [0, count) on `jobs` threads; the first exception stops the others and is rethrown.
template <class Work>
void parallel_for(int count, int jobs, Work work) {
  std::atomic<int> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto worker = [&] {
    for (;;) {
      const int i = next.fetch_add(1);
      if (i >= count || stop) return;
      try {
        work(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::min(jobs, count); ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

int job_count(int jobs) {
  if (jobs > 0) return jobs;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

// The command line's N^3 warning here too: a study at truth N = 400 printed its header and then nothing for 2.5
// minutes (the tenth pass's ST_06). Each truth record is one eigen-analysis at N_truth; each unit hundreds at its N.
void say_model_cost(const StudySpec& spec, const std::vector<const Unit*>& mine, std::ostream& log) {
  int fitted = 0;
  for (const Unit* u : mine) fitted = std::max(fitted, u->elements);
  for (const auto& [what, n, count] : {std::tuple{"truth.elements", spec.truth.elements, "each truth record"},
                                       std::tuple{"the largest fitted N", fitted, "each of a fit's hundreds"}}) {
    const double seconds = core::seconds_per_evaluation(n);
    if (seconds > 1)
      log << "beamid study: " << what << " = " << n << ": one model evaluation (" << count << ") takes about "
          << io::seconds_text(seconds) << " here (it grows as N^3)\n"
          << std::flush;
  }
}

// What the store lacks: the truths (their indices; the others are loaded into `truths`) and this shard's units to run,
// with both in `all` for the plan's estimate.
struct ToRun {
  std::vector<int> truths;
  std::vector<const Unit*> units, all;
  int reused = 0;
};
ToRun to_run(const StudySpec& spec, const Plan& plan, const std::vector<const Unit*>& mine, const Store& store,
             std::vector<Record>& truths) {
  ToRun out;
  for (std::size_t i = 0; i < plan.truths.size(); ++i) {
    if (auto r = load_unit(store, plan.truths[i], spec.fit.estimate)) {
      truths[i] = *r;
    } else {
      out.truths.push_back(static_cast<int>(i));
      out.all.push_back(&plan.truths[i]);
    }
  }
  for (const Unit* u : mine) {
    if (load_unit(store, *u, spec.fit.estimate)) {
      ++out.reused;
    } else {
      out.units.push_back(u);
      out.all.push_back(u);
    }
  }
  return out;
}

// The units of the plan in the store, and how many of this run's (`mine`, computed now or reused) failed: counted only
// among those computed now, a resumed study said 0 failed cases beside tables that held 2 (the twentieth pass's P8).
// One read of each record serves both counts.
std::pair<int, int> present_and_failed(const StudySpec& spec, const Plan& plan, const std::vector<const Unit*>& mine,
                                       const Store& store) {
  const std::unordered_set<const Unit*> own(mine.begin(), mine.end());
  int present = 0, failed = 0;
  for (const Unit& u : plan.units)
    if (const auto r = load_unit(store, u, spec.fit.estimate)) {
      ++present;
      if (own.count(&u) && r->text("status").rfind("failed", 0) == 0) ++failed;
    }
  return {present, failed};
}

// After a run: the tables, when every unit of the plan is in the store; else, for a shard, how many are; and for a
// whole run whose saved units do not all read back (a store file replaced meanwhile), no tables and exit 1, not
// "pending" as if a shard were missing (the twenty-first pass's P1).
void finish_run(const StudySpec& spec, const Plan& plan, const std::vector<const Unit*>& mine, const Store& store,
                const std::string& output_dir, std::ostream& log, RunSummary& summary) {
  const auto [present, failed_units] = present_and_failed(spec, plan, mine, store);
  summary.failed = failed_units;
  if (present == static_cast<int>(plan.units.size())) {
    write_tables(spec, plan, store, output_dir, log);
    summary.tables = true;
    log << "tables written to " << output_dir << "\n";
  } else if (mine.size() == plan.units.size()) {
    throw OutputError(store.directory() + ": " + std::to_string(plan.units.size() - present) + " of the " +
                      std::to_string(plan.units.size()) +
                      " units saved by this run could not be read back (the lines above say why); the tables are not "
                      "written: run the study again to recompute them");
  } else {
    log << present << "/" << plan.units.size() << " units in " << store.directory()
        << "; the tables are written once every shard is done (beamid merge)\n";
  }
}

}  // namespace

std::optional<std::string> validation_error(const RunOptions& o) {
  if (o.jobs < 0) return "jobs = " + std::to_string(o.jobs) + ": must be >= 0 (0: all cores)";
  if (o.shard_count < 1 || o.shard_index < 1 || o.shard_index > o.shard_count)
    return "shard = " + std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count) +
           ": must be K/N with 1 <= K <= N";
  if (o.output_dir.empty()) return "output = '': must name a folder";
  return std::nullopt;
}

namespace {

// A failed truth is said once per reason (its cases become rows with its status): every mode above Nyquist or a
// sensor cut-off below the modes left only failed rows, and nothing on the terminal said why (the twenty-third
// pass's P1).
void say_failed_truths(const std::vector<Record>& truths, std::ostream& log) {
  std::vector<std::string> said;
  for (const Record& t : truths) {
    if (!t.has("status")) continue;
    const std::string status = t.text("status");
    if (status == "ok" || std::find(said.begin(), said.end(), status) != said.end()) continue;
    said.push_back(status);
    log << "beamid study: a truth record " << status << ": its cases are rows with that status\n" << std::flush;
  }
}

}  // namespace

RunSummary run_study(const StudySpec& spec, const RunOptions& options, std::ostream& log, bool terminal) {
  if (auto e = validation_error(options)) throw InputError("beamid study: " + *e);
  if (const std::string problem =
          io::output_folder_problem(options.output_dir, {spec.path, spec.truth.beam_path}, spec.path, spec.name);
      !problem.empty())
    throw InputError("beamid study: --output " + options.output_dir + ": " + problem);
  if (const std::string problem = io::unwritable_folder_problem(options.output_dir); !problem.empty())
    throw InputError("beamid study: --output " + options.output_dir + ": " + problem);
  const Plan plan = make_plan(spec);
  const int jobs = job_count(options.jobs);
  const std::vector<const Unit*> mine = shard(plan.units, options.shard_index, options.shard_count);
  // The size of the run, before anything runs: memory for the truth records kept in memory and one record per
  // thread, and a warning with the expected time for a large plan (a unit at N = 16 takes about 1 s here: the paper
  // study's 762 units took 6.5 min on 2 threads).
  int longest = 0;
  for (int n : spec.sweep.samples) longest = std::max(longest, n);
  // A truth measured through a sensor filter is simulated oversampling times finer, and so is a method's model with
  // that filter in it (sensor_in_model): each thread holds a record that much longer.
  const double fine = spec.truth.sensor.cutoff_hz > 0 ? spec.truth.sensor.oversampling : 1;
  io::check_memory("beamid study " + spec.path,
                   8.0 * spec.truth.experiment.samples * static_cast<double>(plan.truths.size()) +
                       jobs * core::kRecordBytesPerSample * longest * fine,
                   log);
  if (mine.size() > 20000)
    log << "beamid study: " << mine.size() << " units: at about 1 s each that is "
        << io::seconds_text(kSecondsPerUntimedUnit * static_cast<double>(mine.size()) / jobs) << " on " << jobs
        << " thread(s); split it with --shard K/N (beamid merge joins the shards)\n";
  validate_plan(spec, plan);
  if (const std::string problem = io::claim_store(options.output_dir + "/store", spec.path); !problem.empty())
    throw InputError("beamid study: --output " + options.output_dir + ": " + problem);
  const Store store(options.output_dir + "/store", io::commit_label(), &log);
  if (const std::string removed = io::remove_leftovers_of_output(options.output_dir); !removed.empty())
    log << "beamid study: " << removed << "\n";
  log << "beamid study " << spec.path << " (commit " << io::commit_label() << "): '" << spec.name << "', seed "
      << spec.seed << ", " << plan.truths.size() << " truth record(s), " << plan.units.size() << " units";
  if (options.shard_count > 1)
    log << ", shard " << options.shard_index << "/" << options.shard_count << " = " << mine.size();
  log << ", " << jobs << " thread(s), output " << options.output_dir << "\n" << std::flush;
  say_model_cost(spec, mine, log);

  RunSummary summary;
  summary.units = static_cast<int>(mine.size());
  // Truths: every shard needs them; each is saved as soon as it is made, so shards on one file system share them.
  std::vector<Record> truths(plan.truths.size());
  const ToRun to = to_run(spec, plan, mine, store, truths);
  const std::vector<int>& missing_truths = to.truths;
  const std::vector<const Unit*>& pending = to.units;
  summary.reused = to.reused;
  if (summary.reused > 0) log << summary.reused << " unit(s) already in the store, " << pending.size() << " to run\n";
  if (!to.all.empty()) {
    const std::string timings = options.output_dir + "/timings.csv";
    log << plan_text(estimate_plan(to.all, timings, spec.truth.elements), jobs, timings) << "\n" << std::flush;
  }
  if (!missing_truths.empty()) {
    // The first truth's CVODE cross-check grows steeply below rtol 1e-10 (measured on the thin beam at N = 48: 2 s at
    // 1e-10, 75 s at 1e-13), and nothing else is printed until it ends: said before it starts.
    if (spec.truth.rtol < 1e-11)
      log << "beamid study: truth.rtol = " << spec.truth.rtol
          << ": the first truth record's CVODE cross-check takes up to a minute or more (2 s at 1e-10, 75 s at 1e-13 "
             "measured at N = 48)\n"
          << std::flush;
    Progress progress(log, terminal,
                      "truth records (exact modal closed form, N = " + std::to_string(spec.truth.elements) + ")",
                      static_cast<int>(missing_truths.size()));
    parallel_for(static_cast<int>(missing_truths.size()), jobs, [&](int j) {
      const int i = missing_truths[static_cast<std::size_t>(j)];
      Record r = run_truth(spec, plan.truths[static_cast<std::size_t>(i)]);
      store.save(plan.truths[static_cast<std::size_t>(i)].id, r);
      truths[static_cast<std::size_t>(i)] = r;
      progress.tick(r.text("status") != "ok");
    });
  }
  say_failed_truths(truths, log);
  std::atomic<int> failed{0};
  if (!pending.empty()) {
    Progress progress(log, terminal, spec.name, static_cast<int>(pending.size()));
    parallel_for(static_cast<int>(pending.size()), jobs, [&](int j) {
      const Unit& u = *pending[static_cast<std::size_t>(j)];
      const Record& truth = truths[static_cast<std::size_t>(u.truth)];
      Record r = run_unit(spec, u, truth);
      store.save(u.id, r);
      const bool bad = r.text("status").rfind("failed", 0) == 0;
      failed += bad ? 1 : 0;
      progress.tick(bad);
    });
  }
  summary.computed = static_cast<int>(pending.size());
  finish_run(spec, plan, mine, store, options.output_dir, log, summary);
  return summary;
}

void write_tables_from_store(const StudySpec& spec, const std::string& output_dir) {
  const Plan plan = make_plan(spec);
  write_tables(spec, plan, Store(output_dir + "/store", io::commit_label()), output_dir, std::cerr);
}

}  // namespace beamid::study
