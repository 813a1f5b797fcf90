#pragma once
// How the C library's allocator treats the frame-sized images compare allocates and frees by
// the hundred (a 1080p RGBA float image is 33 MB, a run's decoded surfaces 158 MB).
//
// By default glibc returns freed memory above its dynamic mmap threshold to the kernel (unmapped,
// or trimmed off the heap's top), so the next run's images fault every page in again, zeroed by
// the kernel: a warm 1080p compare of 6 layouts x 3 views on lavapipe took about 1.1 million
// minor faults (2.2 s of system time on 2 cores). Retained, a freed image's pages serve the next
// image of its size without a fault.
//
// retainHostBlocks(): blocks up to 32 MiB (every 1080p image) come from the heap, and freed
// memory is never trimmed. The peak is what is live at once plus
// fragmentation, and memory freed after it is kept until exit, so compare asks for it only for
// whole frames: in bands (4K on a CPU device) the peak is a goal (bench/RESULTS.md: retained,
// a 4K compare of 3 layouts in bands peaked at 1,093,396 KiB against 938,304 KiB).
// GBL_RETAIN_HOST_BLOCKS=1 / 0 overrides the choice (measurements).
namespace gbl {

// Applies the policy (true: retain; false: leave the C library's default) unless
// GBL_RETAIN_HOST_BLOCKS says otherwise; returns whether blocks are retained. Call before the
// large allocations.
bool retainHostBlocks(bool wanted);

}  // namespace gbl
