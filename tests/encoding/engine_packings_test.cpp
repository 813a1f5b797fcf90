// An independent check of each engine encoder whose engine's code is public: the engine's packing
// is written out here again from reading its source (the arithmetic, its order and its float32
// type as the source has them; the project compiles with -ffp-contract=off, so nothing is fused),
// without calling any of gbufferlab's encoders, and compared bit for bit with the words
// gbufferlab's CPU codec (cpu_codec.h, the mirror the GPU words are held to by
// codec/gpu_cpu_bits_test) writes for a layout that places the codes where the engine does, on
// 2^20 seeded random inputs plus edge values (axes with signed zeros, the octahedral seams and
// folds, |n.z| below HDRP's 1/1024, inputs on and next to code ties, tiny and huge components).
// A rounding mode, a sign convention or a bit order that drifts on either side fails here.
//
// Where the engine's code fixes the rounding (Bevy's u32(x * 4095 + 0.5), Unity's uint(x * 4095.5),
// Bevy's pack_unorm4x8_), the codes must be equal. Where the engine leaves it to the hardware's
// float -> UNORM / SNORM conversion (HDRP's roughness, URP's SNORM normal, niagara's and Granite's
// 10-bit targets), the Vulkan and D3D specifications ask for round to nearest but leave ties,
// and the exact product's last bits, to the implementation: there the code must be the nearest one
// to the exact product x * (2^b - 1), and either neighbour is accepted only when that product lies
// within float32's rounding (2^-23 relative) of a tie. Those near-ties are counted and must stay
// rare, so that the check is not vacuous. (So a last-bit difference in the arithmetic before such a
// conversion, e.g. niagara's n * (1 / |n|_1) written as n / |n|_1, moves codes only inside that
// latitude and is not seen here; before an engine-defined rounding it is: Bevy's, HDRP's and URP's
// normals disagree on a few hundred of these inputs when division and reciprocal are swapped.)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
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

namespace {

using gbl::CpuCodec;
using gbl::CpuGBuffer;
using gbl::Layout;
using gbl::Surface;

// 2^20 inputs per engine (16 images of 1024 x 64); an eighth under AddressSanitizer, whose
// instrumented codec is about ten times slower (the file stays under a few seconds there).
#if defined(__SANITIZE_ADDRESS__)
constexpr size_t kInputs = size_t(1) << 17;
#else
constexpr size_t kInputs = size_t(1) << 20;
#endif
constexpr int kWidth = 1024;
constexpr int kHeight = 64;
constexpr size_t kImage = size_t(kWidth) * kHeight;

// ---- inputs --------------------------------------------------------------------------------------

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(uint64_t seed) : gen(seed) {}
    double u01() { return double(gen() >> 11) * 0x1.0p-53; }
};

// A direction uniform on the sphere, in double, rounded to float (not renormalised in float: the
// engines' encoders divide by |n|_1 themselves and take whatever vector they are given).
glm::vec3 randomDirection(Rng& r) {
    const double z = 1.0 - 2.0 * r.u01();
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 6.283185307179586 * r.u01();
    return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
}

// A vector with |x| + |y| + |z| = 1 exactly in float, so that every engine's n / |n|_1 is exact
// and its octahedral point is (x, y) itself: the tie tests below place it on a code boundary.
glm::vec3 onL1Sphere(float x, float y, bool lower) {
    const float z = 1.0f - std::fabs(x) - std::fabs(y);
    return glm::vec3(x, y, lower ? -z : z);
}

