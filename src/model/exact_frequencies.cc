#include "model/exact_frequencies.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "core/errors.h"

namespace beamid::model {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// The march advances b*l (or L) by at most this fraction of pi per step. Beam modes are about pi apart in b*l; the
// closest pair found scanning the Euler-Bernoulli tip equation over mu in [1e-3, 1e4], eta in [1e-4, 1e3] was the
// translation and rotation modes of a very heavy tip body, 0.137 = 0.04 pi apart. 0.01 pi keeps a 4x margin on that.
constexpr double kStepFractionOfPi = 0.01;

// The march stops this far below the shear cut-off (relative): there a -> 0, d_a ~ 1/a, and 1 - (omega/omega_c)^2,
// hence a^2, carries a relative rounding error of about eps/1e-9; closer still the sign is not trustworthy.
constexpr double kCutoffMargin = 1e-9;

// The march starts where b*l = 1e-3: a first root lower than that needs m/(rho l) ~ 3/(b l)^4 ~ 1e12, and closer to
// omega = 0 the columns below vanish like powers of omega and lose their sign to rounding.
constexpr double kStartBl = 1e-3;

void require_count(int count) {
  if (count < 1) throw InputError("count = " + std::to_string(count) + ": must be >= 1");
}

void require_valid(const BeamParameters& beam) {
  if (const auto error = validation_error(beam)) throw InputError("beam parameters: " + *error);
}

void require_below_cutoff(const BeamParameters& beam, double omega_rad_s) {
  const double cutoff = shear_cutoff_rad_s(beam);
  const double s = omega_rad_s / cutoff;
  // (1 - s)(1 + s) <= 0 catches omega that rounds onto the cut-off, where a = 0.
  if (!(omega_rad_s > 0 && omega_rad_s < cutoff && (1 - s) * (1 + s) > 0))
    throw InputError("omega_rad_s = " + format_value(omega_rad_s) + ": must be in (0, shear cut-off " +
                     format_value(cutoff) + ")");
}

// Sign-change refinement by false position with the Illinois modification (halve the stale end's value when the
// same end is kept twice, so both ends move), plus a bisection whenever the bracket failed to halve over two steps.
// Requires f_lo, f_hi of opposite signs; returns the root to a bracket of a few ulps.
template <class Function>
double refine_root(const Function& f, double lo, double f_lo, double hi, double f_hi) {
  int kept_side = 0;  // -1: lo kept last time, +1: hi kept last time
  double width_two_steps_ago = std::numeric_limits<double>::infinity(), width_one_step_ago = width_two_steps_ago;
  for (int iteration = 0; iteration < 400; ++iteration) {
    const double width = hi - lo;
    if (width <= 4 * kEpsilon * std::max(std::abs(lo), std::abs(hi))) break;
    const double mid = lo + width / 2;
    double x = hi - f_hi * width / (f_hi - f_lo);
    if (!(x > lo && x < hi) || width > width_two_steps_ago / 2) x = mid;
    width_two_steps_ago = width_one_step_ago;
    width_one_step_ago = width;
    const double f_x = f(x);
    if (f_x == 0) return x;
    if ((f_x < 0) == (f_hi < 0)) {
      hi = x;
      f_hi = f_x;
      if (kept_side == -1) f_lo /= 2;
      kept_side = -1;
    } else {
      lo = x;
      f_lo = f_x;
      if (kept_side == 1) f_hi /= 2;
      kept_side = 1;
    }
  }
  return lo + (hi - lo) / 2;
}

// Marches x_start < next(x_start) < next(next(x_start)) ... and refines each sign change of f, until `count` roots
// are found or next() stops increasing (end of the admissible interval).
template <class Function, class Next>
std::vector<double> march_roots(const Function& f, double x_start, const Next& next, int count) {
  std::vector<double> roots;
  double x = x_start, f_x = f(x);
  while (static_cast<int>(roots.size()) < count) {
    const double x_next = next(x);
    if (!(x_next > x)) break;
    const double f_next = f(x_next);
    if (f_next == 0) {
      // A grid point hit the root exactly: take it and resume one step later, past it.
      roots.push_back(x_next);
      x = next(x_next);
      f_x = f(x);
      continue;
    }
    if ((f_x < 0) != (f_next < 0)) roots.push_back(refine_root(f, x, f_x, x_next, f_next));
    x = x_next;
    f_x = f_next;
  }
  return roots;
}

// Wavenumbers of the undamped Timoshenko beam at omega: U, Psi ~ cosh(ax), sinh(ax), cos(bx), sin(bx).
// With X = omega^2 (rho_r2/EI - rho/k), Y = 4 rho omega^2/EI one has p^2 + 4q = X^2 + Y, and
//   d_a a = a^2 + rho omega^2/k = (sqrt(X^2+Y) - X)/2,  d_b b = b^2 - rho omega^2/k = (sqrt(X^2+Y) + X)/2,
// whose product is Y/4: the larger is summed directly and the smaller taken from the product, so neither cancels.
// Likewise a^2 = 2q/(p + sqrt(p^2+4q)) stays accurate as q -> 0 at the cut-off.
struct Wavenumbers {
  double a, b, d_a, d_b;
  double k_delta_a;  // kAG (a - d_a) = -rho omega^2 / a, exact, no cancellation for stiff shear (slender beams)
  double k_delta_b;  // kAG (b - d_b) = +rho omega^2 / b
};

Wavenumbers wavenumbers(const BeamParameters& beam, double omega_rad_s) {
  const double omega2 = omega_rad_s * omega_rad_s;
  const double rho_omega2 = beam.rho * omega2;
  const double s = omega_rad_s / shear_cutoff_rad_s(beam);
  const double p = omega2 * (beam.rho_r2 / beam.EI + beam.rho / beam.kAG);
  const double q = rho_omega2 / beam.EI * ((1 - s) * (1 + s));
  const double x = omega2 * (beam.rho_r2 / beam.EI - beam.rho / beam.kAG);
  const double y = 4 * rho_omega2 / beam.EI;
  const double root = std::sqrt(x * x + y);
  const double larger = (root + std::abs(x)) / 2, smaller = y / (4 * larger);
  const double da_a = x > 0 ? smaller : larger, db_b = x > 0 ? larger : smaller;
  Wavenumbers w;
  w.a = std::sqrt(2 * q / (p + root));
  w.b = std::sqrt((p + root) / 2);
  w.d_a = da_a / w.a;
  w.d_b = db_b / w.b;
  w.k_delta_a = -rho_omega2 / w.a;
  w.k_delta_b = rho_omega2 / w.b;
  return w;
}

// The frequency determinant divided by cosh(a l) only (so that it neither grows nor underflows with a l).
// Column 2 is replaced by column 2 - column 1 (determinant unchanged): its hyperbolic part becomes exp(-a x) times
// (U, Psi) = (-1, d_a), so the exp(2 a l) growth of the determinant, which cancels analytically, never appears.
// Column 1 is divided by cosh(a l): tanh(a l) and sech(a l) multiply its parts.
double scaled_determinant(const BeamParameters& beam, double omega_rad_s) {
  const Wavenumbers w = wavenumbers(beam, omega_rad_s);
  const double al = w.a * beam.l, bl = w.b * beam.l;
  const double t = std::tanh(al), sech = 1 / std::cosh(al), decay = std::exp(-al);
  const double cos_bl = std::cos(bl), sin_bl = std::sin(bl), ratio = w.d_a / w.d_b;

  // Column 1 / cosh(al): U, Psi, Psi', and kAG (U' - Psi) (the shear force, formed without cancellation).
  const double u1 = 1 - cos_bl * sech;
  const double psi1 = w.d_a * t + w.d_b * sin_bl * sech;
  const double dpsi1 = w.a * w.d_a + w.b * w.d_b * cos_bl * sech;
  const double shear1 = w.k_delta_a * t + w.k_delta_b * sin_bl * sech;
  // Column 2 - column 1.
  const double u2 = -decay + cos_bl - ratio * sin_bl;
  const double psi2 = w.d_a * decay - w.d_a * cos_bl - w.d_b * sin_bl;
  const double dpsi2 = -w.a * w.d_a * decay + w.b * w.d_a * sin_bl - w.b * w.d_b * cos_bl;
  const double shear2 = w.k_delta_a * decay - ratio * w.k_delta_b * cos_bl - w.k_delta_b * sin_bl;

  // Tip conditions: R1 = kAG (U' - Psi) - omega^2 (m U + m c Psi), R2 = EI Psi' - omega^2 (m c U + (J_o + m c^2) Psi).
  const double omega2 = omega_rad_s * omega_rad_s;
  const double mc = beam.m * beam.c, j_tip = beam.J_o + beam.m * beam.c * beam.c;
  const double r1_1 = shear1 - omega2 * (beam.m * u1 + mc * psi1);
  const double r1_2 = shear2 - omega2 * (beam.m * u2 + mc * psi2);
  const double r2_1 = beam.EI * dpsi1 - omega2 * (mc * u1 + j_tip * psi1);
  const double r2_2 = beam.EI * dpsi2 - omega2 * (mc * u2 + j_tip * psi2);
  return r1_1 * r2_2 - r1_2 * r2_1;
}

// Inertia Lambda = [[m, m c], [m c, J + m c^2]] of rigid bodies at one point (their sum when several share it).
struct PointInertia {
  double m = 0, mc = 0, j = 0;
  void add(double mass, double offset, double inertia) {
    m += mass;
    mc += mass * offset;
    j += inertia + mass * offset * offset;
  }
};

// The four free solutions of one segment at omega, in local coordinate xi in [0, L], as rows (U, Psi, S, M) with
// S = kAG (U' - Psi) the shear force and M = EI Psi' the bending moment:
//   U = exp(-a xi):        Psi = -d_a exp(-a xi),  S = -kAG (a - d_a) exp(-a xi),   M = a d_a EI exp(-a xi)
//   U = exp(-a (L - xi)):  Psi = d_a exp(.),       S = kAG (a - d_a) exp(.),        M = a d_a EI exp(.)
//   U = cos(b xi):         Psi = -d_b sin(b xi),   S = -kAG (b - d_b) sin(b xi),    M = -b d_b EI cos(b xi)
//   U = sin(b xi):         Psi = d_b cos(b xi),    S = kAG (b - d_b) cos(b xi),     M = -b d_b EI sin(b xi)
// (the cosh/sinh pairs of the clamped shapes above, rewritten as exponentials decaying away from each end, so that
// no entry grows with a L). Rows are made dimensionless: Psi x l, S x l^3/EI, M x l^2/EI (l the beam's length).
Eigen::Matrix4d segment_solutions(const BeamParameters& beam, const Wavenumbers& w, double L, double xi) {
  const double l = beam.l, s_scale = l * l * l / beam.EI, m_scale = l * l;
  const double e1 = std::exp(-w.a * xi), e2 = std::exp(-w.a * (L - xi));
  const double c = std::cos(w.b * xi), s = std::sin(w.b * xi);
  Eigen::Matrix4d r;
  r << e1, e2, c, s,                                                   //
      -w.d_a * e1 * l, w.d_a * e2 * l, -w.d_b * s * l, w.d_b * c * l,  //
      -w.k_delta_a * e1 * s_scale, w.k_delta_a * e2 * s_scale, -w.k_delta_b * s * s_scale, w.k_delta_b * c * s_scale,
      w.a * w.d_a * e1 * m_scale, w.a * w.d_a * e2 * m_scale, -w.b * w.d_b * c * m_scale, -w.b * w.d_b * s * m_scale;
  return r;
}

// The frequency determinant of a beam cut into segments at its attachments (global-matrix method): four unknown
// amplitudes per segment; two clamp rows U(0) = Psi(0) = 0; at each cut x_k continuity of U and Psi and the jumps
//   S(x_k+) = S(x_k-) - omega^2 (m U + m c Psi),   M(x_k+) = M(x_k-) - omega^2 (m c U + (J + m c^2) Psi)
// of the bodies there (virtual work of their inertia forces); and the tip rows of the 2x2 form with the tip body and
// any attachment at x = l. Zero exactly when a nontrivial mode exists; continuous in omega, so its sign changes at
// the natural frequencies. Inertia terms are scaled with their rows (S: l^3/EI, M: l^2/EI).
double segmented_determinant_value(const BeamParameters& beam, double omega_rad_s) {
  const Wavenumbers w = wavenumbers(beam, omega_rad_s);
  const double omega2 = omega_rad_s * omega_rad_s, l = beam.l;
  PointInertia tip;
  tip.add(beam.m, beam.c, beam.J_o);
  std::vector<Attachment> sorted = beam.attachments;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Attachment& p, const Attachment& q) { return p.x < q.x; });
  std::vector<std::pair<double, PointInertia>> cuts;
  for (const Attachment& a : sorted) {
    if (a.x >= l) {
      tip.add(a.m, a.c, a.J);
    } else {
      if (cuts.empty() || cuts.back().first != a.x) cuts.emplace_back(a.x, PointInertia{});
      cuts.back().second.add(a.m, a.c, a.J);
    }
  }
  const int segments = static_cast<int>(cuts.size()) + 1;
  std::vector<double> ends{0.0};
  for (const auto& cut : cuts) ends.push_back(cut.first);
  ends.push_back(l);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4 * segments, 4 * segments);
  const double s_scale = l * l * l / beam.EI, m_scale = l * l / beam.EI;
  // Rows S - omega^2 (m U + m c Psi) and M - omega^2 (m c U + j Psi) of a solution matrix r (Psi rows carry x l).
  const auto loaded = [&](const Eigen::Matrix4d& r, const PointInertia& p) {
    Eigen::Matrix<double, 2, 4> rows;
    rows.row(0) = r.row(2) - omega2 * s_scale * (p.m * r.row(0) + p.mc / l * r.row(1));
    rows.row(1) = r.row(3) - omega2 * m_scale * (p.mc * r.row(0) + p.j / l * r.row(1));
    return rows;
  };
  // The root: U(0) = 0 or S(0) = k_w U(0); Psi(0) = 0 or M(0) = k_theta Psi(0) (rows scaled as above).
  int row = 0;
  const Eigen::Matrix4d root = segment_solutions(beam, w, ends[1] - ends[0], 0.0);
  a.block<1, 4>(row, 0) = root.row(0);
  if (beam.support.deflection_free()) a.block<1, 4>(row, 0) = root.row(2) - beam.support.k_w * s_scale * root.row(0);
  a.block<1, 4>(row + 1, 0) = root.row(1);
  if (beam.support.rotation_free())
    a.block<1, 4>(row + 1, 0) = root.row(3) - beam.support.k_theta * m_scale / l * root.row(1);
  row += 2;
  for (int k = 0; k + 1 < segments; ++k) {
    const double left_length = ends[k + 1] - ends[k], right_length = ends[k + 2] - ends[k + 1];
    const Eigen::Matrix4d left = segment_solutions(beam, w, left_length, left_length);
    const Eigen::Matrix4d right = segment_solutions(beam, w, right_length, 0.0);
    a.block<2, 4>(row, 4 * k) = left.topRows<2>();
    a.block<2, 4>(row, 4 * (k + 1)) = -right.topRows<2>();
    // S(x+) - S(x-) + omega^2 (...) = 0: -(loaded left rows) + right's S, M rows.
    a.block<2, 4>(row + 2, 4 * k) = -loaded(left, cuts[static_cast<std::size_t>(k)].second);
    a.block<2, 4>(row + 2, 4 * (k + 1)) = right.bottomRows<2>();
    row += 4;
  }
  const double last_length = ends[segments] - ends[segments - 1];
  a.block<2, 4>(row, 4 * (segments - 1)) = loaded(segment_solutions(beam, w, last_length, last_length), tip);
  return a.partialPivLu().determinant();
}

