// The fast encoder variants the CPU codec uses (src/encoding/encodings_fast.h: the vectorised
// best-fit normal search, the best-fit table look-up a row at a time, branch-free sRGB, table
// small floats, float16 by F16C) return the reference encoders' codes
// (src/encoding/encodings.h) for millions of random and adversarial inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "encodings.h"
#include "encodings_fast.h"
#include "engine_encodings.h"

namespace gbl {
namespace {

// ---------------------------------------------------------------------------------------------
// Best-fit normals: the vectorised search returns the reference's codes.

// Counts normals whose codes differ; reports the first few.
size_t compareBestFit(const std::vector<glm::vec3>& normals, const char* what) {
    size_t bad = 0;
    for (const glm::vec3& n : normals) {
        const glm::uvec3 fast = enc::encodeNormalBestFitFast(n), ref = enc::encodeNormalBestFitSearch(n);
        if (fast != ref && bad++ < 5)
            ADD_FAILURE() << what << ": n = (" << n.x << ", " << n.y << ", " << n.z << "): fast " << fast.x << " "
                          << fast.y << " " << fast.z << ", reference " << ref.x << " " << ref.y << " " << ref.z;
    }
    std::printf("[ bestfit  ] %-44s %8zu normals, %zu differ\n", what, normals.size(), bad);
    return bad;
}

TEST(NormalBestFitFast, SameCodesAsTheReferenceOnRandomNormals) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> normals(2000000);
    for (glm::vec3& n : normals) {  // uniform on the sphere, as in the renderer
        const float z = 1.0f - 2.0f * u(rng), phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        n = glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
    EXPECT_EQ(compareBestFit(normals, "uniform on the sphere"), 0u);
}

TEST(NormalBestFitFast, SameCodesAsTheReferenceOnAdversarialNormals) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> special;
    // Axes, face diagonals, body diagonals, in every sign, unit and not, and with -0.
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                const glm::vec3 d = glm::vec3(x, y, z);
                for (float scale : {1.0f, 0.5f, 3.0f, 1e-20f, 1e20f, 1.0f / std::sqrt(glm::dot(d, d) + 1e-30f)})
                    special.push_back(d * scale);
            }
    special.push_back(glm::vec3(-0.0f, -0.0f, 1.0f));
    special.push_back(glm::vec3(0.0f, -0.0f, -0.0f));  // zero: the reference returns (128, 128, 255)
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float tiny = std::numeric_limits<float>::denorm_min(), big = std::numeric_limits<float>::max();
    for (const glm::vec3& n : {glm::vec3(inf, 0, 0), glm::vec3(-inf, inf, 1), glm::vec3(nan, 0, 1),
                               glm::vec3(0, nan, nan), glm::vec3(tiny, tiny, tiny), glm::vec3(tiny, 0, -tiny),
                               glm::vec3(big, big, -big), glm::vec3(big, 1, 0)})
        special.push_back(n);
    EXPECT_EQ(compareBestFit(special, "axes, diagonals, zero, non-finite"), 0u);

    // Directions of integer vectors (lattice rays hit several candidates exactly: near-ties),
    // and the decoded direction of every 24th code (the search's own fixed points), each with
    // its float neighbours.
    std::vector<glm::vec3> lattice;
    for (int x = -12; x <= 12; ++x)
        for (int y = -12; y <= 12; ++y)
            for (int z = -12; z <= 12; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                const glm::vec3 d = glm::normalize(glm::vec3(x, y, z));
                lattice.push_back(d);
                lattice.push_back(glm::vec3(std::nextafter(d.x, 2.0f), d.y, std::nextafter(d.z, -2.0f)));
                lattice.push_back(glm::vec3(d.x, std::nextafter(d.y, -2.0f), std::nextafter(d.z, 2.0f)));
            }
    for (uint32_t c = 0; c < (1u << 24); c += 24) {
        const glm::vec3 d = enc::decodeNormalBestFit(glm::uvec3(c & 255u, (c >> 8) & 255u, c >> 16));
        lattice.push_back(d);
        lattice.push_back(glm::vec3(std::nextafter(d.x, 2.0f), std::nextafter(d.y, -2.0f), d.z));
    }
    EXPECT_EQ(compareBestFit(lattice, "lattice rays, decoded codes, +-1 ulp"), 0u);

