#include "signal/noise_spectrum.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <map>

#include "core/errors.h"

namespace beamid::signal {

std::optional<std::string> validation_error(const LocalPolynomialOptions& o) {
  if (o.degree < 0 || o.degree > 8)
    return "local polynomial degree = " + std::to_string(o.degree) + ": must be in 0..8";
  if (o.half_width < 1 || o.half_width > 1000)
    return "local polynomial half width = " + std::to_string(o.half_width) + ": must be in 1..1000 bins";
  if (2 * o.half_width + 1 <= o.degree + 1)
    return "local polynomial half width = " + std::to_string(o.half_width) + ": 2n + 1 bins must exceed the degree " +
           std::to_string(o.degree) + " + 1 (no degree of freedom is left for the noise)";
  if (o.smoothing_half_width < 0 || o.smoothing_half_width > 100000)
    return "smoothing half width = " + std::to_string(o.smoothing_half_width) + ": must be in 0..100000 bins";
  return std::nullopt;
}

namespace {

// I - Q Q^T for the polynomial basis ((r / n)^d, d = 0..R) at the offsets r: the residual projector of a local fit
// (the basis is real, so it acts on the real and imaginary parts alike).
Eigen::MatrixXd residual_projector(const std::vector<int>& offsets, int degree, int half_width) {
  const auto rows = static_cast<Eigen::Index>(offsets.size());
  Eigen::MatrixXd basis(rows, degree + 1);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (int d = 0; d <= degree; ++d)
      basis(i, d) = std::pow(static_cast<double>(offsets[static_cast<std::size_t>(i)]) / half_width, d);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(rows, degree + 1);
  return Eigen::MatrixXd::Identity(rows, rows) - q * q.transpose();
}

// out[k] = the mean of local[lo..hi], [lo, hi] = [k - m, k + m] clipped to first..last, for k in first..last.
void smooth_over_bins(const std::vector<double>& local, int first, int last, int m, std::vector<double>& out) {
  std::vector<double> prefix(local.size() + 1, 0.0);  // a running sum
  for (std::size_t k = 0; k < local.size(); ++k) prefix[k + 1] = prefix[k] + local[k];
  for (int k = first; k <= last; ++k) {
    const int lo = std::max(first, k - m), hi = std::min(last, k + m);
    out[static_cast<std::size_t>(k)] =
        (prefix[static_cast<std::size_t>(hi + 1)] - prefix[static_cast<std::size_t>(lo)]) / (hi - lo + 1);
  }
}

}  // namespace

BinVariance local_polynomial_variance(const Spectrum& record, const LocalPolynomialOptions& options) {
  if (auto error = validation_error(options)) throw InputError(*error);
  const int n = options.half_width;
  const int width = 2 * n + 1;
  // Complex bins only: 1..Nbar/2 - 1 for an even record (Nbar/2 is real), 1..(Nbar - 1)/2 for an odd one.
  const int first = 1;
  const int last = record.samples % 2 == 0 ? record.samples / 2 - 1 : record.samples / 2;
  if (last - first + 1 < width)
    throw InputError("local polynomial noise estimate: the record has " + std::to_string(std::max(0, last)) +
                     " complex DFT bins, fewer than the " + std::to_string(width) + " one local fit of half width " +
                     std::to_string(n) + " needs");
  BinVariance out;
  out.dof = width - (options.degree + 1);
  std::vector<double> local(static_cast<std::size_t>(last + 1), 0.0);
  std::map<int, Eigen::MatrixXd> projectors;  // by the window's start relative to k (shifted only at the edges)
  Eigen::VectorXd re(width), im(width);
  for (int k = first; k <= last; ++k) {
    const int start = std::clamp(k - n, first, last - 2 * n);
    auto it = projectors.find(start - k);
    if (it == projectors.end()) {
      std::vector<int> offsets(static_cast<std::size_t>(width));
      for (int i = 0; i < width; ++i) offsets[static_cast<std::size_t>(i)] = start - k + i;
      it = projectors.emplace(start - k, residual_projector(offsets, options.degree, n)).first;
    }
    for (int i = 0; i < width; ++i) {
      const std::complex<double> z = record.half[static_cast<std::size_t>(start + i)];
      re(i) = z.real();
      im(i) = z.imag();
    }
    // |e|^2 = y^T (I - Q Q^T) y for the real and the imaginary parts (the projector is idempotent and symmetric).
    local[static_cast<std::size_t>(k)] = (re.dot(it->second * re) + im.dot(it->second * im)) / out.dof;
  }
  out.variance.assign(record.half.size(), 0.0);
  smooth_over_bins(local, first, last, options.smoothing_half_width, out.variance);
  out.variance[0] = out.variance[static_cast<std::size_t>(first)];
  for (std::size_t k = static_cast<std::size_t>(last) + 1; k < out.variance.size(); ++k)
    out.variance[k] = out.variance[static_cast<std::size_t>(last)];
  return out;
}

BinVariance repeated_record_variance(const std::vector<Spectrum>& records, int smoothing_half_width) {
  if (records.size() < 2)
    throw InputError("repeated-record noise estimate: " + std::to_string(records.size()) +
                     " record(s): at least 2 repeats of one experiment are needed");
  if (smoothing_half_width < 0)
    throw InputError("smoothing half width = " + std::to_string(smoothing_half_width) + ": must be >= 0");
  const Spectrum& one = records.front();
  for (std::size_t m = 1; m < records.size(); ++m)
    if (records[m].samples != one.samples || records[m].dt_s != one.dt_s)
      throw InputError("repeated-record noise estimate: record " + std::to_string(m + 1) + " has " +
                       std::to_string(records[m].samples) + " samples at dt " + format_value(records[m].dt_s) +
                       " s, record 1 " + std::to_string(one.samples) + " at " + format_value(one.dt_s) +
                       " s: repeats must share the length and the time step");
  const auto count = static_cast<double>(records.size());
  std::vector<double> local(one.half.size(), 0.0);
  for (std::size_t k = 0; k < local.size(); ++k) {
    std::complex<double> mean = 0;
    for (const Spectrum& r : records) mean += r.half[k] / count;
    for (const Spectrum& r : records) local[k] += std::norm(r.half[k] - mean) / (count - 1);
  }
  BinVariance out;
  out.dof = static_cast<int>(records.size()) - 1;
  out.variance.assign(local.size(), 0.0);
  smooth_over_bins(local, 0, static_cast<int>(local.size()) - 1, smoothing_half_width, out.variance);
  return out;
}

double coloured_excess_threshold(int order, int samples) {
  if (samples <= 0) return std::numeric_limits<double>::infinity();
  return std::max(kColouredExcess, std::exp(3 * std::sqrt(4.0 * order / samples)));
}

std::vector<double> power_excess(const NoiseModel& model, int samples) {
  std::vector<double> g = model_bin_variance(model, samples);
  for (double& v : g) v *= samples;
  return g;
}

ColourExcess colour_excess(const NoiseModel& model, int samples) {
  ColourExcess out;
  if (model.kind == "white" || samples < 4) return out;
  out.by_bin = power_excess(model, samples);
  out.peak_bin =
      static_cast<std::size_t>(std::max_element(out.by_bin.begin() + 1, out.by_bin.end()) - out.by_bin.begin());
  const int order = model.kind == "ar" ? static_cast<int>(model.ar.size()) : 1;
  out.coloured = out.by_bin[out.peak_bin] > coloured_excess_threshold(order, samples);
  return out;
}

NoiseModel fit_autoregressive(const std::vector<double>& e, int max_order) {
  return fit_autoregressive(std::vector<std::vector<double>>{e}, max_order);
}

NoiseModel fit_autoregressive(const std::vector<std::vector<double>>& records, int max_order) {
  if (records.empty()) throw InputError("autoregressive noise model: no record");
  std::size_t shortest = records.front().size(), total = 0;
  for (const auto& e : records) {
    shortest = std::min(shortest, e.size());
    total += e.size();
  }
  if (shortest < 8)
    throw InputError("autoregressive noise model: " + std::to_string(shortest) + " samples: at least 8");
  if (max_order < 0 || max_order > 32)
    throw InputError("autoregressive noise model: order " + std::to_string(max_order) + ": must be in 0..32");
  const auto n = static_cast<double>(total);
  const auto p_max = static_cast<std::size_t>(std::min<long>(max_order, static_cast<long>(shortest) / 4));
  // One mean over every sample (0 for deviations from the records' mean), so that a short record's own mean, which a
  // correlated noise moves far from 0, does not take its low frequencies away.
  double mean = 0;
  for (const auto& e : records)
    for (const double v : e) mean += v / n;
  std::vector<double> gamma(p_max + 1, 0.0);  // biased: the lag products within each record, over the total count
  for (const auto& e : records)
    for (std::size_t l = 0; l <= p_max; ++l)
      for (std::size_t i = 0; i + l < e.size(); ++i) gamma[l] += (e[i] - mean) * (e[i + l] - mean);
  for (double& g : gamma) g /= n;
  NoiseModel best;  // white
  if (!(gamma[0] > 0)) return best;
  // Levinson-Durbin: phi holds the order-p coefficients, v the order-p prediction-error variance.
  std::vector<double> phi;
  double v = gamma[0];
  double best_aic = n * std::log(v);
  for (std::size_t p = 1; p <= p_max; ++p) {
    double acc = gamma[p];
    for (std::size_t j = 0; j < phi.size(); ++j) acc -= phi[j] * gamma[p - 1 - j];
    const double k = acc / v;
    std::vector<double> next(p);
    for (std::size_t j = 0; j + 1 < p; ++j) next[j] = phi[j] - k * phi[p - 2 - j];
    next[p - 1] = k;
    phi = std::move(next);
    v *= 1 - k * k;
    if (!(v > 0)) break;
    const double aic = n * std::log(v) + 2.0 * static_cast<double>(p);
    if (aic < best_aic) {
      best_aic = aic;
      best.kind = "ar";
      best.ar = phi;
    }
  }
  return best;
}

}  // namespace beamid::signal
