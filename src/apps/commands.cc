#include "apps/commands.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/flag_requests.h"
#include "apps/flags.h"
#include "apps/verification.h"
#include "config/beam_file.h"
#include "core/errors.h"
#include "core/limits.h"
#include "galerkin/modes.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/record_samples.h"
#include "io/report_blocks.h"
#include "io/text.h"
#include "model/exact_frequencies.h"
#include "signal/noise.h"
#include "simulation/simulator.h"

namespace beamid::apps {

int run_modes(const Flags& a, std::ostream& out) {
  const api::ModesResult r = api::compute_modes(modes_request_of(a), std::cerr);
  const std::size_t shown = r.frequency_hz.size();
  if (r.kind == "exact") {
    out << "mode,frequency_hz\n";
    for (std::size_t k = 0; k < shown; ++k) out << k + 1 << "," << io::full_precision(r.frequency_hz[k]) << "\n";
    return 0;
  }
  out << "mode,frequency_hz,damping_ratio\n";  // after the computation: a failure prints nothing on stdout
  if (!r.note.empty()) std::cerr << "beamid modes: " << r.note << "\n";
  for (std::size_t k = 0; k < shown; ++k)
    out << k + 1 << "," << io::full_precision(r.frequency_hz[k]) << "," << io::full_precision(r.damping_ratio[k])
        << "\n";
  return 0;
}

int run_simulate(const Flags& a, std::ostream& out) {
  const api::SimulateResult r = api::compute_simulate(simulate_request_of(a), std::cerr);
  const simulation::Experiment& e = r.run.experiment;
  std::ostringstream csv;
  csv << "t_s," << simulation::output_column(e.output) << (r.force_N.empty() ? "" : ",force_N") << "\n";
  for (int i = 0; i < e.samples; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (r.force_N.empty())
      io::write_row(csv, {i * e.dt_s, r.y[k]});
    else
      io::write_row(csv, {i * e.dt_s, r.y[k], r.force_N[k]});
  }
  out << csv.str();
  if (a.has("verbose")) {
    const auto& s = r.trace.stats;
    std::cerr << "beamid simulate (commit " << io::commit_label() << "): beam " << r.run.beam_name
              << ", N = " << r.run.elements << ", " << e.excitation << ", " << e.output << ", dt = " << e.dt_s << " s, "
              << e.samples << " samples, integrator " << s.integrator << ": steps " << s.steps << ", rhs "
              << s.rhs_evaluations << ", jacobians " << s.jacobian_evaluations << ", linear-solver setups "
              << s.linear_solver_setups << ", error-test failures " << s.error_test_failures << ", modes " << s.modes
              << ", eigenvector rcond " << s.eigenvector_rcond;
    if (!s.dominant_error_block.empty())
      std::cerr << "; median step " << s.median_step_s << " s at order " << s.median_order
                << ", largest weighted local error mostly in the " << s.dominant_error_block << " block";
    std::cerr << "\n";
  }
  return 0;
}

namespace {

std::string json_vector(const Eigen::VectorXd& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + io::round_trip(v(i));
  return s + "]";
}

std::string json_matrix(const Eigen::MatrixXd& m) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < m.rows(); ++i) s += (i ? ",\n    " : "") + json_vector(m.row(i).transpose());
  return s + "]";
}

}  // namespace

int run_system(const Flags& a, std::ostream& out) {
  const api::SystemResult r = api::compute_system(model_run_request_of(a), std::cerr);
  const std::string& beam_name = r.run.beam_name;
  const model::BeamParameters& beam = r.run.beam;
  const int n = r.run.elements;
  const galerkin::SecondOrderSystem& system = r.system;
  const simulation::ResponseProblem& p = r.problem;
  // The response problem in the terms of simulation/experiment.h: M w'' + C w' + K w = load P(t), P(t) =
  // amplitude_N sin^2(pi t / pulse_width_s) on [0, pulse_width_s], w(0) = w0, w'(0) = 0, y_i = sensor^T w^(derivative)
  // at t_i = i dt_s.
  out << "{\n  \"beamid\": \"" << io::commit_label() << "\",\n  \"beam\": " << io::json_string(beam_name)
      << ",\n  \"length_m\": " << io::round_trip(beam.l) << ",\n  \"elements\": " << n
      << ",\n  \"dt_s\": " << io::round_trip(p.dt_s) << ",\n  \"samples\": " << p.samples
      << ",\n  \"pulse_width_s\": " << io::round_trip(p.pulse_width_s)
      << ",\n  \"amplitude_N\": " << io::round_trip(p.amplitude_N) << ",\n  \"derivative\": " << p.derivative
      << ",\n  \"load\": " << json_vector(p.load) << ",\n  \"sensor\": " << json_vector(p.sensor)
      << ",\n  \"w0\": " << json_vector(p.w0) << ",\n  \"M\": " << json_matrix(system.M)
      << ",\n  \"C\": " << json_matrix(system.C) << ",\n  \"K\": " << json_matrix(system.K) << "\n}\n";
  return 0;
}

