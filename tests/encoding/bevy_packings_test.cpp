// Bevy's deferred G-buffer (bevyengine/bevy v0.16.0 e9418b3845c1): the native packing and the
// WebGL2 one, each written out again here from reading Bevy's WGSL (not copied) and compared bit
// for bit with the words gbufferlab's CPU codec writes for the layout, on 2^20 seeded inputs with
// edge values (engine_packing_support.h; engine_packings_test.cpp says why and how in full).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine_packing_support.h"
#include "layout_catalog.h"

namespace {

using namespace gbl::test::packing;

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

TEST(EnginePackings, BevyDeferredWordsEqualBevysPacking) {
    const Layout layout = gbl::loadLayout("bevy-deferred");  // the shipped row itself
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
// Bevy on WebGL2 (the same files, their WEBGL2 branches; Naga cannot sample depth textures there,
// core_3d/mod.rs:53-57). Word b = pack_unorm3x4_plus_unorm_20_(vec4(reflectance, metallic,
// diffuse_occlusion, frag_coord.z)) (pbr_deferred_functions.wgsl:35-40); read back with the
// reflectance biased by -0.03333333333 (:103-106), and the lighting takes frag_coord.z from it
// (deferred_lighting.wgsl:51-52). Checked on the shipped layouts/bevy-deferred-webgl2.toml, whose
// `depth` rides in Surface.position.z (wiring_plan.h).
// ==================================================================================================

// pbr_deferred_types.wgsl:74-79: vec3<u32>(saturate(v.xyz) * 15.0 + 0.5); u32(saturate(v.w) *
// U20MAXF + 0.5) (U20MAXF = 1048575.0, :32); (bg << 12) | (sm.z << 8) | (sm.y << 4) | sm.x.
uint32_t bevyPackUnorm3x4PlusUnorm20(glm::vec4 v) {
    uint32_t sm[3];
    for (int k = 0; k < 3; ++k) sm[k] = uint32_t(clamp01(v[k]) * 15.0f + 0.5f);
    const uint32_t bg = uint32_t(clamp01(v.w) * 1048575.0f + 0.5f);
    return (bg << 12u) | (sm[2] << 8u) | (sm[1] << 4u) | sm[0];
}

// pbr_deferred_types.wgsl:82-89 (the 24-bit mask after a 12-bit shift keeps the 20 bits).
glm::vec4 bevyUnpackUnorm3x4PlusUnorm20(uint32_t v) {
    return {float(v & 0xFu) / 15.0f, float((v >> 4u) & 0xFu) / 15.0f, float((v >> 8u) & 0xFu) / 15.0f,
            float((v >> 12u) & 0xFFFFFFu) / 1048575.0f};
}

TEST(EnginePackings, BevyWebgl2WordBEqualsBevysPackingAndReadsBackAsBevy) {
    const Layout layout = gbl::loadLayout("bevy-deferred-webgl2");
    Rng rng(2802);
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = glm::vec3(0.0f, 0.0f, 1.0f);
        s.baseColor = glm::vec3(float(rng.u01()));
        s.roughness = float(rng.u01());
        // 4-bit ties (k + 0.5) / 15 and values outside [0, 1] among uniform ones.
        auto unit4 = [&](size_t salt) {
            if ((i + salt) % 16 == 0) return float((double(rng.gen() % 15) + 0.5) / 15.0);
            if ((i + salt) % 16 == 1) return float(rng.u01() * 1.4 - 0.2);
            return float(rng.u01());
        };
        s.metallic = unit4(0);
        s.occlusion = unit4(5);
        s.specular = unit4(11);
        // The depth: 20-bit code ties (k + 0.5) / 1048575 and the floats either side, 0, 1, outside
        // [0, 1], tiny; else uniform (a reversed-Z depth crowds near 0, so half of these are cubed).
        float z = float(rng.u01());
        const double tie = (double(rng.gen() % 1048575u) + 0.5) / 1048575.0;
        switch (i % 10) {
            case 0: z = float(tie); break;
            case 1: z = std::nextafter(float(tie), 0.0f); break;
            case 2: z = std::nextafter(float(tie), 1.0f); break;
            case 3: {
                const float edges[] = {0.0f, -0.0f, 1.0f, std::nextafter(1.0f, 0.0f), 1e-30f, 1e-7f, -0.25f, 1.5f};
                z = edges[rng.gen() % 8];
                break;
            }
            case 4: case 5: z = z * z * z; break;
            default: break;
        }
        s.position = glm::vec3(0.0f, 0.0f, z);
        keep[i % kImage] = s;
        return s;
    };
    Tally bWord;
    size_t occlusionUlpFlips = 0, depthTies = 0;
    runCodec(layout, 0, make, [&](size_t i, int, int, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        // gbufferlab's specular is UE's (F0 = 0.08 s); Bevy's reflectance r has F0 = 0.16 r^2, so
        // Bevy's input here is r = sqrt(s / 2) (float sqrt, correctly rounded).
        const float reflectance = std::sqrt(clamp01(s.specular) * 0.5f);
        // Rec. 709 luminance of a grey occlusion: the occlusion in real arithmetic; its last ulp can
        // move a 4-bit code only next to a tie (counted, as in the native test).
        const float occ = s.occlusion * 0.2126f + s.occlusion * 0.7152f + s.occlusion * 0.0722f;
        uint32_t b = bevyPackUnorm3x4PlusUnorm20(glm::vec4(reflectance, s.metallic, occ, s.position.z));
        if (occ != s.occlusion && ((w[2] ^ b) & 0xF00u) != 0u) {
            const uint32_t own = bevyPackUnorm3x4PlusUnorm20(glm::vec4(reflectance, s.metallic, s.occlusion, s.position.z));
            if ((w[2] & 0xF00u) == (own & 0xF00u)) {
                ++occlusionUlpFlips;
                b = (b & ~0xF00u) | (own & 0xF00u);
            }
        }
        // Near a tie: the exact product lies within float's rounding of it (the float arithmetic decides).
        const double z20 = double(clamp01(s.position.z)) * 1048575.0;
        depthTies += std::fabs(z20 - std::floor(z20) - 0.5) <= z20 * 0x1.0p-23;
        ++bWord.compared;
        if (w[2] != b)
            bWord.fail("b word of reflectance " + std::to_string(reflectance) + ", metallic " + std::to_string(s.metallic) +
                       ", occlusion " + std::to_string(s.occlusion) + ", depth " + std::to_string(s.position.z) +
                       ": gbufferlab " + hex(w[2]) + ", Bevy " + hex(b));
    });
    std::printf("[ webgl2   ] %zu b words (%zu depths within float rounding of a 20-bit tie, %zu occlusion codes moved by "
                "the dot's last ulp)\n",
                bWord.compared, depthTies, occlusionUlpFlips);
    EXPECT_EQ(bWord.mismatches, 0u);
    EXPECT_GT(depthTies, kInputs / 5);  // the ties were reached, so rounding is tested there
    // Only next to the constructed 4-bit ties (a sixteenth of the inputs), never elsewhere.
    EXPECT_LT(occlusionUlpFlips, kInputs / 16);

    // The read: every combination of the three 4-bit codes with depth codes 0, 1, the top, and
    // random ones, through gbufferlab's decode, against unpack_unorm3x4_plus_unorm_20_ and the bias.
    const CpuCodec codec(layout);
    CpuGBuffer g;
    g.width = 4096;
    g.height = 16;
    const size_t n = size_t(g.width) * size_t(g.height);
    g.targetWords = {std::vector<uint32_t>(n * 4, 0u), std::vector<uint32_t>(n, 1u)};
    for (size_t i = 0; i < n; ++i) {
        const uint32_t depth = i / 4096 == 0 ? 0u : i / 4096 == 1 ? 1u : i / 4096 == 2 ? 1048575u : uint32_t(rng.gen() % 1048576u);
        g.targetWords[0][i * 4 + 2] = depth << 12u | uint32_t(i % 4096);
    }
    const std::vector<Surface> decoded = codec.decode(g);
    Tally read;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t word = g.targetWords[0][i * 4 + 2];
        const glm::vec4 bevy = bevyUnpackUnorm3x4PlusUnorm20(word);
        const float r = clamp01(bevy.x - 0.03333333333f);  // :106, saturate(props.r - 0.03333333333)
        const Surface& d = decoded[i];
        ++read.compared;
        if (d.position.z != bevy.w || d.metallic != bevy.y || d.occlusion != bevy.z || d.specular != 2.0f * r * r)
            read.fail("word " + hex(word) + ": gbufferlab depth " + std::to_string(d.position.z) + " metallic " +
                      std::to_string(d.metallic) + " occlusion " + std::to_string(d.occlusion) + " specular " +
                      std::to_string(d.specular) + ", Bevy " + std::to_string(bevy.w) + " " + std::to_string(bevy.y) + " " +
                      std::to_string(bevy.z) + " reflectance " + std::to_string(r));
    }
    EXPECT_EQ(read.mismatches, 0u);
    // Bevy's comment: the bias makes code 8, the default reflectance 0.5's, read 0.5 exactly
    // (F0 = 0.04); and code 0 stays 0 (saturate).
    EXPECT_EQ(clamp01(bevyUnpackUnorm3x4PlusUnorm20(8u).x - 0.03333333333f), 0.5f);
    EXPECT_EQ(decoded[8].specular, 0.5f);
    EXPECT_EQ(decoded[0].specular, 0.0f);
}

}  // namespace
