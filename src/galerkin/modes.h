// Eigen-analysis of the Galerkin system M w'' + C w' + K w = f P(t).
//
// Undamped modes: K phi = omega^2 M phi with phi^T M phi = 1.
//
// StateSpaceModes is an exact modal form of the damped first-order system, built to be well balanced:
// with the undamped shapes Phi (any accurate basis will do; only balance depends on their accuracy) the exactly
// transformed matrices M~ = Phi^T M Phi (~ I), K~ = Phi^T K Phi (~ Omega^2), C~ = Phi^T C Phi and the scaling
// D = sqrt(diag K~), the state z = [D q; q'] with w = Phi q obeys z' = A z + bP with
//     A = [ 0                 D          ]      b = [ 0             ]
//         [ -M~^-1 K~ D^-1    -M~^-1 C~  ],         [ M~^-1 Phi^T f ],
// whose entries are all of the size of the modal frequencies and damping rates (in the raw form [0 I; -M^-1K -M^-1C]
// they span ~20 orders of magnitude). A = V Lambda V^-1 then decouples it: eta = V^-1 z, eta_k' = lambda_k eta_k + g_k
// P.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "galerkin/second_order_system.h"

namespace beamid::galerkin {

struct UndampedModes {
  Eigen::VectorXd omega_rad_s;  // ascending
  Eigen::MatrixXd shapes;       // columns phi_k, phi^T M phi = 1
};
// Throws NumericalError when M is not positive definite or the eigensolver fails.
UndampedModes undamped_modes(const SecondOrderSystem& system);

struct DampedMode {
  double frequency_hz;          // natural frequency |lambda| / (2 pi)
  double damping_ratio;         // -Re(lambda) / |lambda|
  std::complex<double> lambda;  // eigenvalue with Im(lambda) > 0, rad/s
};

class StateSpaceModes {
 public:
  // Throws NumericalError when a decomposition fails.
  explicit StateSpaceModes(const SecondOrderSystem& system);

  int size() const { return static_cast<int>(lambda_.size()); }
  const Eigen::VectorXcd& eigenvalues() const { return lambda_; }

  // g = V^-1 [0; M~^-1 Phi^T f]: modal input coefficients of the generalised load f (per unit P).
  Eigen::VectorXcd input_coefficients(const Eigen::VectorXd& load) const;
  // V^-1 z(0) for the physical initial state w(0) = w0, w'(0) = v0.
  Eigen::VectorXcd state_coefficients(const Eigen::VectorXd& w0, const Eigen::VectorXd& v0) const;
  // h with y = sum_k h_k eta_k for y = c^T w (derivative 0), c^T w' (1) or c^T w'' without the direct load term (2).
  Eigen::VectorXcd output_coefficients(const Eigen::VectorXd& sensor, int derivative) const;
  // The direct term of the acceleration output: c^T M^-1 f (so c^T w'' = sum h_k eta_k + feedthrough * P).
  double feedthrough(const Eigen::VectorXd& sensor, const Eigen::VectorXd& load) const;
  // The eigenvectors in physical coordinates: column k is x_k with (lambda_k^2 M + lambda_k C + K) x_k = 0, in the
  // order of eigenvalues() (any scaling; the state-space eigenvector is [x_k; lambda_k x_k]).
  Eigen::MatrixXcd physical_vectors() const;
  // Reciprocal condition estimate of V (small: nearly defective, e.g. critically damped, modes).
  double eigenvector_rcond() const { return rcond_; }

  // Underdamped modes (Im lambda > 0), sorted by natural frequency.
  std::vector<DampedMode> underdamped_modes() const;

 private:
  void refine_eigenvalues(const SecondOrderSystem& system);

  Eigen::MatrixXd shapes_;            // Phi
  Eigen::LLT<Eigen::MatrixXd> mass_;  // M~ = Phi^T M Phi
  Eigen::MatrixXd phi_t_mass_;        // Phi^T M, for Phi^-1 w = M~^-1 Phi^T M w
  Eigen::VectorXd scale_;             // D
  Eigen::MatrixXd a_;                 // A
  Eigen::VectorXcd lambda_;
  Eigen::MatrixXcd vectors_;
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu_;
  Eigen::LLT<Eigen::MatrixXd> system_mass_;  // M itself, for the feedthrough
  double rcond_ = 0;
};

}  // namespace beamid::galerkin
