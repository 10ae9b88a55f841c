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
// they span ~20 orders of magnitude). Its eigenpairs A v_k = lambda_k v_k give the physical eigenvectors
// x_k = Phi D^-1 (v_k)_top of T(lambda) = lambda^2 M + lambda C + K. Because M, C, K are symmetric, the first-order
// pencil [C M; M 0] u' = [-K 0; 0 M] u + [f P; 0] in u = [w; w'] is symmetric, its left eigenvectors are its right
// ones phi_k = [x_k; lambda_k x_k], and with n_k = phi_k^T [C M; M 0] phi_k = x_k^T (2 lambda_k M + C) x_k the
// modal coordinates of w = sum_k x_k eta_k are, without inverting the eigenvector matrix,
//     eta_k' = lambda_k eta_k + g_k P,   g_k = x_k^T f / n_k,
//     eta_k(0) = x_k^T [(lambda_k M + C) w(0) + M w'(0)] / n_k,
//     c^T w^(d) = sum_k lambda_k^d (c^T x_k) eta_k   (d = 0, 1; d = 2 adds the direct term c^T M^-1 f P).
// That needs phi_j^T [C M; M 0] phi_k = 0 for j != k, which the computed vectors of a cluster of nearly equal
// eigenvalues (the shear relaxation rates kAG/kAcs of a heavily damped beam agree to ~1e-6) do not satisfy: their
// errors are of order eps / gap within the cluster's span. So eigenvalues within 1e-3 of each other (relative) form a
// block, whose coordinates solve G eta_block = Phi_block^T [C M; M 0] u with the block's Gram matrix
// G_jk = x_j^T (C + (lambda_j + lambda_k) M) x_k, the oblique projection onto the span, which is accurate; between
// blocks the neglected Gram entries are below eps / 1e-3.
//
// The eigenpairs themselves come, when the damping couples the undamped modes weakly (banks-aluminium: first-order
// coupling 2e-4), from a Jacobi iteration in the undamped basis started at each decoupled mode, with a Rayleigh-Ritz
// step for blocks of nearly equal real roots (damped_iteration.cc): a few products of n x n matrices with the 2n
// vectors instead of the dense 2n x 2n nonsymmetric decomposition of A, which remains the fallback when the iteration
// would take more than 12 steps (thick-steel; the thin beam once a relaxation parameter cDI, kAcs, EI or kAG is 10-30 %
// off equal bending and shear relaxation times). Everything after them (refinement, normalisation, clusters,
// coefficients) works in the undamped basis, x_k = Phi q_k.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "galerkin/second_order_system.h"

namespace beamid::galerkin {

struct UndampedModes {
  Eigen::VectorXd omega_rad_s;  // ascending
  Eigen::MatrixXd shapes;       // columns phi_k, phi^T M phi = 1
};
// Throws NumericalError when M is not positive definite or the eigensolver fails.
UndampedModes undamped_modes(const SecondOrderSystem& system);
// The system with constant modal damping of ratio zeta added, a loss law that Kelvin-Voigt and air damping cannot
// take (their ratios grow and fall with frequency; a study's truth with a damping law no fitted model has, issue 35):
// C + M Phi diag(2 zeta omega_k) Phi^T M over every undamped mode (phi_k^T M phi_k = 1), which gives a system without
// other damping the ratio zeta in every mode exactly (Phi^T C Phi = diag(2 zeta omega_k): each modal equation is
// q'' + 2 zeta omega q' + omega^2 q = f) and adds about zeta to the ratios of a lightly damped one. InputError unless
// 0 <= zeta < 1; zeta = 0 returns the system unchanged.
SecondOrderSystem with_modal_damping(SecondOrderSystem system, double damping_ratio);
// The first `modes` of them for the model (forms, beam): InputError when the model has fewer ("the Galerkin model has
// n modes, m are fitted").
UndampedModes lowest_undamped_modes(const BeamForms& forms, const model::BeamParameters& beam, int modes);
// d log f_k / d log q_i of the first `modes` undamped modes of the Galerkin model (forms, beam), exactly: with
// phi_k M-normalised, d(omega_k^2)/dq = phi_k^T (dK/dq - omega_k^2 dM/dq) phi_k, so that
// d log f_k / d log q = q phi_k^T (dK/dq - omega_k^2 dM/dq) phi_k / (2 omega_k^2)  (0 for damping parameters).
// modes x keys.
Eigen::MatrixXd frequency_sensitivities(const BeamForms& forms, const model::BeamParameters& beam,
                                        const std::vector<std::string>& keys, int modes);

struct DampedMode {
  double frequency_hz;          // natural frequency |lambda| / (2 pi)
  double damping_ratio;         // -Re(lambda) / |lambda|
  std::complex<double> lambda;  // eigenvalue with Im(lambda) > 0, rad/s
};

// How StateSpaceModes finds the damped eigenpairs: automatic is the Jacobi iteration in the undamped basis when the
// damping couples the modes weakly enough, else the dense decomposition; dense always decomposes the state matrix
// (for comparisons and benchmarks).
enum class DampedModesMethod { automatic, dense };

class StateSpaceModes {
 public:
  // Throws NumericalError when a decomposition fails.
  explicit StateSpaceModes(const SecondOrderSystem& system, DampedModesMethod method = DampedModesMethod::automatic);

