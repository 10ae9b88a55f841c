// The fuzz targets: each takes arbitrary bytes, feeds them to one reader, and accepts exactly two outcomes, a value
// or a one-line InputError / NumericalError. Anything else (a crash, a sanitizer report, another exception, a hang)
// is a finding. The same functions run under libFuzzer (tests/fuzz/fuzz_main.cc, `make fuzz`) and replay the
// regression inputs in the normal test suite (tests/fuzz/regressions_test.cc), so a fixed crash stays fixed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace beamid::fuzz {

void beam_file(const std::uint8_t* data, std::size_t size);      // [beam] and [geometry] TOML
void study_file(const std::uint8_t* data, std::size_t size);     // study TOML
void csv_record(const std::uint8_t* data, std::size_t size);     // CSV time series
void lvm_record(const std::uint8_t* data, std::size_t size);     // LabVIEW .lvm time series
void npy_record(const std::uint8_t* data, std::size_t size);     // NumPy .npy array
void uff_record(const std::uint8_t* data, std::size_t size);     // UFF dataset 58, ASCII or binary
void command_line(const std::uint8_t* data, std::size_t size);   // beamid arguments, NUL-separated
void store_record(const std::uint8_t* data, std::size_t size);   // a study store record file (study/run/store.h)
void report_blocks(const std::uint8_t* data, std::size_t size);  // a report with generated blocks (io/report_blocks.h)

struct Target {
  std::string name;
  void (*run)(const std::uint8_t*, std::size_t);
};
const std::vector<Target>& targets();

}  // namespace beamid::fuzz
