#include "signal/matrix_pencil.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <numbers>

#include "core/errors.h"
#include "core/limits.h"
#include "core/scratch.h"
#include "signal/noise_spectrum.h"
#include "signal/spikes.h"

namespace beamid::signal {

namespace {

// The amplitudes c_k of all M exponentials z_k by least squares on the whole record y (a complex Vandermonde system),
// and the residual's standard deviation, |y - Re(V c)| / sqrt(n - 2 M) (each exponential has a complex pole and a
// complex amplitude; conjugate pairs make them M real parameters of each kind).
Eigen::VectorXcd amplitudes(const Eigen::VectorXcd& z, const std::vector<double>& y, int order, double& residual_sd,
                            PencilDiagnostics& d) {
  const int n = static_cast<int>(y.size());
  // A growing pole (|z| > 1, noise or an unmodelled transient at a high order) is anchored at the record's end,
  // column z^(i - n + 1), so that no entry exceeds 1 in modulus: anchored at the start, 1.5^307 overflowed to inf and
  // the QR returned zeros for every amplitude. Decaying poles keep the start.
  Eigen::MatrixXcd vandermonde(n, order);
  for (int k = 0; k < order; ++k) {
    const bool growing = std::abs(z(k)) > 1;
    const std::complex<double> ratio = growing ? 1.0 / z(k) : z(k);
    std::complex<double> power = 1.0;
    for (int j = 0; j < n; ++j) {
      vandermonde(growing ? n - 1 - j : j, k) = power;
      power *= ratio;
    }
  }
  const Eigen::Map<const Eigen::VectorXd> record(y.data(), n);
  const Eigen::VectorXcd c = vandermonde.colPivHouseholderQr().solve(record.cast<std::complex<double>>());
  const Eigen::VectorXd residual = record - (vandermonde * c).real();
  residual_sd = residual.norm() / std::sqrt(std::max(1, n - 2 * order));
  const double mean = residual.mean(), spread = (residual.array() - mean).matrix().squaredNorm();
  const double rms = std::sqrt((record.array() - record.mean()).square().mean());
  d.residual_fraction = rms > 0 ? std::sqrt(spread / n) / rms : 0.0;
  d.residual_lag1 =
      spread > 0 ? ((residual.head(n - 1).array() - mean) * (residual.tail(n - 1).array() - mean)).sum() / spread : 0.0;
  if (n >= 64 && spread > 0)
    d.residual_colour = fit_autoregressive(std::vector<double>(residual.data(), residual.data() + n), 16);
  if (!c.allFinite())
    throw NumericalError("matrix pencil: the amplitude least squares did not give finite amplitudes (model order " +
                         std::to_string(order) + "): try a lower --order");
  return c;
}

// The record's Hankel matrix at pencil parameter L: its right singular vectors, (L + 1) square, most dominant first,
// and its singular values, descending.
struct HankelBasis {
  Eigen::MatrixXd v;
  Eigen::VectorXd singular;
};
HankelBasis hankel_basis(const std::vector<double>& y, int pencil) {
  const int n = static_cast<int>(y.size());
  // Hankel matrix Y(i, j) = y_{i+j}, (n - L) x (L + 1), and its right singular vectors. Its storage (36 MB at
  // Nbar = 8192 and L = 599, 60 MB for the steel record's 13,213 samples) is the thread's scratch buffer, kept between
  // calls up to kKeptHankelBytes (so that one long record does not hold hundreds of MB for the process's life).
  constexpr std::size_t kKeptHankelBytes = std::size_t{128} << 20;
  thread_local core::ScratchBuffer scratch;
  const auto rows = static_cast<Eigen::Index>(n - pencil), cols = static_cast<Eigen::Index>(pencil + 1);
  Eigen::Map<Eigen::MatrixXd> hankel(scratch.reserve(static_cast<std::size_t>(rows * cols)), rows, cols);
  struct Release {  // freed on the way out when above the limit, however the call ends
    core::ScratchBuffer& s;
    ~Release() {
      if (s.capacity() * sizeof(double) > kKeptHankelBytes) s.release();
    }
  } release{scratch};
  for (int i = 0; i < n - pencil; ++i)
    for (int j = 0; j <= pencil; ++j) hankel(i, j) = y[static_cast<std::size_t>(i + j)];
  // Its right singular vectors are those of R in Y = Q R. Y is tall, n - L >= 2 L >= L + 1 rows for its L + 1 columns
  // (L <= n / 3, L >= 2), about six rows a column at the default L, and a Householder QR (blocked, in matrix-matrix
  // products) plus the SVD of the (L + 1)-square triangle cost 2 m c^2 + ~3 c^3 flops (m x c = Y's size) against
  // ~4 m c^2 for bidiagonalising Y itself, whose matrix-vector products dominated `beamid fit` and a study's
  // modal-cost cases (measured at Nbar = 4096, L = 599: 0.57-0.65 s against 0.92-1.1 s, on a loaded machine; the
  // subspaces agree to 1.4e-15).
  const Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(hankel);  // in place: Y is not needed again
  const Eigen::MatrixXd triangle = qr.matrixQR().topRows(pencil + 1).triangularView<Eigen::Upper>();
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(triangle, Eigen::ComputeThinV);
  if (!(svd.singularValues()(0) > 0)) throw InputError("the record is zero: there is no mode to identify");
  return {svd.matrixV(), svd.singularValues()};
}

// hankel_basis, computed once per record and L within the process and shared by every later call: one fit's
// modal cost and its modes comparison run the pencil on the same free decay, and a real study's costs and windows run
// it on the same segments (the pencil's QR and SVD, ~Nbar L^2, were most of a measured record's modal fit: 6 pencils
// for 132 model evaluations on the steel record). A record is its exact bytes, so a hit returns what the
// computation would: results do not depend on the order in which a study's threads fill the cache. At most
// kCachedRecords records, each of at most core::kMaxPencilSamples samples (2 MB, and 2.9 MB of vectors at L = 599).
constexpr std::size_t kCachedRecords = 8;
class HankelBasisCache {
 public:
  std::shared_ptr<const HankelBasis> get(const std::vector<double>& y, int pencil) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (const Entry& e : entries_)
        if (e.pencil == pencil && e.y.size() == y.size() &&
            std::memcmp(e.y.data(), y.data(), y.size() * sizeof(double)) == 0)
          return e.v;
    }
    auto v = std::make_shared<const HankelBasis>(hankel_basis(y, pencil));  // outside the lock
    const std::lock_guard<std::mutex> lock(mutex_);
    if (entries_.size() == kCachedRecords) entries_.pop_front();
    entries_.push_back({y, pencil, v});
    return v;
  }

