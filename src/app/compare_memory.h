#pragma once
// The host memory `compare` takes at its peak on a CPU device (lavapipe: device memory is host
// memory), from the frame, its bands and the number of layouts: checked against the budget
// (memory_budget.h) before the first render, so that a --size too large for the machine is one
// line naming the fix instead of a process killed half way. Constants measured in
// compare_memory.cpp.
#include <cstddef>
#include <cstdint>

namespace gbl::compare {

// bandImageRows: the rows of one band's images (the band and its FLIP halo); 0: whole frames.
// temporalFrames: compare --temporal N (the accumulators of N > 1; the same for every N).
double compareMemoryBytes(uint32_t width, uint32_t height, uint32_t bandImageRows, size_t layouts, int views,
                          int temporalFrames = 1);

}  // namespace gbl::compare
