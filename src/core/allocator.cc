#include "core/allocator.h"

#include <malloc.h>

namespace beamid::core {

void keep_freed_memory() {
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // never trim the heap's top below 1 GB of free memory
  mallopt(M_TOP_PAD, 64 << 20);         // and grow it by 64 MB at a time
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // blocks up to 32 MB (glibc's largest threshold) from the heap, not mmap
}

}  // namespace beamid::core
