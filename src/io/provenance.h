// What a program ran: the beamid version and the git commit of the code it was built from (the last commit that
// changed code, studies or build files; see cmake/version.cmake), with a flag for uncommitted changes; the compiler;
// and the versions of the libraries linked (each reported by its adapter, since only the adapter sees the library).
#pragma once

#include <string>
#include <vector>

namespace beamid::io {

std::string version();       // "0.1.0"
std::string commit();        // 12 hex digits, or "unknown" outside a git work tree
bool dirty();                // uncommitted changes to the code when it was built
std::string commit_label();  // commit() with "-dirty" appended when dirty()
std::string compiler();      // "g++ 12.2.0", with ", -march=x86-64-v3" when built for an instruction set
std::string eigen_version();

struct Library {
  std::string name, version;
};
// {"eigen": "3.4.0", "sundials": "6.4.1", ...} in the given order.
std::string libraries_json(const std::vector<Library>& libraries);

}  // namespace beamid::io
