// scansurf: the allocator setting of scansurf/process.h.
#include "scansurf/process.h"

#include <climits>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace scansurf {

bool keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  // No mmap for large blocks (freeing one would unmap it), and no trimming of the heap's top.
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
#else
  return false;
#endif
}

}  // namespace scansurf
