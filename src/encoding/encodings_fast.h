#pragma once
// CPU-only fast variants of encoders of src/encoding/encodings.h, returning the reference's codes for
// every input (the reference stays the mirror of shaders/encodings.glsl; the GPU runs that one).
// The CPU codec (src/codec/cpu_codec.h) uses these. Why each is identical is argued in
// encodings_fast.cpp; tests/codec/cpu_codec_test.cpp compares them with the reference on millions of
// random and adversarial inputs.
#include <cstdint>

#include "encodings.h"

namespace gbl::enc {

// encodeNormalBestFitSearch's codes: the same 128-candidate search, vectorised over the candidates
// (it generates the best-fit table, best_fit_normals.h, and stays the reference tests measure it by).
uvec3 encodeNormalBestFitFast(vec3 n);

// encodeNormalBestFit(vec3(x[j], y[j], z[j]), table)'s codes for j < n, into c0 / c1 / c2. The
// per-normal function does not vectorise (its early return for zero and non-finite input, and the
// table read, which GCC 12 will not gather for the generic x86-64 tuning), so a block is done in
// three passes: the vectorised arithmetic up to the texel index, the table reads alone, then the
// vectorised rest. The same operations in the same order (identical codes; why: in
// encodings_fast.cpp); the early return becomes a select of its codes.
void encodeNormalBestFitRow(int n, const float* x, const float* y, const float* z, const uint32_t* table, uint32_t* c0,
                            uint32_t* c1, uint32_t* c2);

// encodeSrgb8's codes (the number of kSrgbEncodeThresholds <= x) from one table look-up instead
// of 8 dependent binary-search steps. The table has an entry per 2^-7 relative step of float
// (bits >> 16) between the first and the last threshold; no such bucket holds two thresholds
// (their relative spacing is >= 0.89 %, a bucket's <= 0.79 %; srgb8EncodeTable() checks it).
// Identical for all 2^32 float bit patterns (checked exhaustively once; the test samples it).
struct Srgb8EncodeTable {
    static constexpr int kShift = 16;  // bucket = float bits >> kShift (exponent + 7 mantissa bits)
    uint32_t firstBucket = 0;
    uint32_t lastBucket = 0;
    float first = 0.0f;  // kSrgbEncodeThresholds[0]
    float last = 0.0f;   // kSrgbEncodeThresholds[254]
    // Per bucket: bits 0-7 the number of thresholds below the bucket; bits 8-24 the low 16 bits
    // of the threshold inside the bucket, or 0x10000 (never reached) when there is none.
    const uint32_t* entries = nullptr;
};
const Srgb8EncodeTable& srgb8EncodeTable();
// The same form for encodeGamma22's thresholds (kGamma22EncodeThresholds): encodeSrgb8Fast(x,
// gamma22EncodeTable()) == encodeGamma22(x) for every float (a table per threshold array).
const Srgb8EncodeTable& gamma22EncodeTable();
// And for HDRP's fast sRGB (kSrgbFastHdrpEncodeThresholds, engine_encodings.h), which codes |x|:
// encodeSrgb8Fast(|x|, srgbFastHdrpEncodeTable()) == encodeSrgb8FastHdrp(x) for every float. Its
// thresholds follow the same 1.055 x^(1/2.4) - 0.055 power segment as sRGB's upper part, so they
// are as far apart (the build throws otherwise).
const Srgb8EncodeTable& srgbFastHdrpEncodeTable();
// And for unorm_sqrt (kUnormSqrtEncodeThresholds, ((i + 0.5) / 255)^2, engine_encodings.h):
// encodeSrgb8Fast(x, unormSqrtEncodeTable()) == encodeUnormSqrt(x) for every float. Its top two
// thresholds are 0.79 % apart, a bucket at most 0.78 % wide: one threshold a bucket still holds.
const Srgb8EncodeTable& unormSqrtEncodeTable();

// out[j] = table[index[j]] (gatherWords) and out[j] = the byte index[j] of `table` read as
// bytes in little-endian word order, i.e. (table[i / 4] >> 8 (i % 4)) & 0xff (gatherBytes), for
// j < n, by plain scalar loads. Neither the generic tuning nor x86-64-v3/v4 gives GCC a hardware
// gather, so a vectorised loop assembles each vector from scalar loads with lane inserts and
// extracts, all on the vector shuffle ports; split out as a pass of their own, the loads issue on
// the load ports instead (measured: the srgb8 codes of a row in about half the time, Zen 4).
void gatherWords(int n, const uint32_t* index, const uint32_t* table, uint32_t* out);
void gatherBytes(int n, const uint32_t* index, const uint32_t* table, uint32_t* out);

// Branch-free (the bucket is clamped so every input reads a valid entry), so loops vectorise.
inline uint encodeSrgb8Fast(float x, const Srgb8EncodeTable& t) {
    const uint bits = floatBitsToUint(x);
    const uint bucket = min(max(bits >> Srgb8EncodeTable::kShift, t.firstBucket), t.lastBucket) - t.firstBucket;
    const uint32_t e = t.entries[bucket];
    const uint inside = (e & 0xffu) + ((bits & 0xffffu) >= (e >> 8) ? 1u : 0u);
    // Below every threshold (also -0, negatives, NaN): 0; at or above the last: 255.
    return x >= t.last ? 255u : (x >= t.first ? inside : 0u);
}

// encodeSrgb8Fast in the three passes of a row: the bucket (srgb8Bucket, vectorised), its entry
// (gatherWords) and the code from it (srgb8FromEntry, vectorised). The same statements.
inline uint srgb8Bucket(float x, const Srgb8EncodeTable& t) {
    return min(max(floatBitsToUint(x) >> Srgb8EncodeTable::kShift, t.firstBucket), t.lastBucket) - t.firstBucket;
}
inline uint srgb8FromEntry(float x, uint32_t e, const Srgb8EncodeTable& t) {
    const uint inside = (e & 0xffu) + ((floatBitsToUint(x) & 0xffffu) >= (e >> 8) ? 1u : 0u);
    return x >= t.last ? 255u : (x >= t.first ? inside : 0u);
}

// encodeSmallFloatMagnitude's code, branch-free so that loops over it vectorise: its three
// outcomes (overflow, normal, subnormal) are all computed and one is selected. The subnormal
// shift is clamped to [1, 25], which keeps every shift defined and changes nothing: where the
// reference returns 0 (shift > 24), a shift of 25 gives 0 too (mantissa < 2^24, no round-up).
// Identical for every a < 2^31 (checked exhaustively once; tests/codec/cpu_codec_test.cpp samples it).
inline uint encodeSmallFloatMagnitudeFast(uint a, uint mantissaBits) {
    uint shift = 23u - mantissaBits;
    uint maxFinite = (30u << mantissaBits) | ((1u << mantissaBits) - 1u);
    uint overflow = 0x47000000u | (((2u << mantissaBits) - 1u) << (shift - 1u));
    uint odd = (a >> shift) & 1u;
    uint normal = (a - 0x38000000u + ((1u << (shift - 1u)) - 1u) + odd) >> shift;
    uint e = a >> 23u;
    uint sub = min(max(136u - mantissaBits - e, 1u), 25u);
    uint m = (a & 0x7fffffu) | 0x800000u;
    uint q = m >> sub;
    uint rem = m & ((1u << sub) - 1u);
    uint halfway = 1u << (sub - 1u);
    uint subnormal = q + ((rem > halfway || (rem == halfway && (q & 1u) == 1u)) ? 1u : 0u);
    return a >= overflow ? maxFinite : (a >= 0x38800000u ? normal : subnormal);
}

// encodeFloat16 / encodeFloat11 / encodeFloat10 with the branch-free magnitude (same text otherwise).
inline uint encodeFloat16Fast(float x) {
    uint a = floatBitsToUint(x);
    uint sign = (a >> 16u) & 0x8000u;
    return sign | encodeSmallFloatMagnitudeFast(a & 0x7fffffffu, 10u);
}
inline uint encodeFloat11Fast(float x) {
    uint a = floatBitsToUint(x);
    return a >= 0x80000000u ? 0u : encodeSmallFloatMagnitudeFast(a, 6u);
}
inline uint encodeFloat10Fast(float x) {
    uint a = floatBitsToUint(x);
    return a >= 0x80000000u ? 0u : encodeSmallFloatMagnitudeFast(a, 5u);
}

// encodeFloat16Fast(in[j]) for j < n into out. On a CPU with F16C (every x86-64-v3 one) by the
// hardware conversion VCVTPS2PH, 8 at a time: IEEE round to nearest even with subnormals, as the
// reference (its explicit rounding mode, not MXCSR's), then the reference's saturation: a
// magnitude that rounds to infinity (>= 65520, bits 0x477ff000) and infinity and NaN give the
// largest finite half, 0x7bff, with the sign, instead of infinity or NaN. Elsewhere the portable
// loop. Identical codes (tests/encoding/encodings_fast_test.cpp: every float of 2^32 whose low
// bits are sampled, and the rounding points of every exponent).
void encodeFloat16Row(int n, const float* in, uint32_t* out);

}  // namespace gbl::enc