 private:
  struct Entry {
    std::vector<double> y;
    int pencil;
    std::shared_ptr<const HankelBasis> v;
  };
  std::mutex mutex_;
  std::deque<Entry> entries_;
};

// The process's one cache, shared by the poles and the model order (both read a record's basis).
HankelBasisCache& basis_cache() {
  static HankelBasisCache cache;
  return cache;
}

// The M poles z_k of the record y: the eigenvalues of pinv(V1) V2 from the Hankel matrix's M dominant right singular
// vectors (the file's head), with pencil parameter L.
Eigen::VectorXcd pencil_poles(const std::vector<double>& y, int pencil, int order) {
  const Eigen::MatrixXd v = basis_cache().get(y, pencil)->v.leftCols(order);
  const Eigen::MatrixXd v1 = v.topRows(pencil), v2 = v.bottomRows(pencil);
  // pinv(V1) V2 by least squares (V1 has orthonormal-ish columns, full column rank M).
  const Eigen::MatrixXd pencil_matrix = v1.colPivHouseholderQr().solve(v2);
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(pencil_matrix, false);
  // The record, not the method, is at fault: one alternating at the Nyquist frequency (x = (-1)^i) made this an
  // internal error, exit 3 with no file named (the eleventh pass's DG_alt). Said as the record's, which the callers
  // name.
  if (eig.info() != Eigen::Success)
    throw InputError(
        "the matrix pencil finds no poles in it (its eigenvalues did not converge): a record with no "
        "decaying oscillation below the Nyquist frequency, such as one alternating sample by sample");
  return eig.eigenvalues();
}

void by_frequency(std::vector<IdentifiedMode>& modes) {
  std::sort(modes.begin(), modes.end(), [](const auto& a, const auto& b) { return a.frequency_hz < b.frequency_hz; });
}

