#include "io/provenance.h"

#include "beamid/version.h"

namespace beamid::io {

std::string version() { return BEAMID_VERSION; }
std::string commit() { return BEAMID_GIT_COMMIT; }
bool dirty() { return BEAMID_GIT_DIRTY != 0; }
std::string commit_label() { return commit() + (dirty() ? "-dirty" : ""); }

}  // namespace beamid::io
