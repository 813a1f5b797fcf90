#pragma once
// Helpers for loops that stream whole images through memory in blocks.
//
// streamCopy: memcpy for output written once and not read again soon (whole images). On x86-64
// it uses non-temporal stores, which skip each destination cache line's read-for-ownership: for
// a streaming writer that read costs as much memory traffic as the write itself. Call
// streamFence() when done, before the memory is handed to another thread (non-temporal stores
// are weakly ordered).
//
// prefetchAhead: asks for the cache lines `bytes` from p, kPrefetchAhead bytes further on (for a
// loop reading p sequentially: spread over the loop, the requests keep ahead of it). Without it
// each first touch of a line stalls the loop; the hardware prefetcher alone falls behind.
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gbl {

inline void streamCopy(void* dst, const void* src, size_t bytes) {
#if defined(__SSE2__)
    auto* d = static_cast<unsigned char*>(dst);
    const auto* s = static_cast<const unsigned char*>(src);
    const size_t head = (16 - reinterpret_cast<uintptr_t>(d) % 16) % 16;
    if (bytes < head + 16) {
        std::memcpy(d, s, bytes);
        return;
    }
    std::memcpy(d, s, head);
    d += head;
    s += head;
    bytes -= head;
    for (; bytes >= 16; bytes -= 16, d += 16, s += 16)
        _mm_stream_si128(reinterpret_cast<__m128i*>(d), _mm_loadu_si128(reinterpret_cast<const __m128i*>(s)));
    std::memcpy(d, s, bytes);
#else
    std::memcpy(dst, src, bytes);
#endif
}

inline void streamFence() {
#if defined(__SSE2__)
    _mm_sfence();
#endif
}

inline constexpr size_t kPrefetchAhead = 16384;

inline void prefetchAhead(const void* p, size_t bytes) {
    // Integer arithmetic: the lines ahead may lie past the end of the array (prefetches never fault).
    const uintptr_t from = reinterpret_cast<uintptr_t>(p) + kPrefetchAhead;
    for (size_t o = 0; o < bytes; o += 64) __builtin_prefetch(reinterpret_cast<const void*>(from + o), 0, 3);
}

}  // namespace gbl
