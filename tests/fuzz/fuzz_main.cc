// One libFuzzer program per target (BEAMID_FUZZ_TARGET names the function of fuzz_targets.h), built by `make fuzz`
// with clang and -fsanitize=fuzzer,address,undefined.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  beamid::fuzz::BEAMID_FUZZ_TARGET(data, size);
  return 0;
}
