// The fit overlay of one case per cost: the data and the model at the estimate, in time and as DFT magnitudes, with
// the data spikes and their supports. Computed by the case unit (execute.h) and kept in its record (fields
// overlay.*), so the tables only format it: overlay.csv (t_s, data, model_<cost>...), spectrum.csv (frequency_hz,
// data_magnitude, model_<cost>...) and spikes.csv (the data spikes of the first spike cost with their 20 % supports
// in Hz), which plots/make_plots.sh reads.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fit/objective.h"
#include "model/beam_parameters.h"
#include "study/run/store.h"
#include "study/tables/rendered.h"

namespace beamid::study {

struct Overlay {
  std::vector<double> t_s, data, model;
  std::vector<double> frequency_hz, data_magnitude, model_magnitude;
  std::vector<int> spike_bins, support_left, support_right;  // of the data
};

// The data and the model of `options` at the parameters `at`, in time and in DFT magnitude, with the data spikes of
// the options' cost. A model evaluation that fails gives NaN model values (the overlay shows the data alone).
Overlay compute_overlay(const fit::FitOptions& options, const std::vector<double>& data,
                        const model::BeamParameters& at);

void store_overlay(Record& record, const Overlay& overlay);
// The overlay kept in a case record, if there is one.
std::optional<Overlay> stored_overlay(const Record& record);

// The three files; nothing when `overlays` is empty. Every overlay has the samples of the first.
RenderedFiles render_overlay_files(const std::vector<std::pair<std::string, Overlay>>& overlays);

}  // namespace beamid::study
