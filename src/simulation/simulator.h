// Forward simulation of a sampled sensor signal: one interface, two integrators.
//   "cvode": SUNDIALS CVODE BDF with the constant analytic Jacobian; the reference and the synthetic-data generator.
//   "fast":  exact modal propagator (modal_simulator.h): the closed-form response of each state-space mode,
//            exact up to round-off at any dt, with no time-stepping error.
// A failed integration is reported in Trace::status, never thrown, so a study can record it as a row.
#pragma once

#include <complex>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "core/names.h"
#include "galerkin/second_order_system.h"
#include "model/beam_parameters.h"
#include "simulation/experiment.h"

namespace beamid::simulation {

struct CvodeOptions {
  double rtol = 1e-10;
  // Absolute tolerance per state component. 0 (default): rtol times the natural size of that block of the
  // state (times 1e-3 for the displacement block, see below), i.e. the largest |w| of the static deflection under the
  // load (or of the pluck's w0) for displacements and rotations, times the lowest-mode Rayleigh frequency for
  // velocities. The 1e-3 on displacements is there because a short pulse's response is far below its static deflection
  // (16x for the thick-steel check, whose agreement with `fast` at rtol 1e-10 goes from 5e-7 to 2e-8 with it); the
  // rotations keep 1 because the thin beam's rotation equations carry round-off noise that a tighter tolerance would
  // chase (CVODE then stalls). A positive value: this absolute tolerance for all components.
  double atol = 0;
  long max_steps_per_sample = 100000;  // CVodeSetMaxNumSteps between two output times
  // A budget over the whole run (0: none). Past it the run stops after the sample it is on, with a status that says so
  // and the trace's y cut to the samples it reached. The studies' cross-check sets it: a pulse as long as the record
  // keeps the thin beam near its static deflection, where the rotations' round-off floor holds CVODE at order 2 and
  // 2.5e-5 s steps (9.5 million steps, 400 s for 8 s at N = 48, where the plan had said seconds: the twentieth
  // adversarial pass's P5).
  long max_total_steps = 0;
  int max_order = 5;  // BDF order limit, 1..5 (orders 1-2 are A-stable)
  // Newton systems (I - gamma J) x = b: "structured" reduces them exactly to the symmetric positive definite
  // (M + gamma C + gamma^2 K) x2 = M b2 - gamma K b1, x1 = b1 + gamma x2 (half the size, Cholesky, refactored
  // whenever gamma changes, so Newton is exact for this linear ODE); "dense" is SUNDIALS' dense LU of the full
  // first-order Jacobian, kept as a cross-check.
  std::string linear_solver = "structured";
  // Where a long run says once, when it has run 2 s and has more than 5 s to go, how long the rest will take and that
  // `fast` is exact (an undamped beam makes CVODE track every mode: 845,000 steps for 0.5 s of the thin beam, where it
  // had run silently past a 20 s timeout). None: silent (the studies).
  std::ostream* progress = nullptr;
};

// The integrators' names (SimulatorOptions::integrator).
inline const std::string kFast = "fast";
inline const std::string kCvode = "cvode";
const core::NameSet& integrator_names();

struct SimulatorOptions {
  std::string integrator = "fast";  // "fast" | "cvode"
  CvodeOptions cvode;
};
// First violated constraint ("integrator = 'x': must be one of fast, cvode"), or nothing.
std::optional<std::string> validation_error(const SimulatorOptions& options);

// Integrator statistics, reported as data.
struct SimulationStats {
  std::string integrator;
  long steps = 0;
  long rhs_evaluations = 0;
  long jacobian_evaluations = 0;
  long linear_solver_setups = 0;  // LU (dense) or Cholesky (structured) factorisations
  long error_test_failures = 0;
  long nonlinear_convergence_failures = 0;
  // cvode: what set the step size. At every output time, the state component with the largest weighted local error
  // estimate |e_i| w_i (CVodeGetEstLocalErrors, CVodeGetErrWeights) is counted by its block ("displacement",
  // "rotation", "displacement velocity", "rotation velocity"; "state" for a one-block model); the block counted most
  // often, and the median last step (s) and order over the output times.
  std::string dominant_error_block;
  double median_step_s = 0;
  int median_order = 0;
  int modes = 0;  // fast: state-space modes kept
  double eigenvector_rcond =
      0;  // fast: galerkin::StateSpaceModes::eigenvector_rcond (1 / largest eigenvalue condition)
};

struct Trace {
  std::vector<double> y;      // y_i at t_i = i dt (cvode stopped by max_total_steps: the samples it reached)
  std::string status = "ok";  // "ok", or what failed
  SimulationStats stats;
  // fast only: the underdamped state-space eigenvalues (Im > 0), rad/s, as computed for this run (the spike-smooth
  // cost can compare them with the data's poles without a second eigen-decomposition). Empty for cvode.
  std::vector<std::complex<double>> poles_rad_s;
  // fast with a sampled force and ResponseProblem::frf: the sampled system's transfer function from the force's
  // samples to the output's at the DFT bins k = 0..samples/2, G(z_k), z_k = e^{j 2 pi k / samples} (modal_simulator.h).
  std::vector<std::complex<double>> frf;
  bool ok() const { return status == "ok"; }
};

class Simulator {
 public:
  virtual ~Simulator() = default;
  virtual Trace run(const galerkin::SecondOrderSystem& system, const ResponseProblem& problem) const = 0;
};

// InputError for an unknown integrator or bad options.
std::unique_ptr<Simulator> make_simulator(const SimulatorOptions& options);

// Load, sensor and initial state of `experiment` for the beam; InputError if the experiment is not admissible.
// Positions are in metres from the clamp on a beam of length length_m (the forms' own length unless given: a fit
// that estimates l keeps the force and sensor where they are; absent positions mean the tip, whatever l).
ResponseProblem make_problem(const galerkin::BeamForms& forms, const galerkin::SecondOrderSystem& system,
                             const Experiment& experiment);
ResponseProblem make_problem(const galerkin::BeamForms& forms, const galerkin::SecondOrderSystem& system,
                             const Experiment& experiment, double length_m);

// Convenience for one-off runs: assemble, build the problem, run.
Trace simulate(const galerkin::BeamForms& forms, const model::BeamParameters& beam, const Experiment& experiment,
               const SimulatorOptions& options);
// The same for a system already assembled (a study's truth with a damping no parameter gives:
// galerkin::with_modal_damping) of a beam of length length_m.
Trace simulate(const galerkin::BeamForms& forms, const galerkin::SecondOrderSystem& system, double length_m,
               const Experiment& experiment, const SimulatorOptions& options);

}  // namespace beamid::simulation