    // Near-ties by construction: midway between the directions of two neighbouring codes, where
    // two candidates' errors agree to the last bits; and tiny random offsets from the axes.
    std::vector<glm::vec3> ties;
    for (int i = 0; i < 300000; ++i) {
        const glm::uvec3 c(uint32_t(u(rng) * 255.0f), uint32_t(u(rng) * 255.0f), uint32_t(u(rng) * 255.0f));
        glm::uvec3 d = c;
        d[int(u(rng) * 3.0f) % 3] += 1u;
        const glm::vec3 a = enc::decodeNormalBestFit(c), b = enc::decodeNormalBestFit(glm::min(d, glm::uvec3(255u)));
        ties.push_back(glm::normalize(a + b));
        ties.push_back(a + b);  // not unit: the search compares against n itself
    }
    for (int i = 0; i < 300000; ++i) {
        glm::vec3 n(0.0f);
        n[i % 3] = i % 2 ? 1.0f : -1.0f;
        n += glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f) * std::ldexp(1.0f, -int(u(rng) * 24.0f));
        ties.push_back(n);
    }
    EXPECT_EQ(compareBestFit(ties, "midpoints of neighbouring codes, near axes"), 0u);
}

// ---------------------------------------------------------------------------------------------
// Best-fit normals by table, a row at a time (the CPU codec's encodeNormalBestFitRow) against the
// per-normal mirror of the shader (encodeNormalBestFit(n, table)).

size_t compareBestFitRow(const std::vector<glm::vec3>& normals, const char* what) {
    const uint32_t* table = enc::bestFitNormalTable().data();
    std::vector<float> x, y, z;
    for (const glm::vec3& n : normals) {
        x.push_back(n.x);
        y.push_back(n.y);
        z.push_back(n.z);
    }
    const int count = int(normals.size());
    std::vector<uint32_t> c0(normals.size()), c1(normals.size()), c2(normals.size());
    enc::encodeNormalBestFitRow(count, x.data(), y.data(), z.data(), table, c0.data(), c1.data(), c2.data());
    size_t bad = 0;
    for (size_t i = 0; i < normals.size(); ++i) {
        const glm::uvec3 ref = enc::encodeNormalBestFit(normals[i], table), row(c0[i], c1[i], c2[i]);
        if (row != ref && bad++ < 5)
            ADD_FAILURE() << what << ": n = (" << normals[i].x << ", " << normals[i].y << ", " << normals[i].z
                          << "): row " << row.x << " " << row.y << " " << row.z << ", reference " << ref.x << " "
                          << ref.y << " " << ref.z;
    }
    std::printf("[ bestfit  ] row: %-39s %8zu normals, %zu differ\n", what, normals.size(), bad);
    return bad;
}

