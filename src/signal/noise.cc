#include "signal/noise.h"

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <numbers>
#include <random>
#include <sstream>

#include "core/errors.h"
#include "signal/spectrum.h"

namespace beamid::signal {

std::vector<double> gaussian_deviates(std::uint64_t seed, std::size_t count) {
  std::mt19937_64 engine(core::mix64(seed));
  // ((x >> 11) + 0.5) 2^-53 lies strictly inside (0, 1), so ln u1 is finite.
  const auto uniform = [&engine] { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; };
  std::vector<double> g;
  g.reserve(count + 1);
  while (g.size() < count) {
    const double u1 = uniform(), u2 = uniform();
    const double r = std::sqrt(-2 * std::log(u1));
    g.push_back(r * std::cos(2 * std::numbers::pi * u2));
    g.push_back(r * std::sin(2 * std::numbers::pi * u2));
  }
  g.resize(count);
  return g;
}

double rms(const std::vector<double>& signal) {
  if (signal.empty()) return 0;
  double sum = 0;
  for (double v : signal) sum += v * v;
  return std::sqrt(sum / static_cast<double>(signal.size()));
}

std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed) {
  return add_noise(clean, level, seed, NoiseModel{});
}

namespace {

constexpr std::size_t kMaxArOrder = 32;
constexpr double kMaxAlpha = 4;

// The AR filter's impulse response h (h_0 = 1, h_i = sum_j a_j h_{i-j}) until it has stayed below 1e-12 of its peak
// for p + 1 steps, with its energy sum h_i^2, the variance of the process driven by unit innovations.
struct ArResponse {
  std::vector<double> h;
  double energy = 0;
};
ArResponse ar_response(const std::vector<double>& a) {
  constexpr std::size_t kLimit = 10'000'000;
  ArResponse r{{1.0}, 1.0};
  double peak = 1;
  std::size_t quiet = 0;
  while (r.h.size() < kLimit && quiet <= a.size()) {
    double v = 0;
    for (std::size_t j = 0; j < a.size() && j < r.h.size(); ++j) v += a[j] * r.h[r.h.size() - 1 - j];
    r.h.push_back(v);
    r.energy += v * v;
    peak = std::max(peak, std::abs(v));
    quiet = std::abs(v) < 1e-12 * peak ? quiet + 1 : 0;
  }
  return r;
}

// The autocorrelation rho(l) = sum_m h_m h_{m+l} / sum h^2 of the unit-variance AR process.
double autocorrelation(const ArResponse& response, std::size_t l) {
  double r = 0;
  for (std::size_t m = 0; m + l < response.h.size(); ++m) r += response.h[m] * response.h[m + l];
  return r / response.energy;
}

// Power-law noise's bin gains H_k = k^(-alpha/2), k = 0..n/2 (0 at DC), and P, the sum of |H_k|^2 over the whole
// spectrum (the bins 1..n/2 - 1 twice, Nyquist once for an even n): y = c2r(H Z) has E[y_i^2] = P.
struct PowerGains {
  std::vector<double> gain;
  double power = 0;
};
PowerGains power_gains(double alpha, int n) {
  PowerGains g{std::vector<double>(static_cast<std::size_t>(n / 2 + 1), 0.0), 0.0};
  for (int k = 1; k <= n / 2; ++k) {
    const double h = std::pow(static_cast<double>(k), -alpha / 2);
    g.gain[static_cast<std::size_t>(k)] = h;
    g.power += (n % 2 == 0 && k == n / 2 ? 1 : 2) * h * h;
  }
  return g;
}

// The largest root modulus of z^p - a1 z^{p-1} - ... - ap (the companion matrix's spectral radius): the process is
// stationary when it is below 1.
double spectral_radius(const std::vector<double>& a) {
  const auto p = static_cast<Eigen::Index>(a.size());
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(p, p);
  for (Eigen::Index j = 0; j < p; ++j) companion(0, j) = a[static_cast<std::size_t>(j)];
  for (Eigen::Index i = 1; i < p; ++i) companion(i, i - 1) = 1;
  return companion.eigenvalues().cwiseAbs().maxCoeff();
}

std::vector<double> ar_deviates(const std::vector<double>& a, std::uint64_t seed, std::size_t count) {
  // Unit stationary variance: the innovations scaled by 1 / sqrt(sum h_i^2); a burn-in as long as the impulse
  // response starts the record in the stationary state (the deviates before it are discarded).
  const ArResponse response = ar_response(a);
  const std::size_t burn = response.h.size();
  const std::vector<double> g = gaussian_deviates(seed, burn + count);
  std::vector<double> e(burn + count, 0.0);
  for (std::size_t i = 0; i < e.size(); ++i) {
    double v = g[i];
    for (std::size_t j = 0; j < a.size() && j < i; ++j) v += a[j] * e[i - 1 - j];
    e[i] = v;
  }
  const double scale = 1 / std::sqrt(response.energy);
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = scale * e[burn + i];
  return out;
}

std::vector<double> power_deviates(double alpha, std::uint64_t seed, std::size_t count) {
  if (count < 4) return gaussian_deviates(seed, count);  // no band to shape
  // Complex Gaussian bins of unit mean power, shaped by k^(-alpha/2) for k = 1..n/2 (0 at DC), then the inverse DFT,
  // divided by the square root of its expected power.
  const int n = static_cast<int>(count);
  const PowerGains shape = power_gains(alpha, n);
  const std::vector<double> g = gaussian_deviates(seed, 2 * static_cast<std::size_t>(n / 2 + 1));
  std::vector<std::complex<double>> half(static_cast<std::size_t>(n / 2 + 1));
  for (int k = 1; k <= n / 2; ++k) {
    const double gain = shape.gain[static_cast<std::size_t>(k)];
    const bool nyquist = n % 2 == 0 && k == n / 2;  // a real bin
    const auto i = static_cast<std::size_t>(k);
    half[i] = nyquist ? std::complex<double>(gain * g[2 * i], 0)
                      : gain * std::complex<double>(g[2 * i], g[2 * i + 1]) / std::sqrt(2.0);
  }
  std::vector<double> y = inverse_real_dft(half, n);
  const double scale = 1 / std::sqrt(shape.power);
  for (double& v : y) v *= scale;
  return y;
}

}  // namespace

