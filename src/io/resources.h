// Guards for work whose size the inputs set (samples, elements, units): the machine's memory, and a refusal or a
// warning that states the estimate, so that nothing is started that cannot finish.
#pragma once

#include <optional>
#include <ostream>
#include <string>

namespace beamid::io {

// MemAvailable of /proc/meminfo, in bytes (nothing where it cannot be read).
std::optional<double> available_memory_bytes();

// InputError "<what>: needs about X GB of memory; this machine has Y GB available" when `bytes` exceeds the
// available memory; a warning line on `warn` when it exceeds a quarter of it.
void check_memory(const std::string& what, double bytes, std::ostream& warn);

// The peak resident memory of this process so far (getrusage ru_maxrss), in bytes.
double peak_resident_bytes();

// "1.5 GB", "320 MB", "12 kB".
std::string bytes_text(double bytes);
// "45 s", "12 min", "3.2 h".
std::string seconds_text(double seconds);

}  // namespace beamid::io
