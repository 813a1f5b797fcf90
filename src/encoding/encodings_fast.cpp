// encodeNormalBestFitFast. Why the codes equal encodeNormalBestFitSearch's for every input:
// - The reference evaluates 128 candidates i = 0..127 in order, each with the same float
//   expressions (k = 255 - 2i; d = 2 floor(q k / 2) + 1 per component; err = |d / |d| - n|^2) and
//   keeps the first one whose err is strictly below the best so far, starting from 8 and
//   (1, 1, 255). That is: the first index i whose err equals the minimum of the errs that are
//   below 8 (a NaN err is never below anything), or (1, 1, 255) when none is.
// - Here the same expressions, in the same order, are evaluated for all 128 candidates in a loop
//   the compiler vectorises (8 candidates per AVX2 instruction). Each lane performs the identical
//   IEEE-754 single-precision operations (+ - * / sqrt floor are correctly rounded, and
//   -ffp-contract=off forbids FMA), so every err is bit-identical to the reference's.
// - The first index of the minimum is then found lane-wise: lane l keeps the first candidate of
//   the subsequence l, l+8, l+16, ... with the smallest err (strict <, so earlier wins), and the
//   lanes are merged by (err, index). That is the same first-minimum. The winner's d is
//   recomputed with the reference's expressions and converted to codes as the reference does.
// - Non-finite inputs (never produced by the renderer) take the reference path unchanged, so
//   NaN and infinity behave exactly as in the reference (e.g. inf / inf = NaN in q).
#include "encodings_fast.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "engine_encodings.h"
#include "simd_clones.h"

// GCC only: clang 14 (the fuzz build's compiler) rejects __builtin_cpu_supports("f16c"); it takes
// the portable path, bit-identical by contract.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>
#define GBL_HAVE_F16C_PATH 1
#endif

