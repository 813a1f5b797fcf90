#pragma once
// An integer avalanche hash for procedural content: every input bit affects every output bit, so
// lattice values look random yet are identical on every platform and build (no library random
// distributions, whose output the C++ standard leaves to the implementation).
#include <cstdint>

namespace gbl {

inline uint32_t integerHash(uint32_t x, uint32_t y, uint32_t seed) {
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

}  // namespace gbl