  int size() const { return static_cast<int>(lambda_.size()); }
  const Eigen::VectorXcd& eigenvalues() const { return lambda_; }

  // g_k = x_k^T f / n_k: modal input coefficients of the generalised load f (per unit P).
  Eigen::VectorXcd input_coefficients(const Eigen::VectorXd& load) const;
  // eta(0) for the physical initial state w(0) = w0, w'(0) = v0.
  Eigen::VectorXcd state_coefficients(const Eigen::VectorXd& w0, const Eigen::VectorXd& v0) const;
  // h_k = lambda_k^d c^T x_k, with y = sum_k h_k eta_k for y = c^T w (derivative d = 0), c^T w' (1) or c^T w''
  // without the direct load term (2).
  Eigen::VectorXcd output_coefficients(const Eigen::VectorXd& sensor, int derivative) const;
  // The direct term of the acceleration output: c^T M^-1 f (so c^T w'' = sum h_k eta_k + feedthrough * P).
  double feedthrough(const Eigen::VectorXd& sensor, const Eigen::VectorXd& load) const;
  // The eigenvectors in physical coordinates: column k is x_k with (lambda_k^2 M + lambda_k C + K) x_k = 0, in the
  // order of eigenvalues() (any scaling; the state-space eigenvector is [x_k; lambda_k x_k]).
  Eigen::MatrixXcd physical_vectors() const;
  // The reciprocal of the largest eigenvalue condition number of A, 1 / max_k |u_k| |v_k| with the left eigenvector
  // u_k (u_k^T v_k = 1) from the symmetric pencil, or of a cluster's scaled Gram matrix if smaller: small for nearly
  // defective (e.g. critically damped) modes. The condition number of the eigenvector matrix lies between
  // max_k |u_k| |v_k| and 2n times it. The decomposition is refused below 1e3 eps; the modal coefficients' relative
  // error grows like eps / rcond^2 (about 3 % for a 2-DOF system 1e-15 from critical damping, rcond 4.5e-8).
  double eigenvector_rcond() const { return rcond_; }
  // True when the eigenpairs came from the Jacobi iteration in the undamped basis, false when from the dense
  // eigen-decomposition of the state matrix (strongly coupling damping; see damped_iteration.cc).
  bool iterated() const { return iterated_; }

  // d lambda_k / d q for a parameter with derivatives d = (dM, dC, dK) (galerkin::parameter_derivative), all 2n, in the
  // order of eigenvalues(): first-order perturbation of T(lambda) x = 0 with the left eigenvector x^T,
  //   d lambda_k = -x_k^T (lambda_k^2 dM + lambda_k dC + dK) x_k / n_k.
  // Exact for a simple eigenvalue; within a cluster (above) only the cluster's mean moves smoothly.
  Eigen::VectorXcd eigenvalue_derivative(const SecondOrderSystem& d) const;

  // Underdamped modes (Im lambda > 0), sorted by natural frequency, without the pairs that are critically damped to
  // within 1e-6 (zeta > 1 - 1e-6): a nearly multiple real eigenvalue, such as the shear relaxation rate kAG/kAcs that
  // all shear modes share, splits under round-off into complex pairs with zeta = 1 - 1e-19 (extended precision) or
  // 1 - 1e-10 (double), and even a genuine pair that close to critical is no vibration: its damped frequency is
  // |lambda| sqrt(1 - zeta^2) < 1.4e-3 |lambda|, and it decays by e^-4400 within one damped period.
  static constexpr double kCriticalMargin = 1e-6;
  std::vector<DampedMode> underdamped_modes() const;

