#include "signal/sensor_filter.h"

#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace beamid::signal {

std::optional<std::string> validation_error(const SensorFilter& f, double dt_s) {
  if (!(std::isfinite(f.cutoff_hz) && f.cutoff_hz >= 0))
    return "sensor cut-off = " + format_value(f.cutoff_hz) + " Hz: must be >= 0 (0: no filter)";
  if (f.order < 1 || f.order > 8) return "sensor filter order = " + std::to_string(f.order) + ": must be in 1..8";
  if (f.oversampling < 2 || f.oversampling > 64)
    return "sensor filter oversampling = " + std::to_string(f.oversampling) + ": must be in 2..64";
  const double limit = f.oversampling / (8 * dt_s);
  if (f.cutoff_hz > 0 && !(f.cutoff_hz < limit))
    return "sensor cut-off = " + format_value(f.cutoff_hz) + " Hz: must be below " + format_value(limit) +
           " Hz (a quarter of the Nyquist frequency of the " + std::to_string(f.oversampling) +
           "x faster record the filter runs on, where its digital form follows the analog one)";
  return std::nullopt;
}

namespace {

// One second-order section (a first-order one has a2 = b2 = 0): y = b0 x + s1, s1' = b1 x - a1 y + s2,
// s2' = b2 x - a2 y (direct form II transposed), unit gain at DC.
struct Section {
  double b0, b1, b2, a1, a2;
};

std::vector<Section> sections(const SensorFilter& f, double fine_dt_s) {
  const double warped = 2 / fine_dt_s * std::tan(std::numbers::pi * f.cutoff_hz * fine_dt_s);  // Omega_c
  std::vector<Section> out;
  for (int k = 0; k < f.order; ++k) {
    // Analog poles Omega_c e^{j pi (2k + n + 1) / (2n)} in the left half plane; one of each pair, and the real one.
    const std::complex<double> p =
        warped * std::polar(1.0, std::numbers::pi * (2.0 * k + f.order + 1) / (2.0 * f.order));
    if (p.imag() < -1e-12 * warped) continue;  // the conjugate of one taken
    const std::complex<double> z = (1.0 + p * fine_dt_s / 2.0) / (1.0 - p * fine_dt_s / 2.0);  // bilinear
    if (std::abs(p.imag()) <= 1e-12 * warped) {  // real pole: (1 + z^-1) / (1 - z_r z^-1), gain (1 - z_r) / 2
      const double g = (1 - z.real()) / 2;
      out.push_back({g, g, 0, -z.real(), 0});
    } else {  // a pair: (1 + z^-1)^2 / (1 - 2 Re z z^-1 + |z|^2 z^-2), gain (1 + a1 + a2) / 4
      const double a1 = -2 * z.real(), a2 = std::norm(z), g = (1 + a1 + a2) / 4;
      out.push_back({g, 2 * g, g, a1, a2});
    }
  }
  return out;
}

}  // namespace

std::vector<double> sense(const SensorFilter& f, const std::vector<double>& fine, double dt_s,
                          std::optional<double> level_before) {
  if (auto error = validation_error(f, dt_s)) throw InputError(*error);
  const auto r = static_cast<std::size_t>(f.oversampling);
  if (fine.empty() || fine.size() % r != 0)
    throw InputError("sensor filter: a fine record of " + std::to_string(fine.size()) +
                     " samples is not a whole number of " + std::to_string(r) + "-sample steps");
  std::vector<double> y = fine;
  if (f.cutoff_hz > 0)
    for (const Section& s : sections(f, dt_s / f.oversampling)) {
      // The steady state of a constant input x0, the level before t = 0 (unit DC gain: every section's output is x0
      // too, so the next section starts from the same level).
      const double x0 = level_before.value_or(fine.front());
      double s2 = s.b2 * x0 - s.a2 * x0, s1 = s.b1 * x0 - s.a1 * x0 + s2;
      for (double& v : y) {
        const double x = v;
        v = s.b0 * x + s1;
        s1 = s.b1 * x - s.a1 * v + s2;
        s2 = s.b2 * x - s.a2 * v;
      }
    }
  std::vector<double> out(fine.size() / r);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = y[i * r];
  return out;
}

FilterStateSpace state_space(const SensorFilter& f, double dt_s) {
  if (auto error = validation_error(f, dt_s)) throw InputError(*error);
  FilterStateSpace total;  // the identity, extended section by section
  if (!(f.cutoff_hz > 0)) return total;
  for (const Section& s : sections(f, dt_s / f.oversampling)) {
    // One section: y = b0 x + s1, s1' = (b1 - a1 b0) x - a1 s1 + s2, s2' = (b2 - a2 b0) x - a2 s1 (s2 absent for a
    // first-order one, whose a2 = b2 = 0).
    const bool second = s.a2 != 0 || s.b2 != 0;
    const Eigen::Index n = second ? 2 : 1;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b(n), c = Eigen::VectorXd::Zero(n);
    a(0, 0) = -s.a1;
    b(0) = s.b1 - s.a1 * s.b0;
    c(0) = 1;
    if (second) {
      a(0, 1) = 1;
      a(1, 0) = -s.a2;
      b(1) = s.b2 - s.a2 * s.b0;
    }
    // In cascade after `total`: its output C1 s1 + D1 x is this section's input.
    const Eigen::Index m = total.a.rows();
    FilterStateSpace next;
    next.a = Eigen::MatrixXd::Zero(m + n, m + n);
    next.a.topLeftCorner(m, m) = total.a;
    next.a.bottomLeftCorner(n, m) = b * total.c.transpose();
    next.a.bottomRightCorner(n, n) = a;
    next.b.resize(m + n);
    next.b << total.b, b * total.d;
    next.c.resize(m + n);
    next.c << s.b0 * total.c, c;
    next.d = s.b0 * total.d;
    total = std::move(next);
  }
  return total;
}

std::complex<double> sensor_response(const SensorFilter& f, double dt_s, double frequency_hz) {
  if (auto error = validation_error(f, dt_s)) throw InputError(*error);
  const double fine_dt = dt_s / f.oversampling;
  const std::complex<double> zi = std::polar(1.0, -2 * std::numbers::pi * frequency_hz * fine_dt);
  std::complex<double> h = 1;
  if (f.cutoff_hz > 0)
    for (const Section& s : sections(f, fine_dt))
      h *= (s.b0 + s.b1 * zi + s.b2 * zi * zi) / (1.0 + s.a1 * zi + s.a2 * zi * zi);
  return h;
}

}  // namespace beamid::signal
