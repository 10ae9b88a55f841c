#include "apps/verification.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "io/files.h"
#include "io/provenance.h"
#include "io/text.h"
#include "model/exact_frequencies.h"
#include "simulation/modal_simulator.h"
#include "simulation/modal_truncation.h"
#include "simulation/simulator.h"

namespace beamid::apps {
namespace {

constexpr int kModes = 4;

std::string sci(double value, int digits = 2) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*e", digits, value);
  return buffer;
}

std::string fixed(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

// The experiment each preset is checked with: model.md's suggested sampling, a sin^2 pulse at 0.7 l short enough
// to excite the first four modes (spectrum main lobe to about 2/tau), the sensor at the tip.
simulation::Experiment experiment_for(const std::string& preset, double length_m) {
  simulation::Experiment e;
  e.force_x_m = 0.7 * length_m;
  e.force_amplitude_N = 1.0;
  if (preset == "banks-aluminium") {
    e.dt_s = 1e-3, e.samples = 4096, e.pulse_width_s = 4e-3;
  } else {
    e.dt_s = 1e-4, e.samples = 8192, e.pulse_width_s = 4e-4;
  }
  return e;
}

// max |a_i - b_i| and max |b_i| over a record: a trace against its reference.
struct Difference {
  double max_abs = 0, max_reference = 0;
  double relative() const { return max_abs / max_reference; }
};
Difference difference(const std::vector<double>& a, const std::vector<double>& reference) {
  Difference d;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    d.max_abs = std::max(d.max_abs, std::abs(a[i] - reference[i]));
    d.max_reference = std::max(d.max_reference, std::abs(reference[i]));
  }
  return d;
}

// Damping moved as a fit moves it: the relaxation times of bending (cDI/EI) and shear (kAcs/kAG) pulled apart (they
// agree on the thin beam, and differ 10x on the thick one) and the shear damping raised. Each is (key, factor); an
// empty key is the preset itself.
struct Variant {
  std::string key;
  double factor;
};

// One row of model_reduction: a preset, a damping variant and an output, the split and what decides its error, and
// both reductions' max |y_reduced - y| / max |y| against the exact response.
struct ReductionRow {
  std::string preset, variant, output;
  int retained = 0, size = 0;
  double gap_ratio = 1;
  simulation::TruncationDiagnostics diagnostics;
  double truncated = 0, decoupled = 0;
};

std::vector<ReductionRow> model_reduction_rows(const std::vector<std::string>& presets, std::ostream& log) {
  const std::vector<Variant> variants = {{"", 1.0}, {"cDI", 1.1}, {"cDI", 0.7}, {"kAcs", 3.0}};
  std::vector<ReductionRow> rows;
  for (const auto& name : presets) {
    for (const Variant& variant : variants) {
      model::BeamParameters beam = model::preset(name);
      std::string label = "preset";
      if (!variant.key.empty()) {
        model::set_parameter_value(beam, variant.key, variant.factor * model::parameter_value(beam, variant.key));
        label = variant.key + " x " + fixed(variant.factor, 1);
      }
      const galerkin::SplineSpace space(16);
      const galerkin::BeamForms forms(space, beam.l, beam.support);
      const galerkin::SecondOrderSystem system = galerkin::combine(forms, beam);
      simulation::Experiment e = experiment_for(name, beam.l);
      const simulation::TruncationSplit split =
          simulation::widest_gap(galerkin::undamped_modes(system).omega_rad_s, std::numbers::pi / e.dt_s);
      const simulation::TruncationDiagnostics diagnostics = simulation::truncation_diagnostics(system, split.retained);
      for (const std::string& output : simulation::output_names().names()) {
        e.output = output;
        const simulation::ResponseProblem problem = simulation::make_problem(forms, system, e);
        const simulation::Trace exact = simulation::ModalSimulator().run(system, problem);
        const simulation::Trace truncated =
            simulation::truncated_response(system, problem, split.retained, simulation::Truncation::truncated);
        const simulation::Trace decoupled =
            simulation::truncated_response(system, problem, split.retained, simulation::Truncation::decoupled);
        for (const simulation::Trace* trace : {&exact, &truncated, &decoupled})
          if (!trace->ok()) throw NumericalError("verify: " + trace->status);
        rows.push_back({name, label, output, split.retained, static_cast<int>(system.M.rows()), split.gap_ratio,
                        diagnostics, difference(truncated.y, exact.y).relative(),
                        difference(decoupled.y, exact.y).relative()});
      }
      log << "verify: model reduction " << name << " " << label << ": " << split.retained << " of " << system.M.rows()
          << " modes retained\n";
    }
  }
  return rows;
}

// The last line of every block: the commit of the program that computed it, which the one-commit rule of REPORT.md
// (tools/report_commits.py) reads, as it reads a study block's.
std::string written_by() { return "\n*Written by `beamid verify`, commit " + io::commit_label() + ".*\n"; }

void write_model_reduction(const std::string& folder, const std::vector<ReductionRow>& rows, std::ostream& log) {
  std::ostringstream csv, md;
  csv << "preset,variant,elements,retained,size,gap_ratio,coupling_relative,slowest_discarded_re,"
         "slowest_discarded_im,nearest_retained_relative,output,truncated_relative_difference,"
         "decoupled_relative_difference\n";
  md << "Modal truncation at N = 16 against the exact response of the whole model (max |y_reduced - y| / max |y|; "
        "the experiments of fast_vs_cvode). The undamped modes are split at the widest gap of their frequencies "
        "above the record's band (omega_{k+1}/omega_k, k above the Nyquist frequency), which on the thin beam puts "
        "its shear modes near sqrt(kAG/rho_r2) above the cut. `truncated` keeps the retained block alone; "
        "`decoupled` keeps every discarded mode as its own damped oscillator too (its static and dynamic response: "
        "only the damping's coupling between the blocks and within the discarded block is dropped). `coupling` is "
        "the largest |C~_ij| / sqrt(C~_ii C~_jj) between a retained mode i and a discarded mode j in the undamped "
        "basis (zero for damping a M + b K). `slowest discarded root` is the smaller root of lambda^2 + C~_jj lambda "
        "+ omega_j^2 over the discarded modes and `nearest` its distance to the nearest eigenvalue of the retained "
        "block, relative: Kelvin-Voigt shear damping puts every stiff shear mode's slow root near -kAG/kAcs, inside "
        "the retained spectrum. A reduction would have to keep the exactness of the forward run, 1e-7 of max |y| on "
        "every output.\n\n"
        "| preset | variant | retained | gap | coupling | slowest discarded root (1/s) | nearest | output | "
        "truncated | decoupled |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ReductionRow& row : rows) {
    const std::complex<double> root = row.diagnostics.slowest_discarded_rad_s;
    csv << row.preset << "," << row.variant << ",16," << row.retained << "," << row.size << ","
        << io::full_precision(row.gap_ratio) << "," << io::full_precision(row.diagnostics.coupling_relative) << ","
        << io::full_precision(root.real()) << "," << io::full_precision(root.imag()) << ","
        << io::full_precision(row.diagnostics.nearest_retained_relative) << "," << row.output << ","
        << io::full_precision(row.truncated) << "," << io::full_precision(row.decoupled) << "\n";
    const std::string root_text = sci(root.real()) + (root.imag() != 0 ? " + " + sci(root.imag()) + "i" : "");
    md << "| " << row.preset << " | " << row.variant << " | " << row.retained << " of " << row.size << " | "
       << fixed(row.gap_ratio, 1) << " | " << sci(row.diagnostics.coupling_relative, 1) << " | " << root_text << " | "
       << sci(row.diagnostics.nearest_retained_relative, 1) << " | " << row.output << " | " << sci(row.truncated)
       << " | " << sci(row.decoupled) << " |\n";
  }
  io::write_file_atomic(std::filesystem::path(folder) / "model_reduction.csv", csv.str());
  io::write_file_atomic(std::filesystem::path(folder) / "model_reduction.md", md.str() + written_by());
  log << "verify: wrote " << folder << "/model_reduction.{csv,md}\n";
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& verification_files() {
  static const std::vector<std::pair<std::string, std::string>> files{
      {"frequencies.csv", "preset,elements,mode,galerkin_hz,exact_hz,relative_error"},
      {"frequencies.md", "Undamped Galerkin frequencies against the exact Timoshenko determinant"},
      {"fast_vs_cvode.csv", "preset,elements,output,cvode_rtol,"},
      {"fast_vs_cvode.md", "The exact modal propagator (`fast`) against CVODE BDF"},
      {"model_reduction.csv", "preset,variant,elements,retained,"},
      {"model_reduction.md", "Modal truncation at N = 16 against the exact response"}};
  return files;
}

void write_verification(const std::string& folder, std::ostream& log) {
  io::make_folder(folder);
  const std::vector<std::string> presets = model::preset_names();

  // 1. Galerkin against exact frequencies.
  std::ostringstream csv, md;
  csv << "preset,elements,mode,galerkin_hz,exact_hz,relative_error\n";
  md << "Undamped Galerkin frequencies against the exact Timoshenko determinant (model.md section 6): relative error "
        "(f_N - f)/f of modes 1-4. Rayleigh-Ritz bounds every Galerkin frequency from above, and the spline space of "
        "order 2N contains that of order N, so f_2N <= f_N; the `bounds` column checks both for every N from 2 to 32, "
        "up to the round-off floor of the thin beam's matrices (1e-8 relative). All N are in "
        "`results/verification/frequencies.csv`; the table shows a selection.\n\n";
  for (const auto& name : presets) {
    const model::BeamParameters beam = model::preset(name);
    const std::vector<double> exact = model::timoshenko_frequencies_rad_s(beam, kModes);
    md << "**" << name << "**, exact: ";
    for (int k = 0; k < kModes; ++k) md << (k ? ", " : "") << fixed(exact[k] / (2 * std::numbers::pi), 4);
    md << " Hz\n\n| N | mode 1 | mode 2 | mode 3 | mode 4 | bounds |\n|---|---|---|---|---|---|\n";
    std::map<int, Eigen::VectorXd> by_n;  // omega for each N, to compare N with N/2 (nested spaces)
    for (int n = 2; n <= 32; ++n) {
      const galerkin::SplineSpace space(n);
      const Eigen::VectorXd omega = galerkin::undamped_modes(galerkin::assemble(space, beam)).omega_rad_s;
      by_n[n] = omega;
      bool bounds_hold = true;
      std::string row = "| " + std::to_string(n) + " |";
      for (int k = 0; k < kModes; ++k) {
        const double error = (omega(k) - exact[k]) / exact[k];
        constexpr double kFloor = 1e-8;  // round-off floor of the thin beam's matrices (see the galerkin tests)
        bounds_hold = bounds_hold && error > -kFloor;
        if (n % 2 == 0 && n / 2 >= 2) bounds_hold = bounds_hold && omega(k) <= by_n[n / 2](k) * (1 + kFloor);
        csv << name << "," << n << "," << k + 1 << "," << io::full_precision(omega(k) / (2 * std::numbers::pi)) << ","
            << io::full_precision(exact[k] / (2 * std::numbers::pi)) << "," << io::full_precision(error) << "\n";
        row += " " + sci(error) + " |";
      }
      row += bounds_hold ? " yes |" : " **no** |";
      const bool shown = n <= 6 || n == 8 || n == 10 || n == 12 || n == 16 || n == 20 || n == 24 || n == 32;
      if (shown || !bounds_hold) md << row << "\n";
    }
    md << "\n";
  }
  io::write_file_atomic(std::filesystem::path(folder) / "frequencies.csv", csv.str());
  io::write_file_atomic(std::filesystem::path(folder) / "frequencies.md", md.str() + written_by());
  log << "verify: wrote " << folder << "/frequencies.{csv,md}\n";

  // 2. The exact modal propagator against CVODE.
  std::ostringstream csv2, md2;
  csv2 << "preset,elements,output,cvode_rtol,max_abs_difference,max_abs_y,relative_difference,cvode_steps,"
          "cvode_rhs_evaluations,cvode_error_test_failures,fast_modes,fast_eigenvector_rcond\n";
  md2 << "The exact modal propagator (`fast`) against CVODE BDF (Newton with the exact Schur complement of the "
         "analytic Jacobian) at N = 16: "
         "max |y_fast - y_cvode| / max |y| over the whole record. A sin^2 pulse at x_f = 0.7 l, sensor at the tip, "
         "banks-aluminium with dt = 1 ms, 4096 samples, tau = 4 ms; thick-steel with dt = 0.1 ms, 8192 samples, "
         "tau = 0.4 ms. The difference falls with CVODE's tolerance: it is CVODE's error, and `fast` has no "
         "time-stepping error of its own.\n\n"
         "| preset | output | rtol | relative difference | CVODE steps | error-test failures |\n"
         "|---|---|---|---|---|---|\n";
  for (const auto& name : presets) {
    const model::BeamParameters beam = model::preset(name);
    const galerkin::SplineSpace space(16);
    const galerkin::BeamForms forms(space, beam.l, beam.support);
    for (const std::string& output : simulation::output_names().names()) {
      simulation::Experiment e = experiment_for(name, beam.l);
      e.output = output;
      simulation::SimulatorOptions fast_options;
      const simulation::Trace fast = simulation::simulate(forms, beam, e, fast_options);
      if (!fast.ok()) throw NumericalError("verify: " + fast.status);
      for (double rtol : {1e-6, 1e-8, 1e-10}) {
        simulation::SimulatorOptions cvode_options;
        cvode_options.integrator = simulation::kCvode;
        cvode_options.cvode.rtol = rtol;
        const simulation::Trace cvode = simulation::simulate(forms, beam, e, cvode_options);
        if (!cvode.ok()) throw NumericalError("verify: " + cvode.status);
        const Difference d = difference(fast.y, cvode.y);
        const double max_diff = d.max_abs, max_y = d.max_reference;
        csv2 << name << ",16," << output << "," << sci(rtol, 0) << "," << io::full_precision(max_diff) << ","
             << io::full_precision(max_y) << "," << io::full_precision(max_diff / max_y) << "," << cvode.stats.steps
             << "," << cvode.stats.rhs_evaluations << "," << cvode.stats.error_test_failures << "," << fast.stats.modes
             << "," << sci(fast.stats.eigenvector_rcond) << "\n";
        md2 << "| " << name << " | " << output << " | " << sci(rtol, 0) << " | " << sci(max_diff / max_y) << " | "
            << cvode.stats.steps << " | " << cvode.stats.error_test_failures << " |\n";
        log << "verify: " << name << " " << output << " rtol " << rtol << ": relative difference " << max_diff / max_y
            << ", " << cvode.stats.steps << " steps\n";
      }
    }
  }
  io::write_file_atomic(std::filesystem::path(folder) / "fast_vs_cvode.csv", csv2.str());
  io::write_file_atomic(std::filesystem::path(folder) / "fast_vs_cvode.md", md2.str() + written_by());
  log << "verify: wrote " << folder << "/fast_vs_cvode.{csv,md}\n";

  // 3. Modal truncation: what dropping the stiff modes' damping coupling costs (simulation/modal_truncation.h).
  write_model_reduction(folder, model_reduction_rows(presets, log), log);
}

}  // namespace beamid::apps
