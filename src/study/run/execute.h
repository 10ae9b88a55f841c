// What each unit of a study plan (plan.h) computes. Every function returns a record for the store; a failure inside
// a unit (integration, eigen-decomposition, a fit that throws) is a record with a status, never an exception.
#pragma once

#include <vector>

#include "model/beam_parameters.h"
#include "study/plan/plan.h"
#include "study/run/store.h"
#include "study/spec/study_spec.h"

namespace beamid::study {

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
//   fields: status, termination, cost, evaluations, wall_time_s, modes_in_data, spikes, a4, best_start, the overlay
//   fields of study/tables/overlay.h when unit.overlay, and for
//   every estimated key K: estimate.K, standard_error.K, relative_error.K (success is judged by the tables, with
//   the study's tolerances, which are not part of a case's identity)
Record run_case(const StudySpec& spec, const Unit& unit, const Record& truth);

// The Galerkin frequencies of the truth beam at N = elements (kind "frequencies"): fields exact_hz (the first four
// from the frequency determinant) and galerkin_hz (as many).
Record run_frequencies(const StudySpec& spec, int elements);

// One start-distance fit (kind "start", study_spec.h): fields status, termination, cost, evaluations, wall_time_s,
// frequency_offset (exact, of the start), shrunk (1 when the step was shortened to stay in the bounds), and for every
// estimated key K: start.K, estimate.K.
Record run_start(const StudySpec& spec, const Unit& unit, const Record& truth);

// The Cramér-Rao bound (kind "bound"): fields status, method, noise_sd, rcond, and relative_sd.K for every estimated
// key K (the bound on the relative standard deviation of an unbiased estimate of K).
Record run_bound(const StudySpec& spec, const Unit& unit, const Record& truth);

// Any unit of plan.units (the record's field "kind" says which).
Record run_unit(const StudySpec& spec, const Unit& unit, const Record& truth);

// Landscape units: "slice" (fields x, cost), "grid" (x, y, cost row-major in x), "multistart" (start.K, estimate.K,
// status, cost, evaluations; index -1 is the fit started at the truth, the reference minimum).
Record run_landscape(const StudySpec& spec, const Unit& unit, const Record& truth);

}  // namespace beamid::study