// The model order against the pencil parameter L and the modes asked for: InputError naming what to change.
void check_order(const PencilOptions& o, int n, int order, int pencil) {
  if (order > pencil || pencil < 2)
    throw InputError(
        "order M = " + std::to_string(order) + ": must be at most the pencil parameter L = " + std::to_string(pencil) +
        " (the smaller of Nbar/3 = " + std::to_string(n / 3) + " for " + std::to_string(n) + " samples and " +
        std::to_string(o.max_columns - 1) + ", the cap that bounds the SVD's cost): a lower order" +
        (n / 3 < o.max_columns - 1 ? " or a longer record" : ""));
  if (order < 2 * o.modes) {
    // Not given, the order is capped by the record's length: say that, not the flag nobody gave (the second
    // adversarial pass of 2026-11-28, P3).
    if (o.order == 0)
      throw InputError("the record has " + std::to_string(n) + " samples: the matrix pencil needs at least " +
                       std::to_string(6 * o.modes) + " for " + std::to_string(o.modes) + " modes (an order 2 K = " +
                       std::to_string(2 * o.modes) + ", at most Nbar/3): a longer record or fewer modes");
    throw InputError("order M = " + std::to_string(order) + ": must be at least 2 K = " + std::to_string(2 * o.modes) +
                     " (each real mode is a conjugate pair of exponentials)");
  }
}

}  // namespace

std::vector<IdentifiedMode> matrix_pencil(const std::vector<double>& y, double dt_s, const PencilOptions& o,
                                          PencilDiagnostics* diagnostics) {
  const int n = static_cast<int>(y.size());
  if (o.modes < 1) throw InputError("modes = " + std::to_string(o.modes) + ": must be >= 1");
  if (!(dt_s > 0) || !std::isfinite(dt_s)) throw InputError("dt = " + format_value(dt_s) + ": must be > 0");
  if (o.max_columns < 4) throw InputError("max_columns = " + std::to_string(o.max_columns) + ": must be >= 4");
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(y[static_cast<std::size_t>(i)]))
      throw InputError("sample " + std::to_string(i) + " = " + format_value(y[static_cast<std::size_t>(i)]) +
                       ": must be finite");
  if (n > core::kMaxPencilSamples)
    throw InputError("the record has " + std::to_string(n) + " samples: the matrix pencil takes at most " +
                     std::to_string(core::kMaxPencilSamples) +
                     " (its Hankel matrix and QR grow as Nbar L^2); cut the record (--start, --duration) or lower its "
                     "rate (--resample-rate)");
  const int pencil = pencil_columns(o, n);  // L
  const int order = model_order(o, y);
  check_order(o, n, order, pencil);

  const Eigen::VectorXcd z = pencil_poles(y, pencil, order);

  PencilDiagnostics unused;
  PencilDiagnostics& d = diagnostics ? *diagnostics : unused;
  d = {};
  double residual_sd = 0;
  const Eigen::VectorXcd c = amplitudes(z, y, order, residual_sd, d);
  // A pole is a mode of the sampled record only if its natural frequency |lambda| / 2 pi is below the Nyquist
  // frequency: a heavily damped pole beyond it (at a high order, fitting the pulse) is not resolvable from samples
  // at this rate, and was listed as the strongest "mode" at 505-989 Hz of a 1 kHz record.
  const double nyquist_hz = 0.5 / dt_s;

  double largest = 0;
  for (double v : y) largest = std::max(largest, std::abs(v));

  auto energy = [n, dt_s](const IdentifiedMode& m) { return mode_energy(m, dt_s, n); };
  const double noise_energy = 2 * residual_sd * residual_sd * std::log(n / kNoiseFalseAlarm);
  std::vector<IdentifiedMode> modes;
  for (int k = 0; k < order; ++k) {
    // One of each pair. A pole on the unit circle is a steady line (a pure sine of amplitude 1 was dropped, and the
    // note counted only the rounding poles: the seventh pass's F09), kept below with the steady ones.
    if (!(z(k).imag() > 0) || !std::isfinite(std::abs(z(k)))) continue;
    IdentifiedMode m;
    m.lambda = std::log(z(k)) / dt_s;
    const double magnitude = std::abs(m.lambda);
    m.frequency_hz = magnitude / (2 * std::numbers::pi);
    if (m.frequency_hz < o.min_frequency_hz || m.frequency_hz > o.max_frequency_hz || m.frequency_hz >= nyquist_hz)
      continue;
    m.damping_ratio = -m.lambda.real() / magnitude;
    // The amplitude at the pole's anchor: the start for a decaying pole, the end for a growing one (its largest).
    m.amplitude = 2 * std::abs(c(k));
    m.phase_rad = std::arg(c(k));
    // A pole that grows by less than kSteadyGrowth over the record neither decays nor grows measurably: a mains
    // line or a driven tone, or a mode too lightly damped for the record's length, whose noise put |z| just above 1.
    // It is listed with its damping ratio (<= 0), not called a growing oscillation (the sixth pass's S225).
    const bool kept = std::abs(z(k)) < 1 || std::exp(m.lambda.real() * n * dt_s) <= kSteadyGrowth;
    if (kept)
      m.frequency_sd_hz =
          damped_mode_frequency_sd(m.amplitude, -m.lambda.real(), dt_s, n, residual_sd) / (2 * std::numbers::pi);
    if (m.amplitude <= kNegligibleAmplitude * largest) {
      d.negligible += kept;
      continue;
    }
    // Under one cycle in the record a pole is no oscillation the record resolves: an offset and a linear drift are a
    // double pole at z = 1, which rounding and noise split into a pair near 0 Hz (a drift 0.5 + 0.3 t was modal-id's
    // mode 1 at 0.004 Hz, zeta -0.08, in place of the 85.6 Hz mode, and the modal cost paired it with the model's
    // mode 1: the seventeenth pass's P6). Left out as the record's trend, whatever its damping.
    if (m.frequency_hz * n * dt_s < kTrendCycles) {
      d.trend_hz.push_back(m.frequency_hz);
      continue;
    }
    if (kept && energy(m) / 2 <= noise_energy) {
      ++d.below_noise;
      continue;
    }
    if (kept)
      modes.push_back(m);
    else if (m.frequency_hz * n * dt_s >= 2)  // under two cycles in the record a growing pole is a trend (an offset
      d.growing.push_back(m);                 // and a drift were a "growing oscillation at 6.85e-08 Hz": R183)
  }
  // The K strongest, then by frequency. The strength is the mode's energy over the record, so that a heavily damped
  // spurious pole with a large initial amplitude does not outrank a lasting mode.
  std::sort(modes.begin(), modes.end(), [&](const auto& a, const auto& b) { return energy(a) > energy(b); });
  if (static_cast<int>(modes.size()) > o.modes) {
    d.weaker.assign(modes.begin() + o.modes, modes.end());
    modes.resize(static_cast<std::size_t>(o.modes));
  }
  by_frequency(d.weaker);
  by_frequency(modes);
  return modes;
}