namespace gbl::enc {

namespace {

constexpr int kCandidates = 128;
constexpr int kLanes = 8;

// Index of the winning candidate, or -1 when no err is below 8 (the reference keeps (1, 1, 255)).
GBL_SIMD_CLONES int bestCandidate(vec3 n, vec3 q) {
    alignas(32) float err[kCandidates];
    for (int i = 0; i < kCandidates; ++i) {
        float k = float(255 - 2 * i);
        float dx = 2.0f * floor(q.x * k * 0.5f) + 1.0f;
        float dy = 2.0f * floor(q.y * k * 0.5f) + 1.0f;
        float dz = 2.0f * floor(q.z * k * 0.5f) + 1.0f;
        float len = sqrt(dx * dx + dy * dy + dz * dz);
        float ex = dx / len - n.x;
        float ey = dy / len - n.y;
        float ez = dz / len - n.z;
        err[i] = ex * ex + ey * ey + ez * ez;
    }
    float laneErr[kLanes];
    int laneIndex[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        laneErr[l] = 8.0f;
        laneIndex[l] = -1;
    }
    for (int g = 0; g < kCandidates; g += kLanes)
        for (int l = 0; l < kLanes; ++l) {
            const bool better = err[g + l] < laneErr[l];
            laneErr[l] = better ? err[g + l] : laneErr[l];
            laneIndex[l] = better ? g + l : laneIndex[l];
        }
    int best = -1;
    float bestErr = 8.0f;
    for (int l = 0; l < kLanes; ++l)
        if (laneIndex[l] >= 0 && (laneErr[l] < bestErr || (laneErr[l] == bestErr && laneIndex[l] < best))) {
            bestErr = laneErr[l];
            best = laneIndex[l];
        }
    return best;
}

}  // namespace

uvec3 encodeNormalBestFitFast(vec3 n) {
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return encodeNormalBestFitSearch(n);
    // From here on, the reference's own statements.
    float m = max(abs(n.x), max(abs(n.y), abs(n.z)));
    if (!(m > 0.0f)) return uvec3(128u, 128u, 255u);
    vec3 q = vec3(n.x / m, n.y / m, n.z / m);
    const int i = bestCandidate(n, q);
    if (i < 0) return uvec3(128u, 128u, 255u);  // vec3(1, 1, 255), the reference's initial best
    float k = float(255 - 2 * i);
    float dx = 2.0f * floor(q.x * k * 0.5f) + 1.0f;
    float dy = 2.0f * floor(q.y * k * 0.5f) + 1.0f;
    float dz = 2.0f * floor(q.z * k * 0.5f) + 1.0f;
    return uvec3(uint(dx + 255.0f) >> 1u, uint(dy + 255.0f) >> 1u, uint(dz + 255.0f) >> 1u);
}

// encodeNormalBestFitRow. Pass 1 evaluates the reference's statements up to the texel index t
// for every lane, with the early return's condition kept as a mask; lanes it returns for get
// t = 0 and q = 0 (so every table read and every float-to-uint conversion stays defined) and have
// their codes replaced by its (128, 128, 255) in pass 3. Pass 2 reads the table alone (GCC 12
// issues no hardware gather for the generic tuning: the AVX2 clone assembles the lanes from
// scalar loads, the baseline stays scalar), so it holds the other two passes back no more.
// Pass 3 is the reference's rest. Each lane performs the reference's
// IEEE-754 operations in its order (no FMA: -ffp-contract=off), so the codes are identical;
// tests/encoding/encodings_fast_test.cpp compares them on random and adversarial normals.
// The passes meet in local arrays (GCC 12 drops `restrict` in target_clones clones, and a local
// array cannot alias the table); the last pass, which reads no table, writes the codes out.
GBL_SIMD_CLONES_AVX512 void encodeNormalBestFitRow(int n, const float* x, const float* y, const float* z,
                                                   const uint32_t* table, uint32_t* c0, uint32_t* c1, uint32_t* c2) {
    constexpr int kChunk = 128;
    alignas(32) float qx[kChunk], qy[kChunk], qz[kChunk];
    alignas(32) uint32_t t[kChunk], valid[kChunk], entry[kChunk];
    for (int at = 0; at < n; at += kChunk) {
        const int count = std::min(kChunk, n - at);
        const float* __restrict px = x + at;
        const float* __restrict py = y + at;
        const float* __restrict pz = z + at;
        for (int j = 0; j < count; ++j) {
            const float nx = px[j], ny = py[j], nz = pz[j];
            const float m = max(abs(nx), max(abs(ny), abs(nz)));
            const bool ok = !(!(m > 0.0f) || std::isinf(m) || std::isnan(nx) || std::isnan(ny) || std::isnan(nz));
            const float d = ok ? m : 1.0f;
            const float vx = ok ? nx / d : 0.0f, vy = ok ? ny / d : 0.0f, vz = ok ? nz / d : 0.0f;
            const float ax = abs(vx), ay = abs(vy), az = abs(vz);
            const float lo = min(ax, min(ay, az));
            const float mid = max(min(ax, ay), min(max(ax, ay), az));
            const uint i = min(uint(mid * float(kBestFitTableSize)), kBestFitTableSize - 1u);
            const uint jj = min(uint(lo * float(kBestFitTableSize)), kBestFitTableSize - 1u);
            qx[j] = vx;
            qy[j] = vy;
            qz[j] = vz;
            t[j] = i * (i + 1u) / 2u + jj;
            valid[j] = ok ? 1u : 0u;
        }
        gatherBytes(count, t, table, entry);
        // Straight into c0..c2: this pass reads only local arrays (no table), so GCC's alias
        // checks between the three outputs are all the dropped `restrict` costs.
        uint32_t* o0 = c0 + at;
        uint32_t* o1 = c1 + at;
        uint32_t* o2 = c2 + at;
        for (int j = 0; j < count; ++j) {
            const float k = float(255u - 2u * entry[j]);
            const float dx = 2.0f * floor(qx[j] * k * 0.5f) + 1.0f;
            const float dy = 2.0f * floor(qy[j] * k * 0.5f) + 1.0f;
            const float dz = 2.0f * floor(qz[j] * k * 0.5f) + 1.0f;
            const bool ok = valid[j] != 0u;
            o0[j] = ok ? uint(dx + 255.0f) >> 1u : 128u;
            o1[j] = ok ? uint(dy + 255.0f) >> 1u : 128u;
            o2[j] = ok ? uint(dz + 255.0f) >> 1u : 255u;
        }
    }
}

// encodeSrgb8Fast. The reference's binary search returns the number of thresholds <= x (they
// increase strictly; NaN compares false everywhere and gives 0). For x in [first, last), x > 0
// and finite, so its bits order like its value. Its bucket b = bits >> 16 spans the floats with
// those upper bits; `base` counts the thresholds below the bucket, and a threshold inside it (at
// most one, checked here) has the same upper bits, so it is <= x exactly when its low 16 bits are
// <= x's. Count = base + that comparison. Outside [first, last) the count is 0 or 255.
// encodeGamma22 is the same binary search over its own 255 thresholds, so the same table form
// serves it: the thresholds ((i + 0.5) / 255)^2.2 are at least 0.86 % apart (the top two), a
// bucket at most 2^-7 = 0.79 % wide (the build below throws otherwise).
namespace {

Srgb8EncodeTable thresholdTable(const float (&thresholds)[255], std::vector<uint32_t>& v) {
    constexpr int k = Srgb8EncodeTable::kShift;
    const uint32_t first = floatBitsToUint(thresholds[0]) >> k;
    const uint32_t last = floatBitsToUint(thresholds[254]) >> k;
    size_t below = 0;  // thresholds below the current bucket
    for (uint32_t b = first; b <= last; ++b) {
        while (below < 255 && (floatBitsToUint(thresholds[below]) >> k) < b) ++below;
        size_t inside = below;
        while (inside < 255 && (floatBitsToUint(thresholds[inside]) >> k) == b) ++inside;
        if (inside - below > 1) throw std::logic_error("thresholdTable: two thresholds in one bucket");
        const uint32_t cut = inside > below ? (floatBitsToUint(thresholds[below]) & 0xffffu) : 0x10000u;
        v.push_back(uint32_t(below) | (cut << 8));
    }
    return Srgb8EncodeTable{first, last, thresholds[0], thresholds[254], v.data()};
}

}  // namespace

namespace {

void encodeFloat16RowPortable(int n, const float* in, uint32_t* out) {
    for (int j = 0; j < n; ++j) out[j] = encodeFloat16Fast(in[j]);
}

#if defined(GBL_HAVE_F16C_PATH)
__attribute__((target("avx2,f16c"))) void encodeFloat16RowF16c(int n, const float* in, uint32_t* out) {
    const __m256i absMask = _mm256_set1_epi32(0x7fffffff);
    const __m256i saturateFrom = _mm256_set1_epi32(0x477fefff);  // compared with >: a >= 0x477ff000
    const __m256i signMask = _mm256_set1_epi32(0x8000);
    const __m256i maxFinite = _mm256_set1_epi32(0x7bff);
    int j = 0;
    for (; j + 8 <= n; j += 8) {
        const __m256 x = _mm256_loadu_ps(in + j);
        const __m256i bits = _mm256_castps_si256(x);
        const __m256i half = _mm256_cvtepu16_epi32(_mm256_cvtps_ph(x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
        // Signed compare is exact here: the magnitudes are below 2^31.
        const __m256i saturate = _mm256_cmpgt_epi32(_mm256_and_si256(bits, absMask), saturateFrom);
        const __m256i saturated = _mm256_or_si256(_mm256_and_si256(_mm256_srli_epi32(bits, 16), signMask), maxFinite);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + j), _mm256_blendv_epi8(half, saturated, saturate));
    }
    for (; j < n; ++j) out[j] = encodeFloat16Fast(in[j]);
}
#endif

using Float16RowFn = void (*)(int, const float*, uint32_t*);

Float16RowFn pickFloat16Row() {
#if defined(GBL_HAVE_F16C_PATH)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("f16c")) return encodeFloat16RowF16c;
#endif
    return encodeFloat16RowPortable;
}

}  // namespace

void encodeFloat16Row(int n, const float* in, uint32_t* out) {
    static const Float16RowFn fn = pickFloat16Row();
    fn(n, in, out);
}

// Scalar on purpose (encodings_fast.h): no vectorisation, unrolled so the loads stream.
#if defined(__GNUC__) && !defined(__clang__)
#define GBL_SCALAR_LOADS __attribute__((optimize("no-tree-vectorize")))
#else
#define GBL_SCALAR_LOADS
#endif

GBL_SCALAR_LOADS void gatherWords(int n, const uint32_t* index, const uint32_t* table, uint32_t* out) {
#pragma GCC unroll 4
    for (int j = 0; j < n; ++j) out[j] = table[index[j]];
}

GBL_SCALAR_LOADS void gatherBytes(int n, const uint32_t* index, const uint32_t* table, uint32_t* out) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(table);  // byte i = entry i
#pragma GCC unroll 4
    for (int j = 0; j < n; ++j) out[j] = bytes[index[j]];
#else
    for (int j = 0; j < n; ++j) out[j] = (table[index[j] >> 2u] >> ((index[j] & 3u) * 8u)) & 0xffu;
#endif
}

const Srgb8EncodeTable& srgb8EncodeTable() {
    static std::vector<uint32_t> entries;
    static const Srgb8EncodeTable table = thresholdTable(kSrgbEncodeThresholds, entries);
    return table;
}

const Srgb8EncodeTable& srgbFastHdrpEncodeTable() {
    static std::vector<uint32_t> entries;
    static const Srgb8EncodeTable table = thresholdTable(kSrgbFastHdrpEncodeThresholds, entries);
    return table;
}

const Srgb8EncodeTable& unormSqrtEncodeTable() {
    static std::vector<uint32_t> entries;
    static const Srgb8EncodeTable table = thresholdTable(kUnormSqrtEncodeThresholds, entries);
    return table;
}

const Srgb8EncodeTable& gamma22EncodeTable() {
    static std::vector<uint32_t> entries;
    static const Srgb8EncodeTable table = thresholdTable(kGamma22EncodeThresholds, entries);
    return table;
}

}  // namespace gbl::enc
