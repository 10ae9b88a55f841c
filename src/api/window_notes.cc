// The window spread's line (api/fit_request.h: window_spread_line), as the command prints it and Python's messages
// hold it.
#include <cmath>
#include <sstream>

#include "api/fit_request.h"
#include "core/errors.h"

namespace beamid::api {

// "3 of 4 windows converged (window 2: max-evaluations); sd over them: EI 0.1 (formal ..., sandwich ...)", or why
// there is no spread. Each window that does not count is named with its status (reasons cut to 120 characters), so
// that a spread of the budget or of failed windows is not read as the data's.
std::string window_spread_line(const fit::WindowSpread& spread, const fit::FitResult& result) {
  std::ostringstream line;
  line << spread.used << " of " << spread.windows << " windows converged";
  std::string others;
  for (std::size_t k = 0; k < spread.statuses.size(); ++k) {
    if (spread.counted[k]) continue;
    const std::string& status = spread.statuses[k];
    others += (others.empty() ? "" : "; ") + std::string("window ") + std::to_string(k + 1) + ": " +
              (status.size() > 120 ? status.substr(0, 117) + "..." : status);
  }
  if (!others.empty()) line << " (" << others << ")";
  if (spread.used < 2) {
    line << "; no spread: it needs at least 2 converged windows";
    return line.str();
  }
  line << "; sd over them:";
  for (std::size_t i = 0; i < spread.keys.size(); ++i) {
    // A parameter on its bound in some windows is spread over the others only (NaN under two).
    const int off_bound = i < spread.used_per_parameter.size() ? spread.used_per_parameter[i] : spread.used;
    line << (i ? "," : "") << " " << spread.keys[i]
         << (off_bound < spread.used ? " (over the " + std::to_string(off_bound) + " window(s) off its bound)" : "")
         << " " << spread.sd[i] << " (formal " << result.parameters[i].standard_error << ", sandwich "
         << result.parameters[i].robust_standard_error << "; the windows' own formal " << spread.window_formal[i];
    // Model error shows as a spread beyond what each window's own noise gives; the full fit's formal error is the
    // wrong yardstick, the later windows being free decays that carry less information.
    const double ratio = spread.sd[i] / spread.window_formal[i];
    // A spread at the level of rounding (a noise-free record of the model itself: 2e-12 relative) is neither noise
    // nor model error, whatever its ratio to formal errors of the same size (the sixth pass's S264).
    if (spread.sd[i] <= 1e-9 * std::abs(result.parameters[i].estimate))
      line << ": at the level of rounding (a noise-free record the model fits exactly)";
    else if (!std::isfinite(spread.sd[i]))
      line << ": no spread";  // fewer than two windows off its bound
    else if (!std::isfinite(ratio))
      // No yardstick: said, with the likeliest cause when a window holds a parameter on its bound (an EI spread 87
      // times its formal error was left without a word: the twenty-third pass's adv55 P4).
      line << ": no verdict, the windows' own formal error being undefined"
           << (spread.bound_bias ? " (a window holds a parameter on its bound, which also biases its other estimates)"
                                 : " (a window's standard errors are not defined)");
    else if (ratio <= 2)
      line << ": within the windows' noise";
    else
      // Beyond 2 the yardstick may be what is wrong: a window whose weaker modes lie near the noise has their
      // amplitudes fitted to it, and its formal error understates its scatter (a model-exact record at 2 % noise:
      // 1.3-4.5 times; a Monte Carlo of one such window, 2.1 times), and a window with a parameter held on its bound
      // has its other estimates biased by it (the twenty-second pass's P6).
      line << ", " << format_rounded(ratio) << " times it: model error or drift along the record"
           << (spread.bound_bias ? ", a parameter held on its bound in some windows (which biases the others)" : "")
           << ", or windows whose weaker modes lie near the noise, where the formal error understates the scatter "
              "(fit records simulated at this noise to tell)";
    line << ")";
  }
  return line.str();
}

}  // namespace beamid::api
