#include "apps/commands.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/computations.h"
#include "apps/flags.h"
#include "apps/verification.h"
#include "config/beam_file.h"
#include "galerkin/modes.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/report_blocks.h"
#include "io/text.h"
#include "core/errors.h"
#include "model/exact_frequencies.h"
#include "core/limits.h"
#include "signal/noise.h"
#include "simulation/simulator.h"

namespace beamid::apps {

namespace {

// "--count K: the Galerkin model at N = n has S <what>: S printed" when --count asks for more than the model has.
std::string fewer_modes_note(const ModesResult& r, int elements, const std::string& what) {
  if (!r.requested || *r.requested <= r.available) return "";
  return "--count " + std::to_string(*r.requested) + ": the Galerkin model at N = " + std::to_string(elements) +
         " has " + std::to_string(r.available) + " " + what + ": " + std::to_string(r.available) + " printed";
}

}  // namespace

ModesResult compute_modes(const Flags& a) {
  const model::BeamParameters beam = read_beam(a);
  ModesResult r;
  r.requested = a.optional_integer("count");
  a.require(!r.requested || *r.requested >= 1, "count", "must be >= 1");
  if (!a.has("exact") && !a.has("elements"))
    throw InputError("beamid modes: give one of --elements N (Galerkin) and --exact (determinant)");

  if (a.has("exact")) {
    r.kind = "exact";
    const auto omega = model::timoshenko_frequencies_rad_s(beam, r.requested.value_or(4));
    if (r.requested && static_cast<int>(omega.size()) < *r.requested)
      throw InputError("beamid modes: --count = " + std::to_string(*r.requested) + ": only " +
                       std::to_string(omega.size()) + " modes lie below the shear cut-off");
    for (const double w : omega) r.frequency_hz.push_back(w / (2 * std::numbers::pi));
    r.available = static_cast<int>(omega.size());
    return r;
  }

  guard_run_size(a, a.integer("elements"), 0, 0);
  const galerkin::SplineSpace space(a.integer("elements"));
  const galerkin::SecondOrderSystem system = galerkin::assemble(space, beam);
  if (a.has("undamped")) {
    r.kind = "undamped";
    const Eigen::VectorXd omega = galerkin::undamped_modes(system).omega_rad_s;
    r.available = static_cast<int>(omega.size());
    const int shown = std::min(r.requested.value_or(r.available), r.available);
    r.note = fewer_modes_note(r, a.integer("elements"), "modes");
    for (int k = 0; k < shown; ++k) {
      r.frequency_hz.push_back(omega(k) / (2 * std::numbers::pi));
      r.damping_ratio.push_back(0.0);
    }
    return r;
  }
  r.kind = "damped";
  const auto modes = galerkin::StateSpaceModes(system).underdamped_modes();
  r.available = static_cast<int>(modes.size());
  const int shown = std::min(r.requested.value_or(r.available), r.available);
  r.note = fewer_modes_note(r, a.integer("elements"), "underdamped modes");
  for (int k = 0; k < shown; ++k) {
    r.frequency_hz.push_back(modes[static_cast<std::size_t>(k)].frequency_hz);
    r.damping_ratio.push_back(modes[static_cast<std::size_t>(k)].damping_ratio);
  }
  return r;
}

int run_modes(const Flags& a, std::ostream& out) {
  const ModesResult r = compute_modes(a);
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

SimulateResult compute_simulate(const Flags& a) {
  SimulateResult r{read_model_run(a, core::kSimulateBytesPerSample), {}, {}};
  simulation::SimulatorOptions options;
  options.integrator = a.text_or("integrator", options.integrator);
  options.cvode.rtol = a.optional_number("rtol").value_or(options.cvode.rtol);
  options.cvode.atol = a.optional_number("atol").value_or(options.cvode.atol);
  options.cvode.max_order = a.optional_integer("max-order").value_or(options.cvode.max_order);
  if (auto error = simulation::validation_error(options)) throw InputError("beamid simulate: " + *error);
  // A synthetic lab record: white noise of --noise-level times the clean signal's RMS (signal/noise.h).
  const double noise = a.optional_number("noise-level").value_or(0.0);
  a.require(noise >= 0 && noise <= 10, "noise-level", "must be in [0, 10] (times the signal's RMS)");
  a.require(!a.has("seed") || a.has("noise-level"), "seed", "seeds the noise: give --noise-level too");

  const galerkin::SplineSpace space(r.run.elements);
  const galerkin::BeamForms forms(space, r.run.beam.l, r.run.beam.support);
  r.trace = simulation::simulate(forms, r.run.beam, r.run.experiment, options);
  if (!r.trace.ok()) throw NumericalError("beamid simulate: " + r.trace.status);
  r.y = signal::add_noise(r.trace.y, noise, static_cast<std::uint64_t>(a.optional_integer("seed").value_or(1)));
  return r;
}

int run_simulate(const Flags& a, std::ostream& out) {
  const SimulateResult r = compute_simulate(a);
  const simulation::Experiment& e = r.run.experiment;
  std::ostringstream csv;
  csv << "t_s," << simulation::output_column(e.output) << "\n";
  for (int i = 0; i < e.samples; ++i) io::write_row(csv, {i * e.dt_s, r.y[static_cast<std::size_t>(i)]});
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

SystemResult compute_system(const Flags& a) {
  SystemResult r{read_model_run(a, 0), {}, {}};
  const galerkin::SplineSpace space(r.run.elements);
  const galerkin::BeamForms forms(space, r.run.beam.l, r.run.beam.support);
  r.system = galerkin::combine(forms, r.run.beam);
  r.problem = simulation::make_problem(forms, r.system, r.run.experiment);
  return r;
}

int run_system(const Flags& a, std::ostream& out) {
  const SystemResult r = compute_system(a);
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
  write_verification(a.text("output"), out);
  return 0;
}

int run_report(const Flags& a, std::ostream& out) {
  const std::string path = a.text("update");
  const std::filesystem::path results = a.text_or("results", "results");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("beamid report: --update = '" + path + "': cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  std::map<std::string, std::string> contents;
  for (const auto& name : io::block_names(text.str(), path)) {
    const std::filesystem::path file = results / (name + ".md");
    std::ifstream block(file, std::ios::binary);
    if (!block) {
      out << "report: block '" << name << "' kept: " << file.string() << " does not exist\n";
      continue;
    }
    std::ostringstream body;
    body << block.rdbuf();
    contents[name] = body.str();
  }
  const std::string updated = io::replace_blocks(text.str(), contents, path);
  io::write_file_atomic(path, updated);  // a reader sees the old or the new report, never half
  out << "report: " << contents.size() << " generated block(s) refreshed in " << path << "\n";
  return 0;
}

}  // namespace beamid::apps