int pencil_columns(const PencilOptions& o, int samples) { return std::min(samples / 3, o.max_columns - 1); }

int significant_order(const std::vector<double>& y, const PencilOptions& o) {
  const int n = static_cast<int>(y.size()), pencil = pencil_columns(o, n);
  if (pencil < 2) return 0;
  const Eigen::VectorXd& s = basis_cache().get(y, pencil)->singular;
  // The last gap of kSingularGap between neighbours, among values above rounding's (kNegligibleAmplitude of the
  // largest): a record's exponentials stand above its noise by such a gap when it is clean. A measured record's values
  // fall gradually (the steel record's by at most 3.4 between neighbours over its first 64: coloured noise, a clamp's
  // nonlinearity), and a count above a noise floor there took M to 64 and split its modes into close pairs.
  int count = 0;
  const int last = std::min(static_cast<int>(s.size()) - 1, kMaxRecordOrder);
  for (int i = 1; i <= last; ++i)
    if (s(i - 1) > kNegligibleAmplitude * s(0) && s(i - 1) > kSingularGap * s(i)) count = i;
  return count;
}

int model_order(const PencilOptions& o, const std::vector<double>& y) {
  const int columns = pencil_columns(o, static_cast<int>(y.size()));
  if (o.order > 0) return o.order;
  const int floor = 2 * o.modes + 8;
  return std::min(columns, std::max(floor, std::min(significant_order(y, o), kMaxRecordOrder)));
}

bool is_steady(const IdentifiedMode& m) {
  const double sd = std::isfinite(m.frequency_sd_hz) ? 2 * std::numbers::pi * m.frequency_sd_hz : 0.0;
  return -m.lambda.real() <= std::max(3 * sd, kSteadyRounding * std::abs(m.lambda));
}

