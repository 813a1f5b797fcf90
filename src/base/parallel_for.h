#pragma once
// A minimal parallel for: splits [0, count) into contiguous chunks, one per thread, and runs them
// on short-lived std::threads (the calling thread takes the first chunk). For coarse work only
// (whole image bands, milliseconds each): each call starts threads-1 threads (~tens of us).
#include <cstdint>
#include <functional>

namespace gbl {

// std::thread::hardware_concurrency(), at least 1.
int hardwareThreads();

// Calls fn(begin, end) on min(threads, count) disjoint chunks covering [0, count) (threads <= 0:
// hardwareThreads()), concurrently, and returns when all are done. Chunk sizes differ by at
// most one. The first exception thrown by any chunk is rethrown here, after all have finished.
void parallelFor(int64_t count, int threads, const std::function<void(int64_t begin, int64_t end)>& fn);

}  // namespace gbl
