#pragma once
// The best-fit normal table: CryEngine 3's pre-baked look-up (Kaplanyan, "CryENGINE 3: Reaching
// the Speed of Light", SIGGRAPH 2010 Advances course), generated here by one function and read
// by both encoders, encodeNormalBestFit in shaders/normal_encodings.glsl (uploaded as an SSBO, set 0,
// binding kBestFitTableBinding of every G-buffer pass) and its mirror in encodings.h.
//
// Texel (i, j), j <= i < 1024, of the triangle of q = n / max|n|'s middle and smallest |component|
// (mid in [i, i+1) / 1024, lo in [j, j+1) / 1024) holds (255 - k) / 2, k being the odd length of
// the major component that encodeNormalBestFitSearch (the 128-candidate search) picks for the
// texel's centre direction (mid, lo, 1) normalised. Signs and the order of the components do
// not change the best length (the rounding 2 floor(x / 2) + 1 is odd-symmetric), so the triangle
// covers the sphere. 525 312 entries, one byte each, 4 per uint32 (entry t in bits 8 (t % 4) of
// word t / 4): 513 KiB.
#include <cstdint>
#include <vector>

namespace gbl::enc {

inline constexpr uint32_t kBestFitTableSize = 1024;  // CryEngine's 1024 x 1024
static_assert(kBestFitTableSize % 2 == 0, "the generator takes the rows in pairs");
inline constexpr uint32_t kBestFitTableEntries = kBestFitTableSize * (kBestFitTableSize + 1) / 2;
inline constexpr uint32_t kBestFitTableBinding = 15;  // GBL_BEST_FIT_TABLE_BINDING in normal_encodings.glsl

// Generated on first use, about 0.1 s on the idle 2-core machine (0.4-0.9 s when it was loaded;
// tests/encoding BestFitTableHoldsTheSearchAtTexelCentres generates it again on 1 and 3 threads),
// deterministic: the same words on every machine and thread count (IEEE single precision, no FMA
// contraction). Waits for a generation that prefetchBestFitNormalTable started.
const std::vector<uint32_t>& bestFitNormalTable();
// Starts generating the table on a thread of its own (once per process; later calls do nothing),
// so that a command that will need it (a layout with best-fit normals) does not wait for it:
// about 105 ms on the 2-core machine, the largest part of a small compare's set-up.
void prefetchBestFitNormalTable();
// The generator itself (bestFitNormalTable() caches its result); `threads` 0 = all.
std::vector<uint32_t> generateBestFitNormalTable(int threads = 0);

}  // namespace gbl::enc
