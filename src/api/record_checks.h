// What compute_fit (api/fit_request.h) checks of the records against the request before it fits: the time base, a
// measured force channel and its resolution, and the quantity a record states it measures. Each refusal is an
// InputError in the command line's one-line form (api/request.h); warnings go to the stream given.
#pragma once

#include <ostream>
#include <vector>

#include "api/fit_request.h"

namespace beamid::api {

// The model's time base is the record's; a --dt or --samples given must agree with it.
void match_record(const FitRequest& request, const io::TimeSeries& data, simulation::Experiment& experiment);
// A --force-channel: refused beside what cannot take it (windows, the modal cost, CVODE's errors in variables, a
// channel that is also a response, lengths that differ).
void check_force_channel(const FitRequest& request, const std::vector<io::TimeSeries>& channels,
                         const simulation::Experiment& experiment);
// A force whose samples do not resolve it is said to be, on `warnings`.
void warn_unresolved_force(const FitRequest& request, const fit::FitOptions& o, std::ostream& warnings);
// After an output-error fit of a record driven by its force channel (time, freq-band, spike costs, freq-ml without
// --force-noise-sd): when the channel's samples after the hit hold noise that, through the fitted model's resonances,
// reaches more of a bin than the residual does, said on `warnings` (the fit's standard errors leave it out).
void warn_noisy_force(const FitRequest& request, const fit::FitOptions& o, const std::vector<double>& data,
                      const fit::FitResult& result, std::ostream& warnings);
// The errors-in-variables form (freq-ml with a force noise sd): how much its cost rises when the measured force is
// negated and the fit redone from the estimate (one start), NaN when not that form or when the refit fails. A force
// that decides the fit costs far more negated (about 200 on a likelihood-scaled cost of 4,000 at 20 % force noise);
// one its free transient terms replace costs about the same; a channel of the wrong sign costs less.
double negated_force_rise(const fit::FitOptions& o, const std::vector<double>& data, const fit::FitResult& result);
// A record in a unit that is not a motion (N, V) is refused unless the experiment is a free decay.
void check_quantity(const Caller& caller, const std::vector<io::TimeSeries>& channels,
                    const simulation::Experiment& experiment);

}  // namespace beamid::api
