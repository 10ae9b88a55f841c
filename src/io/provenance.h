// What a program ran: the beamid version and the git commit of the code it was built from (the last commit that
// changed code, studies or build files; see cmake/version.cmake), with a flag for uncommitted changes.
#pragma once

#include <string>

namespace beamid::io {

std::string version();        // "0.1.0"
std::string commit();         // 12 hex digits, or "unknown" outside a git work tree
bool dirty();                 // uncommitted changes to the code when it was built
std::string commit_label();   // commit() with "-dirty" appended when dirty()

}  // namespace beamid::io
