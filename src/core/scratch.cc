#include "core/scratch.h"

#include <sys/mman.h>

#include <cstdint>
#include <new>

namespace beamid::core {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;  // x86-64's transparent huge page
}

ScratchBuffer::~ScratchBuffer() { release(); }

void ScratchBuffer::release() {
  if (mapping_) munmap(mapping_, mapped_bytes_);
  mapping_ = nullptr;
  mapped_bytes_ = 0;
  data_ = nullptr;
  capacity_ = 0;
}

double* ScratchBuffer::reserve(std::size_t count) {
  if (count <= capacity_) return data_;
  release();
  if (count > (SIZE_MAX - 2 * kHugePage) / sizeof(double)) throw std::bad_alloc();
  // One huge page more than asked, so that the block can start on a huge-page boundary (the kernel backs only
  // aligned 2 MB ranges with huge pages).
  const std::size_t bytes = count * sizeof(double) + kHugePage;
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t aligned = (address + kHugePage - 1) / kHugePage * kHugePage;
  // A hint only: without transparent huge pages (or with them off) the block is ordinary pages, and correct.
  madvise(reinterpret_cast<void*>(aligned), bytes - (aligned - address), MADV_HUGEPAGE);
  mapping_ = p;
  mapped_bytes_ = bytes;
  data_ = reinterpret_cast<double*>(aligned);
  capacity_ = count;
  return data_;
}

}  // namespace beamid::core