// Edge values shared by the normal encoders.
std::vector<glm::vec3> edgeNormals() {
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
glm::vec3 normalInput(const std::vector<glm::vec3>& edges, Rng& rng, size_t i) {
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
HardwareCode hardwareUnorm(float x, int bits) {
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
HardwareCode hardwareSnorm(float x, int bits) {
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

bool accepts(const HardwareCode& c, uint32_t code) { return code == c.nearest || code == c.other; }

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
void runCodec(const Layout& layout, size_t target, const std::function<Surface(size_t)>& make,
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

std::string hex(uint32_t w) {
    char b[16];
    std::snprintf(b, sizeof b, "0x%08x", w);
    return b;
}

std::string vec(glm::vec3 n) {
    char b[96];
    std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", double(n.x), double(n.y), double(n.z));
    return b;
}

float clamp01(float x) { return std::min(std::max(x, 0.0f), 1.0f); }

// ==================================================================================================
// Bevy (bevyengine/bevy v0.16.0 e9418b3845c1; the same packing in every release since v0.12.0
// bf30a25e). One Rgba32Uint target built by deferred_gbuffer_from_pbr_input
// (crates/bevy_pbr/src/deferred/pbr_deferred_functions.wgsl:25-80):
//   r = pack_unorm4x8_(pow(base_color, 1/2.2), perceptual_roughness)            (:57, :76)
//   g = vec3_to_rgb9e5_(emissive)                                                 (:77)
//   b = pack_unorm4x8_(reflectance, metallic, diffuse_occlusion, 0)               (:42-46)
//   a = pack_24bit_normal_and_flags(octahedral_encode(normalize(N)), flags)       (:49, :79)
// ==================================================================================================

// crates/bevy_pbr/src/render/utils.wgsl:48-53: n = v / (|v.x| + |v.y| + |v.z|); the wrap
// (1 - |n.yx|) * select(-1, 1, n.xy > 0) where n.z < 0; returned as n_xy * 0.5 + 0.5.
glm::vec2 bevyOctahedralEncode(glm::vec3 v) {
    const float l1 = std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);
    const float nx = v.x / l1, ny = v.y / l1, nz = v.z / l1;
    const float wrapX = (1.0f - std::fabs(ny)) * (nx > 0.0f ? 1.0f : -1.0f);
    const float wrapY = (1.0f - std::fabs(nx)) * (ny > 0.0f ? 1.0f : -1.0f);
    const bool keep = nz >= 0.0f;
    const float px = keep ? nx : wrapX, py = keep ? ny : wrapY;
    return {px * 0.5f + 0.5f, py * 0.5f + 0.5f};
}

// crates/bevy_pbr/src/deferred/pbr_deferred_types.wgsl:39-43 (U12MAXF = 4095.0, :30).
uint32_t bevyPack24bitNormalAndFlags(glm::vec2 octahedralNormal, uint32_t flags) {
    const uint32_t unorm1 = uint32_t(clamp01(octahedralNormal.x) * 4095.0f + 0.5f);
    const uint32_t unorm2 = uint32_t(clamp01(octahedralNormal.y) * 4095.0f + 0.5f);
    return (unorm1 & 0xFFFu) | ((unorm2 & 0xFFFu) << 12u) | ((flags & 0xFFu) << 24u);
}

// pbr_deferred_types.wgsl:77-81, pack_unorm4x8_: vec4<u32>(saturate(values) * 255.0 + 0.5).
uint32_t bevyPackUnorm4x8(glm::vec4 v) {
    uint32_t w = 0;
    for (int k = 0; k < 4; ++k) w |= uint32_t(clamp01(v[k]) * 255.0f + 0.5f) << (8 * k);
    return w;
}

// crates/bevy_pbr/src/render/rgb9e5.wgsl:22-45 (EXT_texture_shared_exponent's algorithm):
// exp2 of an integer is exact, so is the division by it.
uint32_t bevyVec3ToRgb9e5(glm::vec3 in) {
    const glm::vec3 rgb(std::min(std::max(in.x, 0.0f), 65408.0f), std::min(std::max(in.y, 0.0f), 65408.0f),
                        std::min(std::max(in.z, 0.0f), 65408.0f));
    const float maxrgb = std::max(rgb.x, std::max(rgb.y, rgb.z));
    const int floorLog2 = int((std::bit_cast<uint32_t>(maxrgb) & 0x7F800000u) >> 23u) - 127;
    int expShared = std::max(-15 - 1, floorLog2) + 1 + 15;
    float denom = std::ldexp(1.0f, expShared - 15 - 9);
    const int maxm = int(std::floor(maxrgb / denom + 0.5f));
    if (maxm == 512) {
        denom *= 2.0f;
        expShared += 1;
    }
    const uint32_t r = uint32_t(std::floor(rgb.x / denom + 0.5f));
    const uint32_t g = uint32_t(std::floor(rgb.y / denom + 0.5f));
    const uint32_t b = uint32_t(std::floor(rgb.z / denom + 0.5f));
    return (uint32_t(expShared) << 27u) | (b << 18u) | (g << 9u) | r;
}

const char* kBevyLayout = R"(name = "bevy-packing"
title = "bevy-deferred's deferred target"
pipeline = "deferred-shading"
source = { engine = "Bevy", talk = "unit test", year = 2023 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "deferred"
format = "R32G32B32A32_UINT"
field = [
  { attribute = "base_color", encoding = "gamma22",     at = ["r[0:7]", "r[8:15]", "r[16:23]"] },
  { attribute = "roughness",  encoding = "unorm",       at = "r[24:31]" },
  { attribute = "emissive",   encoding = "rgb9e5",      at = ["g[0:8]", "g[9:17]", "g[18:26]", "g[27:31]"] },
  { attribute = "specular",   encoding = "reflectance", at = "b[0:7]" },
  { attribute = "metallic",   encoding = "unorm",       at = "b[8:15]" },
  { attribute = "occlusion",  encoding = "unorm",       at = "b[16:23]" },
  { attribute = "normal",     encoding = "normal_octahedral_bevy", at = ["a[0:11]", "a[12:23]"] },
  { attribute = "flags",      at = "a[24:31]", value = 6 },
]
[fallback]
specular_color = "ue4"
diffuse_color = "from_base_color"
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, -1.0]
roughness = 0.0
base_color = 0.0
emissive = 0.0
specular = 0.0
metallic = 0.0
occlusion = 0.0
)";

TEST(EnginePackings, BevyDeferredWordsEqualBevysPacking) {
    const Layout layout = gbl::parseLayout(kBevyLayout, "bevy-packing.toml");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2801);
    // One input per pixel: the normal, and the material values, some of them on 8-bit ties.
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = normalInput(edges, rng, i);
        s.baseColor = glm::vec3(float(rng.u01()), float(rng.u01()), float(rng.u01()));
        s.roughness = i % 16 == 1 ? float((int(i) % 256 + 0.5) / 255.0) : float(rng.u01() * 1.2 - 0.1);
        s.metallic = i % 16 == 2 ? float((int(i) % 256 + 0.5) / 255.0) : float(rng.u01());
        s.occlusion = float(rng.u01());
        s.specular = float(rng.u01());
        // HDR emissive over 2^-30 .. 2^17, channels of one magnitude and not, zero and negative.
        auto mag = [&] { return float(std::exp2(rng.u01() * 47.0 - 30.0)); };
        s.emissive = glm::vec3(mag(), mag(), mag());
        if (i % 3 == 0) s.emissive.y = s.emissive.x * float(rng.u01());
        if (i % 97 == 0) s.emissive = glm::vec3(0.0f, -1.0f, 1e6f);
        if (i % 101 == 0) s.emissive = glm::vec3(0.0f);
        keep[i % kImage] = s;
        return s;
    };
    Tally normal, rWord, gWord, bWord;
    size_t gammaTies = 0, occlusionUlpFlips = 0;
    runCodec(layout, 0, make, [&](size_t i, int, int, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        // a: the normal and the flags, exactly.
        const uint32_t a = bevyPack24bitNormalAndFlags(bevyOctahedralEncode(s.normal), 6u);
        ++normal.compared;
        if (w[3] != a) normal.fail("a word of " + vec(s.normal) + ": gbufferlab " + hex(w[3]) + ", Bevy " + hex(a));
        // g: rgb9e5, exactly.
        const uint32_t g = bevyVec3ToRgb9e5(s.emissive);
        ++gWord.compared;
        if (w[1] != g) gWord.fail("g word of emissive " + vec(s.emissive) + ": gbufferlab " + hex(w[1]) + ", Bevy " + hex(g));
        // r: pack_unorm4x8_(pow(c, 1/2.2), roughness). Bevy's f32 pow is the GPU's (not correctly
        // rounded: exp2(log2(c) / 2.2)); gbufferlab's gamma22 is the exactly rounded code, so
        // the base colour bytes are compared with the exact pow, except within 1e-4 of a code tie
        // where an f32 pow may land on either side. The roughness byte is Bevy's f32 arithmetic.
        glm::vec4 rv;
        bool tie = false;
        for (int k = 0; k < 3; ++k) {
            const double p = std::pow(double(s.baseColor[k]), 1.0 / 2.2);
            tie = tie || std::fabs(p * 255.0 - std::floor(p * 255.0) - 0.5) < 1e-4;
            rv[k] = float(p);
        }
        rv[3] = s.roughness;
        uint32_t r = 0;
        for (int k = 0; k < 3; ++k) r |= uint32_t(std::floor(std::pow(double(s.baseColor[k]), 1.0 / 2.2) * 255.0 + 0.5)) << (8 * k);
        r |= bevyPackUnorm4x8(rv) & 0xFF000000u;
        if (tie) {
            ++gammaTies;
            if ((w[0] ^ r) & 0xFF000000u) rWord.fail("roughness byte of " + std::to_string(s.roughness));
        } else {
            ++rWord.compared;
            if (w[0] != r) rWord.fail("r word of " + vec(s.baseColor) + ", " + std::to_string(s.roughness) + ": gbufferlab " + hex(w[0]) + ", Bevy " + hex(r));
        }
        // b: reflectance, metallic, Rec. 709 luminance of the (monochrome) occlusion, spare 0.
        // gbufferlab stores reflectance = sqrt(specular / 2) (UE's specular to Filament's
        // reflectance, not Bevy's code), so byte 0 is held to that value's exact rounding.
        // Bevy's dot(occlusion, Rec. 709) of a grey occlusion is the occlusion itself in real
        // arithmetic; in float it can move by an ulp and so, next to a tie, move the byte: such
        // bytes (where the dot is not the occlusion's own float) may differ by one, and are counted.
        const float occ = s.occlusion * 0.2126f + s.occlusion * 0.7152f + s.occlusion * 0.0722f;
        uint32_t b = bevyPackUnorm4x8(glm::vec4(0.0f, s.metallic, occ, 0.0f));
        if (occ != s.occlusion && ((w[2] ^ b) & 0x00FF0000u) != 0u) {
            const uint32_t own = bevyPackUnorm4x8(glm::vec4(0.0f, 0.0f, s.occlusion, 0.0f));
            if ((w[2] & 0x00FF0000u) == own) {
                ++occlusionUlpFlips;
                b = (b & ~0x00FF0000u) | own;
            }
        }
        ++bWord.compared;
        if ((w[2] & 0xFFFFFF00u) != b) bWord.fail("b word of metallic " + std::to_string(s.metallic) + ", occlusion " + std::to_string(s.occlusion) + ": gbufferlab " + hex(w[2]) + ", Bevy " + hex(b));
        const double refl = 255.0 * std::sqrt(std::clamp(double(s.specular), 0.0, 1.0) / 2.0);
        if (std::fabs(refl - std::floor(refl) - 0.5) > 1e-4 && (w[2] & 0xFFu) != uint32_t(std::floor(refl + 0.5)))
            bWord.fail("reflectance byte of specular " + std::to_string(s.specular));
    });
    std::printf("[ bevy     ] %zu normals, %zu emissives, %zu r words (+%zu within 1e-4 of a gamma tie), %zu b words "
                "(%zu occlusion bytes moved by the dot's last ulp)\n",
                normal.compared, gWord.compared, rWord.compared, gammaTies, bWord.compared, occlusionUlpFlips);
    EXPECT_EQ(normal.mismatches, 0u);
    EXPECT_EQ(gWord.mismatches, 0u);
    EXPECT_EQ(rWord.mismatches, 0u);
    EXPECT_EQ(bWord.mismatches, 0u);
    EXPECT_LT(gammaTies, kInputs / 100);
    EXPECT_LT(occlusionUlpFlips, 20u);
    // The source's own examples (bevy-deferred.md, from Bevy's arithmetic): +z (2048, 2048);
    // +y (2048, 4095); -z (0, 0): the wrap's sign of 0 is -1.
    EXPECT_EQ(bevyPack24bitNormalAndFlags(bevyOctahedralEncode({0, 0, 1}), 6u), 0x06800800u);
    EXPECT_EQ(bevyPack24bitNormalAndFlags(bevyOctahedralEncode({0, 1, 0}), 6u), 0x06FFF800u);
    EXPECT_EQ(bevyPack24bitNormalAndFlags(bevyOctahedralEncode({0, 0, -1}), 6u), 0x06000000u);
}

// ==================================================================================================
// Unity: core ShaderLibrary/Packing.hlsl (needle-mirror/com.unity.render-pipelines.core 13.0.0
// 6363fa2550da), shared by HDRP's normal buffer and URP's accurate G-buffer normals.
// ==================================================================================================

// Packing.hlsl:57-69, PackNormalOctQuadEncode: n *= rcp(dot(abs(n), 1.0)); t = saturate(-n.z);
// return n.xy + (n.xy >= 0.0 ? t : -t). rcp is modelled as IEEE 1 / x (float32).
glm::vec2 unityPackNormalOctQuadEncode(glm::vec3 n) {
    const float dot = std::fabs(n.x) * 1.0f + std::fabs(n.y) * 1.0f + std::fabs(n.z) * 1.0f;
    const float rcp = 1.0f / dot;
    n.x *= rcp;
    n.y *= rcp;
    n.z *= rcp;
    const float t = clamp01(-n.z);
    return {n.x + (n.x >= 0.0f ? t : -t), n.y + (n.y >= 0.0f ? t : -t)};
}

// Packing.hlsl:543-552, PackFloat2To888: i = (uint2)(f * 4095.5); hi = i >> 8; lo = i & 255;
// (lo.x, lo.y, hi.x | hi.y << 4), returned / 255 into a UNORM8 target, which gives the bytes back.
std::array<uint32_t, 3> unityPackFloat2To888(glm::vec2 f) {
    const uint32_t ix = uint32_t(f.x * 4095.5f), iy = uint32_t(f.y * 4095.5f);
    return {ix & 255u, iy & 255u, (ix >> 8) | ((iy >> 8) << 4)};
}

// The remap both pipelines apply between the two: saturate(oct * 0.5 + 0.5).
glm::vec2 unityRemap(glm::vec2 p) { return {clamp01(p.x * 0.5f + 0.5f), clamp01(p.y * 0.5f + 0.5f)}; }

// HDRP (needle-mirror/com.unity.render-pipelines.high-definition 13.0.0 c667268ac58a)
// Runtime/Material/NormalBuffer.hlsl:27-28: seamThreshold = 1/1024;
// n.z = CopySign(max(seamThreshold, abs(n.z)), n.z), CopySign (core Common.hlsl:697-702, with
// ignoreNegZero) = s >= 0 ? abs(x) : -abs(x), so -0 becomes +1/1024.
glm::vec3 hdrpSeamClamp(glm::vec3 n) {
    const float m = std::max(1.0f / 1024.0f, std::fabs(n.z));
    n.z = n.z >= 0.0f ? std::fabs(m) : -std::fabs(m);
    return n;
}

// HDRP's GBuffer1 (the normal buffer: EncodeIntoNormalBuffer, NormalBuffer.hlsl:20-36, written by
// Lit.hlsl's EncodeIntoGBuffer) and URP's GBuffer2 with accurate normals (UnityGBuffer.hlsl).
std::string unityLayout(const char* name, const char* normalEncoding) {
    return std::string("name = \"") + name + R"("
title = "normal buffer"
pipeline = "deferred-shading"
source = { engine = "Unity", talk = "unit test", year = 2021 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "normals"
format = "R8G8B8A8_UNORM"
field = [
  { attribute = "normal",    encoding = ")" + normalEncoding + R"(", at = ["r + b[0:3]", "g + b[4:7]"] },
  { attribute = "roughness", encoding = ")" + (std::string(name) == "hdrp" ? "unorm" : "gloss") + R"(", at = "a" },
]
[fallback]
base_color = 0.5
metallic = 0.0
specular = 0.5
specular_color = "from_metallic"
diffuse_color = "from_base_color"
occlusion = 1.0
emissive = 0.0
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, 1.0]
roughness = 1.0
)";
}

