#include "mrs_vpr/memory_reuse.hpp"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrs_vpr {

void retainFreedMemory() {
#if defined(__GLIBC__)
  // Blocks up to glibc's largest mmap threshold come from the heap, which is never trimmed below
  // what the process has needed, so freed query buffers are reused rather than refaulted.
  constexpr int kLargestHeapBlock = 32 * 1024 * 1024;
  mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 * 1024 * 1024);
#endif
}

}  // namespace mrs_vpr
