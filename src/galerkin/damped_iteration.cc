// The damped modes by a Jacobi iteration in the undamped modal basis (StateSpaceModes::iterate_damped_modes; the
// method and when it gives way to the dense decomposition are described in modes.h and below).
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <vector>

#include "galerkin/complex_products.h"
#include "galerkin/modes.h"

namespace beamid::galerkin {

using complex = std::complex<double>;

namespace {

// In the undamped basis T~(lambda) = lambda^2 M~ + lambda C~ + K~ is diagonal but for the damping's coupling C~_jk
// (and round-off in M~, K~). Each decoupled mode j, a root of T~_jj(lambda) = 0, starts one eigenpair (q_j = 1):
// one root with Im > 0 for an underdamped mode (its conjugate is its partner), both real roots for an overdamped
// one, 2n in all. A Jacobi step on the other components, q_i -= r_i / T~_ii(lambda) with the residual
// r = T~(lambda) q, alternates with the Rayleigh functional's root nearest lambda (q^T T~(lambda) q = 0, transpose:
// second order in q's error). For weak coupling each step multiplies q's error by about max |T~_ij| / |T~_ii|
// (banks-aluminium: 2e-4 at the first step), so a few steps reach round-off, each one product [M~; C~; K~] Q of the
// unconverged columns (real ones for the real roots) instead of a dense 2n x 2n eigen-decomposition.
//
// Real starts less than 1e-5 apart form a block instead (the thin beam's overdamped shear modes all have their slow
// root near -kAG/kAcs, 21 of them within 1e-6 at N = 16): there T~_ii(lambda) is nearly zero for every member, so
// Jacobi cannot separate them. Their components within the block come from a Rayleigh-Ritz step on the block's
// columns, the small symmetric pencil of T~ linearised at the block's mean lambda_c, (A0 + mu B) y = 0 with
// A0 = Q^T T~(lambda_c) Q and B = Q^T T~'(lambda_c) Q, which must be definite (the neglected mu^2 Q^T M~ Q is of the
// block's relative spread squared; finish() refines every lambda by its Rayleigh functional). The Jacobi steps then
// only touch the components outside the block, and the Rayleigh-Ritz step is repeated once they have converged.
// Wider chains of real roots (below) keep their Rayleigh-Ritz basis as the Jacobi step's coordinates instead.
//
// Strong coupling (thick-steel: ratios up to 26, its two relaxation times 10x apart), an indefinite block, or steps
// that do not shrink return false, and the caller decomposes densely.
class DampedIteration {
 public:
  DampedIteration(const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct, const Eigen::MatrixXd& kt)
      : n_(mt.rows()), mt_(mt), ct_(ct), kt_(kt) {}

  // The steps above; false when the caller must decompose densely.
  bool run() {
    if (!make_starts() || !group(kBlockGap, false) || !group(kWideGap, true)) return false;
    start_products();
    for (std::size_t b = 0; b < blocks_.size(); ++b)
      if (rayleigh_ritz(b) < 0) return false;
    return iterate() && accepted();
  }

  // Every start and, for a complex one, its conjugate partner (next to it, as the dense solver orders them), with
  // q^T K~ q for the Rayleigh functional; returns the number of eigenpairs written (2n when complete).
  Eigen::Index write(Eigen::VectorXcd& lambda, Eigen::MatrixXcd& q, Eigen::MatrixXcd& mass_q,
                     Eigen::MatrixXcd& damping_q, Eigen::VectorXcd& stiffness_forms) const;