std::string NoiseModel::text() const {
  if (kind == "power") return "power:" + format_value(alpha);
  if (kind != "ar") return "white";
  std::string out = "ar:";
  for (std::size_t j = 0; j < ar.size(); ++j) out += (j ? "," : "") + format_value(ar[j]);
  return out;
}

NoiseModel parse_noise_model(const std::string& text) {
  const auto fail = [&](const std::string& constraint) -> NoiseModel { throw NoiseModelError(text, constraint); };
  NoiseModel m;
  if (text == "white") return m;
  const std::size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon), rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  const auto number = [&](const std::string& item) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v)) fail("'" + item + "' is not a finite number");
    return v;
  };
  if (kind == "ar") {
    m.kind = "ar";
    std::stringstream list(rest);
    for (std::string item; std::getline(list, item, ',');) m.ar.push_back(number(item));
    if (m.ar.empty() || rest.back() == ',')
      fail("must read ar:a1,a2,... with at least one coefficient and no empty one");
    if (m.ar.size() > kMaxArOrder) fail("at most " + std::to_string(kMaxArOrder) + " coefficients");
    if (const double r = spectral_radius(m.ar); !(r < 1 - 1e-6))
      fail("not stationary: a root of z^p - a1 z^(p-1) - ... has modulus " + format_rounded(r, 6) +
           " (must be below 1 - 1e-6: nearer 1, the process's variance and correlation time exceed any record)");
    return m;
  }
  if (kind == "power") {
    m.kind = "power";
    m.alpha = number(rest);
    if (!(m.alpha >= 0 && m.alpha <= kMaxAlpha)) fail("alpha must be in [0, 4]");
    return m;
  }
  return fail("must be white, ar:a1,a2,... (autoregressive) or power:alpha (1/f^alpha)");
}

struct Whitener::Plan {
  // AR: the first p rows by the Cholesky factor of their stationary correlation, the rest by the prediction-error
  // filter over the innovations' sd.
  Eigen::LLT<Eigen::MatrixXd> head;
  double innovation_sd = 1;
  // Power: each bin divided by its noise sd in the unitary DFT, sqrt(n |H_k|^2 / P) (power_deviates); the offset bin,
  // which has none, set to 0.
  std::vector<double> bin_scale;
  std::unique_ptr<Dft> dft;
};

Whitener::Whitener(NoiseModel model, Eigen::Index samples)
    : model_(std::move(model)), samples_(samples), plan_(std::make_unique<Plan>()) {
  if (model_.kind == "ar") {
    const std::vector<double>& a = model_.ar;
    const ArResponse response = ar_response(a);
    const Eigen::Index head = std::min(static_cast<Eigen::Index>(a.size()), samples_);
    Eigen::MatrixXd gamma(head, head);
    for (Eigen::Index i = 0; i < head; ++i)
      for (Eigen::Index j = 0; j < head; ++j)
        gamma(i, j) = autocorrelation(response, static_cast<std::size_t>(std::abs(i - j)));
    plan_->head.compute(gamma);
    plan_->innovation_sd = 1 / std::sqrt(response.energy);  // of g_i, for unit process variance
  } else if (model_.kind == "power" && samples_ >= 4) {
    const PowerGains shape = power_gains(model_.alpha, static_cast<int>(samples_));
    plan_->bin_scale.assign(static_cast<std::size_t>(samples_ / 2 + 1), 0.0);
    for (Eigen::Index k = 1; k <= samples_ / 2; ++k) {
      const double gain = shape.gain[static_cast<std::size_t>(k)];
      plan_->bin_scale[static_cast<std::size_t>(k)] =
          1 / std::sqrt(static_cast<double>(samples_) * gain * gain / shape.power);
    }
    plan_->dft = std::make_unique<Dft>(static_cast<int>(samples_), 1.0);
  }
}