// Runs the Unity normal buffer check: `hdrp` selects HDRP's seam clamp and its alpha
// (perceptualRoughness, NormalBuffer.hlsl:35); URP's alpha is smoothness = 1 - perceptual roughness
// (UnityGBuffer.hlsl:210).
void checkUnityNormalBuffer(bool hdrp) {
    const Layout layout = gbl::parseLayout(unityLayout(hdrp ? "hdrp" : "urp", hdrp ? "normal_octahedral_hdrp" : "normal_octahedral_unity"),
                                           hdrp ? "hdrp.toml" : "urp.toml");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(hdrp ? 2802 : 2803);
    std::vector<Surface> keep(kImage);
    Tally t;
    size_t clamped = 0;
    runCodec(layout, 0,
             [&](size_t i) {
                 Surface s;
                 s.normal = normalInput(edges, rng, i);
                 s.roughness = i % 8 == 3 ? float((int(i) % 256 + 0.5) / 255.0) : float(rng.u01());
                 keep[i % kImage] = s;
                 return s;
             },
             [&](size_t i, int, int, const uint32_t* w) {
                 const Surface& s = keep[i % kImage];
                 const glm::vec3 n = hdrp ? hdrpSeamClamp(s.normal) : s.normal;
                 clamped += n.z != s.normal.z;
                 const std::array<uint32_t, 3> rgb = unityPackFloat2To888(unityRemap(unityPackNormalOctQuadEncode(n)));
                 const uint32_t want = rgb[0] | rgb[1] << 8 | rgb[2] << 16;
                 ++t.compared;
                 if ((w[0] & 0x00FFFFFFu) != want)
                     t.fail(std::string(hdrp ? "HDRP" : "URP") + " normal " + vec(s.normal) + ": gbufferlab " + hex(w[0]) +
                            ", Unity " + hex(want));
                 const HardwareCode a = hardwareUnorm(hdrp ? s.roughness : 1.0f - s.roughness, 8);
                 t.nearTies += a.nearTie;
                 if (!accepts(a, w[0] >> 24)) t.fail("alpha of roughness " + std::to_string(s.roughness));
             });
    std::printf("[ %s     ] %zu normal words (%zu with |z| raised to 1/1024), %zu alphas near a tie\n", hdrp ? "hdrp" : "urp ",
                t.compared, clamped, t.nearTies);
    EXPECT_EQ(t.mismatches, 0u);
    // An eighth of the roughnesses are placed on 8-bit ties (URP's 1 - r keeps most of them there);
    // the random rest rarely comes near one.
    EXPECT_GT(t.nearTies, kInputs / 10);
    EXPECT_LT(t.nearTies, kInputs / 8 + kInputs / 1000);
    if (hdrp) {
        EXPECT_GT(clamped, kInputs / 50);  // the clamp is exercised, not only beside it
    }
}

