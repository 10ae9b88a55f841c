// The Markdown report of one fit (beamid fit --report FILE.md): what ran, the estimates with standard errors and
// correlations (formal, assuming independent Gaussian noise), cost, evaluations, stages and termination, the spike
// table with the (A4) check, and the data and model spectra side by side around each spike. The full spectra go to
// FILE.spectra.csv beside it (bin, frequency, |Z|, |U|) for plotting.
#pragma once

#include <limits>
#include <string>

#include "apps/flags.h"
#include "fit/identification.h"
#include "fit/window_spread.h"
#include "galerkin/modes.h"
#include "io/time_series.h"

namespace beamid::apps {

struct ModeComparison;
struct FitReportInput {
  const fit::FitOptions& options;
  const fit::FitResult& result;
  const io::TimeSeries& data;
  const std::string& beam_name;
  const std::vector<std::string>& arguments;
  const std::vector<io::TimeSeries>& channels;  // every record of a joint fit (data is the first)
  const fit::WindowSpread* spread = nullptr;    // --windows, when given
  // compare_modes(*this) when the caller has it already (the command line and Python print it beside the report):
  // the report takes it instead of running the record's pencils again (8 % of a measured record's modal fit).
  const ModeComparison* modes = nullptr;
  // A beam given as TOML text (Python's beam dict, named "<beam dict>"): the report ends with it, so that the fit can
  // be re-run from the report; written with the report, in one piece (appended afterwards by Python, it was cut by a
  // full disk and crossed with another thread's report: the twenty-second pass's P5, P7).
  const std::string* beam_toml = nullptr;
};

// The identified modes beside the data's: the model's underdamped modes at the estimate, each paired by frequency
// with a mode the matrix pencil identifies in the data (after the pulse; signal/matrix_pencil.h).
struct ModePair {
  double data_hz = 0, data_damping_ratio = 0;    // identified in the record
  double model_hz = 0, model_damping_ratio = 0;  // at the estimate
  // The measured frequency's uncertainty (signal/measured_modes.h) and, when its span is notable, what widens it.
  double data_uncertainty_hz = 0;
  std::string data_note;
  // The model frequency's standard error at the estimate, propagated from the fit's covariance (NaN when the fit has
  // none): an estimator that weights the record's modes off their measured precision (the errors-in-variables
  // likelihood down-weights the resonance bins) scatters the model's modes more widely than the record's pencil does.
  double model_uncertainty_hz = std::numeric_limits<double>::quiet_NaN();
  // Decay rates -Re(lambda), 1/s, and the record's uncertainty of its own (signal/measured_modes.h).
  double data_decay_1_s = 0, model_decay_1_s = std::numeric_limits<double>::quiet_NaN();
  double data_decay_uncertainty_1_s = std::numeric_limits<double>::quiet_NaN();
  // A pole no model mode pairs with, below a millionth of the record's largest value (a 20-bit recorder's
  // resolution): the pencil's fit of what does not oscillate, set aside from the misfit verdict (modes_mismatch_note).
  bool set_aside = false;
};
struct ModeComparison {
  std::vector<ModePair> pairs;
  // What the record's modes do not say: a free decay that still holds its excitation (api::lead_in_note).
  std::vector<std::string> notes;
  std::string status = "ok";  // or why the data's modes could not be identified
};
// The standard error of each model mode's frequency at the estimate (NaN where unknown): u_k = f_k sqrt(g_k^T S g_k),
// with g_k = d log f_k / d log q (galerkin::frequency_sensitivities, of the undamped mode nearest in frequency) and S
// the covariance of log q from the fitted parameters' standard errors and correlation. Damping moves the undamped
// frequencies not at all and |lambda| only to second order in zeta.
std::vector<double> model_frequency_uncertainties(const fit::FitResult& result, int elements,
                                                  const std::vector<galerkin::DampedMode>& model);
// K = the cost's spike count (at most 8) modes in the cost's frequency band.
ModeComparison compare_modes(const FitReportInput& input);
// The model mode each data mode pairs with (-1: none): one to one, closest relative frequency first, and only within
// kModePairingWindow of each other.
inline constexpr double kModePairingWindow = 0.2;
std::vector<int> pair_modes(const std::vector<double>& data_hz, const std::vector<double>& model_hz);
// One line for stderr: "modes at the estimate (data | model): 2.4637 | 2.4637 Hz, zeta 0.0809 | 0.0809 %; ...".
std::string modes_line(const ModeComparison& comparison);
// A model that fits a record puts its modes within about 1 % of the record's (model error on the real records here
// is 0.1-0.7 %): beyond kModeMismatch, a "converged" fit with tight standard errors sits in a local minimum or has a
// model that cannot fit the record, which the errors do not include (a start 15 % off in frequency ended with modes
// 15 % apart and 0.4 % errors, nothing said: the sixth pass's S213). A record's mode whose own frequency is uncertain
// by more (2 u, u its measured uncertainty: a frequency that changes with the amplitude) is judged by that instead.
// "" when every pair agrees.
// Within kModeMismatch, the note says when a model mode misses the record's by more than
// kFrequencyMismatchUncertainties of its measured uncertainty combined with the fit's own standard error of that
// frequency (model error, a second hit), which the standard errors do not include either.
inline constexpr double kModeMismatch = 0.02;
inline constexpr double kFrequencyMismatchUncertainties = 10;
std::string modes_mismatch_note(const ModeComparison& comparison);
// The same for the damping: a model whose decay rate at a mode is more than kDampingMismatch (relative) and
// kDampingMismatchUncertainties of the record's own decay-rate uncertainty from the record's. Frequencies can agree to
// 0.07 % while the damping is 43 % off (the seventeenth pass's P1: spike-smooth with a Hann window on a noisy pulse
// record halved cDI, and said nothing). "" when every pair agrees.
inline constexpr double kDampingMismatch = 0.25;
inline constexpr double kDampingMismatchUncertainties = 5;
std::string damping_mismatch_note(const ModeComparison& comparison);

// InputError when the file cannot be written.
// The report as text: the Markdown (which names the spectra's file) and the full spectra as CSV.
struct FitReport {
  std::string markdown;
  std::string spectra_path;  // path + ".spectra.csv"
  std::string spectra_csv;
};
FitReport render_fit_report(const std::string& path, const FitReportInput& input);
// The first line of a fit report (by which a rerun knows the file as its own).
inline constexpr const char* kReportHeading = "# beamid fit report";
// The first line of the report's side file, REPORT.spectra.csv (by which a rerun knows the file as its own).
inline constexpr const char* kSpectraHeader = "bin,frequency_hz,data_magnitude,model_magnitude";
// Before a fit: --report names a file that may be written (check_output_file), is no input, and neither it nor its
// side file is a file beamid did not write (InputError naming --report).
void check_report_outputs(const Flags& a);
// render_fit_report, then both files written by atomic rename (InputError naming --report when a write fails).
void write_fit_report(const std::string& path, const FitReportInput& input);

}  // namespace beamid::apps