Whitener::~Whitener() = default;

Eigen::MatrixXd Whitener::apply(const Eigen::MatrixXd& x) const {
  if (x.rows() != samples_)
    throw InputError("whiten: " + std::to_string(x.rows()) + " rows for a whitener of " + std::to_string(samples_) +
                     " samples");
  const Eigen::Index n = samples_;
  if (model_.kind == "ar") {
    const std::vector<double>& a = model_.ar;
    const auto p = static_cast<Eigen::Index>(a.size());
    Eigen::MatrixXd w(n, x.cols());
    const Eigen::Index head = std::min(p, n);
    w.topRows(head) = plan_->head.matrixL().solve(x.topRows(head));
    for (Eigen::Index i = head; i < n; ++i) {
      Eigen::RowVectorXd r = x.row(i);
      for (Eigen::Index j = 0; j < p; ++j) r -= a[static_cast<std::size_t>(j)] * x.row(i - 1 - j);
      w.row(i) = r / plan_->innovation_sd;
    }
    return w;
  }
  if (plan_->dft) {
    Eigen::MatrixXd w(n, x.cols());
    std::vector<double> column(static_cast<std::size_t>(n));
    for (Eigen::Index c = 0; c < x.cols(); ++c) {
      Eigen::Map<Eigen::VectorXd>(column.data(), n) = x.col(c);
      std::vector<std::complex<double>> half = plan_->dft->transform(column).half;
      for (std::size_t k = 0; k < half.size(); ++k) half[k] *= plan_->bin_scale[k];
      const std::vector<double> y = inverse_real_dft(half, static_cast<int>(n));
      // Dft's bins carry its 1/n, so the unnormalised inverse of the weighted bins is U^H diag(lambda^-1/2) U x.
      w.col(c) = Eigen::Map<const Eigen::VectorXd>(y.data(), n);
    }
    return w;
  }
  return x;
}

Eigen::MatrixXd whiten(const NoiseModel& model, const Eigen::MatrixXd& x) { return Whitener(model, x.rows()).apply(x); }

std::vector<double> model_bin_variance(const NoiseModel& model, int samples) {
  const auto n = static_cast<std::size_t>(samples);
  const double nd = samples;
  std::vector<double> variance(n / 2 + 1, 1 / nd);
  if (model.kind == "power" && samples >= 4) {
    const PowerGains shape = power_gains(model.alpha, samples);
    for (std::size_t k = 0; k < variance.size(); ++k) variance[k] = shape.gain[k] * shape.gain[k] / shape.power;
    return variance;
  }
  if (model.kind != "ar" || samples < 2) return variance;
  // rho(0..p) from the impulse response, the rest by the Yule-Walker recursion.
  const std::vector<double>& a = model.ar;
  const ArResponse response = ar_response(a);
  std::vector<double> rho(n, 0.0);
  for (std::size_t l = 0; l <= a.size() && l < n; ++l) rho[l] = autocorrelation(response, l);
  for (std::size_t l = a.size() + 1; l < n; ++l)
    for (std::size_t j = 0; j < a.size(); ++j) rho[l] += a[j] * rho[l - 1 - j];
  // The lags folded modulo Nbar: c(m) = ((Nbar - m) rho(m) + m rho(Nbar - m)) / Nbar^2, symmetric in m <-> Nbar - m,
  // so that its DFT (Dft's 1/Nbar times Nbar) is real.
  std::vector<double> c(n);
  c[0] = 1 / nd;
  for (std::size_t m = 1; m < n; ++m)
    c[m] = ((nd - static_cast<double>(m)) * rho[m] + static_cast<double>(m) * rho[n - m]) / (nd * nd);
  Dft dft(samples, 1.0);
  const Spectrum s = dft.transform(c);
  for (std::size_t k = 0; k < variance.size(); ++k) variance[k] = nd * s.half[k].real();
  return variance;
}

std::vector<double> model_deviates(const NoiseModel& model, std::uint64_t seed, std::size_t count) {
  if (model.kind == "ar") return ar_deviates(model.ar, seed, count);
  if (model.kind == "power") return power_deviates(model.alpha, seed, count);
  return gaussian_deviates(seed, count);
}

std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed,
                              const NoiseModel& model) {
  if (level == 0) return clean;
  const double sigma = level * rms(clean);
  const std::vector<double> e = model_deviates(model, seed, clean.size());
  std::vector<double> z(clean.size());
  for (std::size_t i = 0; i < clean.size(); ++i) z[i] = clean[i] + sigma * e[i];
  return z;
}

}  // namespace beamid::signal
