#include "study/real_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "config/beam_file.h"
#include "config/document.h"
#include "costs/cost.h"
#include "io/files.h"
#include "io/text.h"
#include "io/time_series.h"
#include "model/errors.h"
#include "model/limits.h"
#include "signal/noise.h"

namespace beamid::study {
namespace fs = std::filesystem;
namespace {

using config::Table;

}  // namespace

RealStudySpec load_real_study(const std::string& path) {
  const config::Document document = config::Document::load(path, "cannot read the study file");
  document.root().only_tables({"study", "record", "beam", "fit"});
  const fs::path dir = fs::path(path).parent_path();
  const auto relative = [&](const std::string& f) { return fs::path(f).is_absolute() ? f : (dir / f).string(); };
  RealStudySpec s;
  s.path = path;
  s.file_hash = io::hex64(signal::fnv1a64(document.text()));
  const auto positive = [](double v) { return v > 0; };
  {
    Table r = document.required("study");
    s.name = r.string("name", std::nullopt);
    s.question = r.string("question", std::nullopt);
    r.finish({"name", "question"});
  }
  {
    Table r = document.required("record");
    s.record_file = relative(r.string("file", std::nullopt));
    if (!io::is_existing_file(s.record_file))
      r.fail("file", "'" + s.record_file + "'", "must be an existing record file");
    s.channel = r.string("channel", "");
    s.units = r.string("units", s.units, {"auto", "g", "as-is"});
    if (r.has("start_s"))
      s.start_s = r.number(
          "start_s", std::nullopt, [](double v) { return v >= 0; }, "must be >= 0");
    if (r.has("duration_s")) s.duration_s = r.number("duration_s", std::nullopt, positive, "must be > 0");
    s.resample = r.boolean("resample", false);
    s.peaks_hz = r.numbers("peaks_hz", positive, "must be > 0 (Hz)");
    if (s.peaks_hz.empty()) r.fail("peaks_hz", "[]", "must list the measured peak frequencies of the modes to fit");
    std::sort(s.peaks_hz.begin(), s.peaks_hz.end());
    r.finish({"file", "channel", "units", "start_s", "duration_s", "resample", "peaks_hz"});
  }
  {
    Table r = document.required("beam");
    s.beam_file = relative(r.string("file", std::nullopt));
    r.finish({"file"});
  }
  {
    Table r = document.required("fit");
    s.elements = r.integer("elements", s.elements, model::kMinElements, model::kMaxElements);
    std::vector<std::string> keys;
    for (const auto& info : model::parameter_table()) keys.emplace_back(info.key);
    s.estimate = r.strings("estimate", true, keys);
    s.costs = r.strings("costs", true, costs::cost_names().names());
    s.max_evaluations = r.integer("max_evaluations", s.max_evaluations, 10, model::kMaxEvaluations);
    s.frequency_weight = r.string("frequency_weight", s.frequency_weight, costs::frequency_weight_names().names());
    if (auto bounds = r.table("bounds")) {
      for (const auto& [k, value] : bounds->entries()) {
        const std::vector<config::Node> a = value.elements();
        const auto line = path + ":" + std::to_string(value.line()) + ": fit.bounds." + k;
        if (std::find(s.estimate.begin(), s.estimate.end(), k) == s.estimate.end())
          throw InputError(line + ": '" + k + "' is not in fit.estimate");
        if (!value.is_array() || a.size() != 2 || !a[0].is_number() || !a[1].is_number())
          throw InputError(line + " = " + value.text() + ": must be [lower, upper]");
        const double lo = *a[0].number(), hi = *a[1].number();
        if (!(lo >= 0 && hi > lo))
          throw InputError(line + " = [" + format_value(lo) + ", " + format_value(hi) +
                           "]: must have 0 <= lower < upper");
        s.bounds[k] = {lo, hi};
      }
    }
    r.finish({"elements", "estimate", "costs", "max_evaluations", "frequency_weight", "bounds"});
  }
  config::load_beam_toml(s.beam_file);  // checked before anything runs
  return s;
}

int run_real_study(const RealStudySpec& spec, const std::string& output_dir, std::ostream& log) {
  const RealResults results = compute_real_study(spec, log);
  for (const Rendered& f : render_real_study(spec, results))
    io::write_file_atomic(std::filesystem::path(output_dir) / f.path, f.text);
  log << "tables written to " << output_dir << "\n";
  int failed = 0;
  for (const RealFit& f : results.fits) failed += f.status.rfind("failed", 0) == 0 ? 1 : 0;
  return failed;
}

}  // namespace beamid::study
