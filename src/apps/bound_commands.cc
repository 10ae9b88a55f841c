// beamid crb: the Cramér-Rao bound of chosen beam parameters for an experiment (fit/cramer_rao.h).
#include <iostream>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/computations.h"
#include "apps/flags.h"
#include "config/beam_file.h"
#include "fit/cramer_rao.h"
#include "io/provenance.h"
#include "io/text.h"
#include "core/errors.h"
#include "core/limits.h"
#include "signal/noise.h"

namespace beamid::apps {

std::vector<FlagSpec> crb_flags() {
  std::vector<FlagSpec> flags = {
      text_flag("beam", "preset or TOML file: the parameter values at which the bound holds", true),
      integer_flag("elements", "Galerkin order N of the model", core::kMinElements, core::kMaxElements, true),
      text_flag("estimate", "comma-separated keys of the parameters to bound, e.g. EI,rho,cDI,gamma", true),
      number_flag("noise-sd", "standard deviation of the white Gaussian noise on each sample, in the output's units"),
      number_flag("noise-level", "noise standard deviation as a fraction of the clean signal's RMS (as the studies)"),
      number_flag("log-step",
                  "first step in ln q of the sensitivities' Ridders extrapolation, for experiments without exact "
                  "sensitivities (plucks; default 1e-2)")};
  for (FlagSpec& f : experiment_flag_specs()) flags.push_back(f);
  return flags;
}

CrbResult compute_crb(const Flags& a) {
  CrbResult r{read_model_run(a, core::kSimulateBytesPerSample), {}, {}, 0, {}, {}};
  const model::BeamParameters& beam = r.run.beam;
  const int n = r.run.elements;
  const simulation::Experiment& e = r.run.experiment;

  std::vector<std::string>& keys = r.keys;
  std::stringstream list(a.text("estimate"));
  for (std::string key; std::getline(list, key, ',');) {
    a.require(model::describe_parameter(beam, key).has_value(), "estimate",
              "'" + key + "' is not a parameter of this beam (valid: " + model::estimable_keys(beam) + ")");
    keys.push_back(key);
  }
  a.require(!keys.empty(), "estimate", "must name at least one parameter");
  if (!a.has("noise-sd") && !a.has("noise-level"))
    throw InputError("beamid crb: give one of --noise-sd S (absolute) and --noise-level L (fraction of the RMS)");
  fit::SensitivityOptions& options = r.options;
  options.log_step = a.optional_number("log-step").value_or(options.log_step);
  a.require(options.log_step > 0 && options.log_step <= 0.1, "log-step", "must lie in (0, 0.1]");

  double& sigma = r.noise_sd;
  if (a.has("noise-sd")) {
    sigma = a.number("noise-sd");
    a.require(sigma > 0, "noise-sd", "must be > 0");
  } else {
    const double level = a.number("noise-level");
    a.require(level > 0, "noise-level", "must be > 0");
    const galerkin::SplineSpace space(n);
    const simulation::Trace clean = simulation::simulate(galerkin::BeamForms(space, beam.l, beam.support), beam, e, {});
    if (!clean.ok()) throw NumericalError("beamid crb: the model could not be evaluated: " + clean.status);
    sigma = level * signal::rms(clean.y);
    a.require(sigma > 0, "noise-level", "the clean signal is zero, so a fraction of its RMS is no noise level");
  }

  fit::CramerRaoBound& b = r.bound;
  try {
    b = fit::beam_cramer_rao_bound(beam, n, e, keys, sigma, {}, options);
  } catch (const InputError& error) {
    throw InputError("beamid crb: --estimate = '" + a.text("estimate") + "': " + error.what());
  }
  if (b.status != "ok") throw NumericalError("beamid crb: " + b.status);
  for (const std::string& key : keys) r.values.push_back(model::parameter_value(beam, key));
  return r;
}

int run_crb(const Flags& a, std::ostream& out) {
  const CrbResult r = compute_crb(a);
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
            << " s, noise sd " << r.noise_sd << "; sensitivities "
            << (b.method == "exact" ? std::string("exact (modal closed form)")
                                    : "by Ridders-extrapolated central differences in ln q from step " +
                                          io::round_trip(r.options.log_step) + " (estimated relative error " +
                                          io::round_trip(b.step_agreement) + ")")
            << ", rcond " << b.rcond << "\n";
  return 0;
}

}  // namespace beamid::apps
