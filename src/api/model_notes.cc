#include "api/model_notes.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "model/exact_frequencies.h"

namespace beamid::api {

namespace {

constexpr int kComparedModes = 6;

// Relative errors (Galerkin / exact - 1) of the first modes both give, or empty when the exact ones cannot be found.
std::vector<double> relative_gaps(const model::BeamParameters& beam, int elements) {
  std::vector<double> exact;
  try {
    exact = model::timoshenko_frequencies_rad_s(beam, kComparedModes);
  } catch (const std::runtime_error&) {
    return {};
  }
  const Eigen::VectorXd galerkin =
      galerkin::undamped_modes(galerkin::assemble(galerkin::SplineSpace(elements), beam)).omega_rad_s;
  std::vector<double> gaps;
  for (std::size_t k = 0; k < exact.size() && static_cast<Eigen::Index>(k) < galerkin.size(); ++k)
    gaps.push_back(galerkin(static_cast<Eigen::Index>(k)) / exact[k] - 1);
  return gaps;
}

}  // namespace

std::string attachment_convergence_note(const model::BeamParameters& beam, int elements) {
  int body = 0;  // the first attachment with rotary inertia on the span, 1-based
  for (std::size_t k = 0; k < beam.attachments.size() && body == 0; ++k) {
    const model::Attachment& a = beam.attachments[k];
    if (a.x < beam.l && (a.J > 0 || a.c != 0)) body = static_cast<int>(k) + 1;
  }
  if (body == 0) return "";
  // Against the same bodies as point masses (J = 0, c = 0): the gap the rotary inertia adds, not the mass's own (with
  // the bare beam as the reference, J = 1e-20 kg m^2 was blamed for a point mass's change: the fourteenth pass's P13).
  model::BeamParameters bare = beam;
  for (model::Attachment& a : bare.attachments) a.J = 0, a.c = 0;
  const std::vector<double> with = relative_gaps(beam, elements), without = relative_gaps(bare, elements);
  std::size_t worst = 0;
  double excess = 0;
  for (std::size_t k = 0; k < std::min(with.size(), without.size()); ++k)
    if (std::abs(with[k]) - std::abs(without[k]) > excess) {
      excess = std::abs(with[k]) - std::abs(without[k]);
      worst = k;
    }
  if (!(excess > kAttachmentExcessGap)) return "";
  const model::Attachment& a = beam.attachments[static_cast<std::size_t>(body - 1)];
  return "attachment " + std::to_string(body) + " at x = " + format_value(a.x) +
         " m has rotary inertia (J + m c^2 = " + format_rounded(a.J + a.m * a.c * a.c, 3) +
         " kg m^2), whose moment jump the cubic splines converge to slowly in N: at N = " + std::to_string(elements) +
         " mode " + std::to_string(worst + 1) + " is " + format_rounded(100 * with[worst], 2) +
         " % from the exact frequency (beamid modes --exact), against " + format_rounded(100 * without[worst], 2) +
         " % with the bodies as point masses; more --elements shrink it (roughly as 1/N)";
}

std::string nearly_defective_note(double eigenvector_rcond) {
  if (!(eigenvector_rcond < kNearlyDefectiveRcond)) return "";
  return "the damped modes are nearly defective (eigenvalue condition " + format_rounded(eigenvector_rcond, 2) + " < " +
         format_rounded(kNearlyDefectiveRcond) +
         ": a mode damped almost exactly critically), where the modal closed form loses accuracy (measured against "
         "CVODE: 5e-7 to 4e-6 of the response's peak at a condition of 0.008 to 0.02, 3e-4 at 0.0013); beamid "
         "simulate --integrator cvode is the check";
}

std::string nearly_defective_note(const model::BeamParameters& beam, int elements) {
  try {
    const galerkin::StateSpaceModes modes(galerkin::assemble(galerkin::SplineSpace(elements), beam));
    return nearly_defective_note(modes.eigenvector_rcond());
  } catch (const std::runtime_error&) {
    return "";  // a model whose modes fail says so where it is run
  }
}

}  // namespace beamid::api
