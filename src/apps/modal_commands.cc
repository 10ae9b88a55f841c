// beamid modal-id: the modes of a free-decay record by the matrix pencil (signal/matrix_pencil.h).
#include <iostream>
#include <sstream>

#include "apps/command_flags.h"
#include "apps/commands.h"
#include "apps/flag_requests.h"
#include "apps/flags.h"
#include "core/errors.h"
#include "core/limits.h"
#include "io/provenance.h"
#include "io/text.h"
#include "signal/matrix_pencil.h"

namespace beamid::apps {

std::vector<FlagSpec> modal_id_flags() {
  std::vector<FlagSpec> flags = {
      text_flag("data",
                "free-decay record: CSV (time, then channels), LabVIEW .lvm, text table (.txt), .npy, .mat or UFF 58 "
                "(cut off the "
                "excitation with --start)",
                true),
      integer_flag("modes", "number K of modes reported: the K strongest decaying oscillations in the band (default 3)",
                   1, core::kMaxSpikes),
      integer_flag("order", "model order M, the exponentials kept by the SVD (default 2 K + 8)", 2, 10000),
      number_flag("min-frequency", "lowest frequency reported, Hz (default 0)"),
      number_flag("max-frequency", "highest frequency reported, Hz (default Nyquist)")};
  for (FlagSpec& f : import_flags()) flags.push_back(f);
  return flags;
}

int run_modal_id(const Flags& a, std::ostream& out) {
  const io::TimeSeries data = read_data(a);
  const api::ModalIdResult r = api::compute_modal_id(modal_id_request_of(a), data);
  const signal::PencilOptions& o = r.options;
  const std::vector<signal::IdentifiedMode>& modes = r.modes;
  std::ostringstream csv;
  csv << "mode,frequency_hz,damping_ratio,amplitude,phase_rad,frequency_sd_hz\n";
  for (std::size_t k = 0; k < modes.size(); ++k) {
    csv << k + 1 << ",";
    io::write_row(csv, {modes[k].frequency_hz, modes[k].damping_ratio, modes[k].amplitude, modes[k].phase_rad,
                        modes[k].frequency_sd_hz});
  }
  out << csv.str();
  for (const std::string& note : r.notes) std::cerr << "beamid modal-id: " << note << "\n";
  std::cerr << "beamid modal-id (commit " << io::commit_label() << "): " << data.path << ", " << data.values.size()
            << " samples at dt = " << data.dt_s << " s; matrix pencil, model order "
            << (o.order > 0 ? o.order : 2 * o.modes + 8) << "\n";
  return 0;
}

}  // namespace beamid::apps