 private:
  struct Start {
    Eigen::Index mode;
    complex lambda;
    bool real;
    Eigen::Index re, im;  // columns of z (im only for complex starts)
    int block;            // index into blocks, or -1
    Eigen::Index member;  // its place in its block
    double last_step;
    bool done;
  };
  // Real starts go together in blocks: "tight" ones, less than 1e-5 apart (relative), whose members the Jacobi step
  // cannot separate at all (above), and "wide" ones, chains of the remaining real starts less than 1e-2 apart, where
  // it can but only slowly: once the thin beam's two relaxation times differ by a percent, its 21 slow shear roots
  // spread over that percent and the damping couples each to its neighbours about as strongly as they are apart.
  // Within a wide block the Jacobi step works in the block's Rayleigh-Ritz basis (below), where T~ is diagonal up to
  // the linearisation's error, so its members converge as fast as isolated starts.
  static constexpr double kBlockGap = 1e-5;
  static constexpr double kWideGap = 1e-2;
  struct Block {
    std::vector<std::size_t> members;  // indices into starts
    std::vector<Eigen::Index> modes;   // their modes, in the same order
    Eigen::ArrayXd outside;            // 0 on the block's own components, 1 elsewhere
    bool wide;
    // A wide block's Rayleigh-Ritz basis Y over its modes, and the diagonals of Y^T M~ Y, Y^T C~ Y, Y^T K~ Y there.
    Eigen::MatrixXd y;
    Eigen::VectorXd m, c, k;
  };

  // The budget: a step costs one product of the 3n x n matrix [M~; C~; K~] with at most 2n columns (12 n^3 flops),
  // the dense decomposition about 25 (2n)^3 = 200 n^3, and measured at N = 16 a step is about 1/12 of it (60-90 us
  // against 1.0-1.3 ms). So the iteration may take 12 steps; it gives up as soon as the contraction it shows predicts
  // more.
  static constexpr int kMaxSteps = 12;
  // A step below 1e-12 (q_j = 1) leaves q about 1e-12 from its limit: the residues carry that relative error (the
  // outputs need 1e-7), the Rayleigh functional's lambda its square.
  static constexpr double kConverged = 1e-12;
  static constexpr double kRoundOff = 1e-9;  // below this a step that stops shrinking is round-off
  // The rotation within a block is determined only to about eps over its eigenvalues' relative spacing (1e-8 for the
  // 21 slow roots that agree to 1e-7): below 1e-6 it is round-off, and a mixing of that size is harmless, because
  // group_clusters takes a block's coefficients through its Gram matrix.
  static constexpr double kBlockRotation = 1e-6;

  // Each decoupled mode's start (above); false when one is within 1e-6 of critical damping or negatively damped.
  bool make_starts();
  // Groups the real starts not yet in a block into chains less than gap apart (relative); false when a chain holds
  // both roots of one mode (near-critical).
  bool group(double gap, bool wide);
  // z and [M~; C~; K~] z of the starts: each q = e_j, so its products are the columns of [M~; C~; K~].
  void start_products();
  // Rayleigh-Ritz on block b's columns (real): rotates their z and products and sets their lambda; returns how far the
  // rotation is from the identity, or a negative value when the linearised pencil is not definite.
  double rayleigh_ritz(std::size_t b);
  // The Jacobi steps until every start is done; false when they do not converge within the budget.
  bool iterate();
  // [M~; C~; K~] z for the columns of the starts not yet done; false when every start is done.
  bool update_products();
  // One start's Rayleigh functional root and its Jacobi correction (into dr_ or dc_); sets size to the correction's
  // largest component; false when the start changed kind (a real start turned complex or back) or degenerated.
  bool real_step(Start& st, double& size);
  bool complex_step(Start& st, double& size);
  // Judges a step of the given size (stalled: at round-off and no longer shrinking) against the budget; false when the
  // iteration should give up.
  bool within_budget(const Start& st, int step, double size, bool stalled) const;
  // A tight block whose members' outer components have converged gets its Rayleigh-Ritz step again (with them); it is
  // done when that no longer rotates it. Clears all_done unless it is done; false when its pencil is not definite.
  bool recheck_block(std::size_t b, bool& all_done);
  // Every pair's residual against the size of its terms (below).
  bool accepted() const;