TEST(NormalBestFitRow, SameCodesAsThePerNormalLookUp) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    // Uniform on the sphere, an odd count (the last block is partial).
    std::vector<glm::vec3> normals(1000003);
    for (glm::vec3& n : normals) {
        const float zz = 1.0f - 2.0f * u(rng), phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - zz * zz));
        n = glm::vec3(r * std::cos(phi), r * std::sin(phi), zz);
    }
    EXPECT_EQ(compareBestFitRow(normals, "uniform on the sphere"), 0u);

    // Texel edges: mid and lo at and beside i / 1024 (the index's rounding), in every sign and
    // order of the components, not unit; and the early return's inputs mixed into a block.
    std::vector<glm::vec3> edges;
    for (int i = 0; i <= 1024; i += 7)
        for (int j = 0; j <= i; j += 13) {
            const float mid = float(i) / 1024.0f, lo = float(j) / 1024.0f;
            for (float dm : {-1.0f, 0.0f, 1.0f}) {
                const float m = dm == 0.0f ? mid : std::nextafter(mid, dm * 2.0f);
                edges.push_back(glm::vec3(m, lo, 1.0f));
                edges.push_back(glm::vec3(-lo, 2.0f, -m) * 0.75f);
                edges.push_back(glm::vec3(-3.0f, std::nextafter(lo, 2.0f), m));
            }
        }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float tiny = std::numeric_limits<float>::denorm_min(), big = std::numeric_limits<float>::max();
    const glm::vec3 specials[] = {glm::vec3(0.0f),         glm::vec3(-0.0f, 0.0f, -0.0f), glm::vec3(inf, 0, 0),
                                  glm::vec3(-inf, inf, 1), glm::vec3(nan, 0, 1),          glm::vec3(0, nan, nan),
                                  glm::vec3(0, 0, nan),    glm::vec3(tiny, tiny, tiny),   glm::vec3(tiny, 0, -tiny),
                                  glm::vec3(big, big, -big), glm::vec3(big, 1, 0),        glm::vec3(0, 0, -1)};
    for (size_t k = 0; k < edges.size(); k += 37) edges.insert(edges.begin() + long(k), specials[(k / 37) % 12]);
    EXPECT_EQ(compareBestFitRow(edges, "texel edges, zero, non-finite"), 0u);
}

// ---------------------------------------------------------------------------------------------
// sRGB and small-float encoders: branch-free / table variants with the reference's codes. Both were
// compared once on all 2^32 float bit patterns (0 differ); here: every place where the code steps
// (each sRGB threshold, each bucket edge, each small-float exponent and rounding boundary) with
// its float neighbours, a sweep over the whole bit range, and the special values.

std::vector<float> floatSweep() {
    std::vector<float> v;
    for (uint64_t bits = 0; bits < (uint64_t(1) << 32); bits += 4099) v.push_back(enc::uintBitsToFloat(uint32_t(bits)));
    const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max(),
                              65504.0f, 65519.996f, 65520.0f, 65024.0f, 64512.0f};
    v.insert(v.end(), std::begin(specials), std::end(specials));
    return v;
}

// x and its float neighbours, `ulps` each way.
void addNeighbours(std::vector<float>& v, float x, int ulps) {
    float lo = x, hi = x;
    v.push_back(x);
    for (int i = 0; i < ulps; ++i) {
        lo = std::nextafter(lo, -std::numeric_limits<float>::infinity());
        hi = std::nextafter(hi, std::numeric_limits<float>::infinity());
        v.push_back(lo);
        v.push_back(hi);
    }
}

TEST(Srgb8EncodeFast, SameCodesAsTheReference) {
    std::vector<float> xs = floatSweep();
    for (float t : enc::kSrgbEncodeThresholds) addNeighbours(xs, t, 4);
    const enc::Srgb8EncodeTable& table = enc::srgb8EncodeTable();
    for (uint32_t b = table.firstBucket; b <= table.lastBucket + 1; ++b)
        addNeighbours(xs, enc::uintBitsToFloat(b << enc::Srgb8EncodeTable::kShift), 2);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    for (int i = 0; i < 2000000; ++i) xs.push_back(u(rng));
    size_t bad = 0;
    for (float x : xs)
        if (enc::encodeSrgb8Fast(x, table) != enc::encodeSrgb8(x) && bad++ < 5)
            ADD_FAILURE() << "x = " << x << " (bits 0x" << std::hex << enc::floatBitsToUint(x) << std::dec
                          << "): fast " << enc::encodeSrgb8Fast(x, table) << ", reference " << enc::encodeSrgb8(x);
    std::printf("[ srgb8    ] %zu values, %zu differ\n", xs.size(), bad);
    EXPECT_EQ(bad, 0u);
}

