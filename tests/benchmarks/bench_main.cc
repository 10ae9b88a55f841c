// The benchmarks' main: BENCHMARK_MAIN with the allocator set as the program sets it (core/allocator.h), so that
// what is measured is what the program does.
#include <benchmark/benchmark.h>

#include "core/allocator.h"

int main(int argc, char** argv) {
  beamid::core::keep_freed_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