// The Euler-Bernoulli tip-body equation divided by cosh L (bounded apart from its polynomial factors in L):
//   sech L + cos L + mu L (cos L tanh L - sin L) - eta L^3 (sin L + tanh L cos L) + mu eta L^4 (sech L - cos L).
double scaled_tip_equation(double mu, double eta, double L) {
  const double c = std::cos(L), s = std::sin(L), t = std::tanh(L), sech = 1 / std::cosh(L);
  const double L3 = L * L * L;
  return sech + c + mu * L * (c * t - s) - eta * L3 * (s + t * c) + mu * eta * L3 * L * (sech - c);
}

}  // namespace

double timoshenko_determinant(const BeamParameters& beam, double omega_rad_s) {
  require_valid(beam);
  if (!beam.attachments.empty() || !beam.support.rigid())
    throw InputError(
        "the 2x2 frequency determinant has a rigid clamp and no attachments on the span: use "
        "segmented_determinant");
  require_below_cutoff(beam, omega_rad_s);
  const double al = wavenumbers(beam, omega_rad_s).a * beam.l;
  return scaled_determinant(beam, omega_rad_s) / std::cosh(al);
}

double segmented_determinant(const BeamParameters& beam, double omega_rad_s) {
  require_valid(beam);
  require_below_cutoff(beam, omega_rad_s);
  return segmented_determinant_value(beam, omega_rad_s);
}