// The sRGB table form (encodings_fast.h) over another curve's 255 thresholds against the
// reference's binary search `ref`: the sweep, each threshold's neighbours, every bucket edge, every
// 5th float of the range the table spans (about 30M), and each value's negative; with `magnitude`
// the table reads |x| (HDRP's fast sRGB codes the magnitude).
void expectTableForm(const float (&thresholds)[255], const enc::Srgb8EncodeTable& table, uint (*ref)(float),
                       bool magnitude, const char* name) {
    std::vector<float> xs = floatSweep();
    for (float t : thresholds) addNeighbours(xs, t, 4);
    for (uint32_t b = table.firstBucket; b <= table.lastBucket + 1; ++b)
        addNeighbours(xs, enc::uintBitsToFloat(b << enc::Srgb8EncodeTable::kShift), 2);
    size_t bad = 0, count = 0;
    auto check = [&](float x) {
        ++count;
        const uint fast = enc::encodeSrgb8Fast(magnitude ? std::fabs(x) : x, table), want = ref(x);
        if (fast != want && bad++ < 5)
            ADD_FAILURE() << name << ": x = " << x << " (bits 0x" << std::hex << enc::floatBitsToUint(x) << std::dec
                          << "): fast " << fast << ", reference " << want;
    };
    for (float x : xs) check(x), check(-x);
    const uint32_t from = (table.firstBucket - 1) << enc::Srgb8EncodeTable::kShift;
    const uint32_t to = (table.lastBucket + 2) << enc::Srgb8EncodeTable::kShift;
    for (uint32_t bits = from; bits < to; bits += 5) check(enc::uintBitsToFloat(bits));
    std::printf("[ %-9s] %zu values, %zu differ\n", name, count, bad);
    EXPECT_EQ(bad, 0u) << name;
}

// HDRP's fast sRGB (hdrp-lit's fresnel0), of |x| (HDRP codes the magnitude: PositivePow).
TEST(Srgb8FastHdrpEncodeFast, SameCodesAsTheReference) {
    const enc::Srgb8EncodeTable& table = enc::srgbFastHdrpEncodeTable();
    expectTableForm(enc::kSrgbFastHdrpEncodeThresholds, table, enc::encodeSrgb8FastHdrp, true, "srgb hdrp");
    // Not the sRGB table: the fast curve has no linear toe, so low values code differently.
    EXPECT_NE(enc::encodeSrgb8Fast(0.001f, table), enc::encodeSrgb8(0.001f));
}

// unorm_sqrt (UE's Cloth fuzz colour): the tightest case, its top thresholds 0.79 % apart in
// buckets up to 0.78 % wide.
TEST(UnormSqrtEncodeFast, SameCodesAsTheReference) {
    expectTableForm(enc::kUnormSqrtEncodeThresholds, enc::unormSqrtEncodeTable(), enc::encodeUnormSqrt, false,
                    "unorm sqrt");
}

// Gamma 2.2 (Bevy's and niagara's base colour).
TEST(Gamma22EncodeFast, SameCodesAsTheReference) {
    const enc::Srgb8EncodeTable& table = enc::gamma22EncodeTable();
    expectTableForm(enc::kGamma22EncodeThresholds, table, enc::encodeGamma22, false, "gamma22");
    // The table is not the sRGB one: the curves differ (0.2: sRGB code 124, gamma 2.2 code 123).
    EXPECT_EQ(enc::encodeSrgb8Fast(0.2f, table), 123u);
    EXPECT_EQ(enc::encodeSrgb8(0.2f), 124u);
}

