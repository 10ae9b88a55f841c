// The command line's flags as typed requests (api/): one mapping a command. The command line and, for now, the
// Python package (python/src/core_module.cc) fill a request from the flags and hand it to the api's compute function,
// which validates it and computes: nothing below this file reads a flag.
#pragma once

#include "api/cost_request.h"
#include "api/design_request.h"
#include "api/experiment_request.h"
#include "api/fit_request.h"
#include "api/model_requests.h"
#include "api/record_requests.h"
#include "apps/flags.h"

namespace beamid::apps {

// The label a command's errors start with: "beamid <command>".
api::Caller caller_of(const Flags& a);
// --dt, --samples, --sensor-x, --output, --excitation, --force-x, --force-amplitude, --pulse-width.
api::ExperimentRequest experiment_request_of(const Flags& a);
// --beam, --elements and the experiment flags.
api::ModelRunRequest model_run_request_of(const Flags& a);
// --spikes, --spike-rule, --min-frequency, --max-frequency, --spike-frequencies, --artefacts; --window,
// --exponential-end; and with them --cost, --eps1..3, --unknown-amplitude, --model-poles, --frequency-weight.
api::SpikeRequest spike_request_of(const Flags& a);
api::WindowRequest window_request_of(const Flags& a);
api::CostRequest cost_request_of(const Flags& a);

api::ModesRequest modes_request_of(const Flags& a);
api::SimulateRequest simulate_request_of(const Flags& a);
api::SpikesRequest spikes_request_of(const Flags& a);
api::CostEvaluationRequest cost_evaluation_request_of(const Flags& a);
// beamid fit's request (the records are read apart: read_channels).
// `force`: the record's --force-channel, read by the caller (apps::read_force_channel), which drives the model.
api::FitRequest fit_request_of(const Flags& a, const std::optional<io::TimeSeries>& force = std::nullopt);
api::CrbRequest crb_request_of(const Flags& a);
api::DesignRequest design_request_of(const Flags& a);
api::ModalIdRequest modal_id_request_of(const Flags& a);

}  // namespace beamid::apps
