// Flag handling shared by the beamid commands: --help, the experiment flags (simulate, fit) and the
// estimated-parameter list (fit).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "fit/parameter_map.h"
#include "io/arguments.h"
#include "model/beam_parameters.h"
#include "simulation/experiment.h"

namespace beamid::apps {

inline const io::FlagSpec kHelpFlag{"help", false, "print this help"};

// With --help: prints "usage: beamid COMMAND synopsis" and the flags to `out`, and returns true.
bool wants_help(const io::Arguments& a, std::ostream& out, const std::string& synopsis);

// a followed by b.
std::vector<io::FlagSpec> join_flags(std::vector<io::FlagSpec> a, const std::vector<io::FlagSpec>& b);

// --dt, --samples, --sensor-x, --output, --excitation, --force-x, --force-amplitude, --pulse-width
std::vector<io::FlagSpec> experiment_flag_specs();
// The experiment those flags describe (defaults of simulation::Experiment), validated for a beam of length_m.
simulation::Experiment read_experiment(const io::Arguments& a, double length_m);
// --estimate KEY,... with bounds [v/F, v F] around each nominal value v, or from --bounds KEY=LO:HI,...
std::vector<fit::EstimatedParameter> parse_estimate(const io::Arguments& a, const model::BeamParameters& nominal,
                                                    double factor);

}  // namespace beamid::apps
