// Checks of the exact frequency references against model.md section 6 and against each other.
// Reference values in model.md are rounded; unless said otherwise a check allows half a unit in the last digit given,
// which a correctly rounded reference always meets and a wrong digit always breaks.
#include "model/exact_frequencies.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.h"

namespace beamid::model {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Nondimensional beam of model.md section 6: rho = EI = l = 1, r^2 = rho_r2/rho = (l/r)^-2, kAG = EI/(3.12 r^2).
BeamParameters nondimensional_beam(double slenderness, double m = 0, double c = 0, double J_o = 0) {
  BeamParameters beam;
  beam.l = 1;
  beam.rho = 1;
  beam.EI = 1;
  beam.rho_r2 = 1 / (slenderness * slenderness);
  beam.kAG = beam.EI / (3.12 * beam.rho_r2);
  beam.m = m;
  beam.c = c;
  beam.J_o = J_o;
  return beam;
}

BeamParameters without_tip_body(BeamParameters beam) {
  beam.m = beam.c = beam.J_o = 0;
  return beam;
}

std::vector<double> to_hz(std::vector<double> omegas_rad_s) {
  for (double& value : omegas_rad_s) value /= kTwoPi;
  return omegas_rad_s;
}

// Compares against a rounded table, with each value's own half-unit of its last digit.
void expect_rounded_match(const std::vector<double>& computed, const std::vector<double>& reference,
                          const std::vector<double>& half_units, const std::string& what) {
  ASSERT_GE(computed.size(), reference.size()) << what;
  for (std::size_t i = 0; i < reference.size(); ++i)
    EXPECT_NEAR(computed[i], reference[i], half_units[i]) << what << ", mode " << i + 1;
}

// The determinant exactly as model.md section 6 writes it (cosh, sinh, no column operations), divided by
// cosh^2(a l) at the end. Accurate only while a l is moderate and kAG not huge; used to check the rearranged form.
double naive_determinant(const BeamParameters& beam, double omega) {
  const double k = beam.kAG, w2 = omega * omega, l = beam.l;
  const double p = beam.rho * w2 * (beam.rho_r2 / (beam.rho * beam.EI) + 1 / k);
  const double q = beam.rho * w2 / beam.EI * (1 - beam.rho_r2 * w2 / k);
  const double a = std::sqrt((-p + std::sqrt(p * p + 4 * q)) / 2), b = std::sqrt((p + std::sqrt(p * p + 4 * q)) / 2);
  const double da = (a * a + beam.rho * w2 / k) / a, db = (b * b - beam.rho * w2 / k) / b;
  const double ch = std::cosh(a * l), sh = std::sinh(a * l), c = std::cos(b * l), s = std::sin(b * l);
  const double U[2] = {ch - c, sh - da / db * s};
  const double dU[2] = {a * sh + b * s, a * ch - da / db * b * c};
  const double Psi[2] = {da * sh + db * s, da * (ch - c)};
  const double dPsi[2] = {da * a * ch + db * b * c, da * (a * sh + b * s)};
  double R1[2], R2[2];
  for (int j = 0; j < 2; ++j) {
    R1[j] = k * (dU[j] - Psi[j]) - w2 * (beam.m * U[j] + beam.m * beam.c * Psi[j]);
    R2[j] = beam.EI * dPsi[j] - w2 * (beam.m * beam.c * U[j] + (beam.J_o + beam.m * beam.c * beam.c) * Psi[j]);
  }
  return (R1[0] * R2[1] - R1[1] * R2[0]) / (ch * ch);
}

TEST(EulerBernoulliRoots, PlainCantileverMatchesModelMd) {
  // 7 digits given: half a unit is 5e-7 (tighter than the 1e-6 of the brief, and still met by the true roots).
  expect_rounded_match(euler_bernoulli_cantilever_roots(5), {1.875104, 4.694091, 7.854757, 10.995541, 14.137168},
                       std::vector<double>(5, 5e-7), "1 + cos L cosh L = 0");
}

TEST(EulerBernoulliRoots, HighModesApproachOddHalfPi) {
  // 1 + cos L cosh L = 0 gives cos L_n = -1/cosh L_n, so L_n - (2n-1) pi/2 = +-sech(L_n) to first order; at n = 40,
  // sech ~ 1e-54, i.e. L_40 equals 79 pi/2 to the last bit (relative 1e-15 allows 2 ulps of the refinement).
  const std::vector<double> roots = euler_bernoulli_cantilever_roots(40);
  ASSERT_EQ(roots.size(), 40u);
  EXPECT_NEAR(roots[39], 79 * std::numbers::pi / 2, 1e-15 * roots[39]);
  for (std::size_t i = 1; i < roots.size(); ++i) EXPECT_GT(roots[i], roots[i - 1]);
}

TEST(EulerBernoulliRoots, TipMassMatchesModelMd) {
  // mu = 1, eta = 0: L^2 to 5 decimals, half-unit 5e-6.
  std::vector<double> squares = euler_bernoulli_tip_body_roots(1, 0, 5);
  for (double& L : squares) L *= L;
  expect_rounded_match(squares, {1.55730, 16.25009, 50.89584, 105.19828, 179.23202}, std::vector<double>(5, 5e-6),
                       "mu = 1, eta = 0 (L^2)");
  // mu = 1, eta = 0.1: L to 6 decimals, half-unit 5e-7.
  expect_rounded_match(euler_bernoulli_tip_body_roots(1, 0.1, 4), {1.195670, 2.505060, 4.975098, 7.983972},
                       std::vector<double>(4, 5e-7), "mu = 1, eta = 0.1");
}

TEST(EulerBernoulliRoots, NoTipBodyIsThePlainCantilever) {
  // Same scaled equation with mu = eta = 0: identical numbers, so exact equality.
  EXPECT_EQ(euler_bernoulli_tip_body_roots(0, 0, 6), euler_bernoulli_cantilever_roots(6));
}

TEST(EulerBernoulliFrequencies, UsesLumpedTipBodyAndScale) {
  // mu = m/(rho l) = 1 and eta = (J_o + m c^2)/(rho l^3) = 0.1 built from c != 0: omega_n = L_n^2 sqrt(EI/(rho l^4)).
  BeamParameters beam;
  beam.l = 2;
  beam.rho = 3;
  beam.rho_r2 = 1e-3;
  beam.kAG = 1e6;
  beam.EI = 5;
  beam.m = 6;      // mu = 6 / (3 * 2) = 1
  beam.c = 0.5;    // m c^2 = 1.5
  beam.J_o = 0.9;  // eta = (0.9 + 1.5) / (3 * 8) = 0.1
  const std::vector<double> omegas = euler_bernoulli_frequencies_rad_s(beam, 4);
  const std::vector<double> roots = euler_bernoulli_tip_body_roots(1, 0.1, 4);
  ASSERT_EQ(omegas.size(), 4u);
  const double scale = std::sqrt(5.0 / (3.0 * 16.0));
  // Only rounding in mu, eta and the scale separates the two: 1e-13 relative.
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(omegas[i], roots[i] * roots[i] * scale, 1e-13 * omegas[i]) << i;
}

TEST(TimoshenkoFrequencies, NondimensionalTableOfModelMd) {
  // Omega = omega for rho = EI = l = 1; 4 decimals given, half-unit 5e-5.
  const std::vector<double> half_unit(4, 5e-5);
  expect_rounded_match(timoshenko_frequencies_rad_s(nondimensional_beam(10), 4), {3.2271, 14.4689, 31.5025, 47.9090},
                       half_unit, "l/r = 10");
  expect_rounded_match(timoshenko_frequencies_rad_s(nondimensional_beam(20), 4), {3.4353, 19.1036, 46.6031, 78.9022},
                       half_unit, "l/r = 20");
  expect_rounded_match(timoshenko_frequencies_rad_s(nondimensional_beam(100), 4), {3.5127, 21.8889, 60.7409, 117.5161},
                       half_unit, "l/r = 100");
}

TEST(TimoshenkoFrequencies, NondimensionalWithTipBody) {
  // 5 decimals given, half-unit 5e-6.
  expect_rounded_match(timoshenko_frequencies_rad_s(nondimensional_beam(20, 1, 0.1, 0.01), 4),
                       {1.36157, 11.10366, 29.04988, 52.33236}, std::vector<double>(4, 5e-6),
                       "l/r = 20, m = 1, c = 0.1, J_o = 0.01");
}

TEST(TimoshenkoFrequencies, BanksAluminiumPreset) {
  // 2.4637, 26.499, 81.670, 164.00 Hz: half-units of 4, 3, 3, 2 decimals.
  expect_rounded_match(to_hz(timoshenko_frequencies_rad_s(preset("banks-aluminium"), 4)),
                       {2.4637, 26.499, 81.670, 164.00}, {5e-5, 5e-4, 5e-4, 5e-3}, "banks-aluminium");
}

TEST(TimoshenkoFrequencies, ThickSteelPreset) {
  // model.md's set B numbers at the digits given (3 decimals with the tip body, 2 without). The preset is built from
  // the unrounded geometry (beam_parameters.cc): the rounded lumps printed in model.md would miss by ~4e-5.
  const BeamParameters beam = preset("thick-steel");
  expect_rounded_match(to_hz(timoshenko_frequencies_rad_s(beam, 4)), {81.740, 579.236, 1665.412, 3260.857},
                       std::vector<double>(4, 5e-4), "thick-steel");
  expect_rounded_match(to_hz(timoshenko_frequencies_rad_s(without_tip_body(beam), 4)),
                       {135.63, 840.22, 2310.82, 4417.17}, std::vector<double>(4, 5e-3),
                       "thick-steel without tip body");
}

TEST(TimoshenkoFrequencies, ThickSteelPresetRoundsToPrintedLumps) {
  // model.md prints rho = 2.944, rho_r2 = 5.52e-5, kAG = 2.451e7, J_o = 8.373e-5: each within half a unit of the
  // last printed digit of the preset's unrounded value.
  const BeamParameters beam = preset("thick-steel");
  EXPECT_NEAR(beam.rho, 2.944, 5e-4);
  EXPECT_NEAR(beam.rho_r2, 5.52e-5, 5e-8);
  EXPECT_NEAR(beam.kAG, 2.451e7, 5e3);
  EXPECT_NEAR(beam.J_o, 8.373e-5, 5e-9);
  EXPECT_DOUBLE_EQ(beam.EI, 1406.25);
}

TEST(TimoshenkoFrequencies, EulerBernoulliOverestimatesThickSteel) {
  // model.md: Euler-Bernoulli is 1.4, 3.2 and 5.8 % high for modes 2-4 of set B without tip body (0.05 % half-unit).
  const BeamParameters beam = without_tip_body(preset("thick-steel"));
  const std::vector<double> timoshenko = timoshenko_frequencies_rad_s(beam, 4);
  const std::vector<double> euler_bernoulli = euler_bernoulli_frequencies_rad_s(beam, 4);
  const double percent[3] = {1.4, 3.2, 5.8};
  for (int i = 1; i < 4; ++i)
    EXPECT_NEAR(100 * (euler_bernoulli[i] / timoshenko[i] - 1), percent[i - 1], 0.05) << "mode " << i + 1;
}

TEST(TimoshenkoFrequencies, TendsToEulerBernoulliForSlenderBeams) {
  // Shear and rotary inertia lower omega_n by about C_n (r/l)^2 with C_n of order (1 + E/kG) L_n^2 / 2 (<= 3e2 for
  // modes 1-4). At l/r = 1e5 that is <= 3e-8, so 1e-7 relative must hold, for the plain beam and for a tip body at
  // c = 0 (mu = 1, eta = J_o/(rho l^3) = 0.1), where the EB tip-mass equation is exact in the limit.
  const std::vector<double> plain = timoshenko_frequencies_rad_s(nondimensional_beam(1e5), 4);
  const std::vector<double> tip = timoshenko_frequencies_rad_s(nondimensional_beam(1e5, 1, 0, 0.1), 4);
  const std::vector<double> L_plain = euler_bernoulli_cantilever_roots(4);
  const std::vector<double> L_tip = euler_bernoulli_tip_body_roots(1, 0.1, 4);
  ASSERT_EQ(plain.size(), 4u);
  ASSERT_EQ(tip.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(plain[i], L_plain[i] * L_plain[i], 1e-7 * plain[i]) << "mode " << i + 1;
    EXPECT_NEAR(tip[i], L_tip[i] * L_tip[i], 1e-7 * tip[i]) << "mode " << i + 1;
    EXPECT_LT(plain[i], L_plain[i] * L_plain[i]) << "shear flexibility can only lower the frequency";
  }
}

TEST(TimoshenkoFrequencies, SlenderDeviationIsSecondOrderToTwelveDigits) {
  // The deviation from EB is C_n (r/l)^2 + O((r/l)^4): going from l/r = 1e4 to 1e6 divides it by 1e4. At l/r = 1e6
  // the deviation is 1e-11..3e-10 relative, so a 1 % match of the ratio needs both roots right to about 1e-13
  // relative (and the determinant free of the kAG (U' - Psi) cancellation, kAG being 3e11 there).
  const std::vector<double> L = euler_bernoulli_cantilever_roots(4);
  const std::vector<double> coarse = timoshenko_frequencies_rad_s(nondimensional_beam(1e4), 4);
  const std::vector<double> fine = timoshenko_frequencies_rad_s(nondimensional_beam(1e6), 4);
  ASSERT_EQ(coarse.size(), 4u);
  ASSERT_EQ(fine.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const double deviation_coarse = 1 - coarse[i] / (L[i] * L[i]);
    const double deviation_fine = 1 - fine[i] / (L[i] * L[i]);
    EXPECT_NEAR(deviation_coarse / deviation_fine, 1e4, 0.01 * 1e4) << "mode " << i + 1;
  }
}

TEST(ExactFrequencies, HeavyTipBodyGivesTwoCloseLowRoots) {
  // A tip body far heavier than the beam (mu = 5000, eta = 1000) puts its translation and rotation modes at
  // L = 0.141 and 0.278, 0.14 apart, well inside one step of a march that advanced by pi/2: both must be found.
  // Reference: the massless-beam 2-DOF model, tip stiffness EI/l^3 [[12, -6 l], [-6 l, 4 l^2]] against
  // diag(mu, eta): mu eta L^8 - (4 mu + 12 eta) L^4 + 12 = 0. The beam's own inertia is at most 1/(3 eta) = 3.3e-4
  // of the tip's, shifting L^4 by at most that and L by a quarter of it, so 1e-4 relative.
  const double mu = 5000, eta = 1000;
  const double A = mu * eta, B = -(4 * mu + 12 * eta), C = 12, disc = std::sqrt(B * B - 4 * A * C);
  const double L_lumped[2] = {std::pow((-B - disc) / (2 * A), 0.25), std::pow((-B + disc) / (2 * A), 0.25)};
  const std::vector<double> L = euler_bernoulli_tip_body_roots(mu, eta, 3);
  ASSERT_EQ(L.size(), 3u);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(L[i], L_lumped[i], 1e-4 * L_lumped[i]) << "mode " << i + 1;
  EXPECT_GT(L[2], 4);  // the next one is a beam mode (near the clamped-clamped 4.730)
  // The Timoshenko march finds the same pair: l/r = 1e4, c = 0, shear correction <= 3e2 (r/l)^2 = 3e-6.
  const std::vector<double> omegas = timoshenko_frequencies_rad_s(nondimensional_beam(1e4, mu, 0, eta), 3);
  ASSERT_EQ(omegas.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(omegas[i], L[i] * L[i], 3e-6 * omegas[i]) << "mode " << i + 1;
}

TEST(TimoshenkoDeterminant, MatchesTheFormulaAsWritten) {
  // The implementation replaces column 2 by column 2 - column 1 and scales by cosh(a l); the determinant must not
  // change. At l/r = 20 and a l < 8 the naive form loses at most cosh^2(a l) ~ 1e7 against its terms, so 1e-7
  // relative (at points between roots, where the value is not itself a cancellation) separates a slip in the
  // algebra (O(1)) from rounding.
  for (const BeamParameters& beam : {nondimensional_beam(20), nondimensional_beam(20, 1, 0.1, 0.01)}) {
    const std::vector<double> roots = timoshenko_frequencies_rad_s(beam, 4);
    ASSERT_EQ(roots.size(), 4u);
    std::vector<double> points = {roots[0] / 2};
    for (int i = 0; i + 1 < 4; ++i) points.push_back((roots[i] + roots[i + 1]) / 2);
    for (double omega : points) {
      const double naive = naive_determinant(beam, omega);
      EXPECT_NEAR(timoshenko_determinant(beam, omega), naive, 1e-7 * std::abs(naive)) << "omega = " << omega;
    }
  }
}

TEST(TimoshenkoDeterminant, ChangesSignAcrossEachRoot) {
  // Roots are refined to a few ulps, so the points 1e-9 relative either side are clearly on either side.
  // (l/r = 10 has only 4 roots below its cut-off 100/sqrt(3.12) = 56.6; the others have at least 8.)
  for (const BeamParameters& beam : {nondimensional_beam(10), nondimensional_beam(20, 1, 0.1, 0.01),
                                     preset("banks-aluminium"), preset("thick-steel")}) {
    const std::vector<double> roots = timoshenko_frequencies_rad_s(beam, 8);
    ASSERT_GE(roots.size(), 4u);
    for (double omega : roots) {
      const double below = timoshenko_determinant(beam, omega * (1 - 1e-9));
      const double above = timoshenko_determinant(beam, omega * (1 + 1e-9));
      EXPECT_LT(below * above, 0) << "omega = " << omega;
    }
  }
}

TEST(TimoshenkoFrequencies, NoRootMissedByTheMarch) {
  // Count sign changes of the determinant on a uniform grid 10x to 100x finer than the march, up to the cut-off,
  // and compare with all roots returned (asking for more than exist also checks the early stop at the cut-off).
  for (const BeamParameters& beam :
       {nondimensional_beam(10), nondimensional_beam(20, 1, 0.1, 0.01), preset("thick-steel")}) {
    const double cutoff = shear_cutoff_rad_s(beam);
    const std::vector<double> roots = timoshenko_frequencies_rad_s(beam, 1000);
    ASSERT_LT(roots.size(), 1000u);
    ASSERT_GE(roots.size(), 4u);
    EXPECT_LT(roots.back(), cutoff);
    for (std::size_t i = 1; i < roots.size(); ++i) EXPECT_GT(roots[i], roots[i - 1]);
    const int grid = 200000;
    int sign_changes = 0;
    double previous = timoshenko_determinant(beam, cutoff * 0.5 / grid);
    for (int i = 1; i < grid; ++i) {
      const double value = timoshenko_determinant(beam, cutoff * (i + 0.5) / grid);
      if ((value < 0) != (previous < 0)) ++sign_changes;
      previous = value;
    }
    EXPECT_EQ(static_cast<std::size_t>(sign_changes), roots.size()) << "roots below the cut-off: " << roots.size();
  }
}

TEST(ExactFrequencies, InvalidArgumentsThrow) {
  const BeamParameters beam = nondimensional_beam(20);
  const double cutoff = shear_cutoff_rad_s(beam);
  EXPECT_THROW(timoshenko_frequencies_rad_s(beam, 0), InputError);
  EXPECT_THROW(timoshenko_frequencies_rad_s(beam, -3), InputError);
  EXPECT_THROW(euler_bernoulli_cantilever_roots(0), InputError);
  EXPECT_THROW(euler_bernoulli_tip_body_roots(1, 0, 0), InputError);
  EXPECT_THROW(euler_bernoulli_tip_body_roots(-1, 0, 3), InputError);
  EXPECT_THROW(euler_bernoulli_tip_body_roots(1, std::nan(""), 3), InputError);
  EXPECT_THROW(euler_bernoulli_frequencies_rad_s(beam, 0), InputError);
  for (double omega : {0.0, -1.0, cutoff, 2 * cutoff, std::nan("")})
    EXPECT_THROW(timoshenko_determinant(beam, omega), InputError) << "omega = " << omega;
  EXPECT_NO_THROW(timoshenko_determinant(beam, cutoff * (1 - 1e-6)));

  BeamParameters invalid = beam;
  invalid.EI = -1;
  EXPECT_THROW(timoshenko_frequencies_rad_s(invalid, 2), InputError);
  EXPECT_THROW(euler_bernoulli_frequencies_rad_s(invalid, 2), InputError);

  // The message names the argument, its value and the constraint.
  try {
    timoshenko_frequencies_rad_s(beam, 0);
    FAIL() << "no exception";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "count = 0: must be >= 1");
  }
  try {
    timoshenko_determinant(beam, -1);
    FAIL() << "no exception";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("omega_rad_s = -1: must be in (0, shear cut-off ", 0), 0u)
        << error.what();
  }
}

