#include "simulation/cvode_simulator.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <ostream>
#include <string>

#include "core/errors.h"

#if SUNDIALS_VERSION_MAJOR >= 7
#define BEAMID_SUN_COMM_NULL SUN_COMM_NULL
#else
#define BEAMID_SUN_COMM_NULL nullptr
#endif

namespace beamid::simulation {
namespace {

// Everything the C callbacks need, reached through CVODE's user_data.
// The acceleration is M^-1 (f P - K w - C v) with M, C, K as stored: never through a precomputed M^-1 K. For the thin
// beam the rotation rows of M^-1 K reach ~1e17 and its rounding is a fixed perturbation of the system that shifts
// the low eigenvalues by ~1e-6 relative (a measured 2e-4 error over a 4 s record); K w rounds afresh at every call.
struct Rhs {
  const ResponseProblem* problem;
  const galerkin::SecondOrderSystem* system;
  Eigen::LLT<Eigen::MatrixXd> mass;
  int n;
  mutable Eigen::VectorXd force;

  // v' = M^-1 (f P - K w - C v)
  void acceleration(double t, const double* w, const double* v, double* out) const {
    Eigen::Map<const Eigen::VectorXd> wv(w, n), vv(v, n);
    Eigen::Map<Eigen::VectorXd> a(out, n);
    force.noalias() = problem->force_N(t) * problem->load;
    force.noalias() -= system->K * wv;
    force.noalias() -= system->C * vv;
    a = mass.solve(force);
  }
};

int rhs_trampoline(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  const auto* rhs = static_cast<const Rhs*>(user_data);
  const double* state = N_VGetArrayPointer(y);
  double* derivative = N_VGetArrayPointer(ydot);
  const int n = rhs->n;
  std::copy(state + n, state + 2 * n, derivative);  // w' = v
  rhs->acceleration(t, state, state + n, derivative + n);
  return 0;
}

int jacobian_trampoline(sunrealtype, N_Vector, N_Vector, SUNMatrix jac, void* user_data, N_Vector, N_Vector, N_Vector) {
  const auto* rhs = static_cast<const Rhs*>(user_data);
  const int n = rhs->n;
  // SUNDIALS dense matrices are column-major like Eigen's default: map and fill [[0, I], [-M^-1 K, -M^-1 C]].
  Eigen::Map<Eigen::MatrixXd> j(SUNDenseMatrix_Data(jac), 2 * n, 2 * n);
  j.setZero();
  j.topRightCorner(n, n).setIdentity();
  j.bottomLeftCorner(n, n) = -rhs->mass.solve(rhs->system->K);  // only for the dense cross-check solver
  j.bottomRightCorner(n, n) = -rhs->mass.solve(rhs->system->C);
  return 0;
}

// The "structured" Newton solver, a SUNDIALS matrix-embedded linear solver. CVODE asks for (I - gamma J) x = b with
// J = [[0, I], [-M^-1 K, -M^-1 C]]; row 1 gives x1 = b1 + gamma x2, and row 2 times M gives
//   (M + gamma C + gamma^2 K) x2 = M b2 - gamma K b1,
// symmetric positive definite and half the size. It is refactored whenever CVODE's gamma changes.
struct StructuredSolver {
  void* cvode = nullptr;
  const galerkin::SecondOrderSystem* system = nullptr;
  double gamma = std::numeric_limits<double>::quiet_NaN();
  Eigen::LLT<Eigen::MatrixXd> factor;
  long factorizations = 0;
  Eigen::VectorXd rhs, x2;
};

SUNLinearSolver_Type structured_type(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }

int structured_solve(SUNLinearSolver solver, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
  auto* s = static_cast<StructuredSolver*>(solver->content);
  sunrealtype gamma = 0;
  if (CVodeGetCurrentGamma(s->cvode, &gamma) != CV_SUCCESS) return -1;
  const auto& sys = *s->system;
  if (gamma != s->gamma) {
    s->factor.compute(sys.M + gamma * sys.C + (gamma * gamma) * sys.K);
    if (s->factor.info() != Eigen::Success) return -1;  // unrecoverable: M, K not SPD
    s->gamma = gamma;
    ++s->factorizations;
  }
  const Eigen::Index n = sys.M.rows();
  Eigen::Map<const Eigen::VectorXd> bv(N_VGetArrayPointer(b), 2 * n);
  Eigen::Map<Eigen::VectorXd> xv(N_VGetArrayPointer(x), 2 * n);
  s->rhs.noalias() = sys.M * bv.tail(n);
  s->rhs.noalias() -= gamma * (sys.K * bv.head(n));
  s->x2 = s->factor.solve(s->rhs);
  xv.head(n) = bv.head(n) + gamma * s->x2;  // b may alias x: read b1 before writing x2
  xv.tail(n) = s->x2;
  return 0;
}

int structured_free(SUNLinearSolver solver) {
  solver->content = nullptr;  // owned by the run below
  SUNLinSolFreeEmpty(solver);
  return 0;
}

// CVODE's own messages go into the status instead of stderr.
void error_trampoline(int, const char* module, const char* function, char* message, void* user_data) {
  auto* text = static_cast<std::string*>(user_data);
  *text = std::string(module) + "." + function + ": " + message;
}

std::string flag_name(int flag) {
  char* name = CVodeGetReturnFlagName(flag);  // malloc'd by SUNDIALS
  std::string result = name ? name : std::to_string(flag);
  std::free(name);
  return result;
}

// RAII owners of the SUNDIALS objects; the context is freed last.
struct Session {
  SUNContext context = nullptr;
  N_Vector y = nullptr, atol = nullptr;
  N_Vector local_error = nullptr, weights = nullptr;  // for the step diagnosis
  SUNMatrix a = nullptr;
  SUNLinearSolver solver = nullptr;
  void* cvode = nullptr;
  ~Session() {
    if (cvode) CVodeFree(&cvode);
    if (solver) SUNLinSolFree(solver);
    if (a) SUNMatDestroy(a);
    for (N_Vector* v : {&weights, &local_error, &atol, &y})
      if (*v) N_VDestroy(*v);
    if (context) SUNContext_Free(&context);
  }
};

// The absolute tolerances, per component, when CvodeOptions::atol is 0: each block of w (block components from start)
// at its natural size w_scale, the velocities at that size times the Rayleigh frequency of the static deflection.
void set_absolute_tolerances(const CvodeOptions& options, const Eigen::VectorXd& w_scale, double rayleigh_rad_s,
                             int block, Eigen::Map<Eigen::VectorXd> atol) {
  const int n = static_cast<int>(w_scale.size());
  const double tiny = std::numeric_limits<double>::min();
  for (int start = 0; start < n; start += block) {
    // 1e-3 on the first block (transverse displacement, what sensors see); 1 on the rotations, whose thin-beam
    // equations carry round-off noise (a huge shear balance cancelling) that a tighter tolerance would chase.
    const double factor = start == 0 ? 1e-3 : 1.0;
    const double size = std::max(tiny, factor * options.rtol * w_scale.segment(start, block).cwiseAbs().maxCoeff());
    atol.segment(start, block).setConstant(size);
    // Velocities: the block's size times the Rayleigh frequency of the static deflection; 10x looser for the rotation
    // velocities. Those carry a round-off floor: the thin beam's shear balance kAG (u_x - alpha) / rho_r2 turns an
    // eps-level error in u_x - alpha into a rotation acceleration about 1e13 times larger, and once the response
    // reaches its static size (a pulse longer than a quarter period of mode 1) that floor lies above rtol 1e-10 of
    // the block's size, so CVODE chased it. Measured at N = 48, 0.3 s of record: 167,840 steps after a 100 ms pulse
    // against 18,670 after a 4 ms one, with the largest weighted local error in the rotation velocities, and at
    // rtol 1e-9 only 8,674 (a genuine accuracy limit falls by 10^(1/5) = 1.6x per decade, not 19x). The sensor
    // never sees a rotation velocity: with the looser bound the long pulse takes 19,896 steps, its velocity agrees
    // with the exact modal solution to 5.8e-9 of max |v| (8.0e-9 before) and its acceleration to 3.2e-7 (2.4e-7
    // before: the acceleration sits at that round-off floor either way); the 4 ms pulse is unchanged (18,413
    // steps; acceleration 6.9e-8, 5.5e-8 before). 100x looser took the thin beam's acceleration past 1e-7.
    const double velocity_factor = start == 0 ? 1.0 : 10.0;
    atol.segment(n + start, block).setConstant(std::max(tiny, velocity_factor * size * rayleigh_rad_s));
  }
}

// The displacements' natural size: the static deflection under the load (or the pluck's w0), and the Rayleigh
// frequency of that shape in `rayleigh_rad_s`. A pulse much shorter than the beam's period moves it by about its
// impulse, omega tau / 2 of the static deflection, and a tolerance sized to the static deflection let errors of the
// response's own size through (125 % of the peak acceleration at tau = 1e-12 s, 1.9e-4 at 1e-8 s: the fifteenth
// pass's P2): scaled down where it is more than 100x that impulse response. Ordinary pulses (the presets' 4 and
// 0.4 ms) keep the static size, and their runs. Zero when nothing excites the beam.
Eigen::VectorXd natural_displacements(const galerkin::SecondOrderSystem& system, const ResponseProblem& p,
                                      double& rayleigh_rad_s) {
  Eigen::VectorXd w_scale = p.w0;
  if (p.amplitude_N != 0) w_scale = system.K.llt().solve(p.amplitude_N * p.load);
  if (!(w_scale.norm() > 0)) return w_scale;
  rayleigh_rad_s = std::sqrt(w_scale.dot(system.K * w_scale) / w_scale.dot(system.M * w_scale));
  if (p.amplitude_N != 0 && p.pulse_width_s > 0) w_scale *= std::min(1.0, 100 * 0.5 * rayleigh_rad_s * p.pulse_width_s);
  return w_scale;
}

// Why a given absolute tolerance is too loose for displacements of natural size `displacements` (max |w|), or "": above
// 1e-3 of it, it leaves errors of its own size, as a looser rtol does (--atol 1 was 255 % off the exact response and
// 1e308 gave 1e34 m, exit 0: the fourteenth pass's P1).
std::string loose_atol_problem(double atol, const Eigen::VectorXd& displacements) {
  const double natural_m = displacements.cwiseAbs().maxCoeff();
  // Below 1e-10 of it CVODE failed in its own words, not naming --atol: below 1e-14 double precision cannot meet it,
  // and at 1e-12 it ran out of steps (the fifteenth and sixteenth passes' P9, P7). 1e-10 is the default rtol's.
  if (atol < 1e-10 * natural_m)
    return "cvode: atol = " + format_value(atol) + " is below 1e-10 of the displacements' natural size here (" +
           format_rounded(natural_m, 3) + "), tighter than CVODE meets within its steps; leave --atol out (rtol " +
           "sets it)";
  if (atol <= 1e-3 * natural_m) return "";
  return "cvode: atol = " + format_value(atol) + " is above 1e-3 of the displacements' natural size here (" +
         format_rounded(natural_m, 3) +
         ", the static deflection under the load, scaled to a short pulse's impulse, or the pluck's), so the "
         "response " +
         "would carry errors of its size; leave --atol out (rtol sets it)";
}

// Attaches CvodeOptions::linear_solver to the session: "dense" (the cross-check, with the analytic Jacobian) or the
// structured solver above (which the caller owns). Returns CVODE's flag.
int attach_linear_solver(Session& s, StructuredSolver& structured, const galerkin::SecondOrderSystem& system,
                         const std::string& linear_solver, int n) {
  if (linear_solver == "dense") {
    s.a = SUNDenseMatrix(2 * n, 2 * n, s.context);
    s.solver = SUNLinSol_Dense(s.y, s.a, s.context);
    const int flag = CVodeSetLinearSolver(s.cvode, s.solver, s.a);
    if (flag < 0) return flag;
    return CVodeSetJacFn(s.cvode, jacobian_trampoline);
  }
  structured.cvode = s.cvode;
  structured.system = &system;
  s.solver = SUNLinSolNewEmpty(s.context);
  s.solver->content = &structured;
  s.solver->ops->gettype = structured_type;
  s.solver->ops->solve = structured_solve;
  s.solver->ops->free = structured_free;
  return CVodeSetLinearSolver(s.cvode, s.solver, nullptr);
}

// Adds CVODE's counters to stats (CVodeReInit resets them: they are added up across the restart).
void add_counters(void* cvode, bool dense, SimulationStats& stats) {
  long value = 0;
  CVodeGetNumSteps(cvode, &value), stats.steps += value;
  CVodeGetNumRhsEvals(cvode, &value), stats.rhs_evaluations += value;
  CVodeGetNumJacEvals(cvode, &value), stats.jacobian_evaluations += value;
  if (dense) CVodeGetNumLinSolvSetups(cvode, &value), stats.linear_solver_setups += value;
  CVodeGetNumErrTestFails(cvode, &value), stats.error_test_failures += value;
  CVodeGetNumNonlinSolvConvFails(cvode, &value), stats.nonlinear_convergence_failures += value;
}

// After sample i: whether the run has taken more than `budget` steps (0: no budget), counting those of an earlier
// session (the one before the pulse's end) in trace.stats; if so, the trace says so and keeps samples 0..i.
bool stopped_by_budget(void* cvode, long budget, int i, const ResponseProblem& p, Trace& trace) {
  if (budget <= 0) return false;
  long steps = 0;
  CVodeGetNumSteps(cvode, &steps);
  if (trace.stats.steps + steps <= budget) return false;
  trace.y.resize(static_cast<std::size_t>(i) + 1);
  trace.status = "cvode: stopped at its budget of " + std::to_string(budget) + " steps after " + std::to_string(i + 1) +
                 " of " + std::to_string(p.samples) + " samples (t = " + format_value(i * p.dt_s) + " s)";
  return true;
}

// Step-size diagnosis (SimulationStats::dominant_error_block): per output time, the block of the component with the
// largest weighted local error estimate, and the last step and order.
class StepDiagnosis {
 public:
  StepDiagnosis(Session& s, int n, int block)
      : s_(s),
        n_(n),
        block_(block),
        names_(block == n ? std::vector<std::string>{"state", "state"}
                          : std::vector<std::string>{"displacement", "rotation", "displacement velocity",
                                                     "rotation velocity"}),
        counts_(names_.size(), 0) {
    s.local_error = N_VNew_Serial(2 * n, s.context);
    s.weights = N_VNew_Serial(2 * n, s.context);
  }

