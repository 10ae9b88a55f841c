// The process's allocator set to keep what the program frees (glibc's mallopt), called first by every entry point
// that runs models: the beamid program, the benchmarks and the Python module.
//
// Why: a model evaluation allocates and frees matrices of tens of kB to tens of MB (the damped modes' products, the
// record-length outputs, a matrix pencil's factors), and glibc hands a freed heap top above its trim threshold
// (128 kB) back to the system, so that the next evaluation faults the same pages in again: one fault per 4 kB, about
// 16 us on the virtual machines this runs on. Measured side by side (perf stat, results byte-identical):
// BM_SimulateFast/16 (one exact forward run of the thin beam) 0.90 ms and 12 page faults a run by default, 0.50 ms and
// none with the heap kept; a measured record's modal fit (README's steel record) 49,063 faults in all by default. A
// study's worker threads allocate from their own arenas, which glibc trims less: there the gain is about 5 %.
// The cost: the process holds its peak heap, plus at most 64 MB of padding, until it exits.
#pragma once

namespace beamid::core {

void keep_freed_memory();

}  // namespace beamid::core
