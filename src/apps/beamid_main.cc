// beamid: command-line entry point. Dispatches to the subcommands of apps/commands.h; any error is one line on
// stderr ("beamid: ...") and a non-zero exit status (2 for bad input, 3 for a numerical failure).
#include <iostream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "io/provenance.h"
#include "model/errors.h"

int main(int argc, char** argv) {
  using namespace beamid;
  const std::vector<std::string> all(argv + 1, argv + argc);
  if (all.empty() || all[0] == "--help" || all[0] == "-h" || all[0] == "help") {
    std::cout << apps::overview();
    return all.empty() ? 2 : 0;
  }
  if (all[0] == "--version") {
    std::cout << "beamid " << io::version() << " (commit " << io::commit_label() << ")\n";
    return 0;
  }
  const std::vector<std::string> rest(all.begin() + 1, all.end());
  try {
    if (all[0] == "modes") return apps::run_modes(rest, std::cout);
    if (all[0] == "simulate") return apps::run_simulate(rest, std::cout);
    if (all[0] == "spikes") return apps::run_spikes(rest, std::cout);
    if (all[0] == "cost") return apps::run_cost(rest, std::cout);
    if (all[0] == "fit") return apps::run_fit(rest, std::cout);
    if (all[0] == "verify") return apps::run_verify(rest, std::cout);
    if (all[0] == "report") return apps::run_report(rest, std::cout);
    if (all[0] == "study") return apps::run_study(rest, std::cout);
    if (all[0] == "merge") return apps::run_merge(rest, std::cout);
    if (all[0] == "real") return apps::run_real(rest, std::cout);
    std::cerr << "beamid: unknown command '" << all[0] << "' (commands: modes, simulate, spikes, cost, fit, verify, report)\n";
    return 2;
  } catch (const InputError& error) {
    std::cerr << "beamid: " << error.what() << "\n";
    return 2;
  } catch (const NumericalError& error) {
    std::cerr << "beamid: " << error.what() << "\n";
    return 3;
  } catch (const std::exception& error) {
    std::cerr << "beamid: internal error: " << error.what() << "\n";
    return 1;
  }
}
