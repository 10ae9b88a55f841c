// The admissible ranges of the sizes a user chooses, stated once: the command line (apps/) and the study files
// (study/) check against these, so a range cannot differ between two places that accept the same quantity. Beside
// them, the measured resource figures that guard a run before it starts.
#pragma once

namespace beamid::core {

// Galerkin order N of a fitted or simulated model. One model evaluation costs about 3 s at N = 200 and grows as N^3
// (measured on this 2-core machine: 0.07 s at N = 50, 0.44 s at 100, 3.2 s at 200), so N = 400 takes about 25 s
// and 1000 would take minutes per evaluation: 400 is the largest N a single command finishes in reasonable time.
inline constexpr int kMinElements = 1;
inline constexpr int kMaxElements = 400;
inline constexpr int kMinTruthElements = 48;  // N_truth of a synthetic study: finer than any fitted N
inline constexpr int kMaxTruthElements = 400;
inline constexpr int kMinStudySamples = 16;  // record length Nbar in a study
inline constexpr int kMaxStudySamples = 1 << 22;
inline constexpr int kMaxSamples = 1 << 28;      // Nbar of a command (memory is checked against the machine too)
inline constexpr int kMaxSpikes = 64;            // NM
inline constexpr int kMaxStarts = 1000;          // starts of a multi-start fit
inline constexpr int kMaxEvaluations = 1000000;  // per optimizer run
// Rigid bodies on the span of one beam. Real beams carry a handful; the exact reference solves a dense
// 4(K+1)-square system per trial frequency (K = 100: 404 x 404, ~40 ms, a few thousand trials per root march).
inline constexpr int kMaxAttachments = 100;
// Records of one joint fit (a real study's [[record]]s): far more than a lab series, and each is a full fit's work.
inline constexpr int kMaxRecords = 64;

// Samples of a record the matrix pencil takes (signal/matrix_pencil.h): its Hankel matrix is Nbar x 600 doubles and
// its QR costs about 2 Nbar 600^2 flops (measured 0.6 s at Nbar = 4096), so 2^18 samples take about 1.3 GB and
// 40 s; 1e6 ran for minutes without a word and 1e7 ended in bad_alloc. A longer record is cut (--start, --duration)
// or resampled (--resample-rate) first.
inline constexpr int kMaxPencilSamples = 1 << 18;
// Units a study may plan: a unit's plan entry (its canonical text and settings) takes about 1 KB, and one takes
// about 1 s to run, so a million units are 1 GB of plan and 6 days on 2 threads; a sweep of 1e8 planned into 7 GB
// and then ended in bad_alloc. A larger design is split into several study files (or sharded, beamid merge).
inline constexpr double kMaxStudyUnits = 1e6;

// Measured resource use (peak RSS and wall time on this machine, `/usr/bin/time`), for the estimates that guard a
// run before it starts (apps/command_flags.cc, study/run/runner.cc):
inline constexpr double kSecondsPerEvaluationAtN200 = 3.2;  // one model evaluation, growing as N^3
// One model evaluation's decomposition at order N, s: kSecondsPerEvaluationAtN200 (N / 200)^3.
inline double seconds_per_evaluation(double elements) {
  const double r = elements / 200.0;
  return kSecondsPerEvaluationAtN200 * r * r * r;
}
// A simulated record's share of one evaluation, per sample and element (measured: 0.034 s for 1e6 samples at N = 8,
// time cost).
inline constexpr double kSecondsPerSampleAndElement = 4.3e-9;
inline constexpr double kModelBytesPerElement2 = 2.7e3;  // the model's matrices: 106 MB at N = 200, as N^2
inline constexpr double kSimulateBytesPerSample = 110;   // simulate: 108 MB at 1e6 samples, 404 MB at 4e6
inline constexpr double kRecordBytesPerSample = 210;     // reading a CSV record and fitting it: 206/797 MB

}  // namespace beamid::core
