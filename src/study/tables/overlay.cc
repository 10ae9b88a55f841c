#include "study/tables/overlay.h"

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/text.h"
#include "signal/spectrum.h"

namespace beamid::study {

Overlay compute_overlay(const fit::FitOptions& options, const std::vector<double>& data,
                        const model::BeamParameters& at) {
  Overlay out;
  fit::Objective objective(options, data);
  const auto model = objective.evaluate(at, fit::Objective::Response::always);
  const double dt = options.experiment.dt_s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < data.size(); ++i) {
    out.t_s.push_back(static_cast<double>(i) * dt);
    out.data.push_back(data[i]);
    out.model.push_back(i < model.y.size() ? model.y[i] : nan);
  }
  signal::Dft dft(static_cast<int>(data.size()), dt);
  const signal::Spectrum zs = dft.transform(data);
  const bool complete = model.y.size() == data.size();
  const signal::Spectrum us = complete ? dft.transform(model.y) : zs;
  for (int k = 0; k <= zs.last_bin(); ++k) {
    out.frequency_hz.push_back(zs.frequency_hz(k));
    out.data_magnitude.push_back(zs.magnitude(k));
    out.model_magnitude.push_back(complete ? us.magnitude(k) : nan);
  }
  // The spike costs' data spikes only: the modal cost's pairs are the identified modes, with no bin (spikes.csv listed
  // them all at bin 0, 0 Hz, when modal was a real study's first cost: the fifteenth pass's P3).
  if (options.cost.name == costs::kSpikeCost || options.cost.name == costs::kSpikeSmoothCost)
    for (const auto& p : objective.cost().data_spikes()) {
      out.spike_bins.push_back(p.data.bin);
      out.support_left.push_back(p.data.n_left);
      out.support_right.push_back(p.data.n_right);
    }
  return out;
}

void store_overlay(Record& r, const Overlay& o) {
  r.set("overlay.t_s", o.t_s);
  r.set("overlay.data", o.data);
  r.set("overlay.model", o.model);
  r.set("overlay.frequency_hz", o.frequency_hz);
  r.set("overlay.data_magnitude", o.data_magnitude);
  r.set("overlay.model_magnitude", o.model_magnitude);
  const auto doubles = [](const std::vector<int>& v) { return std::vector<double>(v.begin(), v.end()); };
  r.set("overlay.spike_bins", doubles(o.spike_bins));
  r.set("overlay.support_left", doubles(o.support_left));
  r.set("overlay.support_right", doubles(o.support_right));
}

std::optional<Overlay> stored_overlay(const Record& r) {
  if (!r.has("overlay.t_s")) return std::nullopt;
  const auto ints = [&](const std::string& key) {
    std::vector<int> out;
    for (double v : r.numbers(key)) out.push_back(static_cast<int>(v));
    return out;
  };
  Overlay o;
  o.t_s = r.numbers("overlay.t_s");
  o.data = r.numbers("overlay.data");
  o.model = r.numbers("overlay.model");
  o.frequency_hz = r.numbers("overlay.frequency_hz");
  o.data_magnitude = r.numbers("overlay.data_magnitude");
  o.model_magnitude = r.numbers("overlay.model_magnitude");
  o.spike_bins = ints("overlay.spike_bins");
  o.support_left = ints("overlay.support_left");
  o.support_right = ints("overlay.support_right");
  return o;
}

RenderedFiles render_overlay_files(const std::vector<std::pair<std::string, Overlay>>& overlays) {
  if (overlays.empty()) return {};

  const Overlay& first = overlays.front().second;
  std::ostringstream ts, fs_, sp;
  ts << "t_s,data";
  fs_ << "frequency_hz,data_magnitude";
  for (const auto& [cost, o] : overlays) ts << ",model_" << cost, fs_ << ",model_" << cost;
  ts << "\n";
  fs_ << "\n";
  for (std::size_t i = 0; i < first.t_s.size(); ++i) {
    ts << io::round_trip(first.t_s[i]) << "," << io::round_trip(first.data[i]);
    for (const auto& [cost, o] : overlays) ts << "," << io::round_trip(o.model[i]);
    ts << "\n";
  }
  for (std::size_t k = 0; k < first.frequency_hz.size(); ++k) {
    fs_ << io::round_trip(first.frequency_hz[k]) << "," << io::round_trip(first.data_magnitude[k]);
    for (const auto& [cost, o] : overlays) fs_ << "," << io::round_trip(o.model_magnitude[k]);
    fs_ << "\n";
  }
  // The data spikes (from the first spike cost's overlay), with their 20 % supports in Hz.
  sp << "spike,bin,frequency_hz,magnitude,support_low_hz,support_high_hz\n";
  for (const auto& [cost, o] : overlays) {
    if (o.spike_bins.empty()) continue;
    const double df = o.frequency_hz.size() > 1 ? o.frequency_hz[1] : 0;
    for (std::size_t l = 0; l < o.spike_bins.size(); ++l) {
      const int k = o.spike_bins[l];
      sp << l + 1 << "," << k << "," << io::round_trip(k * df) << ","
         << io::round_trip(o.data_magnitude[static_cast<std::size_t>(k)]) << ","
         << io::round_trip((k - o.support_left[l] - 0.5) * df) << ","
         << io::round_trip((k + o.support_right[l] + 0.5) * df) << "\n";
    }
    break;
  }
  return {{"overlay.csv", ts.str()}, {"spectrum.csv", fs_.str()}, {"spikes.csv", sp.str()}};
}

}  // namespace beamid::study
