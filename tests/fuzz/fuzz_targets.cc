#include "fuzz_targets.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "apps/cli.h"
#include "config/beam_file.h"
#include "core/errors.h"
#include "io/report_blocks.h"
#include "io/time_series.h"
#include "study/run/record_schema.h"
#include "study/run/store.h"
#include "study/spec/study_spec.h"

namespace beamid::fuzz {
namespace {

std::string text_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// The accepted outcomes: a result, or a one-line input or numerical error.
template <class F>
void expect_value_or_error(F f) {
  try {
    f();
  } catch (const InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) throw std::logic_error("a multi-line error");
  } catch (const NumericalError&) {
  }
}

}  // namespace

void beam_file(const std::uint8_t* data, std::size_t size) {
  expect_value_or_error([&] { config::parse_beam_toml(text_of(data, size), "fuzz.toml"); });
}

void study_file(const std::uint8_t* data, std::size_t size) {
  expect_value_or_error([&] { study::parse_study(text_of(data, size), "fuzz.toml", "."); });
}

void csv_record(const std::uint8_t* data, std::size_t size) {
  expect_value_or_error([&] { io::parse_time_series(text_of(data, size), "fuzz.csv"); });
}

void lvm_record(const std::uint8_t* data, std::size_t size) {
  expect_value_or_error([&] { io::parse_time_series(text_of(data, size), "fuzz.lvm"); });
}

void npy_record(const std::uint8_t* data, std::size_t size) {
  io::ImportOptions o;
  o.sample_rate_hz = 1000;  // an array has no time base
  o.channel = "1";
  expect_value_or_error([&] { io::parse_time_series(text_of(data, size), "fuzz.npy", o); });
}

void uff_record(const std::uint8_t* data, std::size_t size) {
  io::ImportOptions o;
  o.channel = "1";
  expect_value_or_error([&] { io::parse_time_series(text_of(data, size), "fuzz.uff", o); });
}

void command_line(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args{"beamid"};
  std::string current;
  for (std::size_t i = 0; i < size && args.size() < 64; ++i) {
    if (data[i] == 0) {
      args.push_back(current);
      current.clear();
    } else {
      current += static_cast<char>(data[i]);
    }
  }
  if (!current.empty()) args.push_back(current);
  std::ostringstream out, err;
  const int status = apps::check_command_line(args, out, err);
  const std::string e = err.str();
  // The contract: success, or one line on stderr with status 2.
  if (status != 0 && !(status == 2 && (e.empty() || e.find('\n') == e.size() - 1)))
    throw std::logic_error("command line: status " + std::to_string(status) + ", stderr '" + e + "'");
}

// A store record as found on disk (a damaged, altered or foreign one): the store reads it back checked against a
// case's schema, or moves it aside, and never crashes. Each input is one file in a per-process folder.
void store_record(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  // The folder goes with the process (libFuzzer ends by exit(), which runs static destructors): a fuzz pass leaves
  // nothing in the temporary directory.
  struct ProcessFolder {
    fs::path path = fs::temp_directory_path() / ("beamid-fuzz-store-" + std::to_string(::getpid()));
    ~ProcessFolder() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const ProcessFolder folder;
  const fs::path& dir = folder.path;
  std::ostringstream log;
  const study::Store store(dir.string(), "fuzz", &log);
  {
    std::ofstream out(dir / "0123456789abcdef.rec", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  study::Unit unit;
  unit.kind = study::UnitKind::Case;
  unit.id = "0123456789abcdef";
  expect_value_or_error([&] {
    const auto record = study::load_unit(store, unit, {"EI", "rho"});
    if (record) record->numbers("estimate.EI");
  });
  std::error_code ec;
  fs::remove_all(dir / "damaged", ec);
  if (log.str().find('\n') != log.str().size() - 1 && !log.str().empty())
    throw std::logic_error("store: a log that is not one line: " + log.str());
}

// A report with generated blocks: its names and the replaced text, and each block's source file, or a one-line error
// (a name outside the results folder among them).
void report_blocks(const std::uint8_t* data, std::size_t size) {
  const std::string text = text_of(data, size);
  expect_value_or_error([&] {
    std::map<std::string, std::string> contents;
    for (const std::string& name : io::block_names(text, "fuzz.md")) {
      const auto file = io::block_source("results", name, "fuzz.md");
      if (file.is_absolute() || file.lexically_normal().string().rfind("results", 0) != 0)
        throw std::logic_error("block '" + name + "' reads " + file.string() + ", outside results/");
      contents[name] = "generated\n";
    }
    io::replace_blocks(text, contents, "fuzz.md");
  });
}

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"beam_file", beam_file},       {"study_file", study_file},     {"csv_record", csv_record},
      {"lvm_record", lvm_record},     {"npy_record", npy_record},     {"uff_record", uff_record},
      {"command_line", command_line}, {"store_record", store_record}, {"report_blocks", report_blocks}};
  return all;
}

}  // namespace beamid::fuzz