std::vector<double> timoshenko_frequencies_rad_s(const BeamParameters& beam, int count) {
  require_count(count);
  require_valid(beam);
  const double omega_last = shear_cutoff_rad_s(beam) * (1 - kCutoffMargin);
  // Low-frequency b = (rho omega^2/EI)^(1/4) gives the start for b l = kStartBl.
  const double omega_start =
      std::min(kStartBl * kStartBl / (beam.l * beam.l) * std::sqrt(beam.EI / beam.rho), omega_last / 2);
  // b/omega decreases with omega (b^2/omega^2 = (p + sqrt(X^2 + Y))/(2 omega^2) and Y/omega^2 is constant), so
  // db/domega <= b/omega and the step domega = f pi omega / (b l) advances b l by at most f pi.
  const auto next = [&](double omega) {
    const double bl = wavenumbers(beam, omega).b * beam.l;
    return std::min(omega + kStepFractionOfPi * kPi * omega / bl, omega_last);
  };
  // Attachments on the span cut the beam into segments (segmented_determinant); without them the closed 2x2 form.
  if (beam.attachments.empty() && beam.support.rigid()) {
    const auto f = [&](double omega) { return scaled_determinant(beam, omega); };
    return march_roots(f, omega_start, next, count);
  }
  const auto f = [&](double omega) { return segmented_determinant_value(beam, omega); };
  return march_roots(f, omega_start, next, count);
}

