#include "mm/sim/memory.hpp"

#include <cstdlib>  // defines __GLIBC__ under glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mm::sim {

void retain_freed_memory() {
#if defined(__GLIBC__)
  constexpr int mmap_threshold = 32 << 20;  // glibc's largest
  constexpr int trim_threshold = 256 << 20;
  mallopt(M_MMAP_THRESHOLD, mmap_threshold);
  mallopt(M_TRIM_THRESHOLD, trim_threshold);
#endif
}

}  // namespace mm::sim
