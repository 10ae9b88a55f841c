// Runs a study: the truths first, then every other unit of the plan (or of one shard of it) on `jobs` threads,
// saving each finished unit at once (store.h), then the tables (tables.h) when every unit is in the store.
// The results do not depend on the thread count or the order in which units finish: each unit is a pure function
// of its settings and seed, and the tables are built from the store in plan order.
#pragma once

#include <ostream>
#include <string>

#include "study/spec/study_spec.h"

namespace beamid::study {

struct RunOptions {
  std::string output_dir;  // results/<study>
  int jobs = 0;            // 0: all cores
  int shard_index = 1;     // K of --shard K/N
  int shard_count = 1;     // N
};
// First violated constraint ("jobs = -1: must be >= 0"), or nothing.
std::optional<std::string> validation_error(const RunOptions& options);

struct RunSummary {
  int units = 0;        // in this shard
  int computed = 0;     // run now
  int reused = 0;       // found in the store
  int failed = 0;       // units (of this shard, computed or reused) whose status is "failed"
  bool tables = false;  // every unit of the study was present, and the tables were written
};

// Progress and ETA go to `log` (a bar on a terminal, plain lines otherwise).
RunSummary run_study(const StudySpec& spec, const RunOptions& options, std::ostream& log, bool terminal);

// Builds the tables from a store that holds every unit (after merging shards): InputError naming the missing count
// otherwise.
void write_tables_from_store(const StudySpec& spec, const std::string& output_dir);

}  // namespace beamid::study
