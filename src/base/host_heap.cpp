#include "host_heap.h"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace gbl {

bool retainLargeBlocks(bool wanted) {
    if (const char* v = std::getenv("GBL_HOST_HEAP"); v && *v) {
        if (std::strcmp(v, "retain") == 0) wanted = true;
        if (std::strcmp(v, "default") == 0) wanted = false;
    }
#if defined(__GLIBC__)
    if (!wanted) return false;
    // Blocks below 1 GiB from the heap, and no trimming of its top: freed images stay mapped.
    return mallopt(M_MMAP_THRESHOLD, 1 << 30) == 1 && mallopt(M_TRIM_THRESHOLD, -1) == 1;
#else
    return false;
#endif
}

}  // namespace gbl