 private:
  // The damped modes in the undamped modal basis by a Jacobi iteration from the decoupled modes (damped_iteration.cc),
  // or by the dense eigen-decomposition of the balanced state matrix (dense_modes.cc); both set lambda_, q_, mass_q_
  // and damping_q_. The iteration returns false when the damping couples the modes too strongly for it (then the dense
  // one runs).
  //
  // separate_close_modes rotates each group of nearly equal undamped frequencies (shapes_, M Phi, C Phi and M~, K~, C~
  // with them) so that M~ = I and K~ is diagonal within the group to round-off, unless every member of the group is
  // overdamped on its own (its roots then go to the iteration's Rayleigh-Ritz blocks, which take the coupling within
  // the group; modes.cc).
  void separate_close_modes(const Eigen::VectorXd& omega, Eigen::MatrixXd& mt, Eigen::MatrixXd& kt,
                            Eigen::MatrixXd& ct);
  bool iterate_damped_modes(const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct, const Eigen::MatrixXd& kt,
                            Eigen::VectorXcd& stiffness_forms);
  // Eigenvalues with their vectors q_k in the undamped basis, as the dense decompositions find them.
  struct Eigenpairs {
    Eigen::VectorXcd lambda;
    Eigen::MatrixXcd q;
  };
  // The dense decomposition of the state matrix A (above): accurate to eps ||A|| in lambda, so for the eigenvalues
  // much larger than eps ||A|| in magnitude.
  static Eigenpairs decompose_state_matrix(const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                                           const Eigen::MatrixXd& kt, const Eigen::VectorXd& scale);
  // The same for the reversed pencil mu^2 K~ + mu C~ + M~ in mu = 1/lambda, accurate to eps ||B|| in mu: for the
  // small eigenvalues of a beam whose damping rates span more orders of magnitude than double precision resolves in
  // A (below). Returns lambda = 1/mu.
  static Eigenpairs decompose_reversed_state_matrix(const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                                                    const Eigen::MatrixXd& kt);
  // The larger eigenvalues of a graded spectrum from `dense`, the smaller from `reversed` (dense_modes.cc);
  // NumericalError when they do not add up to 2n.
  static Eigenpairs combine_graded(const Eigenpairs& dense, const Eigenpairs& reversed, const Eigen::MatrixXd& mt,
                                   const Eigen::MatrixXd& ct, const Eigen::MatrixXd& kt, const Eigen::VectorXd& scale);
  // Newton's method on T~(lambda) q = 0 from each pair (inverse iteration with the Rayleigh functional,
  // dense_modes.cc), to round-off in a few steps; a pair whose residual does not fall is left as it is for the checks
  // to judge.
  static void refine_eigenpairs(Eigenpairs& pairs, const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                                const Eigen::MatrixXd& kt);
  // The relative residual an eigenpair of a dense decomposition may have before the graded path (below) recomputes
  // the pairs, and after it before the modes are refused. A residual eta moves an eigenvalue by about eta times its
  // condition and its vector by eta over its gap; the outputs need 1e-7 (the iteration accepts 1e-8 and, within
  // blocks, 1e-7). Measured: the dense path's largest residual is 5e-13 to 2e-12 for thick-steel (N = 4-16) and up to
  // 1.2e-8 on the thin beam's first mode with cDI 10x its preset (eps ||A|| with ||A|| ~ 5e8 1/s against
  // lambda ~ 15 1/s), which the Rayleigh functional then corrects; with cDI/EI = 10-2000 s it is 2e-5 to 1 (modes of
  // the wrong sign, spurious pairs), and 1e-14 to 1e-10 after the graded path.
  static constexpr double kDenseResidual = 1e-7;
  // Takes the eigenpairs (q_, lambda_, their products; K~ q_k into stiffness_q and q_k^T K~ q_k into
  // stiffness_forms).
  void adopt(Eigenpairs pairs, const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct, const Eigen::MatrixXd& kt,
             Eigen::MatrixXcd& stiffness_q, Eigen::VectorXcd& stiffness_forms);
  // Why an eigenpair cannot be trusted, or "": its residual T~(lambda) q against the size of its terms above
  // kDenseResidual, or a pole in the right half-plane (a passive beam, M > 0, C >= 0, K > 0, cannot gain energy:
  // Re lambda = -q^H C~ q / (2 q^H M~ q) <= 0 for a complex lambda, and a real one is negative).
  std::string doubtful_eigenpair(const Eigen::MatrixXcd& stiffness_q) const;
  // NumericalError when an underdamped mode's decay rate is not resolved by the double-precision damping matrix `c`
  // (saying which mode and by how much): Re lambda
  // = -x^H C x / (2 x^H M x), and entries of C rounded to eps |C| (its assembly, or any use of it) move x^H C x by up
  // to eps |x|^T |C| |x|. Where a mode's strain in a heavily damped component is a small difference of large entries
  // (the thin beam's first mode under shear damping kAcs = 1e11 N s, 1e10 times its preset), that bound reaches the
  // decay rate itself: with kAcs = 1e9, 1e10, 1e11 and 3e11 at N = 8 it is 0.009, 0.095, 1.25 and 8.1 of it, and the
  // damping ratio the dense decomposition gave was off a 50-digit reference of the same M, C, K by 6e-5, 2e-3, 6 % and
  // 48 % (its frequency within 1e-8): the bound is 20-140x pessimistic, and kDecayResolution keeps the error below
  // about 0.5 %. A cheap bound on |x|^T |C| |x| (max row sum of |C| times |Phi|_F^2 |q|^2) passes the usual beam
  // without forming x.
  void require_resolved_decay_rates(const Eigen::MatrixXd& c) const;
  static constexpr double kDecayResolution = 0.1;
  // Everything after the eigenpairs: refinement, normalisation, clusters and the condition estimate; returns rcond.
  double finish(const Eigen::VectorXcd& stiffness_forms, const Eigen::VectorXd& scale);
  // lambda_k from the Rayleigh functional of T at x_k (modes.cc), given the forms a_k = x_k^T M x_k, b_k = x_k^T C x_k,
  // c_k = x_k^T K x_k.
  void refine_eigenvalues(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b, const Eigen::VectorXcd& c);