// ---- Attachments on the span (issue 11): the segmented determinant.

// An Euler-Bernoulli cantilever (rho = EI = l = 1) with a point mass mu (no rotary inertia) at xi and nothing at the
// tip, written independently of the library: two segments in the global coordinate s with the classical solutions
// cosh, sinh, cos, sin of L s; conditions y1(0) = y1'(0) = 0; y, y', y'' continuous at xi and the shear jump
// y2''' - y1''' = mu L^4 y(xi) (EI [y'''] = M omega^2 y with omega^2 = L^4 EI/(rho l^4)); y2''(1) = y2'''(1) = 0.
double euler_bernoulli_point_mass_determinant(double mu, double xi, double L) {
  const auto derivative = [L](double s, int order) {
    const double ch = std::cosh(L * s), sh = std::sinh(L * s), c = std::cos(L * s), n = std::sin(L * s);
    const double f = std::pow(L, order);
    switch (order) {
      case 0:
        return Eigen::RowVector4d(ch, sh, c, n);
      case 1:
        return Eigen::RowVector4d(f * sh, f * ch, -f * n, f * c);
      case 2:
        return Eigen::RowVector4d(f * ch, f * sh, -f * c, -f * n);
      default:
        return Eigen::RowVector4d(f * sh, f * ch, f * n, -f * c);
    }
  };
  Eigen::Matrix<double, 8, 8> a = Eigen::Matrix<double, 8, 8>::Zero();
  a.block<1, 4>(0, 0) = derivative(0, 0);
  a.block<1, 4>(1, 0) = derivative(0, 1);
  for (int order = 0; order < 3; ++order) {
    a.block<1, 4>(2 + order, 0) = derivative(xi, order);
    a.block<1, 4>(2 + order, 4) = -derivative(xi, order);
  }
  a.block<1, 4>(5, 0) = -derivative(xi, 3) - mu * std::pow(L, 4) * derivative(xi, 0);
  a.block<1, 4>(5, 4) = derivative(xi, 3);
  a.block<1, 4>(6, 4) = derivative(1, 2);
  a.block<1, 4>(7, 4) = derivative(1, 3);
  return a.determinant();
}

