#pragma once
// What the engine packing tests share (tests/encoding/*_packings_test.cpp): seeded inputs with the
// normal encoders' edge values, the hardware's float -> UNORM / SNORM conversions with their
// latitude at ties, and the driver that encodes 2^20 Surfaces through gbufferlab's CPU codec and
// hands each pixel's words to the engine's own packing, written out again in the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cpu_codec.h"
#include "layout.h"
#include "surface.h"
#include "sanitizers.h"

namespace gbl::test::packing {

using gbl::CpuCodec;
using gbl::CpuGBuffer;
using gbl::Layout;
using gbl::Surface;

using gbl::CpuCodec;
using gbl::CpuGBuffer;
using gbl::Layout;
using gbl::Surface;

// 2^20 inputs per engine (16 images of 1024 x 64); an eighth under AddressSanitizer, whose
// instrumented codec is about ten times slower (the file stays under a few seconds there).
#if GBL_ASAN
inline constexpr size_t kInputs = size_t(1) << 17;
#else
inline constexpr size_t kInputs = size_t(1) << 20;
#endif
inline constexpr int kWidth = 1024;
inline constexpr int kHeight = 64;
inline constexpr size_t kImage = size_t(kWidth) * kHeight;

// ---- inputs --------------------------------------------------------------------------------------

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(uint64_t seed) : gen(seed) {}
    double u01() { return double(gen() >> 11) * 0x1.0p-53; }
};

// A direction uniform on the sphere, in double, rounded to float (not renormalised in float: the
// engines' encoders divide by |n|_1 themselves and take whatever vector they are given).
inline glm::vec3 randomDirection(Rng& r) {
    const double z = 1.0 - 2.0 * r.u01();
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 6.283185307179586 * r.u01();
    return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
}

// A vector with |x| + |y| + |z| = 1 exactly in float, so that every engine's n / |n|_1 is exact
// and its octahedral point is (x, y) itself: the tie tests below place it on a code boundary.
inline glm::vec3 onL1Sphere(float x, float y, bool lower) {
    const float z = 1.0f - std::fabs(x) - std::fabs(y);
    return glm::vec3(x, y, lower ? -z : z);
}

