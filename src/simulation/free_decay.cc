#include "simulation/free_decay.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace beamid::simulation {

const char* const kNoFreeDecayMode = "free decay: the model has no underdamped mode below the Nyquist frequency";

std::vector<std::size_t> free_decay_pole_indices(const std::vector<std::complex<double>>& poles, double dt) {
  const double nyquist_rad_s = std::numbers::pi / dt;
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < poles.size(); ++k)
    if (poles[k].imag() > 0 && poles[k].imag() < nyquist_rad_s && std::isfinite(poles[k].real())) kept.push_back(k);
  std::stable_sort(kept.begin(), kept.end(),
                   [&poles](std::size_t a, std::size_t b) { return poles[a].imag() < poles[b].imag(); });
  return kept;
}

FreeDecayFit fit_free_decay(const std::vector<std::complex<double>>& poles, double dt,
                            const std::vector<double>& data) {
  if (!(dt > 0)) throw InputError("free decay: dt = " + format_value(dt) + ": must be > 0");
  if (data.empty()) throw InputError("free decay: no data");
  FreeDecayFit out;
  for (const std::size_t k : free_decay_pole_indices(poles, dt)) out.poles_rad_s.push_back(poles[k]);
  if (out.poles_rad_s.empty()) {
    out.status = kNoFreeDecayMode;
    return out;
  }
  const auto n = static_cast<Eigen::Index>(data.size());
  const auto k = static_cast<Eigen::Index>(out.poles_rad_s.size());
  Eigen::MatrixXd basis(n, 2 * k + 1);
  basis.col(0).setOnes();
  for (Eigen::Index m = 0; m < k; ++m) {
    const std::complex<double> lambda = out.poles_rad_s[static_cast<std::size_t>(m)];
    // e^{lambda dt i} by repeated multiplication would drift; the exponential of each t_i is exact to round-off.
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::complex<double> e = std::exp(lambda * (static_cast<double>(i) * dt));
      basis(i, 1 + 2 * m) = e.real();
      basis(i, 2 + 2 * m) = e.imag();
    }
  }
  const Eigen::Map<const Eigen::VectorXd> z(data.data(), n);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(basis);
  if (qr.rank() < basis.cols()) {
    out.status = "free decay: the modal basis is rank-deficient (" + std::to_string(qr.rank()) + " of " +
                 std::to_string(basis.cols()) + " columns: modes too close or too fast for the record)";
    return out;
  }
  const Eigen::VectorXd c = qr.solve(z);
  const Eigen::VectorXd y = basis * c;
  out.y.assign(y.data(), y.data() + n);
  out.amplitudes.assign(c.data(), c.data() + c.size());
  return out;
}

}  // namespace beamid::simulation