// Roots of the above by a scan in steps of 1e-3 in L (far below their ~pi spacing) and bisection to 1e-14.
std::vector<double> euler_bernoulli_point_mass_roots(double mu, double xi, int count) {
  std::vector<double> roots;
  const auto f = [&](double L) { return euler_bernoulli_point_mass_determinant(mu, xi, L); };
  for (int step = 100; static_cast<int>(roots.size()) < count && step < 30000; ++step) {
    double lo = step * 1e-3, hi = (step + 1) * 1e-3, f_lo = f(lo);
    if ((f_lo < 0) == (f(hi) < 0)) continue;
    while (hi - lo > 1e-14 * hi) {
      const double mid = (lo + hi) / 2, f_mid = f(mid);
      if ((f_mid < 0) == (f_lo < 0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    roots.push_back((lo + hi) / 2);
  }
  return roots;
}

TEST(AttachedBodies, SlenderBeamWithAPointMassIsEulerBernoulli) {
  // l/r = 3e4: Timoshenko's shear and rotary-inertia corrections are O((r/l)^2 (b l)^2 (1 + E/kG)) = 1.1e-9 x 121 x
  // 4.1 = 5e-7 at mode 4 (b l ~ 11). 1e-6 relative bounds that; a wrong jump sign or a mass counted at the wrong
  // point moves the frequencies by percents.
  for (const double xi : {0.25, 0.6, 0.95}) {
    const double mu = 0.5;
    BeamParameters beam = nondimensional_beam(3e4);
    beam.attachments.push_back({xi, mu, 0, 0});
    const std::vector<double> timoshenko = timoshenko_frequencies_rad_s(beam, 4);
    const std::vector<double> roots = euler_bernoulli_point_mass_roots(mu, xi, 4);
    ASSERT_EQ(roots.size(), 4u);
    ASSERT_EQ(timoshenko.size(), 4u);
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(timoshenko[k] / (roots[k] * roots[k]), 1.0, 1e-6) << "xi = " << xi << ", mode " << k + 1;
  }
}

TEST(AttachedBodies, MasslessAttachmentAndAttachmentAtTheTipMatchTheTwoByTwoForm) {
  // The segmented determinant and the closed 2x2 form are different algebra for the same roots: they agree to the
  // refinement's few ulps, amplified by the conditioning of each; 1e-12 allows that.
  for (const auto& name : preset_names()) {
    const BeamParameters plain = preset(name);
    const std::vector<double> reference = timoshenko_frequencies_rad_s(plain, 6);
    BeamParameters massless = plain;  // a body of no mass cuts the beam in two and changes nothing
    massless.attachments.push_back({0.4 * plain.l, 0, 0, 0});
    BeamParameters moved = plain;  // the tip body given as an attachment at x = l
    moved.attachments.push_back({plain.l, plain.m, plain.J_o, plain.c});
    moved.m = moved.c = moved.J_o = 0;
    const std::vector<double> cut = timoshenko_frequencies_rad_s(massless, 6);
    const std::vector<double> at_tip = timoshenko_frequencies_rad_s(moved, 6);
    ASSERT_EQ(cut.size(), 6u);
    ASSERT_EQ(at_tip.size(), 6u);
    for (int k = 0; k < 6; ++k) {
      EXPECT_NEAR(cut[k] / reference[k], 1.0, 1e-12) << name << " mode " << k + 1;
      EXPECT_NEAR(at_tip[k] / reference[k], 1.0, 1e-12) << name << " mode " << k + 1;
    }
  }
}

TEST(AttachedBodies, OffsetAndInertiaEnterAsTheTipBodysDo) {
  // Two bodies at one point act as one with the summed inertia Lambda = [[m, m c], [m c, J + m c^2]]: a 0.1 kg body
  // with offset 0.01 m and J = 2e-6 plus a 0.05 kg body with offset -0.02 m equal one body with m = 0.15, m c = 0,
  // J + m c^2 = 2e-6 + 1e-5 + 2e-5 (so J = 3.2e-5, c = 0). The same matrix up to the rounding of the sums: 1e-12.
  BeamParameters two = preset("thick-steel"), one = two;
  two.attachments = {{0.2, 0.1, 2e-6, 0.01}, {0.2, 0.05, 0, -0.02}};
  one.attachments = {{0.2, 0.15, 3.2e-5, 0}};
  const std::vector<double> a = timoshenko_frequencies_rad_s(two, 4), b = timoshenko_frequencies_rad_s(one, 4);
  ASSERT_EQ(a.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[k] / b[k], 1.0, 1e-12) << "mode " << k + 1;
  // The segmented determinant refuses what the 2x2 one refuses; the Euler-Bernoulli tip equation has no span bodies.
  EXPECT_THROW(segmented_determinant(two, 0.0), InputError);
  EXPECT_THROW(segmented_determinant(two, shear_cutoff_rad_s(two)), InputError);
  EXPECT_THROW(euler_bernoulli_frequencies_rad_s(two, 2), InputError);
}

// ---- A compliant clamp (issue 11): root springs k_theta, k_w in the segmented determinant.

TEST(CompliantClamp, StiffSpringsAreTheRigidClamp) {
  // Springs of 1e18 (N m/rad, N/m) against EI/l ~ 1e0-1e4: the clamp yields by ~1e-14 of the beam's own
  // compliance; what remains is the rounding of rows scaled by k l/EI ~ 1e14-1e18 (measured 8e-12): 1e-10.
  for (const auto& name : preset_names()) {
    BeamParameters beam = preset(name);
    const std::vector<double> rigid = timoshenko_frequencies_rad_s(beam, 4);
    beam.support.k_theta = beam.support.k_w = 1e18;
    const std::vector<double> stiff = timoshenko_frequencies_rad_s(beam, 4);
    ASSERT_EQ(stiff.size(), 4u);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(stiff[k] / rigid[k], 1.0, 1e-10) << name << " mode " << k + 1;
  }
}

TEST(CompliantClamp, SofterSpringsLowerEveryFrequency) {
  // Rayleigh: less stiffness, lower (or equal) eigenvalues; strictly lower here since every mode rotates the root.
  BeamParameters beam = preset("thick-steel");
  std::vector<double> previous = timoshenko_frequencies_rad_s(beam, 4);
  for (const double k_theta : {1e6, 1e4, 1e2}) {
    beam.support.k_theta = k_theta;
    const std::vector<double> f = timoshenko_frequencies_rad_s(beam, 4);
    for (int k = 0; k < 4; ++k) EXPECT_LT(f[k], previous[k]) << "k_theta = " << k_theta << ", mode " << k + 1;
    previous = f;
  }
}

TEST(CompliantClamp, FreeRotationIsThePinnedFreeBeam) {
  // A slender beam (l/r = 3e4, Euler-Bernoulli to ~1e-7) whose root may rotate against a vanishing spring
  // (k_theta l/EI = 1e-9) is a pinned-free beam: a rigid rotation at ~sqrt(3 k_theta/(rho l^3)) = 5.5e-5 and then
  // the flexible modes of tan L = tanh L, L = 3.9266023120, 7.0685827560, 10.2101761242 (each to 1e-10), with
  // omega = L^2 for rho = EI = l = 1. 1e-6 bounds the shear and spring corrections.
  BeamParameters beam = nondimensional_beam(3e4);
  beam.support.k_theta = 1e-9;
  const std::vector<double> f = timoshenko_frequencies_rad_s(beam, 4);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_NEAR(f[0], std::sqrt(3e-9), 1e-3 * std::sqrt(3e-9));  // a rigid bar on a rotational spring, to O(k)
  const double pinned_free[] = {3.9266023120, 7.0685827560, 10.2101761242};
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(f[k + 1] / (pinned_free[k] * pinned_free[k]), 1.0, 1e-6) << "flexible mode " << k + 1;
}

}  // namespace
}  // namespace beamid::model
