#pragma once
// How the C library's allocator treats the large images a command allocates and frees by the
// dozen (a 4K RGBA float image is 133 MB).
//
// glibc serves every block above its mmap threshold (at most 32 MiB) with a fresh mmap and
// unmaps it on free, so each 4K image's every page faults in, zeroed by the kernel, on first
// touch: a 4K compare of the four seed layouts on an H200 took 726,647 minor page faults (2.8 GB),
// and a run's 133 MB HDR download took 100 ms. Retained, freed blocks are reused by the next
// image of the same size without a fault.
//
// retainLargeBlocks(): large blocks come from the heap and freed memory is kept for reuse (no
// trimming). Peak memory is what is live at once, as before, but memory freed after the peak is
// not returned until exit. compare uses it on a GPU device; on a CPU device (lavapipe), whose
// 4K peak in bands is a goal measured with the default policy, it keeps the default.
// GBL_HOST_HEAP=retain / default overrides the choice (measurements).
namespace gbl {

// Applies the policy (true: retain; false: the C library's default) unless GBL_HOST_HEAP says
// otherwise; returns whether large blocks are retained. Call before the large allocations.
bool retainLargeBlocks(bool wanted);

}  // namespace gbl
