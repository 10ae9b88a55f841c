// A linear filter on the model's output and the decimation after it, carried through the closed-form response
// (issue 32: a sensor's anti-alias filter in a fitted model, signal/sensor_filter.h, without simulating the record
// R times finer and filtering it sample by sample).
//
// The filter runs on the fine grid dt_f = dt / R: s_{n+1} = A s_n + B x_n, y_n = C s_n + D x_n, and the record keeps
// y_{R m}. After the pulse the model's output is a sum of exponentials, x_n = Re sum_k a_k mu_k^n (mu_k = e^{lambda_k
// dt_f}). The filter's response to one of them from the state s_n = v(mu) a mu^n, v(mu) = (mu I - A)^-1 B, is
// H(mu) a mu^n with H(mu) = C v(mu) + D: that is the particular solution, and every other start differs from it by the
// filter's own decay C A^{n - n1} r (r = the state at the pulse's end n1 minus the particular states there). So the
// sensed record after the pulse is the modal sum with every amplitude times H(mu_k), read on the record's grid, plus a
// transient of order(A) states that dies at the filter's rate; only the short stretch of the pulse is simulated on the
// fine grid and filtered sample by sample. A term (t - tau) mu^n (a sensitivity's, simulation/sensitivities.h) has the
// particular response H (t - tau) mu^n + dt_f mu H'(mu) mu^n, H'(mu) = C v'(mu), v'(mu) = -(mu I - A)^-1 v(mu).
// Nothing is approximated: the result is the fine path's (filter every fine sample, keep every R-th) up to round-off.
#pragma once

#include <Eigen/Dense>
#include <complex>

namespace beamid::simulation {

class OutputFilter {
 public:
  // The filter's matrices on the fine grid (A square, B and C of its order) and R >= 1. InputError for mismatched
  // sizes or R < 1.
  OutputFilter(Eigen::MatrixXd a, Eigen::VectorXd b, Eigen::VectorXd c, double d, int decimation);

  int decimation() const { return decimation_; }
  Eigen::Index order() const { return a_.rows(); }

  // The state of a constant input held forever: (I - A)^-1 B level (the filter's start when its input was `level`
  // before the record).
  Eigen::VectorXd steady_state(double level) const;

  // The filter's response to mu^n: v(mu), H(mu) and their derivatives in mu.
  struct Response {
    std::complex<double> h, dh;
    Eigen::VectorXcd v, dv;
  };
  Response at(std::complex<double> mu) const;

  // Runs the filter over the fine samples x (rows) of every column from `state` (order x columns, advanced in place),
  // and writes the outputs of the rows that fall on the record's grid (row n = R m) into record's row m.
  void run(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::MatrixXd& state,
           Eigen::Ref<Eigen::MatrixXd> record) const;

  // Adds the filter's decay C A^{R m - n1} r (one column per r) to the record's rows m with R m >= n1, until it has
  // fallen below 1e-18 of its start.
  void add_transient(Eigen::Ref<Eigen::MatrixXd> record, int n1, Eigen::MatrixXd r) const;

 private:
  Eigen::MatrixXd a_, a_decimated_;  // A and A^R
  Eigen::VectorXd b_, c_;
  double d_;
  int decimation_;
};

}  // namespace beamid::simulation