TEST(EnginePackings, HdrpNormalBufferEqualsEncodeIntoNormalBuffer) {
    checkUnityNormalBuffer(true);
    // The source's consequences (hdrp-lit.md): the Y-up floor (0, 1, 0) is (2047, 4093), the wall
    // (1, 0, 0) (4093, 2047); -z (4095, 4095): the fold's sign of +0 is +1.
    auto codes = [](glm::vec3 n) {
        const std::array<uint32_t, 3> b = unityPackFloat2To888(unityRemap(unityPackNormalOctQuadEncode(hdrpSeamClamp(n))));
        return glm::uvec2(b[0] | (b[2] & 15u) << 8, b[1] | (b[2] >> 4) << 8);
    };
    EXPECT_EQ(codes({0, 1, 0}), glm::uvec2(2047u, 4093u));
    EXPECT_EQ(codes({1, 0, 0}), glm::uvec2(4093u, 2047u));
    EXPECT_EQ(codes({0, 0, 1}), glm::uvec2(2047u, 2047u));
    EXPECT_EQ(codes({0, 0, -1}), glm::uvec2(4095u, 4095u));
}

TEST(EnginePackings, UrpAccurateNormalsEqualPackNormal) { checkUnityNormalBuffer(false); }

// HDRP's GBuffer2.rgb: fresnel0 through FastLinearToSRGB into a UNORM target (HDRP 13.0.0
// Runtime/Material/Lit/Lit.hlsl:661), read back by FastSRGBToLinear (:839); core 13.0.0
// ShaderLibrary/Color.hlsl:166-179: saturate(1.055 * PositivePow(c, 0.416666667) - 0.055), and
// :151-159: c * (c * (c * 0.305306011 + 0.682171111) + 0.012522878).
double hdrpFastLinearToSrgb(float c) {  // in double: a GPU's pow is not correctly rounded
    return std::clamp(1.055 * std::pow(double(std::fabs(c)), double(0.416666667f)) - 0.055, 0.0, 1.0);
}
float hdrpFastSrgbToLinear(float c) { return c * (c * (c * 0.305306011f + 0.682171111f) + 0.012522878f); }

