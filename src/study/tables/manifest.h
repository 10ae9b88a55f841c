// What a study ran, for every study kind (synthetic and real): manifest.json (study, question, study file and its
// hash, the study's own fields, then commit, dirty flag, version, compiler and the versions of the linked libraries)
// and provenance.csv (study, cases, commit: read by the plot scripts).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/provenance.h"

namespace beamid::study {

struct Manifest {
  std::string study, question, study_file, study_file_hash;
  // Further fields as (key, JSON value), written before and after the provenance block.
  std::vector<std::pair<std::string, std::string>> before, after;
};

std::string manifest_json(const Manifest& manifest);
std::string provenance_csv(const std::string& study, int cases);

// Every third-party library beamid links, with its version as its adapter reports it.
std::vector<io::Library> linked_libraries();

}  // namespace beamid::study