int run_verify(const Flags& a, std::ostream& out) {
  // The same rule as study, real and merge: an output folder is new, empty or beamid's own (a manifest.json or a
  // store/ in it), never a folder of the user's files (verify overwrote a user's frequencies.csv).
  const std::string output = a.text("output");
  a.require(!output.empty(), "output", "must name a folder");
  std::error_code ec;
  if (std::filesystem::exists(output, ec) && !std::filesystem::is_directory(output, ec))
    a.require(false, "output", "is not a folder");
  if (std::filesystem::is_directory(output, ec))
    for (const auto& entry : std::filesystem::directory_iterator(output, ec)) {
      const std::string name = entry.path().filename().string();
      const auto& ours = verification_files();
      // A temporary of beamid's (io::is_leftover_temporary: a killed run's, or another verify's in progress) is no
      // user's file (a killed verify refused to run again into its folder: the twenty-first pass's P10); left alone.
      if (io::is_leftover_temporary(entry.path()) && entry.is_regular_file() && !entry.is_symlink()) continue;
      const auto own = std::find_if(ours.begin(), ours.end(), [&](const auto& f) { return f.first == name; });
      const bool written_by_verify = own != ours.end() && entry.is_regular_file() &&
                                     io::read_file_head(entry.path(), "cannot read", own->second.size()) == own->second;
      if (!written_by_verify)
        a.require(false, "output",
                  "holds " + name +
                      ", which verify did not write: its folder holds only its own "
                      "tables (choose a new or an empty folder)");
    }
  // Its own leftovers, of a killed verify, once their process is gone (the twenty-ninth pass's adv66 P2).
  if (const std::string removed = io::remove_leftovers_of_output(output); !removed.empty())
    std::cerr << "beamid verify: " << removed << "\n";
  write_verification(output, out);
  return 0;
}

// A report and each block's source are read whole: 64 MB is hundreds of times REPORT.md with every block (a 1 GB
// source ended in std::bad_alloc under a 3 GB limit: the twenty-first pass's P4).
constexpr std::uintmax_t kMaxReportBytes = std::uintmax_t{64} << 20;

int run_report(const Flags& a, std::ostream& out) {
  const std::string path = a.text("update");
  // Read as every user file is: a pipe or a device is refused at once, not waited on (io::read_file). The report
  // first: a missing one was blamed on the default --results (the thirteenth pass's 11).
  std::ostringstream text;
  text << io::read_file(path, "cannot read the report given to --update", kMaxReportBytes);
  const std::filesystem::path results = a.text_or("results", "results");
  if (!std::filesystem::is_directory(results)) {
    if (!a.has("results"))
      throw InputError(
          "beamid report: no results/ folder here (the default of --results): run it in the project's "
          "folder, or give --results DIR");
    a.require(false, "results", "must be an existing folder of study results (results/)");
  }
  // A binary file is no Markdown report (random bytes were "0 generated block(s) refreshed", exit 0: the third pass's
  // P431).
  if (auto problem = io::binary_text_problem(text.str(), path)) {
    const std::string where = problem->substr(path.size() + 2);  // "byte N is 0xXX: ..."
    a.require(false, "update", where.substr(0, where.find(':')) + ": a binary file, not a Markdown report");
  }
  std::map<std::string, std::string> contents;
  const std::vector<std::string> names = io::block_names(text.str(), path);
  const std::vector<std::size_t> lines = io::block_lines(text.str(), path);
  for (std::size_t b = 0; b < names.size(); ++b) {
    const std::string& name = names[b];
    // Errors about a block name the report's line of its BEGIN marker (the twenty-first pass's P9).
    const std::string where = "beamid report: " + path + ":" + std::to_string(lines[b]);
    // A block's text comes from results/<name>.md and nowhere else (io::block_source), and never from the report
    // itself (it would paste itself in).
    const std::filesystem::path file = io::block_source(results, name, where);
    std::error_code ec;
    if (std::filesystem::equivalent(file, path, ec) && !ec)
      throw InputError(where + ": block '" + name + "' would read the report itself (" + file.string() + ")");
    if (!std::filesystem::exists(file, ec)) {
      out << "report: block '" << name << "' kept: " << file.string() << " does not exist\n";
      continue;
    }
    std::string content = io::read_file(file, "block '" + name + "': cannot read its source", kMaxReportBytes);
    // A UTF-8 byte-order mark (editors' and spreadsheets' exports on Windows) marks the file's encoding, not its text:
    // pasted after the BEGIN marker, it stopped the table there from rendering (the twenty-eighth pass's adv64 P4).
    if (content.rfind("\xEF\xBB\xBF", 0) == 0) content.erase(0, 3);
    // A source is one of beamid's tables: text, and no marker of its own, which would break the next refresh (its
    // END line closed the block early: the sixteenth pass's P8).
    // Text, as the report itself must be: a control byte other than a tab or a line end (an ESC in a study file's
    // name reached a block through report.md) was pasted, and the next refresh refused the report as binary (the
    // twenty-second pass's P4).
    if (auto problem = io::binary_text_problem(content, file.string()))
      throw InputError("beamid report: " + *problem + " (block '" + name + "': its source must be text)");
    io::check_line_ends(content, file.string());
    if (content.find('\0') != std::string::npos)
      throw InputError("beamid report: " + file.string() + ": block '" + name +
                       "': its source holds NUL bytes, no text");
    if (const std::size_t line = io::marker_line(content); line > 0)
      throw InputError("beamid report: " + file.string() + ":" + std::to_string(line) + ": block '" + name +
                       "': its source holds a GENERATED marker, which would break the report's next refresh");
    contents[name] = std::move(content);
  }
  const std::string updated = io::replace_blocks(text.str(), contents, path);
  io::write_file_atomic(path, updated);  // a reader sees the old or the new report, never half
  out << "report: " << contents.size() << " generated block(s) refreshed in " << path << "\n";
  return 0;
}

}  // namespace beamid::apps