const char* kHdrpFresnelLayout = R"(name = "hdrp-fresnel0"
title = "HDRP's GBuffer1 and GBuffer2"
pipeline = "deferred-shading"
source = { engine = "Unity HDRP", talk = "unit test", year = 2021 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "GBuffer1"
format = "R8G8B8A8_UNORM"
field = [
  { attribute = "normal",    encoding = "normal_octahedral_hdrp", at = ["r + b[0:3]", "g + b[4:7]"] },
  { attribute = "roughness", encoding = "unorm", at = "a" },
]
[[target]]
name = "GBuffer2"
format = "R8G8B8A8_UNORM"
field = [
  { attribute = "specular_color", encoding = "srgb8_fast_hdrp", at = ["r", "g", "b"] },
]
[fallback]
base_color = 0.5
metallic = 0.0
specular = 0.5
diffuse_color = "from_base_color"
occlusion = 1.0
emissive = 0.0
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, 1.0]
roughness = 1.0
specular_color = 0.0
)";

TEST(EnginePackings, HdrpFresnel0EqualsFastLinearToSrgbAndItsCubic) {
    const Layout layout = gbl::parseLayout(kHdrpFresnelLayout, "hdrp-fresnel0.toml");
    const CpuCodec codec(layout);
    Rng rng(2808);
    std::vector<Surface> surfaces(kImage), decoded;
    CpuGBuffer g;
    size_t compared = 0, nearTies = 0, mismatches = 0, decodeMismatches = 0;
    for (size_t first = 0; first < kInputs; first += kImage) {
        for (size_t j = 0; j < kImage; ++j) {
            Surface& s = surfaces[j];
            // F0 from 0 to 1, a third of it below sRGB's toe (0.0031308) where HDRP's curve is its own.
            for (int k = 0; k < 3; ++k) {
                const double u = rng.u01();
                s.specularColor[k] = j % 3 == 0 ? float(u * 0.004) : float(u * 1.1 - 0.05);
            }
            if (first == 0 && j < 256) s.specularColor = glm::vec3(float(j) / 255.0f, 0.0f, -0.0f);
        }
        codec.encode(surfaces, kWidth, kHeight, g);
        codec.decode(g, decoded);
        for (size_t j = 0; j < kImage; ++j) {
            const uint32_t w = g.targetWords.at(1)[j];
            for (int k = 0; k < 3; ++k) {
                const uint32_t code = (w >> (8 * k)) & 255u;
                const double v = 255.0 * hdrpFastLinearToSrgb(surfaces[j].specularColor[k]);
                ++compared;
                if (std::fabs(v - std::floor(v) - 0.5) < 1e-4) {
                    ++nearTies;  // HDRP's pow lands on either side
                    if (code != uint32_t(std::floor(v)) && code != uint32_t(std::floor(v)) + 1u) ++mismatches;
                } else if (code != uint32_t(std::floor(v + 0.5)) && mismatches++ < 8) {
                    ADD_FAILURE() << "F0 " << surfaces[j].specularColor[k] << ": gbufferlab code " << code << ", HDRP "
                                  << std::floor(v + 0.5);
                }
                // The decode: the UNORM texel read as float (code / 255, correctly rounded) through the cubic.
                const float want = hdrpFastSrgbToLinear(float(code) / 255.0f);
                if (std::bit_cast<uint32_t>(decoded[j].specularColor[k]) != std::bit_cast<uint32_t>(want) &&
                    decodeMismatches++ < 8)
                    ADD_FAILURE() << "code " << code << ": gbufferlab decodes " << decoded[j].specularColor[k] << ", HDRP "
                                  << want;
            }
            if ((w >> 24) != 0u && mismatches++ < 8) ADD_FAILURE() << "alpha of GBuffer2 written: " << hex(w);
        }
    }
    std::printf("[ hdrp f0  ] %zu codes (%zu within 1e-4 of a tie), decoded by the cubic\n", compared, nearTies);
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(decodeMismatches, 0u);
    EXPECT_LT(nearTies, compared / 1000);
}

// ==================================================================================================
// HDRP's GBuffer3 and its AO tag (HDRP 13.0.0 c667268ac58a Runtime/Material/Lit/Lit.hlsl; the same
// at Unity-Technologies/Graphics 1390609c). EncodeIntoGBuffer (:686-705):
//   outGBuffer3 = float4(bakeDiffuseLighting * ambientOcclusion + emissiveColor, 0.0);
//   outGBuffer3.rgb *= GetCurrentExposureMultiplier();
//   if (all(outGBuffer3.rgb == 0.0)) { outGBuffer3.xz = AO_IN_GBUFFER3_TAG.xz; outGBuffer3.y = ambientOcclusion; }
// with AO_IN_GBUFFER3_TAG = float3(1 << 11, 1, 1 << 10); the hardware converts the floats into
// B10G11R11_UFLOAT_PACK32. DecodeFromGBuffer (:944-953): if (all(gbuffer3.xz == tag.xz)) AO =
// gbuffer3.y; else { gbuffer3 *= 1 / exposure; AO = 1; emissive (or baked + emissive) = gbuffer3 }.
// gbufferlab's scenes: bakeDiffuseLighting = 0 and exposure 1.
// ==================================================================================================

// The hardware's float -> unsigned small float (Vulkan spec, "Unsigned 11-Bit / 10-Bit
// Floating-Point Numbers": 5-bit exponent, bias 15, `mbits` of mantissa, no sign; D3D11's
// conversion rules: round to nearest even, negative -> 0, denormals kept), computed in double from
// the float's exact value. Values beyond the largest finite (65024, 64512) are not given here.
uint32_t smallFloatRne(float x, int mbits) {
    if (!(x > 0.0f)) return 0u;  // 0, -0 and negative
    const double v = double(x);
    int e2 = 0;
    std::frexp(v, &e2);                                // v = f 2^e2, f in [0.5, 1)
    const int e = std::max(e2 - 1, -14);               // the binade; denormals share 2^-14's step
    const double q = std::nearbyint(std::ldexp(v, mbits - e));  // the mantissa with its leading 1, rounded to even
    uint64_t m = uint64_t(q);
    int field = e + 15;
    if (m >= (uint64_t(2) << mbits)) {  // rounded up into the next binade
        m >>= 1;
        ++field;
    }
    if (m < (uint64_t(1) << mbits)) return uint32_t(m);  // a denormal (field 0)
    return uint32_t(field) << mbits | uint32_t(m - (uint64_t(1) << mbits));
}

