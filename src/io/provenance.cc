#include "io/provenance.h"

#include <Eigen/Core>

#include "beamid/version.h"
#include "io/text.h"

namespace beamid::io {

std::string version() { return BEAMID_VERSION; }
std::string commit() { return BEAMID_GIT_COMMIT; }
bool dirty() { return BEAMID_GIT_DIRTY != 0; }
std::string commit_label() { return commit() + (dirty() ? "-dirty" : ""); }

std::string compiler() {
#if defined(BEAMID_ARCH_NAME)
  const std::string arch = ", -march=" BEAMID_ARCH_NAME;  // the build's instruction set (CMakeLists.txt: BEAMID_ARCH)
#else
  const std::string arch;  // the compiler's portable baseline
#endif
#if defined(__clang__)
  return "clang " __clang_version__ + arch;
#elif defined(__GNUC__)
  return "g++ " __VERSION__ + arch;
#else
  return "unknown" + arch;
#endif
}

std::string eigen_version() {
  return std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION);
}

std::string libraries_json(const std::vector<Library>& libraries) {
  std::string s = "{";
  for (std::size_t i = 0; i < libraries.size(); ++i)
    s += (i ? ", " : "") + json_string(libraries[i].name) + ": " + json_string(libraries[i].version);
  return s + "}";
}

}  // namespace beamid::io
