// Small systems with known answers shared by the simulation tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "galerkin/second_order_system.h"
#include "simulation/experiment.h"

namespace beamid::simulation::testing {

// m x'' + c x' + k x = P(t): a one-degree-of-freedom oscillator in the SecondOrderSystem form.
inline galerkin::SecondOrderSystem oscillator(double m, double c, double k) {
  galerkin::SecondOrderSystem s;
  s.M = Eigen::MatrixXd::Constant(1, 1, m);
  s.C = Eigen::MatrixXd::Constant(1, 1, c);
  s.K = Eigen::MatrixXd::Constant(1, 1, k);
  return s;
}

// Released from x0 at rest, sampled displacement/velocity/acceleration.
inline ResponseProblem release(double x0, int derivative, double dt_s, int samples) {
  ResponseProblem p;
  p.load = Eigen::VectorXd::Ones(1);
  p.sensor = Eigen::VectorXd::Ones(1);
  p.w0 = Eigen::VectorXd::Constant(1, x0);
  p.derivative = derivative;
  p.dt_s = dt_s;
  p.samples = samples;
  return p;
}

// Free decay of an underdamped oscillator from x0 at rest: x = x0 e^{-s t}(cos wd t + (s/wd) sin wd t),
// s = c/(2m), wd = sqrt(k/m - s^2); derivatives in closed form.
inline double free_decay(double m, double c, double k, double x0, int derivative, double t) {
  const double s = c / (2 * m), wd = std::sqrt(k / m - s * s);
  const double e = std::exp(-s * t), cs = std::cos(wd * t), sn = std::sin(wd * t);
  const double w2 = k / m;
  if (derivative == 0) return x0 * e * (cs + s / wd * sn);
  if (derivative == 1) return -x0 * e * w2 / wd * sn;
  return -x0 * e * w2 * (cs - s / wd * sn);  // x'' = -(c x' + k x)/m
}

// max |a_i - b_i| / max |b_i| over a record: a trace against its reference.
inline double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return diff / scale;
}

}  // namespace beamid::simulation::testing