// The texel the lighting pass reads back: exact.
float smallFloatValue(uint32_t code, int mbits) {
    const uint32_t m = code & ((1u << mbits) - 1u), field = code >> mbits;
    if (field == 0) return float(std::ldexp(double(m), -14 - mbits));
    return float(std::ldexp(1.0 + std::ldexp(double(m), -mbits), int(field) - 15));
}

// EncodeIntoGBuffer's GBuffer3 word for emissive `e` and ambient occlusion `ao`.
uint32_t hdrpGBuffer3(glm::vec3 e, float ao) {
    glm::vec3 rgb = glm::vec3(0.0f) * ao + e;  // bakeDiffuseLighting = 0
    rgb *= 1.0f;                               // GetCurrentExposureMultiplier() = 1
    float x = rgb.x, y = rgb.y, z = rgb.z;
    if (rgb.x == 0.0f && rgb.y == 0.0f && rgb.z == 0.0f) {
        x = float(1 << 11);
        y = ao;
        z = float(1 << 10);
    }
    return smallFloatRne(x, 6) | smallFloatRne(y, 6) << 11 | smallFloatRne(z, 5) << 22;
}

const char* kHdrpGBuffer3Layout = R"(name = "hdrp-gbuffer3"
title = "HDRP's GBuffer3 with its AO tag"
pipeline = "deferred-shading"
source = { engine = "Unity HDRP", talk = "unit test", year = 2021 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "GBuffer1"
format = "R8G8B8A8_UNORM"
field = [
  { attribute = "normal",    encoding = "normal_octahedral_hdrp", at = ["r + b[0:3]", "g + b[4:7]"] },
  { attribute = "roughness", encoding = "unorm", at = "a" },
]
[[target]]
name = "GBuffer3"
format = "B10G11R11_UFLOAT_PACK32"
field = [
  { attribute = "emissive", encoding = "float11_11_10_hdrp_ao_tag", at = ["r", "g", "b"] },
]
[fallback]
base_color = 0.5
metallic = 0.0
specular = 0.5
specular_color = "from_metallic"
diffuse_color = "from_base_color"
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, 1.0]
roughness = 1.0
emissive = 0.0
occlusion = 1.0
)";

// The i-th (emissive, AO): edges first, then a third with emissive exactly 0 (the tag), a third
// small (float11's denormals, and values that quantise to 0 without being 0), a third wide.
struct EmissiveAo {
    glm::vec3 e;
    float ao;
};
EmissiveAo hdrpGBuffer3Input(Rng& rng, size_t i) {
    // AO edges: 0, -0, 1, float11's smallest denormal (2^-20) and half of it (a tie: to 0), the
    // largest denormal and the first normal (2^-14), ties of the 6-bit mantissa, beyond 1.
    static const float kAo[] = {0.0f, -0.0f, 1.0f, 0x1.0p-20f, 0x1.0p-21f, 0x1.8p-21f, 63.0f * 0x1.0p-20f,
                                0x1.0p-14f, 0x1.fcp-15f, 1.0f + 0.5f / 64.0f, 1.0f + 1.5f / 64.0f, 0.5f + 0.25f / 64.0f,
                                0.75f, 0.999f, 1e-7f, 2.0f};
    static const glm::vec3 kE[] = {{0, 0, 0}, {-0.0f, 0, -0.0f}, {1e-30f, 0, 0}, {0, 0, 0x1.0p-21f},
                                   {0, 0x1.0p-20f, 0}, {2048.0f, 0.0f, 1024.0f}, {2048.0f, 0.5f, 1024.0f},
                                   {65024.0f, 65024.0f, 64512.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 0.0f, 0.0f}};
    constexpr size_t nAo = sizeof kAo / sizeof kAo[0], nE = sizeof kE / sizeof kE[0];
    if (i < nAo * nE) return {kE[i / nAo], kAo[i % nAo]};
    EmissiveAo in;
    const double u = rng.u01();
    in.ao = i % 7 == 0 ? kAo[i % nAo] : i % 5 == 0 ? float(std::ldexp(rng.u01(), -14 - int(i % 8))) : float(u);
    switch (i % 3) {
        case 0: in.e = glm::vec3(i % 2 ? -0.0f : 0.0f, 0.0f, 0.0f); break;
        case 1:
            for (int k = 0; k < 3; ++k) in.e[k] = float(std::ldexp(rng.u01(), -12 - int(rng.u01() * 12.0)));
            break;
        default:
            for (int k = 0; k < 3; ++k) in.e[k] = float(std::exp2(rng.u01() * 29.9 - 14.0) * (k == 2 ? 0.98 : 1.0));
            break;
    }
    return in;
}

