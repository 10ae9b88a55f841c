#include "signal/spectrum.h"

#include <fftw3.h>

#include <cmath>
#include <cstring>
#include <mutex>
#include <numbers>

#include "core/errors.h"

namespace beamid::signal {
namespace {

// FFTW's planner is not thread-safe (execution of an existing plan is): plans are made and destroyed under a lock.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

std::optional<std::string> validation_error(const WindowOptions& options) {
  if (options.name != "rectangular" && options.name != "hann" && options.name != "exponential")
    return "window = '" + options.name + "': must be one of rectangular, hann, exponential";
  if (options.name == "exponential" &&
      !(std::isfinite(options.exponential_end) && options.exponential_end >= 1e-6 && options.exponential_end < 1))
    // Below 1e-6 the window adds a decay of more than 14 / T to every mode and leaves nothing of the record's end to
    // see a mode in (at 1e-300 the "spikes" were at 131.8 Hz and at Nyquist, the modes gone); impact testing uses
    // 1e-2 to 1e-4.
    return "exponential_end = " + format_value(options.exponential_end) +
           ": must be in [1e-6, 1) (the window's value at the record's end; 1e-2 to 1e-4 is usual)";
  return std::nullopt;
}

std::vector<double> window_weights(const WindowOptions& options, int samples) {
  std::vector<double> w(static_cast<std::size_t>(samples), 1.0);
  if (options.name == "hann") {
    for (int i = 0; i < samples; ++i) {
      const double s = std::sin(std::numbers::pi * i / samples);
      w[static_cast<std::size_t>(i)] = s * s;
    }
  } else if (options.name == "exponential") {
    const double alpha = -std::log(options.exponential_end);
    for (int i = 0; i < samples; ++i) w[static_cast<std::size_t>(i)] = std::exp(-alpha * i / samples);
  }
  return w;
}

double window_decay_rate(const WindowOptions& options, double record_s) {
  return options.name == "exponential" ? -std::log(options.exponential_end) / record_s : 0.0;
}

double window_snr_retention(const std::vector<double>& weights, double decay_rate_per_s, double dt_s) {
  // Envelopes as e^{-sigma t_i} by the recurrence's product, summed with the window's weights and without.
  const double step = std::exp(-decay_rate_per_s * dt_s);
  double envelope = 1, windowed = 0, plain = 0, power = 0;
  for (double w : weights) {
    windowed += w * envelope;
    plain += envelope;
    power += w * w;
    envelope *= step;
  }
  if (power <= 0 || plain <= 0) return 0;
  return windowed * windowed / power / (plain * plain / static_cast<double>(weights.size()));
}

std::complex<double> Spectrum::at(long k) const {
  const long n = samples;
  long r = k % n;
  if (r < 0) r += n;
  if (r <= n / 2) return half[static_cast<std::size_t>(r)];
  return std::conj(half[static_cast<std::size_t>(n - r)]);
}

struct Dft::Plan {
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan plan = nullptr;
};

Dft::Dft(int samples, double dt_s, WindowOptions window)
    : samples_(samples), dt_s_(dt_s), window_(std::move(window)), plan_(std::make_unique<Plan>()) {
  if (samples < 2) throw InputError("DFT: samples = " + std::to_string(samples) + ": must be >= 2");
  if (!(std::isfinite(dt_s) && dt_s > 0)) throw InputError("DFT: dt_s = " + format_value(dt_s) + ": must be > 0");
  if (auto error = validation_error(window_)) throw InputError("DFT: " + *error);
  weights_ = window_weights(window_, samples);
  std::lock_guard<std::mutex> lock(planner_mutex());
  plan_->in = fftw_alloc_real(static_cast<std::size_t>(samples));
  plan_->out = fftw_alloc_complex(static_cast<std::size_t>(samples / 2 + 1));
  if (!plan_->in || !plan_->out) throw NumericalError("DFT: cannot allocate FFTW buffers");
  plan_->plan = fftw_plan_dft_r2c_1d(samples, plan_->in, plan_->out, FFTW_ESTIMATE);
  if (!plan_->plan) throw NumericalError("DFT: FFTW could not plan a transform of " + std::to_string(samples));
}

Dft::~Dft() {
  std::lock_guard<std::mutex> lock(planner_mutex());
  if (plan_->plan) fftw_destroy_plan(plan_->plan);
  fftw_free(plan_->in);
  fftw_free(plan_->out);
}

Spectrum Dft::transform(const std::vector<double>& z) {
  if (static_cast<int>(z.size()) != samples_)
    throw InputError("DFT: record of " + std::to_string(z.size()) + " samples given to a transform of " +
                     std::to_string(samples_));
  for (int i = 0; i < samples_; ++i)
    plan_->in[i] = weights_[static_cast<std::size_t>(i)] * z[static_cast<std::size_t>(i)];
  fftw_execute(plan_->plan);
  Spectrum s;
  s.samples = samples_;
  s.dt_s = dt_s_;
  s.half.resize(static_cast<std::size_t>(samples_ / 2 + 1));
  const double scale = 1.0 / samples_;  // the paper's 1/Nbar
  for (std::size_t k = 0; k < s.half.size(); ++k)
    s.half[k] = std::complex<double>(plan_->out[k][0], plan_->out[k][1]) * scale;
  return s;
}

double fourier_least_squares(const Spectrum& model, const Spectrum& data) {
  if (model.samples != data.samples || model.half.size() != data.half.size())
    throw InputError("Fourier least squares: model and data spectra differ in length");
  const int n = data.samples;
  double sum = 0;
  for (int k = 0; k <= n / 2; ++k) {
    const double d = std::norm(model.half[static_cast<std::size_t>(k)] - data.half[static_cast<std::size_t>(k)]);
    const bool single = k == 0 || (n % 2 == 0 && k == n / 2);
    sum += single ? d : 2 * d;
  }
  return sum;
}

double upper_band_energy_fraction(const Spectrum& record) {
  double total = 0, upper = 0;
  for (int k = 0; k <= record.last_bin(); ++k) {
    // Bins 1..Nbar/2 - 1 stand for themselves and their conjugates; the offset and, for an even length, Nyquist once.
    const double w = (k == 0 || (record.samples % 2 == 0 && k == record.last_bin())) ? 1.0 : 2.0;
    const double e = w * std::norm(record.half[static_cast<std::size_t>(k)]);
    total += e;
    if (4 * k > record.samples) upper += e;
  }
  return total > 0 ? upper / total : 0.0;
}

std::string fftw_library_version() { return fftw_version; }

std::vector<double> inverse_real_dft(const std::vector<std::complex<double>>& half, int samples) {
  if (samples < 2 || half.size() != static_cast<std::size_t>(samples / 2 + 1))
    throw InputError("inverse DFT: " + std::to_string(half.size()) + " bins for " + std::to_string(samples) +
                     " samples: must be samples/2 + 1");
  fftw_complex* in = nullptr;
  double* out = nullptr;
  fftw_plan plan = nullptr;
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
    in = fftw_alloc_complex(half.size());
    out = fftw_alloc_real(static_cast<std::size_t>(samples));
    if (in && out) plan = fftw_plan_dft_c2r_1d(samples, in, out, FFTW_ESTIMATE);
  }
  std::vector<double> y;
  if (plan) {
    for (std::size_t k = 0; k < half.size(); ++k) in[k][0] = half[k].real(), in[k][1] = half[k].imag();
    fftw_execute(plan);  // c2r overwrites its input, which is ours
    y.assign(out, out + samples);
  }
  std::lock_guard<std::mutex> lock(planner_mutex());
  if (plan) fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  if (y.empty()) throw NumericalError("inverse DFT: FFTW could not plan a transform of " + std::to_string(samples));
  return y;
}

}  // namespace beamid::signal
