// Writing a study's files: atomic text files, provenance (compiler and library versions), and the fit-overlay and
// spectrum tables that plots/make_plots.sh reads (overlay.csv, spectrum.csv, spikes.csv).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "study/execute.h"
#include "study/text.h"

namespace beamid::study {

// Writes `text` to `path` through a temporary file and a rename (readers never see half a file); creates folders.
void write_file(const std::filesystem::path& path, const std::string& text);
// A JSON string literal.
std::string json_string(const std::string& s);
std::string compiler();
// {"eigen": "3.4.0", "sundials": ..., "ceres": ..., "nlopt": ..., "fftw": ..., "tomlplusplus": ...}
std::string library_versions_json();

// overlay.csv (t_s, data, model_<cost>...), spectrum.csv (frequency_hz, data_magnitude, model_<cost>...) and
// spikes.csv (the data spikes of the first spike cost with their 20 % supports in Hz); nothing when empty.
void write_overlay_files(const std::filesystem::path& dir, const std::vector<std::pair<std::string, Overlay>>& overlays);

}  // namespace beamid::study
