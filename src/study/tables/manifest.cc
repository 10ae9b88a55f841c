#include "study/tables/manifest.h"

#include "config/document.h"
#include "fit/optimizer.h"
#include "io/text.h"
#include "signal/spectrum.h"
#include "simulation/cvode_simulator.h"

namespace beamid::study {

std::vector<io::Library> linked_libraries() {
  return {{"eigen", io::eigen_version()},           {"sundials", simulation::sundials_library_version()},
          {"ceres", fit::ceres_library_version()},  {"nlopt", fit::nlopt_library_version()},
          {"fftw", signal::fftw_library_version()}, {"tomlplusplus", config::toml_library_version()}};
}

std::string manifest_json(const Manifest& m) {
  std::string s = "{\n  \"study\": " + io::json_string(m.study) + ",\n  \"question\": " + io::json_string(m.question) +
                  ",\n  \"study_file\": " + io::json_string(m.study_file) + ",\n  \"study_file_fnv1a64\": \"" +
                  m.study_file_hash + "\"";
  for (const auto& [key, value] : m.before) s += ",\n  \"" + key + "\": " + value;
  s += ",\n  \"commit\": \"" + io::commit() + "\",\n  \"dirty\": " + (io::dirty() ? "true" : "false") +
       ",\n  \"beamid_version\": \"" + io::version() + "\",\n  \"compiler\": " + io::json_string(io::compiler()) +
       ",\n  \"libraries\": " + io::libraries_json(linked_libraries());
  for (const auto& [key, value] : m.after) s += ",\n  \"" + key + "\": " + value;
  return s + "\n}\n";
}

std::string provenance_csv(const std::string& study, int cases) {
  return "key,value\nstudy," + study + "\ncases," + std::to_string(cases) + "\ncommit," + io::commit_label() + "\n";
}

}  // namespace beamid::study