  const Eigen::Index n_;
  const Eigen::MatrixXd& mt_;
  const Eigen::MatrixXd& ct_;
  const Eigen::MatrixXd& kt_;
  std::vector<Start> starts_;
  std::vector<Block> blocks_;
  Eigen::Index columns_ = 0;
  Eigen::MatrixXd stacked_;      // [M~; C~; K~]
  Eigen::ArrayXd md_, cd_, kd_;  // the diagonals of M~, C~, K~
  Eigen::MatrixXd z_;            // real and imaginary parts of every q
  Eigen::MatrixXd products_;     // [M~; C~; K~] z
  // The steps' work vectors.
  Eigen::VectorXd rr_, dr_;
  Eigen::VectorXcd qc_, mc_, cc_, kc_, rc_, dc_;
  Eigen::ArrayXd tr_;
  Eigen::ArrayXcd tc_;
  std::vector<Eigen::Index> cols_;
};

bool DampedIteration::make_starts() {
  for (Eigen::Index j = 0; j < n_; ++j) {
    const double a = mt_(j, j), b = ct_(j, j), c = kt_(j, j), disc = b * b - 4 * a * c;
    // Within 1e-6 of critical damping the two real roots (or the pair) nearly coincide and the eigenvector
    // problem is ill-conditioned: the dense decomposition with its cluster handling decides.
    if (std::abs(disc) < 1e-6 * b * b || b < 0) return false;
    if (disc < 0) {
      starts_.push_back({j, complex(-b, std::sqrt(-disc)) / (2 * a), false, columns_, columns_ + 1, -1, 0, 1.0, false});
      columns_ += 2;
    } else {
      const double q = -0.5 * (b + std::sqrt(disc));  // cancellation-free: q / a and c / q
      starts_.push_back({j, q / a, true, columns_++, -1, -1, 0, 1.0, false});
      starts_.push_back({j, c / q, true, columns_++, -1, -1, 0, 1.0, false});
    }
  }
  return true;
}

bool DampedIteration::group(double gap, bool wide) {
  std::vector<std::size_t> real;
  for (std::size_t t = 0; t < starts_.size(); ++t)
    if (starts_[t].real && starts_[t].block < 0) real.push_back(t);
  std::sort(real.begin(), real.end(),
            [&](std::size_t x, std::size_t y) { return starts_[x].lambda.real() < starts_[y].lambda.real(); });
  for (std::size_t first = 0; first < real.size();) {
    std::size_t last = first;
    while (last + 1 < real.size() &&
           std::abs(starts_[real[last + 1]].lambda.real() - starts_[real[last]].lambda.real()) <=
               gap * std::abs(starts_[real[last]].lambda.real()))
      ++last;
    if (last > first) {
      Block block{{}, {}, Eigen::ArrayXd::Ones(n_), wide, {}, {}, {}, {}};
      for (std::size_t i = first; i <= last; ++i) {
        Start& st = starts_[real[i]];
        if (block.outside(st.mode) == 0) return false;  // both roots of one mode: near-critical
        block.outside(st.mode) = 0;
        st.member = static_cast<Eigen::Index>(block.members.size());
        st.block = static_cast<int>(blocks_.size());
        block.members.push_back(real[i]);
        block.modes.push_back(st.mode);
      }
      blocks_.push_back(std::move(block));
    }
    first = last + 1;
  }
  return true;
}

void DampedIteration::start_products() {
  stacked_.resize(3 * n_, n_);
  stacked_ << mt_, ct_, kt_;
  md_ = mt_.diagonal();
  cd_ = ct_.diagonal();
  kd_ = kt_.diagonal();
  z_ = Eigen::MatrixXd::Zero(n_, columns_);
  products_ = Eigen::MatrixXd::Zero(3 * n_, columns_);
  for (const Start& st : starts_) {
    z_(st.mode, st.re) = 1;
    products_.col(st.re) = stacked_.col(st.mode);
  }
}

double DampedIteration::rayleigh_ritz(std::size_t b) {
  const Eigen::Index n = n_;
  const auto& members = blocks_[b].members;
  const auto s = static_cast<Eigen::Index>(members.size());
  Eigen::MatrixXd q(n, s), pm(n, s), pc(n, s), pk(n, s);
  double centre = 0;
  for (Eigen::Index i = 0; i < s; ++i) {
    const Start& st = starts_[members[static_cast<std::size_t>(i)]];
    q.col(i) = z_.col(st.re);
    pm.col(i) = products_.col(st.re).segment(0, n);
    pc.col(i) = products_.col(st.re).segment(n, n);
    pk.col(i) = products_.col(st.re).segment(2 * n, n);
    centre += st.lambda.real() / static_cast<double>(s);
  }
  const Eigen::MatrixXd am = q.transpose() * pm, ac = q.transpose() * pc, ak = q.transpose() * pk;
  const Eigen::MatrixXd a0 = ak + centre * ac + centre * centre * am;
  const Eigen::MatrixXd slope = ac + 2 * centre * am;
  const double sign = slope(0, 0) > 0 ? 1.0 : -1.0;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> pencil(0.5 * (a0 + a0.transpose()),
                                                                         0.5 * sign * (slope + slope.transpose()));
  if (pencil.info() != Eigen::Success) return -1;  // not definite
  Eigen::MatrixXd y = pencil.eigenvectors();
  for (Eigen::Index i = 0; i < s; ++i)
    if (y(i, i) < 0) y.col(i) = -y.col(i);
  const double change = (y - Eigen::MatrixXd::Identity(s, s)).cwiseAbs().maxCoeff();
  if (blocks_[b].wide) {
    Block& block = blocks_[b];
    block.y = q(block.modes, Eigen::all) * y;
    const auto& modes = block.modes;
    block.m = (block.y.transpose() * mt_(modes, modes) * block.y).diagonal();
    block.c = (block.y.transpose() * ct_(modes, modes) * block.y).diagonal();
    block.k = (block.y.transpose() * kt_(modes, modes) * block.y).diagonal();
  }
  const Eigen::MatrixXd qy = q * y, pmy = pm * y, pcy = pc * y, pky = pk * y;
  for (Eigen::Index i = 0; i < s; ++i) {
    Start& st = starts_[members[static_cast<std::size_t>(i)]];
    z_.col(st.re) = qy.col(i);
    products_.col(st.re) << pmy.col(i), pcy.col(i), pky.col(i);
    st.lambda = centre - sign * pencil.eigenvalues()(i);  // A0 y = nu sign B y, so mu = -sign nu
    st.last_step = 1.0;  // the rotation moved its components: its next step starts afresh
  }
  return change;
}

bool DampedIteration::update_products() {
  cols_.clear();
  for (const Start& st : starts_) {
    if (st.done) continue;
    cols_.push_back(st.re);
    if (!st.real) cols_.push_back(st.im);
  }
  if (cols_.empty()) return false;
  Eigen::MatrixXd gathered(n_, static_cast<Eigen::Index>(cols_.size()));
  for (std::size_t c = 0; c < cols_.size(); ++c) gathered.col(static_cast<Eigen::Index>(c)) = z_.col(cols_[c]);
  const Eigen::MatrixXd product = stacked_ * gathered;
  for (std::size_t c = 0; c < cols_.size(); ++c) products_.col(cols_[c]) = product.col(static_cast<Eigen::Index>(c));
  return true;
}

bool DampedIteration::real_step(Start& st, double& size) {
  const Eigen::Index n = n_;
  const auto q = z_.col(st.re);
  const auto mq = products_.col(st.re).segment(0, n), cq = products_.col(st.re).segment(n, n),
             kq = products_.col(st.re).segment(2 * n, n);
  // The Rayleigh functional's real root nearest lambda (cancellation-free, as in refine_eigenvalues).
  const double a = q.dot(mq), b = q.dot(cq), c = q.dot(kq), disc = b * b - 4 * a * c;
  if (!(disc >= 0) || a == 0) return false;  // a real start turned complex
  const double half = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (half == 0) return false;
  const double x1 = half / a, x2 = c / half, l = st.lambda.real();
  const double lambda = std::abs(x1 - l) <= std::abs(x2 - l) ? x1 : x2;
  st.lambda = lambda;
  rr_ = lambda * lambda * mq + lambda * cq + kq;
  tr_ = lambda * lambda * md_ + lambda * cd_ + kd_;
  dr_ = -(rr_.array() / tr_).matrix();
  if (st.block < 0) {
    dr_(st.mode) = 0;
  } else if (!blocks_[static_cast<std::size_t>(st.block)].wide) {
    dr_.array() *= blocks_[static_cast<std::size_t>(st.block)].outside;
  } else {
    // Within a wide block the same step in its basis, q_B = Y u: Y^T T~_BB(lambda) Y is diagonal but for the
    // linearisation's error (relative: the block's spread times lambda over the fast shear roots, 1e-6 for the
    // slow shear roots), so du_j = -(Y^T r_B)_j / (Y^T T~_BB(lambda) Y)_jj, and u's own component stays 1.
    const Block& block = blocks_[static_cast<std::size_t>(st.block)];
    Eigen::VectorXd du =
        -(block.y.transpose() * rr_(block.modes)).cwiseQuotient(lambda * lambda * block.m + lambda * block.c + block.k);
    du(st.member) = 0;
    dr_(block.modes) = block.y * du;
  }
  size = dr_.cwiseAbs().maxCoeff();
  return true;
}

bool DampedIteration::complex_step(Start& st, double& size) {
  const Eigen::Index n = n_;
  qc_.real() = z_.col(st.re);
  qc_.imag() = z_.col(st.im);
  mc_.real() = products_.col(st.re).segment(0, n);
  mc_.imag() = products_.col(st.im).segment(0, n);
  cc_.real() = products_.col(st.re).segment(n, n);
  cc_.imag() = products_.col(st.im).segment(n, n);
  kc_.real() = products_.col(st.re).segment(2 * n, n);
  kc_.imag() = products_.col(st.im).segment(2 * n, n);
  const complex a = (qc_.array() * mc_.array()).sum(), b = (qc_.array() * cc_.array()).sum(),
                c = (qc_.array() * kc_.array()).sum();
  const std::optional<complex> root = nearest_root(a, b, c, st.lambda);
  if (!root) return false;
  const complex lambda = *root;
  if (!(lambda.imag() > 1e-8 * std::abs(lambda))) return false;  // turned real: its conjugate would duplicate it
  st.lambda = lambda;
  const complex l2 = lambda * lambda;
  rc_ = l2 * mc_ + lambda * cc_ + kc_;
  tc_ = l2 * md_.cast<complex>() + lambda * cd_.cast<complex>() + kd_.cast<complex>();
  dc_ = -(rc_.array() * tc_.conjugate() / tc_.abs2()).matrix();  // r / T without a library complex division
  dc_(st.mode) = 0;
  size = dc_.cwiseAbs().maxCoeff();
  return true;
}

bool DampedIteration::within_budget(const Start& st, int step, double size, bool stalled) const {
  // The first step is the first-order perturbation of q, and about the factor by which each step shrinks the error:
  // at 0.5 and above the iteration cannot be expected to converge (the thin beam: 2.2e-4; with cDI, kAcs, EI or
  // kAG 1-10 % off, so that its two relaxation times differ, up to 7.7e-2, and then 8-10 steps with the wide
  // blocks; thick-steel: 26).
  if (!std::isfinite(size) || (step == 0 && size >= 0.5)) return false;
  if (step > 0 && !stalled && size > kConverged) {
    // Not contracting, or contracting too slowly to reach kConverged within the budget at the rate of this step
    // (error_next ~ rate * error): the dense decomposition is cheaper. (30 % off in a relaxation time, for
    // example, gives up by the second step.)
    const double rate = size / st.last_step;
    if (!(rate < 1)) return false;
    if (step + std::log(kConverged / size) / std::log(rate) > kMaxSteps) return false;
  }
  return true;
}

bool DampedIteration::recheck_block(std::size_t b, bool& all_done) {
  if (blocks_[b].wide || starts_[blocks_[b].members.front()].done) return true;
  bool converged = true;
  for (std::size_t t : blocks_[b].members) converged = converged && starts_[t].last_step < kRoundOff;
  if (!converged) {
    all_done = false;
    return true;
  }
  const double change = rayleigh_ritz(b);
  if (change < 0) return false;
  if (change <= kBlockRotation) {
    for (std::size_t t : blocks_[b].members) starts_[t].done = true;
  } else {
    all_done = false;
  }
  return true;
}

bool DampedIteration::iterate() {
  rr_.resize(n_);
  dr_.resize(n_);
  for (Eigen::VectorXcd* v : {&qc_, &mc_, &cc_, &kc_, &rc_, &dc_}) v->resize(n_);
  tr_.resize(n_);
  tc_.resize(n_);
  for (int step = 0; step < kMaxSteps; ++step) {
    // (At step 0 the products are the columns of [M~; C~; K~] themselves, or their rotations.)
    if (step > 0 && !update_products()) break;
    bool all_done = true;
    for (Start& st : starts_) {
      if (st.done) continue;
      double size = 0;
      if (!(st.real ? real_step(st, size) : complex_step(st, size))) return false;
      const bool stalled = size < kRoundOff && size > 0.5 * st.last_step;
      if (!within_budget(st, step, size, stalled)) return false;
      st.last_step = size;
      if (size <= kConverged || stalled) {
        // At round-off: keep q with its products (the step is not applied). A tight block's member waits for its
        // block.
        if (st.block < 0 || blocks_[static_cast<std::size_t>(st.block)].wide) st.done = true;
        continue;
      }
      all_done = false;
      if (st.real) {
        z_.col(st.re) += dr_;
      } else {
        z_.col(st.re) += dc_.real();
        z_.col(st.im) += dc_.imag();
      }
    }
    for (std::size_t b = 0; b < blocks_.size(); ++b)
      if (!recheck_block(b, all_done)) return false;
    if (all_done) break;
  }
  for (const Start& st : starts_)
    if (!st.done) return false;
  return true;
}

// Acceptance: every pair's residual T~(lambda) q against the size of its terms must be small, else the dense
// decomposition decides: 1e-8 for a single start, 1e-7 for a block's member, whose mixing within the block is only
// determined to about eps over its spacing (above). A converged start's components are within 1e-12 of their
// Jacobi limit, but its residual is that times T~_jj(lambda), which for the stiff shear components exceeds the
// pair's own terms: measured on the thin beam 4e-12 at the truth and 1.8e-10 to 3.3e-10 (singles), 1.0e-8 (blocks)
// with a relaxation parameter 1-10 % off. A residual of 1e-8 moves the eigenvector by that much (the outputs need
// 1e-7) and the Rayleigh functional's eigenvalue by its square.
// (Component by component in real arithmetic on the columns of z and the products: the 2n starts' residuals and
// copies below took a fifth of the iteration when each formed its complex vectors first.)
// The running maxima keep a NaN once one appears (std::max would drop it), so that it fails the test below.
bool DampedIteration::accepted() const {
  const Eigen::Index n = n_;
  const auto raise = [](double& maximum, double value) {
    if (!(value <= maximum)) maximum = value;
  };
  for (const Start& st : starts_) {
    const auto mr = products_.col(st.re).segment(0, n), cr = products_.col(st.re).segment(n, n),
               kr = products_.col(st.re).segment(2 * n, n);
    const double lr = st.lambda.real(), li = st.lambda.imag();
    const double l2r = lr * lr - li * li, l2i = 2 * lr * li, l_abs = std::abs(st.lambda);
    double residual = 0, size = 0;
    if (st.real) {
      for (Eigen::Index j = 0; j < n; ++j) {
        raise(residual, std::abs(l2r * mr(j) + lr * cr(j) + kr(j)));
        raise(size, l2r * std::abs(mr(j)) + l_abs * std::abs(cr(j)) + std::abs(kr(j)));
      }
    } else {
      const auto mi = products_.col(st.im).segment(0, n), ci = products_.col(st.im).segment(n, n),
                 ki = products_.col(st.im).segment(2 * n, n);
      const double l2_abs = l_abs * l_abs;
      // |x + iy| without hypot's care for overflow (the products here are far from it) and its cost.
      const auto modulus = [](double x, double y) { return std::sqrt(x * x + y * y); };
      for (Eigen::Index j = 0; j < n; ++j) {
        const double re = l2r * mr(j) - l2i * mi(j) + lr * cr(j) - li * ci(j) + kr(j);
        const double im = l2r * mi(j) + l2i * mr(j) + lr * ci(j) + li * cr(j) + ki(j);
        raise(residual, modulus(re, im));
        raise(size, l2_abs * modulus(mr(j), mi(j)) + l_abs * modulus(cr(j), ci(j)) + modulus(kr(j), ki(j)));
      }
    }
    if (!(residual <= (st.block < 0 ? 1e-8 : 1e-7) * size)) return false;
  }
  return true;
}

Eigen::Index DampedIteration::write(Eigen::VectorXcd& lambda, Eigen::MatrixXcd& q, Eigen::MatrixXcd& mass_q,
                                    Eigen::MatrixXcd& damping_q, Eigen::VectorXcd& stiffness_forms) const {
  const Eigen::Index n = n_;
  const Eigen::Index m = 2 * n;
  lambda.resize(m);
  q.resize(n, m);
  mass_q.resize(n, m);
  damping_q.resize(n, m);
  stiffness_forms.resize(m);
  Eigen::Index k = 0;
  for (const Start& st : starts_) {
    const auto zr = z_.col(st.re);
    const auto kr = products_.col(st.re).segment(2 * n, n);
    if (st.real) {
      lambda(k) = st.lambda.real();
      q.col(k).real() = zr;
      mass_q.col(k).real() = products_.col(st.re).segment(0, n);
      damping_q.col(k).real() = products_.col(st.re).segment(n, n);
      q.col(k).imag().setZero();
      mass_q.col(k).imag().setZero();
      damping_q.col(k).imag().setZero();
      stiffness_forms(k) = zr.dot(kr);
      ++k;
      continue;
    }
    const auto zi = z_.col(st.im);
    const auto ki = products_.col(st.im).segment(2 * n, n);
    const complex stiffness(zr.dot(kr) - zi.dot(ki), zr.dot(ki) + zi.dot(kr));
    for (int copy = 0; copy < 2; ++copy, ++k) {
      const double sign = copy == 0 ? 1.0 : -1.0;
      lambda(k) = copy == 0 ? st.lambda : std::conj(st.lambda);
      q.col(k).real() = zr;
      q.col(k).imag() = sign * zi;
      mass_q.col(k).real() = products_.col(st.re).segment(0, n);
      mass_q.col(k).imag() = sign * products_.col(st.im).segment(0, n);
      damping_q.col(k).real() = products_.col(st.re).segment(n, n);
      damping_q.col(k).imag() = sign * products_.col(st.im).segment(n, n);
      stiffness_forms(k) = copy == 0 ? stiffness : std::conj(stiffness);
    }
  }
  return k;
}

}  // namespace

bool StateSpaceModes::iterate_damped_modes(const Eigen::MatrixXd& mt, const Eigen::MatrixXd& ct,
                                           const Eigen::MatrixXd& kt, Eigen::VectorXcd& stiffness_forms) {
  DampedIteration iteration(mt, ct, kt);
  if (!iteration.run()) return false;
  return iteration.write(lambda_, q_, mass_q_, damping_q_, stiffness_forms) == 2 * mt.rows();
}

}  // namespace beamid::galerkin