TEST(EnginePackings, HdrpGBuffer3EqualsEncodeIntoGBufferWithItsAoTag) {
    const Layout layout = gbl::parseLayout(kHdrpGBuffer3Layout, "hdrp-gbuffer3.toml");
    const CpuCodec codec(layout);
    Rng rng(2809);
    std::vector<Surface> surfaces(kImage), decoded;
    CpuGBuffer g;
    size_t compared = 0, tags = 0, aoDenormals = 0, mismatches = 0, decodeMismatches = 0;
    for (size_t first = 0; first < kInputs; first += kImage) {
        for (size_t j = 0; j < kImage; ++j) {
            const EmissiveAo in = hdrpGBuffer3Input(rng, first + j);
            surfaces[j] = Surface{};
            surfaces[j].normal = glm::vec3(0.0f, 1.0f, 0.0f);
            surfaces[j].emissive = in.e;
            surfaces[j].occlusion = in.ao;
        }
        codec.encode(surfaces, kWidth, kHeight, g);
        codec.decode(g, decoded);
        for (size_t j = 0; j < kImage; ++j) {
            const Surface& s = surfaces[j];
            const uint32_t w = g.targetWords.at(1)[j], want = hdrpGBuffer3(s.emissive, s.occlusion);
            ++compared;
            if (w != want && mismatches++ < 8)
                ADD_FAILURE() << "emissive " << vec(s.emissive) << " AO " << s.occlusion << ": gbufferlab " << hex(w)
                              << ", HDRP " << hex(want);
            // DecodeFromGBuffer on the texel's floats.
            const float r = smallFloatValue(want & 2047u, 6), gg = smallFloatValue((want >> 11) & 2047u, 6),
                        b = smallFloatValue(want >> 22, 5);
            const bool tag = r == float(1 << 11) && b == float(1 << 10);
            tags += tag;
            aoDenormals += tag && ((want >> 11) & 2047u) != 0 && ((want >> 11) & 2047u) < 64u;
            const float ao = tag ? gg : 1.0f;
            const glm::vec3 e = tag ? glm::vec3(0.0f) : glm::vec3(r, gg, b);  // * 1 / exposure
            auto bits = [](float f) { return std::bit_cast<uint32_t>(f); };
            if ((bits(decoded[j].occlusion) != bits(ao) || bits(decoded[j].emissive.x) != bits(e.x) ||
                 bits(decoded[j].emissive.y) != bits(e.y) || bits(decoded[j].emissive.z) != bits(e.z)) &&
                decodeMismatches++ < 8)
                ADD_FAILURE() << "word " << hex(want) << ": gbufferlab decodes emissive " << vec(decoded[j].emissive)
                              << " AO " << decoded[j].occlusion << ", HDRP " << vec(e) << " AO " << ao;
        }
    }
    std::printf("[ hdrp gb3 ] %zu words (%zu AO tags, %zu of them with a denormal AO)\n", compared, tags, aoDenormals);
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(decodeMismatches, 0u);
    EXPECT_GT(tags, kInputs / 4);  // the tag, with and without emissive's signed zeros, is a third of the inputs
    EXPECT_GT(aoDenormals, kInputs / 100);
    // The words the issue names: AO 1 -> 0xC81E0680, AO 0 -> 0xC8000680.
    EXPECT_EQ(hdrpGBuffer3(glm::vec3(0.0f), 1.0f), 0xC81E0680u);
    EXPECT_EQ(hdrpGBuffer3(glm::vec3(0.0f), 0.0f), 0xC8000680u);
}

// ==================================================================================================
// URP without accurate normals (urp-deferred): GBuffer2 R8G8B8A8_SNORM holds PackNormal(n) = n
// itself (UnityGBuffer.hlsl:109-110, universal 13.0.0 830d63151c83) and smoothness in alpha
// (:210); the hardware's float -> SNORM8 conversion quantises both. Desktop half is float.
// ==================================================================================================

const char* kUrpSnormLayout = R"(name = "urp-snorm"
title = "urp-deferred's GBuffer2"
pipeline = "deferred-shading"
source = { engine = "Unity URP", talk = "unit test", year = 2021 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "GBuffer2"
format = "R8G8B8A8_SNORM"
field = [
  { attribute = "normal",    encoding = "snorm", at = ["r", "g", "b"] },
  { attribute = "roughness", encoding = "gloss", at = "a[0:6]" },
]
[fallback]
base_color = 0.5
metallic = 0.0
specular = 0.5
specular_color = "from_metallic"
diffuse_color = "from_base_color"
occlusion = 1.0
emissive = 0.0
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, 1.0]
roughness = 1.0
)";

TEST(EnginePackings, UrpSnormNormalsEqualTheHardwareConversion) {
    const Layout layout = gbl::parseLayout(kUrpSnormLayout, "urp-snorm.toml");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2804);
    std::vector<Surface> keep(kImage);
    Tally t;
    runCodec(layout, 0,
             [&](size_t i) {
                 Surface s;
                 s.normal = normalInput(edges, rng, i);
                 if (i % 8 == 5) s.normal.x = float((int(i) % 255 - 127 + 0.5) / 127.0);  // on SNORM ties
                 s.roughness = float(rng.u01());
                 keep[i % kImage] = s;
                 return s;
             },
             [&](size_t i, int, int, const uint32_t* w) {
                 const Surface& s = keep[i % kImage];
                 for (int k = 0; k < 3; ++k) {
                     const HardwareCode c = hardwareSnorm(s.normal[k], 8);
                     t.nearTies += c.nearTie;
                     ++t.compared;
                     if (!accepts(c, (w[0] >> (8 * k)) & 255u))
                         t.fail("component " + std::to_string(k) + " of " + vec(s.normal) + ": gbufferlab " + hex(w[0]));
                 }
                 // smoothness = 1 - perceptual roughness, in [0, 1]: a non-negative SNORM8 code.
                 const HardwareCode a = hardwareSnorm(1.0f - s.roughness, 8);
                 t.nearTies += a.nearTie;
                 if (!accepts(a, w[0] >> 24)) t.fail("alpha of roughness " + std::to_string(s.roughness) + ": " + hex(w[0]));
             });
    std::printf("[ urp snorm] %zu components, %zu near a tie\n", t.compared, t.nearTies);
    EXPECT_EQ(t.mismatches, 0u);
    // An eighth of the x components are placed on SNORM ties (a few of them clamp at 1).
    EXPECT_GT(t.nearTies, kInputs / 9);
    EXPECT_LT(t.nearTies, kInputs / 8 + edges.size() + kInputs / 500);
}

// ==================================================================================================
// niagara (zeux/niagara @95f289b7b8c0): gbuffer1 = A2B10G10R10_UNORM_PACK32 (niagara.cpp:636)
// written by mesh.frag.glsl:86 as vec4(encodeOct(nrm) * 0.5 + 0.5 + deband * (0.5 / 1023),
// specgloss.a, 0.0), deband = gradientNoise(gl_FragCoord.xy) * 2 - 1 (:60).
// ==================================================================================================

// src/shaders/math.h:52-58.
glm::vec2 niagaraEncodeOct(glm::vec3 v) {
    const float r = 1.0f / (std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z));
    const glm::vec2 p(v.x * r, v.y * r);
    const glm::vec2 s(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f);
    return v.z <= 0.0f ? glm::vec2((1.0f - std::fabs(p.y)) * s.x, (1.0f - std::fabs(p.x)) * s.y) : p;
}

