// A table rendered as text, with its path relative to the study's results folder. Table writers return these (they
// compute nothing and touch no file); study/tables/tables.cc writes them all, atomically.
#pragma once

#include <string>
#include <vector>

namespace beamid::study {

struct Rendered {
  std::string path;  // e.g. "summary.csv", "landscape/basin.csv"
  std::string text;
};
using RenderedFiles = std::vector<Rendered>;

}  // namespace beamid::study