// Edge values shared by the normal encoders.
inline std::vector<glm::vec3> edgeNormals() {
    std::vector<glm::vec3> v;
    const float zeros[2] = {0.0f, -0.0f};
    for (int axis = 0; axis < 3; ++axis)  // the six axes, with every sign of zero beside them
        for (float sign : {1.0f, -1.0f})
            for (float z0 : zeros)
                for (float z1 : zeros) {
                    glm::vec3 n(z0, z1, 0.0f);
                    if (axis == 0) n = glm::vec3(sign, z0, z1);
                    if (axis == 1) n = glm::vec3(z0, sign, z1);
                    if (axis == 2) n = glm::vec3(z0, z1, sign);
                    v.push_back(n);
                }
    for (float sx : {1.0f, -1.0f})  // diagonals, and the octahedron's edges (one zero)
        for (float sy : {1.0f, -1.0f}) {
            for (float sz : {1.0f, -1.0f}) v.push_back(glm::vec3(sx, sy, sz) * 0.57735027f);
            for (float z : zeros) v.push_back(glm::vec3(sx * 0.70710678f, sy * 0.70710678f, z));
            for (float z : zeros) {
                v.push_back(glm::vec3(z, sx * 0.70710678f, sy * 0.70710678f));
                v.push_back(glm::vec3(sx * 0.70710678f, z, sy * 0.70710678f));
            }
        }
    // The equator (the fold's seam) and HDRP's 1/1024 band around it.
    const float seam = 1.0f / 1024.0f;
    const float zs[] = {0.0f,   1e-30f,        1e-7f,         seam * 0.5f,  std::nextafter(seam, 0.0f), seam,
                        std::nextafter(seam, 1.0f), seam * 1.5f, 0.01f, 1e-40f /* subnormal */};
    for (int k = 0; k < 64; ++k) {
        const double a = 6.283185307179586 * (k + 0.25) / 64.0;
        for (float z : zs)
            for (float s : {1.0f, -1.0f}) {
                const float c = float(std::cos(a) * std::sqrt(1.0 - double(z) * z));
                const float d = float(std::sin(a) * std::sqrt(1.0 - double(z) * z));
                v.push_back(glm::vec3(c, d, s * z));
            }
    }
    // The lower hemisphere's fold lines x = +-0 and y = +-0, and near them.
    for (int k = 1; k < 64; ++k) {
        const float c = float(std::cos(1.5707963267948966 * k / 64.0));
        const float s = float(std::sin(1.5707963267948966 * k / 64.0));
        for (float z : zeros)
            for (float t : {1.0f, -1.0f}) {
                v.push_back(glm::vec3(z, t * c, -s));
                v.push_back(glm::vec3(t * c, z, -s));
                v.push_back(glm::vec3(t * 1e-7f, t * c, -s));
                v.push_back(glm::vec3(t * c, -t * 1e-30f, -s));
            }
    }
    // Code boundaries of the 12-bit quantisers: u = (k + 0.5) / 4095 (Bevy's rounding) and
    // u = k / 4095.5 (Unity's truncation), and the floats either side, on both hemispheres.
    for (int k = 0; k < 4095; k += 7) {
        const float xs[] = {float((k + 0.5) / 4095.0 * 2.0 - 1.0), float(k / 4095.5 * 2.0 - 1.0),
                            float((k + 0.5) / 1023.0 * 2.0 - 1.0)};
        for (float x : xs)
            for (float e : {x, std::nextafter(x, -2.0f), std::nextafter(x, 2.0f)}) {
                const float y = 0.25f * (1.0f - std::fabs(e));
                for (bool lower : {false, true}) {
                    v.push_back(onL1Sphere(e, y, lower));
                    v.push_back(onL1Sphere(-y, e, lower));
                    // Scaled, so |n|_1 is not 1: n / |n|_1 and n * (1 / |n|_1) may differ in the last
                    // bit here, next to a boundary, where that moves a code.
                    for (float scale : {0.6f, 0.77f, 1.3f})
                        v.push_back(onL1Sphere(e, y, lower) * scale);
                }
            }
    }
    // Tiny and huge components (no NaN, no infinity): |n|_1 stays finite.
    v.push_back(glm::vec3(1e-38f, 1e-38f, 1e-38f));
    v.push_back(glm::vec3(-1e-38f, 2e-38f, -3e-38f));
    v.push_back(glm::vec3(1e30f, -1e30f, 1e30f));
    v.push_back(glm::vec3(3e37f, 1e37f, -2e37f));
    v.push_back(glm::vec3(1.0f, 1e-40f, -1e-40f));
    v.push_back(glm::vec3(-1e-40f, 1.0f, -1e-40f));
    return v;
}

// The i-th normal: the edge values first, then random directions (a tenth of them near the
// equator, where HDRP's clamp and the fold meet).
inline glm::vec3 normalInput(const std::vector<glm::vec3>& edges, Rng& rng, size_t i) {
    if (i < edges.size()) return edges[i];
    glm::vec3 n = randomDirection(rng);
    if (i % 10 == 0) n.z = float((rng.u01() * 2.0 - 1.0) * 0.003);
    return n;
}

// ---- the hardware conversions (Vulkan spec, "Conversion from Floating-Point to Normalized
// Fixed-Point"; round to nearest, ties and the product's last bits left to the implementation) ----

struct HardwareCode {
    uint32_t nearest = 0, other = 0;  // other == nearest unless near a tie
    bool nearTie = false;
};

// UNORM: clamp(x, 0, 1) * (2^bits - 1), exact in double (24 + 16 bits).
inline HardwareCode hardwareUnorm(float x, int bits) {
    const double v = double(std::min(std::max(x, 0.0f), 1.0f)) * double((1u << bits) - 1u);
    HardwareCode c;
    c.nearest = uint32_t(std::floor(v + 0.5));
    const double frac = v - std::floor(v);
    if (std::fabs(frac - 0.5) <= v * 0x1.0p-23) {
        c.nearTie = true;
        c.nearest = uint32_t(std::floor(v));
        c.other = c.nearest + 1u;
    } else {
        c.other = c.nearest;
    }
    return c;
}