std::vector<double> euler_bernoulli_cantilever_roots(int count) { return euler_bernoulli_tip_body_roots(0, 0, count); }

std::vector<double> euler_bernoulli_tip_body_roots(double mu, double eta, int count) {
  require_count(count);
  if (!(std::isfinite(mu) && mu >= 0)) throw InputError("mu = " + format_value(mu) + ": must be finite and >= 0");
  if (!(std::isfinite(eta) && eta >= 0)) throw InputError("eta = " + format_value(eta) + ": must be finite and >= 0");
  // The scaled equation is 2 at L = 0, so the march can start there; roots are about pi apart in L.
  const auto next = [](double L) { return L + kStepFractionOfPi * kPi; };
  const auto f = [&](double L) { return scaled_tip_equation(mu, eta, L); };
  return march_roots(f, 0.0, next, count);
}

std::vector<double> euler_bernoulli_frequencies_rad_s(const BeamParameters& beam, int count) {
  require_valid(beam);
  if (!beam.attachments.empty() || !beam.support.rigid())
    throw InputError(
        "the Euler-Bernoulli tip-body equation has a rigid clamp and no attachments on the span: use "
        "timoshenko_frequencies_rad_s");
  const double mu = beam.m / (beam.rho * beam.l);
  const double eta = (beam.J_o + beam.m * beam.c * beam.c) / (beam.rho * std::pow(beam.l, 3));
  const double scale = std::sqrt(beam.EI / (beam.rho * std::pow(beam.l, 4)));  // omega_n = L_n^2 scale
  std::vector<double> omegas = euler_bernoulli_tip_body_roots(mu, eta, count);
  for (double& omega : omegas) omega = omega * omega * scale;
  return omegas;
}

}  // namespace beamid::model
