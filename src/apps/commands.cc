#include "apps/commands.h"

#include <cmath>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/verification.h"
#include "io/provenance.h"
#include "galerkin/modes.h"
#include "io/arguments.h"
#include "io/csv.h"
#include "io/report_blocks.h"
#include "model/beam_toml.h"
#include "model/errors.h"
#include "model/exact_frequencies.h"
#include "simulation/simulator.h"

namespace beamid::apps {
namespace {

const io::FlagSpec kBeam{"beam", true, "preset (banks-aluminium, thick-steel) or a TOML file with a [beam] table"};
const io::FlagSpec kElements{"elements", true, "Galerkin order N >= 1 (cubic B-spline elements)"};

int elements(const io::Arguments& a) {
  const int n = a.integer("elements");
  a.require(n >= 1 && n <= 1000, "elements", "must be an integer in 1..1000");
  return n;
}

}  // namespace

std::string overview() {
  return std::string("beamid ") + io::version() + " (commit " + io::commit_label() +
         "): identification of Timoshenko-beam parameters (Banks & Wang 1993)\n"
         "\n"
         "usage: beamid COMMAND [flags]     (beamid COMMAND --help for its flags)\n"
         "  modes      natural frequencies and damping ratios (Galerkin or exact)\n"
         "  simulate   sampled sensor signal of a pulse or pluck experiment, as CSV\n"
         "  spikes     the DFT spikes of a record, with their 20 % supports\n"
         "  cost       the time, spike or spike-smooth cost of a prediction against data\n"
         "  fit        identify beam parameters from a record (NLopt or Ceres, direct or staged)\n"
         "  verify     forward-model verification tables (Galerkin vs exact, fast vs CVODE)\n"
         "  report     refresh the generated blocks of REPORT.md from results/\n"
         "  study      run a study file (studies/*.toml): cases in parallel, resumable, tables in results/<study>/\n"
         "  merge      combine the results of a study's shards (--shard K/N) into the tables of one run\n"
         "  real       fit a measured free-decay record with each cost (studies/real-steel.toml)\n";
}

int run_modes(const Args& args, std::ostream& out) {
  const io::Arguments a("modes", args,
                        {kHelpFlag, kBeam, kElements, {"exact", false, "exact Timoshenko frequencies from the determinant"},
                         {"undamped", false, "undamped Galerkin frequencies (damping_ratio 0)"},
                         {"count", true, "number of modes (default: all underdamped Galerkin modes, 4 exact)"}});
  if (wants_help(a, out, "--beam B (--elements N [--undamped] | --exact) [--count K]")) return 0;
  const model::BeamParameters beam = model::resolve_beam(a.text("beam"));
  const std::optional<int> count = a.optional_integer("count");
  a.require(!count || *count >= 1, "count", "must be >= 1");
  if (a.has("exact") == a.has("elements"))
    throw InputError("beamid modes: give exactly one of --elements N (Galerkin) and --exact (determinant)");

  if (a.has("exact")) {
    if (a.has("undamped")) throw InputError("beamid modes: --undamped goes with --elements, not --exact");
    const auto omega = model::timoshenko_frequencies_rad_s(beam, count.value_or(4));
    if (count && static_cast<int>(omega.size()) < *count)
      throw InputError("beamid modes: --count = " + std::to_string(*count) + ": only " +
                       std::to_string(omega.size()) + " modes lie below the shear cut-off");
    out << "mode,frequency_hz\n";
    for (std::size_t k = 0; k < omega.size(); ++k)
      out << k + 1 << "," << io::full_precision(omega[k] / (2 * std::numbers::pi)) << "\n";
    return 0;
  }

  const galerkin::SplineSpace space(elements(a));
  const galerkin::SecondOrderSystem system = galerkin::assemble(space, beam);
  out << "mode,frequency_hz,damping_ratio\n";
  if (a.has("undamped")) {
    const Eigen::VectorXd omega = galerkin::undamped_modes(system).omega_rad_s;
    const int shown = std::min<int>(count.value_or(static_cast<int>(omega.size())), static_cast<int>(omega.size()));
    for (int k = 0; k < shown; ++k)
      out << k + 1 << "," << io::full_precision(omega(k) / (2 * std::numbers::pi)) << ","
          << io::full_precision(0.0) << "\n";
    return 0;
  }
  const auto modes = galerkin::StateSpaceModes(system).underdamped_modes();
  const std::size_t shown = std::min<std::size_t>(count.value_or(static_cast<int>(modes.size())), modes.size());
  for (std::size_t k = 0; k < shown; ++k)
    out << k + 1 << "," << io::full_precision(modes[k].frequency_hz) << ","
        << io::full_precision(modes[k].damping_ratio) << "\n";
  return 0;
}

int run_simulate(const Args& args, std::ostream& out) {
  std::vector<io::FlagSpec> flags{kHelpFlag, kBeam, kElements};
  for (const auto& f : experiment_flag_specs()) flags.push_back(f);
  const io::Arguments a(
      "simulate", args,
      join_flags(flags, {
       {"integrator", true, "fast | cvode (default fast)"},
       {"rtol", true, "CVODE relative tolerance (default 1e-10)"},
       {"atol", true, "CVODE absolute tolerance (default: rtol times the state's natural size)"},
       {"max-order", true, "CVODE BDF order limit 1..5 (default 5)"},
       {"verbose", false, "say on stderr what ran, with the integrator statistics"}}));
  if (wants_help(a, out, "--beam B --elements N [experiment flags] [--integrator fast|cvode]")) return 0;
  const std::string beam_name = a.text("beam");
  const model::BeamParameters beam = model::resolve_beam(beam_name);
  const int n = elements(a);

  const simulation::Experiment e = read_experiment(a, beam.l);

  simulation::SimulatorOptions options;
  options.integrator = a.text_or("integrator", options.integrator);
  options.cvode.rtol = a.optional_number("rtol").value_or(options.cvode.rtol);
  options.cvode.atol = a.optional_number("atol").value_or(options.cvode.atol);
  options.cvode.max_order = a.optional_integer("max-order").value_or(options.cvode.max_order);
  if (auto error = simulation::validation_error(options)) throw InputError("beamid simulate: " + *error);

  const galerkin::SplineSpace space(n);
  const galerkin::BeamForms forms(space, beam.l);
  const simulation::Trace trace = simulation::simulate(forms, beam, e, options);
  if (!trace.ok()) throw NumericalError("beamid simulate: " + trace.status);

  std::ostringstream csv;
  csv << "t_s," << simulation::output_column(e.output) << "\n";
  for (int i = 0; i < e.samples; ++i) io::write_row(csv, {i * e.dt_s, trace.y[static_cast<std::size_t>(i)]});
  out << csv.str();
  if (a.has("verbose")) {
    const auto& s = trace.stats;
    std::cerr << "beamid simulate (commit " << io::commit_label() << "): beam " << beam_name << ", N = " << n
              << ", " << e.excitation << ", " << e.output << ", dt = " << e.dt_s << " s, " << e.samples
              << " samples, integrator " << s.integrator << ": steps " << s.steps << ", rhs " << s.rhs_evaluations
              << ", jacobians " << s.jacobian_evaluations << ", linear-solver setups " << s.linear_solver_setups << ", error-test failures " << s.error_test_failures
              << ", modes " << s.modes << ", eigenvector rcond " << s.eigenvector_rcond << "\n";
  }
  return 0;
}

int run_verify(const Args& args, std::ostream& out) {
  const io::Arguments a("verify", args, {kHelpFlag, {"output", true, "folder for the CSV and Markdown tables"}});
  if (wants_help(a, out, "--output DIR")) return 0;
  write_verification(a.text("output"), out);
  return 0;
}

int run_report(const Args& args, std::ostream& out) {
  const io::Arguments a("report", args,
                        {kHelpFlag, {"update", true, "the Markdown report whose generated blocks are refreshed"},
                         {"results", true, "folder the block names are relative to (default results)"}});
  if (wants_help(a, out, "--update REPORT.md [--results DIR]")) return 0;
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
  const std::string temporary = path + ".tmp";
  {
    std::ofstream write(temporary, std::ios::binary);
    write << updated;
    if (!write) throw InputError("beamid report: cannot write " + temporary);
  }
  std::filesystem::rename(temporary, path);  // atomic: a reader sees the old or the new report, never half
  out << "report: " << contents.size() << " generated block(s) refreshed in " << path << "\n";
  return 0;
}

}  // namespace beamid::apps
