#include "simulation/output_filter.h"

#include <string>

#include "core/errors.h"

namespace beamid::simulation {

OutputFilter::OutputFilter(Eigen::MatrixXd a, Eigen::VectorXd b, Eigen::VectorXd c, double d, int decimation)
    : a_(std::move(a)), b_(std::move(b)), c_(std::move(c)), d_(d), decimation_(decimation) {
  if (a_.rows() != a_.cols() || b_.size() != a_.rows() || c_.size() != a_.rows())
    throw InputError("output filter: A is " + std::to_string(a_.rows()) + " x " + std::to_string(a_.cols()) +
                     ", B has " + std::to_string(b_.size()) + " rows and C " + std::to_string(c_.size()) +
                     ": they must agree");
  if (decimation_ < 1)
    throw InputError("output filter: decimation = " + std::to_string(decimation_) + ": must be >= 1");
  a_decimated_ = Eigen::MatrixXd::Identity(a_.rows(), a_.cols());
  for (int k = 0; k < decimation_; ++k) a_decimated_ = a_ * a_decimated_;
}

Eigen::VectorXd OutputFilter::steady_state(double level) const {
  const Eigen::Index n = order();
  if (n == 0) return {};
  return (Eigen::MatrixXd::Identity(n, n) - a_).partialPivLu().solve(b_) * level;
}

OutputFilter::Response OutputFilter::at(std::complex<double> mu) const {
  const Eigen::Index n = order();
  Response r;
  if (n == 0) {
    r.h = d_;
    r.dh = 0;
    return r;
  }
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(mu * Eigen::MatrixXcd::Identity(n, n) -
                                                 a_.cast<std::complex<double>>());
  r.v = lu.solve(b_.cast<std::complex<double>>());
  r.dv = -lu.solve(r.v);  // d/dmu (mu I - A)^-1 B = -(mu I - A)^-2 B
  const Eigen::VectorXcd c = c_.cast<std::complex<double>>();
  r.h = c.dot(r.v) + d_;  // dot conjugates its first argument: C is real
  r.dh = c.dot(r.dv);
  return r;
}

void OutputFilter::run(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::MatrixXd& state,
                       Eigen::Ref<Eigen::MatrixXd> record) const {
  for (Eigen::Index n = 0; n < x.rows(); ++n) {
    if (n % decimation_ == 0 && n / decimation_ < record.rows()) {
      auto row = record.row(n / decimation_);
      row = d_ * x.row(n);
      if (order() > 0) row += c_.transpose() * state;
    }
    if (order() > 0) state = a_ * state + b_ * x.row(n);
  }
}

void OutputFilter::add_transient(Eigen::Ref<Eigen::MatrixXd> record, int n1, Eigen::MatrixXd r) const {
  if (order() == 0 || r.cols() == 0) return;
  // To the first record sample at or after n1: A^{R m1 - n1}, fewer than R fine steps.
  const Eigen::Index m1 = (n1 + decimation_ - 1) / decimation_;
  for (Eigen::Index n = n1; n < m1 * decimation_; ++n) r = a_ * r;
  const double start = r.cwiseAbs().maxCoeff();
  if (!(start > 0)) return;
  for (Eigen::Index m = m1; m < record.rows(); ++m) {
    record.row(m) += c_.transpose() * r;
    r = a_decimated_ * r;
    if (r.cwiseAbs().maxCoeff() <= 1e-18 * start) break;
  }
}

}  // namespace beamid::simulation