// src/shaders/math.h:99-102: fract(52.9829189 * fract(dot(uv, vec2(0.06711056, 0.00583715)))),
// fract(x) = x - floor(x), the dot's products added in order.
float niagaraGradientNoise(glm::vec2 uv) {
    const float d = uv.x * 0.06711056f + uv.y * 0.00583715f;
    const float f = 52.9829189f * (d - std::floor(d));
    return f - std::floor(f);
}

const char* kNiagaraLayout = R"(name = "niagara-packing"
title = "niagara's gbuffer1"
pipeline = "deferred-shading"
source = { engine = "niagara", talk = "unit test", year = 2024 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "gbuffer1"
format = "A2B10G10R10_UNORM_PACK32"
field = [
  { attribute = "normal",    encoding = "normal_octahedral_dithered", bits = 10, at = ["r", "g"] },
  { attribute = "roughness", encoding = "gloss",                      at = "b" },
]
[fallback]
base_color = 0.5
metallic = 0.0
specular = 0.5
specular_color = "from_metallic"
diffuse_color = "from_base_color"
occlusion = 1.0
emissive = 0.0
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, 1.0]
roughness = 1.0
)";

TEST(EnginePackings, NiagaraNormalsEqualEncodeOctWithItsDeband) {
    const Layout layout = gbl::parseLayout(kNiagaraLayout, "niagara-packing.toml");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2805);
    std::vector<Surface> keep(kImage);
    Tally t;
    runCodec(layout, 0,
             [&](size_t i) {
                 Surface s;
                 s.normal = normalInput(edges, rng, i);
                 s.roughness = float(rng.u01());
                 keep[i % kImage] = s;
                 return s;
             },
             [&](size_t i, int x, int y, const uint32_t* w) {
                 const Surface& s = keep[i % kImage];
                 // gl_FragCoord.xy of pixel (x, y) is its centre (no sample shading).
                 const float deband = niagaraGradientNoise(glm::vec2(float(x) + 0.5f, float(y) + 0.5f)) * 2.0f - 1.0f;
                 const glm::vec2 o = niagaraEncodeOct(s.normal);
                 const float d = deband * (0.5f / 1023.0f);
                 const HardwareCode r = hardwareUnorm(o.x * 0.5f + 0.5f + d, 10);
                 const HardwareCode g = hardwareUnorm(o.y * 0.5f + 0.5f + d, 10);
                 const HardwareCode b = hardwareUnorm(1.0f - s.roughness, 10);  // specgloss.a = 1 - roughness factor
                 t.nearTies += r.nearTie + g.nearTie + b.nearTie;
                 ++t.compared;
                 if (!accepts(r, w[0] & 1023u) || !accepts(g, (w[0] >> 10) & 1023u) || !accepts(b, (w[0] >> 20) & 1023u) ||
                     (w[0] >> 30) != 0u)
                     t.fail("normal " + vec(s.normal) + " at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            "): gbufferlab " + hex(w[0]) + ", niagara " + hex(r.nearest | g.nearest << 10 | b.nearest << 20));
             });
    std::printf("[ niagara  ] %zu words, %zu codes near a tie\n", t.compared, t.nearTies);
    EXPECT_EQ(t.mismatches, 0u);
    EXPECT_LT(t.nearTies, kInputs / 1000);
}

// ==================================================================================================
// Granite (Themaister/Granite @cdb82322f886): the normal target A2B10G10R10_UNORM_PACK32
// (application/scene_viewer_application.cpp:692) holds Normal = 0.5 * normal + 0.5
// (assets/shaders/inc/render_target.h:24) through the hardware's UNORM conversion; alpha unwritten.
// ==================================================================================================

const char* kGraniteLayout = R"(name = "granite-packing"
title = "Granite's normal target"
pipeline = "deferred-shading"
source = { engine = "Granite", talk = "unit test", year = 2018 }
[depth]
format = "D32_SFLOAT"
[[target]]
name = "normal"
format = "A2B10G10R10_UNORM_PACK32"
field = [
  { attribute = "normal", encoding = "normal_xyz", bits = 10, at = ["r", "g", "b"] },
]
[[target]]
name = "pbr"
format = "R8G8_UNORM"
field = [
  { attribute = "metallic",  encoding = "unorm", at = "r" },
  { attribute = "roughness", encoding = "unorm", at = "g" },
]
[fallback]
base_color = 0.5
specular = 0.5
specular_color = "from_metallic"
diffuse_color = "from_base_color"
occlusion = 1.0
emissive = 0.0
[space]
normal = "world"
up = "y"
[clear]
normal = [0.0, 0.0, 1.0]
roughness = 1.0
metallic = 0.0
)";

TEST(EnginePackings, GraniteNormalsEqualHalfNormalPlusHalf) {
    const Layout layout = gbl::parseLayout(kGraniteLayout, "granite-packing.toml");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2806);
    std::vector<Surface> keep(kImage);
    Tally t;
    runCodec(layout, 0,
             [&](size_t i) {
                 Surface s;
                 s.normal = normalInput(edges, rng, i);
                 if (i % 8 == 6) s.normal.y = float(((int(i) % 1023) + 0.5) / 1023.0 * 2.0 - 1.0);  // on ties
                 keep[i % kImage] = s;
                 return s;
             },
             [&](size_t i, int, int, const uint32_t* w) {
                 const Surface& s = keep[i % kImage];
                 ++t.compared;
                 for (int k = 0; k < 3; ++k) {
                     const HardwareCode c = hardwareUnorm(0.5f * s.normal[k] + 0.5f, 10);
                     t.nearTies += c.nearTie;
                     if (!accepts(c, (w[0] >> (10 * k)) & 1023u))
                         t.fail("component " + std::to_string(k) + " of " + vec(s.normal) + ": gbufferlab " + hex(w[0]));
                 }
             });
    std::printf("[ granite  ] %zu words, %zu codes near a tie\n", t.compared, t.nearTies);
    EXPECT_EQ(t.mismatches, 0u);
    // An eighth of the y components are placed on 10-bit ties, and some edge values are on them.
    EXPECT_GT(t.nearTies, kInputs / 9);
    EXPECT_LT(t.nearTies, kInputs / 8 + edges.size() + kInputs / 500);
}

}  // namespace
