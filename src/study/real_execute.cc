// The computing half of a real-data study (real_study.h): import the record, measure its peaks, fit it with each
// cost, and evaluate the identified model; every fit that fails is a result with its status.
#include <chrono>
#include <cmath>
#include <numbers>

#include "config/beam_file.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "io/provenance.h"
#include "model/errors.h"
#include "signal/spectrum.h"
#include "signal/spikes.h"
#include "study/format.h"
#include "study/real_study.h"

namespace beamid::study {

RealResults compute_real_study(const RealStudySpec& spec, std::ostream& log) {
  RealResults out;
  io::ImportOptions import;
  import.channel = spec.channel;
  import.units = spec.units;
  import.start_s = spec.start_s;
  import.duration_s = spec.duration_s;
  import.resample = spec.resample;
  out.record = io::read_time_series(spec.record_file, import);
  const io::TimeSeries& record = out.record;
  out.nominal = config::load_beam_toml(spec.beam_file);
  const model::BeamParameters& nominal = out.nominal;
  log << "beamid real " << spec.path << " (commit " << io::commit_label() << "): " << record.values.size()
      << " samples at " << g4(1 / record.dt_s) << " Hz from " << spec.record_file << " (" << record.notes << ") "
      << spec.costs.size() << " fits at N = " << spec.elements << "\n";

  fit::FitOptions base;
  base.start = nominal;
  base.elements = spec.elements;
  base.experiment.excitation = simulation::kFreeDecay;
  base.experiment.dt_s = record.dt_s;
  base.experiment.samples = static_cast<int>(record.values.size());
  base.cost.spikes.frequencies_hz = spec.peaks_hz;
  base.cost.spikes.count = static_cast<int>(spec.peaks_hz.size());
  base.cost.frequency_weight = spec.frequency_weight;
  base.optimizer.max_evaluations = spec.max_evaluations;
  for (const auto& key : spec.estimate) {
    const double v = model::parameter_value(nominal, key);
    const auto b = spec.bounds.count(key) ? spec.bounds.at(key) : std::make_pair(v / 2, v * 2);
    base.estimate.push_back({key, b.first, b.second});
  }
  {  // the data's sub-bin peak frequencies near peaks_hz, and damping ratios sigma / |lambda| from the 3-bin rates
    signal::Dft dft(static_cast<int>(record.values.size()), record.dt_s);
    const signal::Spectrum z = dft.transform(record.values);
    for (const auto& s : signal::detect_spikes(z, base.cost.spikes)) {
      const auto e = signal::three_bin_estimate(z, s.bin);
      out.measured_hz.push_back(e.ok ? e.frequency_hz : s.frequency_hz);
      const double w = 2 * std::numbers::pi * out.measured_hz.back();
      out.measured_zeta.push_back(e.ok ? e.decay_rate_1_s / std::hypot(e.decay_rate_1_s, w) : std::nan(""));
    }
  }
  if (out.measured_hz.size() != spec.peaks_hz.size())
    throw InputError(spec.path + ": record.peaks_hz: " + std::to_string(spec.peaks_hz.size() - out.measured_hz.size()) +
                     " of the peaks have no local maximum of the record's spectrum within 5 %");
  for (const auto& cost : spec.costs) {
    fit::FitOptions o = base;
    o.cost.name = cost;
    o.optimizer.method = fit::default_optimizer(cost);
    const auto t0 = std::chrono::steady_clock::now();
    RealFit f;
    f.cost = cost;
    fit::FitResult r;
    try {
      r = fit::fit(o, record.values);
      f.status = r.status;
    } catch (const std::exception& e) {
      f.status = std::string("failed: ") + e.what();
    }
    f.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    log << cost << ": " << f.status << ", cost " << g4(r.cost) << ", " << r.evaluations << " evaluations\n";
    if (f.status.rfind("failed", 0) == 0) {
      out.fits.push_back(f);
      continue;
    }
    f.cost_value = r.cost;
    f.evaluations = r.evaluations;
    f.parameters = r.parameters;
    // Identified modes: the Galerkin modes at the estimate nearest to each measured peak (paired by frequency).
    const galerkin::SplineSpace space(spec.elements);
    const auto damped = galerkin::StateSpaceModes(galerkin::assemble(space, r.beam)).underdamped_modes();
    for (const double measured : out.measured_hz) {
      const galerkin::DampedMode* best = nullptr;
      for (const auto& d : damped)
        if (best == nullptr || std::abs(d.frequency_hz - measured) < std::abs(best->frequency_hz - measured)) best = &d;
      f.identified_hz.push_back(best->frequency_hz);
      f.zeta.push_back(best->damping_ratio);
    }
    f.overlay = compute_overlay(o, record.values, r.beam);  // residuals in time and frequency
    out.fits.push_back(std::move(f));
  }
  return out;
}

}  // namespace beamid::study