  Eigen::VectorXcd lambda_;
  // Everything in the undamped modal basis w = Phi q: the eigenvectors q_k (x_k = Phi q_k), n x 2n, and M~ q_k, C~ q_k
  // with M~ = Phi^T M Phi, C~ = Phi^T C Phi (so x_j^T M x_k = q_j^T M~ q_k, and so on).
  Eigen::MatrixXd shapes_;          // Phi, n x n
  Eigen::MatrixXcd q_;              // q_k
  Eigen::MatrixXcd mass_q_;         // M~ q_k
  Eigen::MatrixXcd damping_q_;      // C~ q_k
  Eigen::VectorXcd normalisation_;  // n_k = x_k^T (2 lambda_k M + C) x_k
  // Clusters of nearly equal eigenvalues (indices into lambda_) and the LU of their Gram matrices (above).
  std::vector<std::vector<Eigen::Index>> clusters_;
  // G = D S D with D^-1 = diag(inverse_scale) and S's LU, real for a cluster of real eigenpairs (its right-hand side
  // is solved by real and imaginary parts), complex otherwise.
  struct ClusterGram {
    bool real = false;
    Eigen::VectorXd inverse_scale;
    Eigen::PartialPivLU<Eigen::MatrixXd> real_lu;
    Eigen::PartialPivLU<Eigen::MatrixXcd> complex_lu;
    Eigen::VectorXcd solve(const Eigen::VectorXcd& rhs) const;
  };
  std::vector<ClusterGram> cluster_gram_;
  // eta from rhs_k = phi_k^T [C M; M 0] u: rhs_k / n_k, and the Gram solve within each cluster.
  Eigen::VectorXcd modal_solve(const Eigen::VectorXcd& rhs) const;
  // x_k^T v = q_k^T (basis^T v) for every k, with basis = Phi (or M Phi, C Phi for x_k^T M v, x_k^T C v).
  Eigen::VectorXcd project(const Eigen::MatrixXd& basis, const Eigen::VectorXd& v) const;
  // Sets clusters_ and cluster_gram_ from lambda_, q_ and their products; returns the smallest reciprocal condition of
  // a cluster's Gram matrix scaled to a unit diagonal (1 without clusters).
  double group_clusters();
  Eigen::LLT<Eigen::MatrixXd> system_mass_;       // M itself, for the feedthrough
  Eigen::MatrixXd mass_shapes_, damping_shapes_;  // M Phi and C Phi, for the initial state's coefficients
  double rcond_ = 0;
  bool iterated_ = false;
};

}  // namespace beamid::galerkin