double mode_energy(const IdentifiedMode& m, double dt_s, int n) {
  const double r2 = std::exp(2 * m.lambda.real() * dt_s);
  return m.amplitude * m.amplitude * (r2 < 1 ? (1 - std::pow(r2, n)) / (1 - r2) : n);
}

std::vector<IdentifiedMode> lightly_damped_modes(const std::vector<double>& decay, double dt_s, PencilOptions options,
                                                 const std::vector<double>& wanted_hz, double window,
                                                 int* heavily_damped, PencilDiagnostics* diagnostics) {
  if (heavily_damped) *heavily_damped = 0;
  if (!wanted_hz.empty()) return modes_near(decay, dt_s, options, wanted_hz, window, diagnostics, kHeavilyDampedRatio);
  const int k = options.modes;
  options.modes = k + 4;
  PencilDiagnostics unused;
  PencilDiagnostics& d = diagnostics ? *diagnostics : unused;
  std::vector<IdentifiedMode> modes = matrix_pencil(decay, dt_s, options, &d);
  const auto light = [](const IdentifiedMode& m) { return m.damping_ratio <= kHeavilyDampedRatio; };
  const auto heavy = std::erase_if(modes, [&](const IdentifiedMode& m) { return !light(m); });
  std::erase_if(d.weaker, [&](const IdentifiedMode& m) { return !light(m); });
  if (heavily_damped) *heavily_damped = static_cast<int>(heavy);
  const int n = static_cast<int>(decay.size());
  std::sort(modes.begin(), modes.end(),
            [&](const auto& a, const auto& b) { return mode_energy(a, dt_s, n) > mode_energy(b, dt_s, n); });
  if (static_cast<int>(modes.size()) > k) {
    d.weaker.insert(d.weaker.end(), modes.begin() + k, modes.end());
    modes.resize(static_cast<std::size_t>(k));
  }
  by_frequency(d.weaker);
  by_frequency(modes);
  return modes;
}

std::vector<IdentifiedMode> modes_near(const std::vector<double>& decay, double dt_s, PencilOptions options,
                                       const std::vector<double>& wanted_hz, double window,
                                       PencilDiagnostics* diagnostics, double max_damping_ratio) {
  if (wanted_hz.empty()) throw InputError("modes_near: no frequency chosen");
  const auto [low, high] = std::minmax_element(wanted_hz.begin(), wanted_hz.end());
  options.min_frequency_hz = std::max(options.min_frequency_hz, *low * (1 - window));
  options.max_frequency_hz = std::min(options.max_frequency_hz, *high * (1 + window));
  options.modes = 3 * static_cast<int>(wanted_hz.size()) + 4;
  PencilDiagnostics unused;
  PencilDiagnostics& d = diagnostics ? *diagnostics : unused;
  const std::vector<IdentifiedMode> found = matrix_pencil(decay, dt_s, options, &d);
  std::vector<IdentifiedMode> chosen;
  std::vector<bool> taken(found.size(), false);
  for (double f : wanted_hz) {
    std::size_t best = found.size();
    const IdentifiedMode* heavy = nullptr;  // the strongest candidate left out as heavily damped, for the message
    for (std::size_t i = 0; i < found.size(); ++i) {
      if (std::abs(found[i].frequency_hz / f - 1) > window) continue;
      if (found[i].damping_ratio > max_damping_ratio) {
        if (!heavy || found[i].amplitude > heavy->amplitude) heavy = &found[i];
        continue;
      }
      if (best == found.size() || found[i].amplitude > found[best].amplitude) best = i;
    }
    if (best == found.size())
      throw InputError("no identified mode within " + format_rounded(100 * window, 3) + " % of " + format_value(f) +
                       " Hz" +
                       (f * (1 - window) >= 0.5 / dt_s
                            ? " (above the Nyquist frequency " + format_rounded(0.5 / dt_s) + " Hz of this record)"
                            : "") +
                       (heavy ? " (the pole at " + format_rounded(heavy->frequency_hz) + " Hz has damping ratio " +
                                    format_rounded(heavy->damping_ratio, 3) +
                                    ": the excitation or noise rather than a mode; cut the record after the "
                                    "excitation, --start)"
                              : ""));
    chosen.push_back(found[best]);
    taken[best] = true;
  }
  for (std::size_t i = 0; i < found.size(); ++i)
    if (!taken[i]) d.weaker.push_back(found[i]);
  by_frequency(d.weaker);
  return chosen;
}

}  // namespace beamid::signal