  void record() {
    if (CVodeGetEstLocalErrors(s_.cvode, s_.local_error) < 0 || CVodeGetErrWeights(s_.cvode, s_.weights) < 0) return;
    const double* e = N_VGetArrayPointer(s_.local_error);
    const double* w = N_VGetArrayPointer(s_.weights);
    int worst = 0;
    for (int j = 1; j < 2 * n_; ++j)
      if (std::abs(e[j] * w[j]) > std::abs(e[worst] * w[worst])) worst = j;
    const int velocity = worst >= n_ ? 1 : 0;
    const int within = (worst % n_) / block_;
    ++counts_[static_cast<std::size_t>(block_ == n_ ? velocity : 2 * velocity + within)];
    double h = 0;
    int q = 0;
    CVodeGetLastStep(s_.cvode, &h);
    CVodeGetLastOrder(s_.cvode, &q);
    steps_s_.push_back(h);
    orders_.push_back(q);
  }

  void finish(SimulationStats& stats) const {
    if (steps_s_.empty()) return;
    const auto most = std::max_element(counts_.begin(), counts_.end()) - counts_.begin();
    stats.dominant_error_block = names_[static_cast<std::size_t>(most)];
    const auto middle = [](std::vector<double> v) {
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    stats.median_step_s = middle(steps_s_);
    stats.median_order = static_cast<int>(middle(orders_));
  }

 private:
  Session& s_;
  const int n_, block_;
  const std::vector<std::string> names_;
  std::vector<long> counts_;
  std::vector<double> steps_s_, orders_;
};

// The sensor's reading c^T w, c^T v or c^T a at time t_s from the state [w; v].
double sensor_output(const ResponseProblem& p, const Rhs& rhs, double t_s, const double* state,
                     std::vector<double>& accel) {
  const int n = rhs.n;
  if (p.derivative == 0) return p.sensor.dot(Eigen::Map<const Eigen::VectorXd>(state, n));
  if (p.derivative == 1) return p.sensor.dot(Eigen::Map<const Eigen::VectorXd>(state + n, n));
  rhs.acceleration(t_s, state, state + n, accel.data());
  return p.sensor.dot(Eigen::Map<const Eigen::VectorXd>(accel.data(), n));
}

// A failed CVODE call as a trace's status: the call, its flag and CVODE's own message, and what to do about the one
// failure a valid beam meets, a model too stiff (or too lightly damped) for CVODE's step budget at this tolerance.
std::string failure_status(const std::string& what, int flag, const std::string& cvode_message) {
  std::string status =
      "cvode: " + what + " returned " + flag_name(flag) + (cvode_message.empty() ? "" : " (" + cvode_message + ")");
  if (flag == CV_TOO_MUCH_WORK)
    status +=
        ": CVODE needs more steps than it may take for this beam; --integrator fast gives the exact response "
        "without time steps";
  return status;
}

// The note of CvodeOptions::progress: after each output sample, the time the rest will take at the pace so far; said
// when 2 s have passed and more than 5 s remain, and again whenever the expected whole run has doubled since it was
// last said (the pace can fall steeply: a pulse as long as the record said "about 6 s more" and ran 400 s).
class ProgressNote {
 public:
  ProgressNote(std::ostream* out, int samples) : out_(out), samples_(samples) {}
  void after(int sample) {
    if (!out_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rest = elapsed * (samples_ - sample - 1) / (sample + 1);
    if (elapsed < 2 || rest < 5 || (said_total_s_ > 0 && elapsed + rest < 2 * said_total_s_)) return;
    *out_ << "beamid: cvode: about " << static_cast<long>(std::ceil(rest)) << " s more for this run (" << sample + 1
          << " of " << samples_ << " samples in " << static_cast<long>(elapsed) << " s"
          << (said_total_s_ > 0 ? ", slower than said before" : "")
          << ": the beam's lightly damped modes force small steps); --integrator fast gives the exact response\n";
    said_total_s_ = elapsed + rest;
  }

 private:
  std::ostream* out_;
  int samples_;
  double said_total_s_ = 0;  // the whole run's expected time when last said; 0: not said yet
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

Trace CvodeSimulator::run(const galerkin::SecondOrderSystem& system, const ResponseProblem& p) const {
  Trace trace;
  trace.stats.integrator = "cvode." + options_.linear_solver;
  trace.y.assign(static_cast<std::size_t>(p.samples), 0.0);
  if (p.output_filter)  // a caller's slip, not the data's: the filter is the fast closed form's (output_filter.h)
    throw InputError("cvode: an output filter is carried by the fast simulator only (simulate finer and filter)");

  const int n = static_cast<int>(system.M.rows());
  Rhs rhs{&p, &system, Eigen::LLT<Eigen::MatrixXd>(system.M), n, {}};
  if (rhs.mass.info() != Eigen::Success) {
    trace.status = "cvode: mass matrix is not positive definite";
    return trace;
  }

  // Natural size of each block of the state, for the absolute tolerances (see CvodeOptions::atol).
  double rayleigh_rad_s = 0;
  Eigen::VectorXd w_scale = natural_displacements(system, p, rayleigh_rad_s);
  if (!(w_scale.norm() > 0)) {  // no excitation at all: the response is exactly zero
    trace.stats.integrator = "cvode (zero input)";
    return trace;
  }
  // Blocks of w with their own units: (displacement, rotation) coefficients for the beam; one block otherwise.
  const int block = (n % 2 == 0) ? n / 2 : n;
  Session s;
  std::string cvode_message;
  const auto failed = [&](const std::string& what, int flag) {
    trace.status = failure_status(what, flag, cvode_message);
    return trace;
  };
  if (SUNContext_Create(BEAMID_SUN_COMM_NULL, &s.context) != 0) {
    trace.status = "cvode: SUNContext_Create failed";
    return trace;
  }
  s.y = N_VNew_Serial(2 * n, s.context);
  s.atol = N_VNew_Serial(2 * n, s.context);
  Eigen::Map<Eigen::VectorXd> y(N_VGetArrayPointer(s.y), 2 * n), atol(N_VGetArrayPointer(s.atol), 2 * n);
  y.head(n) = p.w0;
  y.tail(n).setZero();
  if (options_.atol > 0) {
    // (Its "" must not become the status: every accepted --atol failed with an empty message, the fifteenth pass's P1.)
    if (std::string problem = loose_atol_problem(options_.atol, w_scale.head(block)); !problem.empty()) {
      trace.status = std::move(problem);
      return trace;
    }
    atol.setConstant(options_.atol);
  } else {
    set_absolute_tolerances(options_, w_scale, rayleigh_rad_s, block, atol);
  }

  s.cvode = CVodeCreate(CV_BDF, s.context);
  int flag = CVodeInit(s.cvode, rhs_trampoline, 0.0, s.y);
  if (flag < 0) return failed("CVodeInit", flag);
  CVodeSetErrHandlerFn(s.cvode, error_trampoline, &cvode_message);
  CVodeSetUserData(s.cvode, &rhs);
  CVodeSVtolerances(s.cvode, options_.rtol, s.atol);
  CVodeSetMaxNumSteps(s.cvode, options_.max_steps_per_sample);
  // BDF orders 3-5 are unstable for the lightly damped kHz modes once h is large: let CVODE detect the stability
  // limit and lower the order, instead of shrinking the step (otherwise ~1e8 steps at rtol 1e-10).
  CVodeSetStabLimDet(s.cvode, SUNTRUE);
  CVodeSetMaxOrd(s.cvode, options_.max_order);
  StructuredSolver structured;
  const bool dense = options_.linear_solver == "dense";
  flag = attach_linear_solver(s, structured, system, options_.linear_solver, n);
  if (flag < 0) return failed("CVodeSetLinearSolver", flag);

  const bool pulse = p.pulse_width_s > 0 && p.amplitude_N != 0;
  bool restarted = !pulse;
  if (pulse) CVodeSetStopTime(s.cvode, p.pulse_width_s);
  std::vector<double> accel(static_cast<std::size_t>(n));
  StepDiagnosis diagnosis(s, n, block);
  ProgressNote note(options_.progress, p.samples);
  for (int i = 0; i < p.samples; ++i) {
    const double t_out = i * p.dt_s;
    if (i > 0) {
      // Cross the end of the pulse first: stop exactly there and restart the BDF history.
      if (!restarted && t_out > p.pulse_width_s) {
        double t_reached = 0;
        flag = CVode(s.cvode, p.pulse_width_s, s.y, &t_reached, CV_NORMAL);
        if (flag < 0) return failed("CVode", flag);
        add_counters(s.cvode, dense, trace.stats);
        flag = CVodeReInit(s.cvode, p.pulse_width_s, s.y);
        if (flag < 0) return failed("CVodeReInit", flag);
        CVodeSetStopTime(s.cvode, 2 * p.samples * p.dt_s + p.pulse_width_s);  // past the last sample: no stop
        restarted = true;
      }
      double t_reached = 0;
      if (!p.force_samples_N.empty()) CVodeSetStopTime(s.cvode, t_out);  // a sampled force's kink: never crossed
      flag = CVode(s.cvode, t_out, s.y, &t_reached, CV_NORMAL);
      if (flag < 0) return failed("CVode at t = " + format_value(t_out) + " s", flag);
      diagnosis.record();
      note.after(i);
    }
    trace.y[i] = sensor_output(p, rhs, t_out, N_VGetArrayPointer(s.y), accel);
    if (i + 1 < p.samples && stopped_by_budget(s.cvode, options_.max_total_steps, i, p, trace)) break;
  }
  add_counters(s.cvode, dense, trace.stats);
  trace.stats.linear_solver_setups += structured.factorizations;
  diagnosis.finish(trace.stats);
  return trace;
}

std::string sundials_library_version() { return SUNDIALS_VERSION; }

}  // namespace beamid::simulation
