// The computing half of a real-data study (real_study.h): import the records, measure their peaks, fit them jointly
// with each candidate model and cost, and evaluate the identified model; every fit that fails is a result with its
// status.
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string_view>
#include <tuple>

#include "config/beam_file.h"
#include "core/errors.h"
#include "core/limits.h"
#include "costs/cost.h"
#include "fit/window_spread.h"
#include "galerkin/modes.h"
#include "galerkin/second_order_system.h"
#include "galerkin/spline_space.h"
#include "io/provenance.h"
#include "io/resources.h"
#include "signal/measured_modes.h"
#include "study/real/real_study.h"
#include "study/tables/format.h"

namespace beamid::study {
namespace {

// The readers name the command line's flags (--sample-rate); a real study's user wrote its keys
// (record.sample_rate_hz): an error names those, with the study file and the record (the second pass's N519).
std::string in_study_keys(std::string message, const RealRecordSpec& r) {
  // Longer flags first, so that --resample-rate is not read as --resample.
  const std::pair<const char*, const char*> keys[] = {{"--resample-rate", "resample_rate_hz"},
                                                      {"--time-variable", "time_variable"},
                                                      {"--time-channel", "time_channel"},
                                                      {"--sample-rate", "sample_rate_hz"},
                                                      {"--resample", "resample"},
                                                      {"--variable", "variable"},
                                                      {"--channel", "channel"},
                                                      {"--start", "start_s"},
                                                      {"--duration", "duration_s"},
                                                      {"--units", "units"}};
  // The line of the first key the message names (of the record's table when it names none): "study.toml:11: ...".
  std::string line = r.where.at("");
  std::size_t first = std::string::npos;
  for (const auto& [flag, key] : keys)
    if (const std::size_t at = message.find(flag); at < first && r.where.contains(key)) {
      first = at;
      line = r.where.at(key);
    }
  for (const auto& [flag, key] : keys) {
    const std::string replacement = "record '" + r.name + "'." + key;
    for (std::size_t at = message.find(flag); at != std::string::npos;
         at = message.find(flag, at + replacement.size())) {
      const std::size_t end = at + std::string_view(flag).size();
      if (end < message.size() && (std::isalnum(static_cast<unsigned char>(message[end])) || message[end] == '-')) {
        at += 1;  // a longer flag's prefix
        continue;
      }
      message.replace(at, end - at, replacement);
    }
  }
  return line + ": " + message;
}

RealRecordData import_record(const RealStudySpec& spec, const RealRecordSpec& r) {
  RealRecordData out;
  io::ImportOptions import;
  import.channel = r.channel;
  import.units = r.units;
  import.start_s = r.start_s;
  import.duration_s = r.duration_s;
  import.resample = r.resample;
  import.sample_rate_hz = r.sample_rate_hz;
  import.resample_rate_hz = r.resample_rate_hz;
  import.variable = r.variable;
  import.time_variable = r.time_variable;
  import.time_channel = r.time_channel;
  try {
    out.series = io::read_time_series(r.file, import);
  } catch (const InputError& error) {
    throw InputError(in_study_keys(error.what(), r));
  }
  out.nominal = config::load_beam_toml(r.beam_file.empty() ? spec.beam_file : r.beam_file);
  // The record's modes near peaks_hz, with their uncertainty, by the estimator every command shares (they had been
  // three-bin DFT estimates, 0.1-0.2 % from what modal-id and fit reported for the same record: issue 31).
  // A peak the record cannot hold (the eighth pass's RQ19: 900 Hz in a record sampled at 1652 Hz was "no identified
  // mode within 0.05 of 900 Hz").
  const double nyquist_hz = 0.5 / out.series.dt_s;
  for (const double f : r.peaks_hz)
    if (f >= nyquist_hz)
      throw InputError(r.where.at("peaks_hz") + ": record '" + r.name + "'.peaks_hz = " + format_value(f) +
                       " Hz: must lie below the record's Nyquist frequency, " + format_rounded(nyquist_hz, 6) + " Hz");
  signal::MeasureOptions measure;
  measure.wanted_hz = r.peaks_hz;
  signal::MeasuredModes found;
  try {
    found = signal::measure_modes(out.series.values, out.series.dt_s, measure);
  } catch (const InputError& error) {
    // The window the record was cut to may be the cause: said with it (the eighth pass's RQ09 blamed peaks_hz alone
    // for a start_s after the decay had died).
    const std::string window = " (in the record's " + std::to_string(out.series.values.size()) +
                               " samples from t = " + format_rounded(out.series.t0_s, 6) + " s" +
                               (r.start_s ? ", its start_s: a later start leaves less of the decay" : "") + ")";
    throw InputError(r.where.at("peaks_hz") + ": record '" + r.name + "'.peaks_hz: " + error.what() + window);
  }
  // Each record is fitted as a free decay from its first sample: one that still holds its hit is said to (the seventh
  // pass's RU05: the UnB record without its start_s gave EI 4.5 % off with nothing said).
  if (const long peak = signal::quiet_lead_in(out.series.values); peak >= 0)
    out.measured_notes.push_back(
        "the record is largest at t = " +
        format_rounded(out.series.t0_s + static_cast<double>(peak) * out.series.dt_s, 4) +
        " s after a quieter lead-in: it is no free decay from its start, and its fits take the excitation for part "
        "of the decay; set the record's start_s a little after that time");
  // Two peaks that find one mode would count it twice in every verdict (the eighth pass's RQ15: 14.3 and 14.45 Hz
  // both took the 14.316 Hz mode, "within 2 u (2/2)").
  for (std::size_t a = 0; a < found.modes.size(); ++a)
    for (std::size_t b = a + 1; b < found.modes.size(); ++b)
      if (found.modes[a].mode.lambda == found.modes[b].mode.lambda)
        throw InputError(r.where.at("peaks_hz") + ": record '" + r.name + "'.peaks_hz: " + format_value(r.peaks_hz[a]) +
                         " and " + format_value(r.peaks_hz[b]) + " Hz find the same mode (" +
                         format_rounded(found.modes[a].mode.frequency_hz, 6) + " Hz): list each measured mode once");
  for (const signal::MeasuredMode& m : found.modes) {
    out.measured_hz.push_back(m.mode.frequency_hz);
    out.measured_zeta.push_back(m.mode.damping_ratio);
    out.measured_uncertainty_hz.push_back(m.uncertainty_hz);
    if (const std::string note = signal::uncertainty_note(m); !note.empty()) out.measured_notes.push_back(note);
  }
  return out;
}

// The records as one candidate models them: each record's beam (the candidate's file, else the record's), the
// candidate's nominal values on it, as a free decay with its own spikes.
std::vector<fit::Record> candidate_records(const RealStudySpec& spec, const CandidateSpec& c,
                                           const std::vector<RealRecordData>& data) {
  std::vector<fit::Record> records;
  for (const int index : c.records) {
    const auto k = static_cast<std::size_t>(index);
    fit::Record r;
    r.name = spec.records[k].name;
    r.start = c.beam_file.empty() ? data[k].nominal : config::load_beam_toml(c.beam_file);
    for (const auto& [key, value] : c.values) model::set_nominal_value(r.start, key, value);
    r.experiment.excitation = simulation::kFreeDecay;
    r.experiment.dt_s = data[k].series.dt_s;
    r.experiment.samples = static_cast<int>(data[k].series.values.size());
    r.data = data[k].series.values;
    r.spike_frequencies_hz = spec.records[k].peaks_hz;
    records.push_back(std::move(r));
  }
  return records;
}

// The candidate's estimated keys with their bounds: shared keys around record 1's nominal value, per-record keys
// (recordK.KEY) around record K's; a position's upper bound at most the beam's length.
std::vector<fit::EstimatedParameter> candidate_estimate(const CandidateSpec& c,
                                                        const std::vector<fit::Record>& records) {
  std::vector<fit::EstimatedParameter> estimate;
  const auto bounded = [&](const std::string& key, const std::string& local, const model::BeamParameters& beam) {
    const double v = model::parameter_value(beam, local);
    const bool position = model::attachment_field(local) && model::attachment_field(local)->second == "x";
    fit::EstimatedParameter p = fit::bounds_around(key, v, 2);
    if (position) p.upper = beam.l;
    if (c.bounds.count(local)) std::tie(p.lower, p.upper) = c.bounds.at(local);
    estimate.push_back(p);
  };
  for (const std::string& key : c.estimate) bounded(key, key, records.front().start);
  for (const std::string& key : c.per_record)
    for (std::size_t k = 0; k < records.size(); ++k) {
      const auto fixed = c.fixed.find(c.records[k]);  // this record keeps its nominal value of key
      if (fixed != c.fixed.end() && std::find(fixed->second.begin(), fixed->second.end(), key) != fixed->second.end())
        continue;
      bounded("record" + std::to_string(k + 1) + "." + key, key, records[k].start);
    }
  return estimate;
}

// Every record's identified modes: the Galerkin modes at the estimate nearest to each measured peak.
void identify_modes(const RealStudySpec& spec, const std::vector<RealRecordData>& all, const fit::FitResult& r,
                    RealFit& f) {
  const galerkin::SplineSpace space(spec.elements), finer(2 * spec.elements);
  double squares = 0;
  int count = 0;
  f.worst_misfit = 0, f.worst_in_uncertainty = 0;
  const auto nearest = [](const std::vector<galerkin::DampedMode>& modes, double hz) {
    const galerkin::DampedMode* best = nullptr;
    for (const auto& d : modes)
      if (best == nullptr || std::abs(d.frequency_hz - hz) < std::abs(best->frequency_hz - hz)) best = &d;
    return best;
  };
  for (std::size_t k = 0; k < f.records.size(); ++k) {
    const auto damped = galerkin::StateSpaceModes(galerkin::assemble(space, r.records[k].beam)).underdamped_modes();
    const auto fine = galerkin::StateSpaceModes(galerkin::assemble(finer, r.records[k].beam)).underdamped_modes();
    f.identified_hz.emplace_back();
    f.zeta.emplace_back();
    f.discretisation_hz.emplace_back();
    const RealRecordData& record = all[static_cast<std::size_t>(f.records[k])];
    std::vector<const galerkin::DampedMode*> partners;
    for (std::size_t m = 0; m < record.measured_hz.size(); ++m) {
      const double measured = record.measured_hz[m];
      const galerkin::DampedMode* best = nearest(damped, measured);
      for (std::size_t j = 0; j < partners.size(); ++j)
        if (partners[j] == best && f.shared_mode.empty())
          f.shared_mode = "the measured " + format_rounded(record.measured_hz[j], 6) + " and " +
                          format_rounded(measured, 6) + " Hz of record " + std::to_string(f.records[k] + 1) +
                          " pair with one model mode, " + format_rounded(best->frequency_hz, 6) + " Hz (A4)",
          f.shared_record = f.records[k];
      partners.push_back(best);
      const double discretisation = std::abs(nearest(fine, best->frequency_hz)->frequency_hz - best->frequency_hz);
      f.identified_hz.back().push_back(best->frequency_hz);
      f.zeta.back().push_back(best->damping_ratio);
      f.discretisation_hz.back().push_back(discretisation);
      const double e = best->frequency_hz / measured - 1;
      squares += e * e;
      f.worst_misfit = std::max(f.worst_misfit, std::abs(e));
      f.worst_in_uncertainty =
          std::max(f.worst_in_uncertainty, std::abs(best->frequency_hz - measured) /
                                               std::hypot(record.measured_uncertainty_hz[m], discretisation));
      ++count;
    }
  }
  f.rms_misfit = std::sqrt(squares / count);
}

// What the study runs, before it runs (the records, the candidates, the costs, N), and the N^3 warning.
void log_what_runs(const RealStudySpec& spec, const RealResults& out, std::ostream& log) {
  log << "beamid real " << spec.path << " (commit " << io::commit_label() << "): " << out.records.size()
      << " record(s) (";
  for (std::size_t k = 0; k < out.records.size(); ++k)
    log << (k ? "; " : "") << out.records[k].series.values.size() << " samples at "
        << g4(1 / out.records[k].series.dt_s) << " Hz from " << spec.records[k].file;
  log << "), " << spec.candidates.size() << " candidate(s) x " << spec.costs.size()
      << " cost(s) at N = " << spec.elements << "\n";
  // The command line's N^3 warning (api/experiment_request.cc), here too: at N = 400 the study was silent for minutes.
  const double seconds = core::seconds_per_evaluation(spec.elements);
  if (seconds > 1)
    log << "beamid real: fit.elements = " << spec.elements << ": one model evaluation takes about "
        << io::seconds_text(seconds) << " here (it grows as N^3), and a fit takes hundreds\n";
  // The longest the fits may take, said before they start when over a minute, as fit's command line does: each
  // cost's budget (times fit.starts for the costs that use them) times one evaluation (the modal cost's is the
  // eigen-analysis alone; the others simulate every record). 1000 starts ran 7.5 minutes without a word (the
  // eleventh pass's RV_29).
  double samples = 0;
  for (const RealRecordData& r : out.records) samples += static_cast<double>(r.series.values.size());
  double worst = 0;
  for (const std::string& cost : spec.costs) {
    const bool started = spec.start_from.empty() || cost == spec.start_from;
    const double per_evaluation =
        seconds + (cost == costs::kModalCost ? 0.0 : core::kSecondsPerSampleAndElement * samples * spec.elements);
    worst += per_evaluation * spec.max_evaluations * (started ? spec.starts : 1);
  }
  worst *= static_cast<double>(spec.candidates.size());
  if (worst > 60)
    log << "beamid real: the fits may take up to " << io::seconds_text(worst) << " here (" << spec.candidates.size()
        << " candidate(s), fit.max_evaluations = " << spec.max_evaluations << ", fit.starts = " << spec.starts
        << "): lower fit.starts or fit.max_evaluations, or cut the records\n";
  log << std::flush;
}

// A candidate's fit options before the cost is chosen: record 1's start and experiment, its spikes, the study's
// weights and budget, the candidate's estimated keys and bounds.
fit::FitOptions candidate_options(const RealStudySpec& spec, const CandidateSpec& candidate,
                                  const std::vector<fit::Record>& records) {
  fit::FitOptions base;
  base.start = records.front().start;
  base.experiment = records.front().experiment;
  base.elements = spec.elements;
  base.cost.spikes.frequencies_hz = records.front().spike_frequencies_hz;
  base.cost.spikes.count = static_cast<int>(base.cost.spikes.frequencies_hz.size());
  base.cost.frequency_weight = spec.frequency_weight;
  base.cost.mode_weight = spec.mode_weight;
  base.optimizer.max_evaluations = spec.max_evaluations;
  base.estimate = candidate_estimate(candidate, records);
  return base;
}

// Every record read and measured, its notes logged; one measurement listed twice refused.
std::vector<RealRecordData> import_records(const RealStudySpec& spec, std::ostream& log) {
  std::vector<RealRecordData> records;
  for (const RealRecordSpec& r : spec.records) {
    records.push_back(import_record(spec, r));
    for (const std::string& note : records.back().measured_notes)
      log << "beamid real: record '" << r.name << "': " << note << "\n";
    // One measurement under two names would count twice in every joint fit (the tenth pass's RL_02: EI's standard
    // error sqrt(2) too small, exit 0).
    // Two windows of one file's channel that overlap share their samples too (the eleventh pass's RL_u2s: the
    // second starting one sample later was accepted, EI's error 1.8 times smaller).
    const io::TimeSeries& b = records.back().series;
    for (std::size_t k = 0; k + 1 < records.size(); ++k) {
      const io::TimeSeries& a = records[k].series;
      const bool one_channel = std::filesystem::equivalent(spec.records[k].file, r.file) &&
                               spec.records[k].channel == r.channel && a.dt_s == b.dt_s;
      const double a_end = a.t0_s + static_cast<double>(a.values.size()) * a.dt_s,
                   b_end = b.t0_s + static_cast<double>(b.values.size()) * b.dt_s;
      if (a.values == b.values || (one_channel && a.t0_s < b_end && b.t0_s < a_end))
        throw InputError(r.where.at("") + ": record '" + r.name + "' holds samples of record '" + spec.records[k].name +
                         "' (" + spec.records[k].where.at("") +
                         "): one measurement fitted twice counts its information twice; list it once, or give "
                         "the two windows of one file (start_s, duration_s) that do not overlap");
    }
  }
  return records;
}

}  // namespace

RealResults compute_real_study(const RealStudySpec& spec, std::ostream& log) {
  RealResults out;
  out.records = import_records(spec, log);
  log_what_runs(spec, out, log);

  for (const CandidateSpec& candidate : spec.candidates) {
    const std::vector<fit::Record> records = candidate_records(spec, candidate, out.records);
    const fit::FitOptions base = candidate_options(spec, candidate, records);
    // The route from nominal starts (start_from): its cost from the starts, every later cost from its estimate.
    std::optional<fit::FitResult> from;
    for (const auto& cost : spec.costs) {
      fit::FitOptions o = base;
      o.cost.name = cost;
      o.optimizer.method = fit::default_optimizer(cost);
      const bool refines = !spec.start_from.empty() && cost != spec.start_from;
      if (!refines) o.starts = spec.starts, o.seed = spec.seed;
      std::vector<fit::Record> started = records;
      if (refines && from) {
        for (std::size_t k = 0; k < started.size(); ++k) started[k].start = from->records[k].beam;
        o.start = started.front().start;
      }
      const auto t0 = std::chrono::steady_clock::now();
      RealFit f;
      f.candidate = candidate.name;
      f.records = candidate.records;
      f.cost = cost;
      fit::FitResult r;
      try {
        r = fit::fit(o, started);
        // The tables compare with the nominal values: a refinement's start is the other cost's estimate.
        if (refines && from)
          for (std::size_t i = 0; i < r.parameters.size(); ++i) r.parameters[i].start = from->parameters[i].start;
        if (cost == spec.start_from && r.status != "failed") from = r;
        f.status = r.status;
        // a failed fit carries its reason into the tables (the status column held a bare "failed")
        if (r.status == "failed") f.status = "failed: " + (r.termination.empty() ? "no reason given" : r.termination);
      } catch (const std::exception& e) {
        f.status = std::string("failed: ") + e.what();
      }
      log << candidate.name << ", " << cost << ": " << f.status << ", cost " << g4(r.cost) << ", " << r.evaluations
          << " evaluations";
      if (refines)
        log << (from ? ", from the " + spec.start_from + " estimate"
                     : ", from the nominal values (the " + spec.start_from + " fit failed)");
      else if (o.starts > 1)
        log << ", best of " << o.starts << " starts (start " << r.best_start + 1 << ")";
      if (f.status.rfind("failed", 0) == 0) {
        log << "\n";
        f.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        out.fits.push_back(f);
        continue;
      }
      f.cost_value = r.cost;
      f.evaluations = r.evaluations;
      f.parameters = r.parameters;
      f.identifiability = r.identifiability;
      identify_modes(spec, out.records, r, f);
      if (spec.windows >= 2) {
        try {  // records too short for the windows: the fit stays, without a window spread
          const fit::WindowSpread w = fit::window_spread(o, records, r, spec.windows);
          f.window_sd = w.sd;
          f.windows_used = w.used;
          log << ", " << w.used << "/" << w.windows << " windows converged";
        } catch (const InputError& e) {
          log << ", no window spread: " << e.what();
        }
      }
      log << "\n";
      fit::FitOptions first = o;  // the first record's model (its spikes are the base options')
      first.start = records.front().start;
      first.experiment = records.front().experiment;
      first.estimate.clear();
      try {  // residuals in time and frequency; a failure leaves the fit without an overlay, never stops the study
        f.overlay = compute_overlay(first, records.front().data, r.records.front().beam);
      } catch (const std::exception& e) {
        log << candidate.name << ", " << cost << ": no overlay: " << e.what() << "\n";
      }
      f.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      out.fits.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace beamid::study
