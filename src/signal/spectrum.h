// The DFT of a sampled record with the paper's scaling (3.2)-(3.4):
//   Z(k) = (1/Nbar) sum_{i=0}^{Nbar-1} w_i z_i exp(-j 2 pi k i / Nbar),   f_k = k / (Nbar dt) = k df,
// where w is an optional window applied identically to data and model:
//   "rectangular" (default) w_i = 1;
//   "hann"        w_i = sin^2(pi i / Nbar) (periodic Hann; halves the leakage of a record cut off mid-decay);
//   "exponential" w_i = exp(-alpha i / Nbar) with exp(-alpha) = exponential_end, the impact-testing window that adds a
//                 known decay rate alpha / T to every mode (T = Nbar dt) and forces short records to die out.
// Only k = 0..Nbar/2 is stored; the full DFT of a real signal follows as Z(k mod Nbar) with Z(Nbar - k) = conj Z(k),
// which is how a bin k^u + j outside 0..Nbar/2 in the spike cost is read (Spectrum::at).
// FFTW is used through Dft only; its plan is made once per record length (FFTW_ESTIMATE, so that the algorithm and
// hence the round-off are the same on every run: tables must be byte-identical) and reused for every evaluation.
#pragma once

#include <complex>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace beamid::signal {

struct WindowOptions {
  std::string name = "rectangular";  // "rectangular" | "hann" | "exponential"
  double exponential_end = 0.01;     // w at i = Nbar (exponential only), in [1e-6, 1)
};
// First violated constraint ("window = 'x': must be one of rectangular, hann, exponential"), or nothing.
std::optional<std::string> validation_error(const WindowOptions& options);

// w_0..w_{Nbar-1}.
std::vector<double> window_weights(const WindowOptions& options, int samples);
// The decay rate (1/s) the window adds to every mode of a record of length record_s: the exponential window
// e^{-alpha t / T}, alpha = -ln(exponential_end), adds alpha / T; the others add none.
double window_decay_rate(const WindowOptions& options, double record_s);
// The share of a decaying mode's signal-to-noise ratio at its spike that a window keeps, against the rectangular one.
// For z_i = A e^{-sigma t_i} cos(omega t_i) + white noise, t_i = i dt, the spike's height goes as |sum_i w_i
// e^{-sigma t_i}| and the noise's as sqrt(sum_i w_i^2), so the ratio is
//   rho = (sum_i w_i e^{-sigma t_i})^2 / sum_i w_i^2  /  ((sum_i e^{-sigma t_i})^2 / Nbar).
// 1 for the rectangular window and a mode that does not decay, above 1 for the exponential window on a mode that does
// (it follows the envelope, as a matched filter would), and far below 1 for a Hann window on a mode that has died out
// before the window opens: sigma T = 16 gives rho = 0.016 (4 pi^4 / (sigma T)^4 in the limit), and the spike is then
// the noise's (the seventeenth pass's P1: spike-smooth with a Hann window halved cDI on a pulse record at 1 % noise).
double window_snr_retention(const std::vector<double>& weights, double decay_rate_per_s, double dt_s);

struct Spectrum {
  int samples = 0;                         // Nbar
  double dt_s = 0;                         // sampling interval
  std::vector<std::complex<double>> half;  // Z(0..Nbar/2)

  double df_hz() const { return 1.0 / (samples * dt_s); }
  double frequency_hz(double k) const { return k * df_hz(); }
  int last_bin() const { return samples / 2; }  // Nbar/2 (integer division)
  // Z(k) of the full DFT for any integer k (index modulo Nbar, conjugate symmetry above Nbar/2).
  std::complex<double> at(long k) const;
  double magnitude(long k) const { return std::abs(at(k)); }
};

// Reusable transform for records of one length. Not thread-safe (it owns its FFTW buffers): one per thread.
class Dft {
 public:
  // InputError unless samples >= 2 and dt_s > 0, or the window is invalid.
  Dft(int samples, double dt_s, WindowOptions window = {});
  ~Dft();
  Dft(const Dft&) = delete;
  Dft& operator=(const Dft&) = delete;

  int samples() const { return samples_; }
  double dt_s() const { return dt_s_; }
  const WindowOptions& window() const { return window_; }
  // InputError unless z.size() == samples().
  Spectrum transform(const std::vector<double>& z);

 private:
  struct Plan;
  int samples_;
  double dt_s_;
  WindowOptions window_;
  std::vector<double> weights_;
  std::unique_ptr<Plan> plan_;
};

// Plain Fourier least squares over the full DFT: sum_{k=0}^{Nbar-1} |U(k) - Z(k)|^2, computed from the stored halves
// (k = 0 and, for even Nbar, k = Nbar/2 once, the others twice). With the rectangular window it equals
// sum_i (y_i - z_i)^2 / Nbar (Parseval), i.e. the time-domain cost over Nbar.
double fourier_least_squares(const Spectrum& model, const Spectrum& data);

// The fraction of a record's energy (Parseval: sum over the whole spectrum of |Z(k)|^2) at frequencies above a quarter
// of the sampling rate, the upper half of its band: about 0.5 for white noise, 0.076 for a sin^2 pulse 4 samples wide,
// 1e-5 for one 20 samples wide. A measured force held linear between its samples (simulation/experiment.h) is
// misrepresented where it has such content. 0 for a record of zeros.
double upper_band_energy_fraction(const Spectrum& record);

// FFTW's version string, for provenance.
std::string fftw_library_version();

// The real signal of `samples` samples whose DFT has the bins `half` (0..samples/2, as Spectrum::half holds them;
// the imaginary parts of bin 0 and, for an even length, of bin samples/2 are ignored): FFTW's inverse (c2r),
// unnormalised, y_i = sum over the whole spectrum of Y_k e^{2 pi j i k / samples}. InputError when half.size() is
// not samples/2 + 1.
std::vector<double> inverse_real_dft(const std::vector<std::complex<double>>& half, int samples);

}  // namespace beamid::signal