TEST(SmallFloatEncodeFast, SameCodesAsTheReference) {
    std::vector<float> xs = floatSweep();
    // Every exponent, with mantissas at and around the rounding points of 10, 6 and 5 kept bits
    // (and of the subnormal shifts), in both signs.
    for (uint32_t sign = 0; sign < 2; ++sign)
        for (uint32_t e = 0; e < 256; ++e)
            for (int k = 0; k < 24; ++k)
                for (uint32_t m : {(1u << k) - 1u, 1u << k, (1u << k) + 1u, (3u << k) >> 1, ((3u << k) >> 1) + 1u,
                                   ((3u << k) >> 1) - 1u, 0x7fffffu, 0x400000u | (1u << k)}) {
                    const uint32_t bits = (sign << 31) | (e << 23) | (m & 0x7fffffu);
                    xs.push_back(enc::uintBitsToFloat(bits));
                }
    size_t bad = 0;
    for (float x : xs) {
        const uint32_t f[3] = {enc::encodeFloat16Fast(x), enc::encodeFloat11Fast(x), enc::encodeFloat10Fast(x)};
        const uint32_t r[3] = {enc::encodeFloat16(x), enc::encodeFloat11(x), enc::encodeFloat10(x)};
        for (int i = 0; i < 3; ++i)
            if (f[i] != r[i] && bad++ < 5)
                ADD_FAILURE() << "x = " << x << " (bits 0x" << std::hex << enc::floatBitsToUint(x) << std::dec
                              << "), float" << (i == 0 ? 16 : i == 1 ? 11 : 10) << ": fast " << f[i] << ", reference "
                              << r[i];
    }
    std::printf("[ float16  ] %zu values x 3 encoders, %zu differ\n", xs.size(), bad);
    EXPECT_EQ(bad, 0u);
}

// The row form (F16C's VCVTPS2PH plus saturation where the CPU has it) against the reference
// encodeFloat16: every float whose upper 16 bits are any of the 65536 and whose lower 16 bits sit
// at or next to a multiple of 2^12 (the rounding points of normal halves), and the rounding points
// of every subnormal shift (the sweep above), in rows of odd lengths so that the 8-wide loop's
// tails run.
TEST(Float16Row, SameCodesAsTheReference) {
    std::vector<float> xs = floatSweep();
    for (uint32_t hi = 0; hi < 0x10000u; ++hi)
        for (uint32_t k = 0; k < 16; ++k)  // lower 16 bits: k 2^12 (odd k: a normal half's rounding point), +-1
            for (uint32_t lo : {(k << 12) - 1u, k << 12, (k << 12) + 1u})
                xs.push_back(enc::uintBitsToFloat((hi << 16) | (lo & 0xffffu)));
    for (uint32_t sign = 0; sign < 2; ++sign)
        for (uint32_t e = 90; e < 150; ++e)  // half's subnormals and the overflow: rounding at bits 13-23
            for (int k = 12; k < 24; ++k)
                for (uint32_t m : {(1u << k) - 1u, 1u << k, (1u << k) + 1u, (3u << k) - 1u, 3u << k, (3u << k) + 1u})
                    xs.push_back(enc::uintBitsToFloat((sign << 31) | (e << 23) | (m & 0x7fffffu)));
    std::vector<uint32_t> codes(xs.size());
    size_t at = 0;
    for (int len = 1; at < xs.size(); len = len % 37 + 1) {  // rows of 1..37 floats
        const int n = int(std::min<size_t>(size_t(len), xs.size() - at));
        enc::encodeFloat16Row(n, xs.data() + at, codes.data() + at);
        at += size_t(n);
    }
    size_t bad = 0;
    for (size_t i = 0; i < xs.size(); ++i)
        if (codes[i] != enc::encodeFloat16(xs[i]) && bad++ < 5)
            ADD_FAILURE() << "bits 0x" << std::hex << enc::floatBitsToUint(xs[i]) << ": row 0x" << codes[i]
                          << ", reference 0x" << enc::encodeFloat16(xs[i]);
    std::printf("[ float16  ] row form: %zu values, %zu differ\n", xs.size(), bad);
    EXPECT_EQ(bad, 0u);
}

}  // namespace
}  // namespace gbl