// SNORM: clamp(x, -1, 1) * (2^(bits-1) - 1), two's complement in the low `bits` bits.
inline HardwareCode hardwareSnorm(float x, int bits) {
    const double v = double(std::min(std::max(x, -1.0f), 1.0f)) * double((1u << (bits - 1)) - 1u);
    const uint32_t mask = (1u << bits) - 1u;
    HardwareCode c;
    const double frac = v - std::floor(v);
    if (std::fabs(frac - 0.5) <= std::fabs(v) * 0x1.0p-23) {
        c.nearTie = true;
        c.nearest = uint32_t(int32_t(std::floor(v))) & mask;
        c.other = uint32_t(int32_t(std::floor(v)) + 1) & mask;
    } else {
        c.nearest = c.other = uint32_t(int32_t(std::floor(v + 0.5))) & mask;
    }
    return c;
}

inline bool accepts(const HardwareCode& c, uint32_t code) { return code == c.nearest || code == c.other; }

// ---- the driver ----------------------------------------------------------------------------------

struct Tally {
    size_t compared = 0, mismatches = 0, nearTies = 0;
    void fail(const std::string& what) {
        if (mismatches++ < 8) ADD_FAILURE() << what;
    }
};

// Encodes kInputs Surfaces (make(i) gives the i-th) through gbufferlab's CPU codec for `layout`,
// in images of kWidth x kHeight, and hands each pixel's words of target `target` to check(i, x, y,
// words). The pixel (x, y) is the one the codec encoded at (what a dithered encoder reads).
inline void runCodec(const Layout& layout, size_t target, const std::function<Surface(size_t)>& make,
              const std::function<void(size_t, int, int, const uint32_t*)>& check) {
    const CpuCodec codec(layout);
    std::vector<Surface> surfaces(kImage);
    CpuGBuffer g;
    for (size_t first = 0; first < kInputs; first += kImage) {
        for (size_t j = 0; j < kImage; ++j) surfaces[j] = make(first + j);
        codec.encode(surfaces, kWidth, kHeight, g);
        const std::vector<uint32_t>& w = g.targetWords.at(target);
        const size_t words = w.size() / kImage;  // wordsPerPixel of the target
        ASSERT_EQ(w.size(), kImage * words);
        ASSERT_GE(words, 1u);
        for (size_t j = 0; j < kImage; ++j) check(first + j, int(j % kWidth), int(j / kWidth), &w[j * words]);
    }
}

// The same for checks that read several targets of one pixel (a selector's id in one target, what
// it switches in another): check(i, g, j) with the image's words `g` and the pixel's index j.
inline void runCodecAllTargets(const Layout& layout, size_t inputs, const std::function<Surface(size_t)>& make,
                               const std::function<void(size_t, const CpuGBuffer&, size_t)>& check) {
    const CpuCodec codec(layout);
    std::vector<Surface> surfaces(kImage);
    CpuGBuffer g;
    for (size_t first = 0; first < inputs; first += kImage) {
        for (size_t j = 0; j < kImage; ++j) surfaces[j] = make(first + j);
        codec.encode(surfaces, kWidth, kHeight, g);
        for (size_t j = 0; j < kImage; ++j) check(first + j, g, j);
    }
}

// The index of the target named `name` in `layout` (a shipped row's target); fails the test when absent.
inline size_t targetIndex(const Layout& layout, const std::string& name) {
    for (size_t t = 0; t < layout.targets.size(); ++t)
        if (layout.targets[t].name == name) return t;
    ADD_FAILURE() << layout.name << " has no target " << name;
    return 0;
}

inline std::string hex(uint32_t w) {
    char b[16];
    std::snprintf(b, sizeof b, "0x%08x", w);
    return b;
}

inline std::string vec(glm::vec3 n) {
    char b[96];
    std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", double(n.x), double(n.y), double(n.z));
    return b;
}

inline float clamp01(float x) { return std::min(std::max(x, 0.0f), 1.0f); }

}  // namespace gbl::test::packing
