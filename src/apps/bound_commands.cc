// beamid crb: the Cramér-Rao bound of chosen beam parameters for an experiment (fit/cramer_rao.h).
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

}  // namespace beamid::apps
