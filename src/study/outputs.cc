#include "study/outputs.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include <Eigen/Core>
#include <ceres/version.h>
#include <fftw3.h>
#include <nlopt.h>
#include <sundials/sundials_config.h>
#include <toml++/toml.h>

#include "model/errors.h"

namespace beamid::study {
namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out) throw InputError(tmp.string() + ": cannot write");
  }
  fs::rename(tmp, path);
}

std::string compiler() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "g++ " __VERSION__;
#else
  return "unknown";
#endif
}

std::string library_versions_json() {
  int major = 0, minor = 0, bugfix = 0;
  nlopt_version(&major, &minor, &bugfix);
  std::ostringstream os;
  os << "{\"eigen\": \"" << EIGEN_WORLD_VERSION << "." << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION
     << "\", \"sundials\": \"" << SUNDIALS_VERSION << "\", \"ceres\": \"" << CERES_VERSION_STRING
     << "\", \"nlopt\": \"" << major << "." << minor << "." << bugfix << "\", \"fftw\": \"" << fftw_version
     << "\", \"tomlplusplus\": \"" << TOML_LIB_MAJOR << "." << TOML_LIB_MINOR << "." << TOML_LIB_PATCH << "\"}";
  return os.str();
}

std::string json_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}


void write_overlay_files(const fs::path& dir, const std::vector<std::pair<std::string, Overlay>>& overlays) {
  if (overlays.empty()) return;

      const Overlay& first = overlays.front().second;
      std::ostringstream ts, fs_, sp;
      ts << "t_s,data";
      fs_ << "frequency_hz,data_magnitude";
      for (const auto& [cost, o] : overlays) ts << ",model_" << cost, fs_ << ",model_" << cost;
      ts << "\n";
      fs_ << "\n";
      for (std::size_t i = 0; i < first.t_s.size(); ++i) {
        ts << full(first.t_s[i]) << "," << full(first.data[i]);
        for (const auto& [cost, o] : overlays) ts << "," << full(o.model[i]);
        ts << "\n";
      }
      for (std::size_t k = 0; k < first.frequency_hz.size(); ++k) {
        fs_ << full(first.frequency_hz[k]) << "," << full(first.data_magnitude[k]);
        for (const auto& [cost, o] : overlays) fs_ << "," << full(o.model_magnitude[k]);
        fs_ << "\n";
      }
      // The data spikes (from the first spike cost's overlay), with their 20 % supports in Hz.
      sp << "spike,bin,frequency_hz,magnitude,support_low_hz,support_high_hz\n";
      for (const auto& [cost, o] : overlays) {
        if (o.spike_bins.empty()) continue;
        const double df = o.frequency_hz.size() > 1 ? o.frequency_hz[1] : 0;
        for (std::size_t l = 0; l < o.spike_bins.size(); ++l) {
          const int k = o.spike_bins[l];
          sp << l + 1 << "," << k << "," << full(k * df) << "," << full(o.data_magnitude[static_cast<std::size_t>(k)])
             << "," << full((k - o.support_left[l] - 0.5) * df) << "," << full((k + o.support_right[l] + 0.5) * df)
             << "\n";
        }
        break;
      }
      write_file(dir / "overlay.csv", ts.str());
      write_file(dir / "spectrum.csv", fs_.str());
      write_file(dir / "spikes.csv", sp.str());}

}  // namespace beamid::study
