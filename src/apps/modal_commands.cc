// beamid modal-id: the modes of a free-decay record by the matrix pencil (signal/matrix_pencil.h).
#include <iostream>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/computations.h"
#include "apps/flags.h"
#include "io/provenance.h"
#include "io/text.h"
#include "core/errors.h"
#include "core/limits.h"
#include "signal/matrix_pencil.h"

namespace beamid::apps {

std::vector<FlagSpec> modal_id_flags() {
  std::vector<FlagSpec> flags = {
      text_flag("data",
                "free-decay record: CSV (time, then channels) or LabVIEW .lvm (cut off the excitation with "
                "--start)",
                true),
      integer_flag("modes", "number K of modes reported: the K strongest decaying oscillations in the band (default 3)",
                   1, core::kMaxSpikes),
      integer_flag("order", "model order M, the exponentials kept by the SVD (default 2 K + 8)", 2, 10000),
      number_flag("min-frequency", "lowest frequency reported, Hz (default 0)"),
      number_flag("max-frequency", "highest frequency reported, Hz (default Nyquist)")};
  for (FlagSpec& f : import_flags()) flags.push_back(f);
  return flags;
}

ModalIdResult compute_modal_id(const Flags& a, const io::TimeSeries& data) {
  ModalIdResult r;
  signal::PencilOptions& o = r.options;
  o.modes = a.optional_integer("modes").value_or(o.modes);
  o.order = a.optional_integer("order").value_or(o.order);
  o.min_frequency_hz = a.optional_number("min-frequency").value_or(o.min_frequency_hz);
  o.max_frequency_hz = a.optional_number("max-frequency").value_or(o.max_frequency_hz);
  a.require(o.min_frequency_hz >= 0, "min-frequency", "must be >= 0");
  a.require(o.max_frequency_hz > o.min_frequency_hz, "max-frequency", "must exceed --min-frequency");
  try {
    r.modes = signal::matrix_pencil(data.values, data.dt_s, o);
  } catch (const InputError& error) {
    throw InputError("beamid modal-id: --data = '" + data.path + "': " + error.what());
  }
  return r;
}

int run_modal_id(const Flags& a, std::ostream& out) {
  const io::TimeSeries data = read_data(a);
  const ModalIdResult r = compute_modal_id(a, data);
  const signal::PencilOptions& o = r.options;
  const std::vector<signal::IdentifiedMode>& modes = r.modes;
  std::ostringstream csv;
  csv << "mode,frequency_hz,damping_ratio,amplitude,phase_rad\n";
  for (std::size_t k = 0; k < modes.size(); ++k) {
    csv << k + 1 << ",";
    io::write_row(csv, {modes[k].frequency_hz, modes[k].damping_ratio, modes[k].amplitude, modes[k].phase_rad});
  }
  out << csv.str();
  if (static_cast<int>(modes.size()) < o.modes)
    std::cerr << "beamid modal-id: --modes " << o.modes << ": the record shows only " << modes.size()
              << " decaying oscillation(s) in the band: " << modes.size() << " printed\n";
  std::cerr << "beamid modal-id (commit " << io::commit_label() << "): " << data.path << ", " << data.values.size()
            << " samples at dt = " << data.dt_s << " s; matrix pencil, model order "
            << (o.order > 0 ? o.order : 2 * o.modes + 8) << "\n";
  return 0;
}

}  // namespace beamid::apps
