// beamid crb: the Cramér-Rao bound of chosen beam parameters for an experiment (fit/cramer_rao.h); beamid design: the
// candidate experiments ranked by that bound (fit/experiment_design.h).
#include <iostream>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/flag_requests.h"
#include "apps/flags.h"
#include "config/beam_file.h"
#include "core/errors.h"
#include "core/limits.h"
#include "fit/cramer_rao.h"
#include "fit/experiment_design.h"
#include "io/provenance.h"
#include "io/text.h"
#include "signal/noise.h"

namespace beamid::apps {

std::vector<FlagSpec> crb_flags() {
  std::vector<FlagSpec> flags = {
      text_flag("beam", "preset or TOML file: the parameter values at which the bound holds", true),
      integer_flag("elements", "Galerkin order N of the model", core::kMinElements, core::kMaxElements, true),
      text_flag("estimate", "comma-separated keys of the parameters to bound, e.g. EI,rho,cDI,gamma", true),
      number_flag("noise-sd", "standard deviation of the white Gaussian noise on each sample, in the output's units"),
      number_flag("noise-level", "noise standard deviation as a fraction of the clean signal's RMS (as the studies)"),
      text_flag("noise-model",
                "the noise's colour at that sd: white | ar:a1,... | power:alpha, as simulate's (default "
                "white)"),
      number_flag("log-step",
                  "first step in ln q of the sensitivities' Ridders extrapolation, for experiments without exact "
                  "sensitivities (plucks; default 1e-2)")};
  for (FlagSpec& f : experiment_flag_specs()) flags.push_back(f);
  return flags;
}

int run_crb(const Flags& a, std::ostream& out) {
  const api::CrbResult r = api::compute_crb(crb_request_of(a), std::cerr);
  const std::vector<std::string>& keys = r.keys;
  const fit::CramerRaoBound& b = r.bound;
  const simulation::Experiment& e = r.run.experiment;
  std::ostringstream csv;
  csv << "parameter,value,crb_sd,crb_relative_sd\n";
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    csv << keys[k] << "," << io::full_precision(r.values[k]) << "," << io::full_precision(b.sd(i)) << ","
        << io::full_precision(b.relative_sd(i)) << "\n";
  }
  out << csv.str();
  std::cerr << "beamid crb (commit " << io::commit_label() << "): beam " << r.run.beam_name
            << ", N = " << r.run.elements << ", " << e.output << ", " << e.samples << " samples at dt = " << e.dt_s
            << " s, noise sd " << r.noise_sd << " (" << b.noise_model << "); sensitivities "
            << (b.method == "exact" ? std::string("exact (modal closed form)")
                                    : "by Ridders-extrapolated central differences in ln q from step " +
                                          io::round_trip(r.options.log_step) + " (estimated relative error " +
                                          io::round_trip(b.step_agreement) + ")")
            << ", rcond " << b.rcond << "\n";
  return 0;
}

std::vector<FlagSpec> design_flags() {
  const std::string list = " (a comma-separated list; an item may be a range START:STOP:COUNT)";
  return {
      text_flag("beam", "preset or TOML file: the parameter values at which the bounds hold", true),
      integer_flag("elements", "Galerkin order N of the model", core::kMinElements, core::kMaxElements, true),
      text_flag("estimate", "comma-separated keys of the parameters of interest, estimated together, e.g. EI,rho",
                true),
      number_flag("noise-sd", "standard deviation of the white Gaussian noise on every channel, in the output's units"),
      number_flag("noise-level", "each channel's noise standard deviation as a fraction of its clean RMS"),
      text_flag("noise-model", "the noise's colour at that sd: white | ar:a1,... | power:alpha (default white)"),
      text_flag("criterion",
                "D (the geometric mean of the bound's relative sds: D-optimal), A (their root mean square: "
                "A-optimal), or a parameter's key (its relative sd alone) (default D)"),
      text_flag("sensor-x", "sensor positions, m, that a channel may take (default: the tip)" + list),
      integer_flag("sensors", "channels a candidate has: every set of this many --sensor-x positions (default 1)", 1,
                   64),
      text_flag("force-x", "force positions, m (default: the tip)" + list),
      text_flag("pulse-width", "sin^2 pulse widths, s (default 0.01)" + list),
      text_flag("dt", "sampling intervals, s (default 1e-3)" + list),
      text_flag("samples", "record lengths in samples (default 4096)" + list),
      text_flag("output", simulation::output_names().alternatives() + " (default displacement)"),
      text_flag("excitation", "pulse only (the default): its sensitivities are exact"),
      number_flag("force-amplitude", "pulse peak F0, N (default 1)")};
}

int run_design(const Flags& a, std::ostream& out) {
  const api::DesignResult r = api::compute_design(design_request_of(a), std::cerr);
  const fit::DesignOptions& o = r.options;
  std::ostringstream csv;
  csv << "rank,sensors_x_m,force_x_m,pulse_width_s,dt_s,samples,criterion";
  for (const std::string& key : o.keys) csv << ",relative_sd_" << key;
  csv << ",status\n";
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const fit::DesignRow& row = r.rows[i];
    std::string sensors;  // several channels: their positions separated by ';' (one CSV field)
    for (const double x : row.candidate.sensors_x_m) sensors += (sensors.empty() ? "" : ";") + io::round_trip(x);
    csv << (row.status == "ok" ? std::to_string(i + 1) : std::string()) << "," << sensors << ","
        << io::round_trip(row.candidate.force_x_m) << "," << io::round_trip(row.candidate.pulse_width_s) << ","
        << io::round_trip(row.candidate.dt_s) << "," << row.candidate.samples << ","
        << io::full_precision(row.criterion);
    for (Eigen::Index k = 0; k < row.relative_sd.size(); ++k) csv << "," << io::full_precision(row.relative_sd(k));
    csv << "," << io::csv_quoted(row.status) << "\n";
  }
  out << csv.str();
  // The ranking in one line: the best and the worst candidate with a bound, and their ratio (the design's gain).
  const fit::DesignRow& best = r.rows.front();
  std::size_t bounded = 0;
  while (bounded < r.rows.size() && r.rows[bounded].status == "ok") ++bounded;
  std::cerr << "beamid design (commit " << io::commit_label() << "): beam " << r.run.beam_name << ", N = " << o.elements
            << ", " << r.rows.size() << " candidates ranked by " << o.criterion << " ("
            << (o.criterion == fit::kDOptimal   ? "the geometric mean of the bound's relative sds"
                : o.criterion == fit::kAOptimal ? "the root mean square of the bound's relative sds"
                                                : "the bound on " + o.criterion + "'s relative sd")
            << "), noise "
            << (o.noise_sd > 0 ? "sd " + io::round_trip(o.noise_sd) : "level " + io::round_trip(o.noise_level)) << " ("
            << o.noise_model << ")";
  if (bounded > 0) {
    const fit::DesignRow& worst = r.rows[bounded - 1];
    std::cerr << "; best " << io::round_trip(best.criterion) << ", worst " << io::round_trip(worst.criterion) << " ("
              << io::round_trip(worst.criterion / best.criterion) << "x)";
  }
  if (bounded < r.rows.size())
    std::cerr << "; " << r.rows.size() - bounded << " without a bound (singular information: status column)";
  std::cerr << "\n";
  return 0;
}

}  // namespace beamid::apps
