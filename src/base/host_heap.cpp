#include "host_heap.h"

#include "env_flag.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace gbl {

bool retainHostBlocks(bool wanted) {
    wanted = envChoice("GBL_RETAIN_HOST_BLOCKS").value_or(wanted);
#if defined(__GLIBC__)
    if (!wanted) return false;
    // 32 MiB: every 1080p image (a 4K one, 133 MB, is still mapped and unmapped: on an H200 a
    // threshold of 1 GiB did not make the 4K compare faster: 59e738b, 2026-11-25).
    const bool threshold = mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1;
    const bool trim = mallopt(M_TRIM_THRESHOLD, -1) == 1;  // never give the heap's top back
    return threshold && trim;
#else
    return false;
#endif
}

}  // namespace gbl
