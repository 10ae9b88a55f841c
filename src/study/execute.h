// What each unit of a study plan (plan.h) computes. Every function returns a record for the store; a failure inside
// a unit (integration, eigen-decomposition, a fit that throws) is a record with a status, never an exception.
#pragma once

#include <vector>

#include "model/beam_parameters.h"
#include "study/plan.h"
#include "study/store.h"
#include "study/study_spec.h"

namespace beamid::study {

model::BeamParameters truth_beam(const StudySpec& spec);
// The success tolerance of a parameter: fit.damping_tolerance for damping parameters, fit.success_tolerance else.
double tolerance(const StudySpec& spec, const std::string& key);

// The clean record of a truth unit: CVODE at N_truth and truth.rtol; also the Galerkin modes of the truth beam.
//   fields: status, y (the samples), mode_frequency_hz, mode_damping_ratio, steps, wall_time_s
Record run_truth(const StudySpec& spec, const Unit& truth);

// Number of modes in a clean record: modes of the truth beam below the Nyquist frequency whose DFT magnitude (the
// largest over the 3 bins around the mode) reaches 1 % of the largest such magnitude (40 dB below the strongest
// mode: what a spectrum of a noisy record shows plainly).
int modes_in_data(const std::vector<double>& clean, double dt_s, const std::vector<double>& mode_frequency_hz);

// Checks every unit's fit options before anything runs (InputError naming the study file, the unit and the
// violated constraint), so a bad combination stops the study at once instead of filling it with failed rows.
void validate_plan(const StudySpec& spec, const Plan& plan);

// One fit (kind "case"). `truth` is the truth unit's record.
//   fields: status, termination, cost, evaluations, wall_time_s, modes_in_data, spikes, a4, best_start, and for
//   every estimated key K: estimate.K, standard_error.K, relative_error.K (success is judged by the tables, with
//   the study's tolerances, which are not part of a case's identity)
Record run_case(const StudySpec& spec, const Unit& unit, const Record& truth);

// Landscape units: "slice" (fields x, cost), "grid" (x, y, cost row-major in x), "multistart" (start.K, estimate.K,
// status, cost, evaluations; index -1 is the fit started at the truth, the reference minimum).
Record run_landscape(const StudySpec& spec, const Unit& unit, const Record& truth);

// The fit overlay and spectra for one case (for the plots): data, model at the estimate, and their DFT magnitudes.
struct Overlay {
  std::vector<double> t_s, data, model;
  std::vector<double> frequency_hz, data_magnitude, model_magnitude;
  std::vector<int> spike_bins, support_left, support_right;  // of the data
};
Overlay overlay(const StudySpec& spec, const Unit& unit, const Record& truth, const Record& result);

}  // namespace beamid::study
