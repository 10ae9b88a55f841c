#include "fuzz_targets.h"

#include <sstream>

#include "apps/cli.h"
#include "config/beam_file.h"
#include "core/errors.h"
#include "io/time_series.h"
#include "study/study_spec.h"

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

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"beam_file", beam_file},   {"study_file", study_file}, {"csv_record", csv_record},    {"lvm_record", lvm_record},
      {"npy_record", npy_record}, {"uff_record", uff_record}, {"command_line", command_line}};
  return all;
}

}  // namespace beamid::fuzz
