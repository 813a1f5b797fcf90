// The material layers as shipped engines pack them (issue 40, item 4): each engine's arithmetic
// written out again here from reading its source (not copied), and compared bit for bit with the
// words gbufferlab's CPU codec writes for the shipped row, on 2^20 seeded inputs with the edge
// values (ties of every quantiser, out-of-range values); then the engine's read of those words
// against the codec's decode. The rows and their pins:
//   bevy-deferred-clearcoat  bevyengine/bevy v0.19.0 c6f634ca (pull request 23359, fca2279c)
//   hdrp-lit, hdrp-lit-apv   HDRP 13.0.0 c667268a, core 13.0.0 6363fa25 (the coat mask; the
//                            anisotropic feature under the selector)
//   ue5-clearcoat, ue5-cloth UE 5.3.2, Mephisto1024/Toon_Engine 1a10ef19
//   ue5, ue5-anisotropy      the same, the shading model per pixel (the selector)
// and UE's clear-coat bottom normal (r.ClearCoatNormal = 1, off by default), against
// engine_encodings.h's encoder and decoder directly and in its row, ue5-clearcoat-normal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "encodings.h"
#include "engine_packing_support.h"
#include "layout_catalog.h"

namespace {

using namespace gbl::test::packing;

// The i-th scalar input: ties of the quantiser with `steps` steps over [0, top] and the floats
// beside them, the ends, out-of-range values, then uniform values over [-0.1, 1.1].
float scalarInput(Rng& rng, size_t i, int steps, float top) {
    const size_t ties = size_t(steps) * 3;
    if (i < ties) {
        const int k = int(i / 3);
        const float t = float((k + 0.5) / steps * top);
        return i % 3 == 0 ? t : i % 3 == 1 ? std::nextafter(t, -1.0f) : std::nextafter(t, 2.0f);
    }
    const float edges[] = {0.0f, -0.0f, 1.0f, top, std::nextafter(top, 2.0f), -1e-30f, -1.0f, 2.0f, 1e-40f, 0.5f};
    if (i < ties + std::size(edges)) return edges[i - ties];
    if (i % 7 == 0) {  // a tie of a random step, as a float may round it either way
        const int k = int(rng.u01() * steps);
        return float((k + 0.5) / steps * top);
    }
    return float(rng.u01() * 1.2 - 0.1);
}

// WGSL's round(): to the nearest integer, a half to the even one (WGSL spec, "round").
float wgslRound(float x) {
    const float f = std::floor(x);
    const float d = x - f;  // exact for the magnitudes here
    if (d > 0.5f) return f + 1.0f;
    if (d < 0.5f) return f;
    return std::fmod(f, 2.0f) == 0.0f ? f : f + 1.0f;
}

// ==================================================================================================
// Bevy 0.19: word b's fourth byte (pbr_deferred_functions.wgsl:42-50 at v0.19.0 c6f634ca):
//   clearcoat = u32(round(saturate(clearcoat) * 15.0))
//   roughness = u32(round(clamp(clearcoat_perceptual_roughness, 0.0, 0.5) * 30.0))
//   byte      = pack_unorm4x8_'s w of f32(clearcoat | roughness << 4) / 255.0
// read back (:113-116): c = u32(round(props.a * 255.0)); clearcoat = f32(c & 15) / 15.0,
// roughness = f32(c >> 4) / 30.0.
// ==================================================================================================

uint32_t bevyClearcoatByte(float clearcoat, float roughness) {
    const uint32_t c = uint32_t(wgslRound(clamp01(clearcoat) * 15.0f));
    const uint32_t r = uint32_t(wgslRound(std::min(std::max(roughness, 0.0f), 0.5f) * 30.0f));
    const float props = float(c | (r << 4u)) / 255.0f;
    return uint32_t(clamp01(props) * 255.0f + 0.5f);  // pack_unorm4x8_, pbr_deferred_types.wgsl:69-72
}

TEST(LayerPackings, BevyClearcoatByteEqualsPullRequest23359) {
    const Layout layout = gbl::loadLayout("bevy-deferred-clearcoat");
    const Layout before = gbl::loadLayout("bevy-deferred");  // Bevy 0.16: the byte spare
    const size_t target = targetIndex(layout, "deferred");
    Rng rng(4023);
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = glm::normalize(glm::vec3(float(rng.u01()) - 0.5f, float(rng.u01()) - 0.5f, float(rng.u01()) - 0.5f) + glm::vec3(0, 0, 1e-3f));
        s.baseColor = glm::vec3(float(rng.u01()), float(rng.u01()), float(rng.u01()));
        s.roughness = float(rng.u01());
        s.metallic = float(rng.u01());
        s.occlusion = float(rng.u01());
        s.specular = float(rng.u01());
        s.emissive = glm::vec3(float(rng.u01() * 4.0));
        // Strength and roughness on their own ties, in every combination over the inputs.
        s.coat = scalarInput(rng, i % 4096, 15, 1.0f);
        s.coatRoughness = scalarInput(rng, (i / 4096) % 4096, 30, 1.0f);
        keep[i % kImage] = s;
        return s;
    };
    // The same Surfaces through Bevy 0.16's row: everything but the byte is unchanged.
    const CpuCodec older(before);
    CpuGBuffer g;
    Tally byte, rest;
    size_t strengthTies = 0, roughnessTies = 0;
    std::vector<uint32_t> oldWords;
    runCodec(layout, target, make, [&](size_t i, int x, int y, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        if (x == 0 && y == 0) {  // once per image: the old row's words of the same Surfaces
            older.encode(keep, kWidth, kHeight, g);
            oldWords = g.targetWords.at(0);
        }
        const uint32_t want = bevyClearcoatByte(s.coat, s.coatRoughness);
        ++byte.compared;
        if ((w[2] >> 24u) != want)
            byte.fail("coat " + std::to_string(s.coat) + ", roughness " + std::to_string(s.coatRoughness) +
                      ": gbufferlab byte " + std::to_string(w[2] >> 24u) + ", Bevy " + std::to_string(want));
        // A tie of WGSL's round, where quantizeUnorm's floor(x + 0.5) would round up.
        const float c15 = clamp01(s.coat) * 15.0f, r30 = std::min(std::max(s.coatRoughness, 0.0f), 0.5f) * 30.0f;
        strengthTies += c15 - std::floor(c15) == 0.5f && std::fmod(std::floor(c15), 2.0f) == 0.0f;
        roughnessTies += r30 - std::floor(r30) == 0.5f && std::fmod(std::floor(r30), 2.0f) == 0.0f;
        const uint32_t* o = &oldWords[size_t(y * kWidth + x) * 4];
        ++rest.compared;
        if (o[0] != w[0] || o[1] != w[1] || o[3] != w[3] || (o[2] & 0x00FFFFFFu) != (w[2] & 0x00FFFFFFu))
            rest.fail("words beside the byte differ from bevy-deferred's at input " + std::to_string(i));
    });
    std::printf("[ bevy 0.19] %zu clear-coat bytes (%zu strength and %zu roughness ties rounded to even)\n",
                byte.compared, strengthTies, roughnessTies);
    EXPECT_EQ(byte.mismatches, 0u);
    EXPECT_EQ(rest.mismatches, 0u);
    EXPECT_GT(strengthTies, 100u);  // the inputs reach the ties where half-up and half-even part
    EXPECT_GT(roughnessTies, 100u);
    // The pull request's own defaults: StandardMaterial's clearcoat 0, roughness 0.5 -> 0xF0.
    EXPECT_EQ(bevyClearcoatByte(0.0f, 0.5f), 0xF0u);
    EXPECT_EQ(bevyClearcoatByte(1.0f, 1.0f), 0xFFu);
    EXPECT_EQ(bevyClearcoatByte(0.3f, 0.15f), 4u | (4u << 4u));  // 4.5 -> 4, 4.5 -> 4: ties to even

    // Bevy's read of every byte against the codec's decode.
    const gbl::CpuCodec codec(layout);
    std::vector<Surface> all(256);
    for (int c = 0; c < 256; ++c) {
        all[size_t(c)].normal = glm::vec3(0, 0, 1);
        all[size_t(c)].coat = float(c & 15) / 15.0f;
        all[size_t(c)].coatRoughness = float(c >> 4) / 30.0f;
    }
    CpuGBuffer one;
    codec.encode(all, 256, 1, one);
    const std::vector<Surface> back = codec.decode(one);
    for (int c = 0; c < 256; ++c) {
        const uint32_t b = one.targetWords.at(target)[size_t(c) * 4 + 2] >> 24u;
        ASSERT_EQ(b, uint32_t(c));  // every byte is reachable, and each is its own code
        const float props = float(b) / 255.0f;  // unpack_unorm4x8_ (pbr_deferred_types.wgsl:58-65)
        const uint32_t read = uint32_t(wgslRound(props * 255.0f));
        EXPECT_EQ(back[size_t(c)].coat, float(read & 15u) / 15.0f) << c;
        EXPECT_EQ(back[size_t(c)].coatRoughness, float(read >> 4u) / 30.0f) << c;
        EXPECT_EQ(back[size_t(c)].coatNormal, glm::vec3(0.0f)) << c;  // clearcoat_N = N: the base normal
    }
}

// ==================================================================================================
// HDRP 13: GBuffer2.a = PackFloatInt8bit(coatMask, materialFeatureId, 8) (Lit.hlsl:664-667 at
// c667268a), PackFloatInt(f, i, 8, 256) = t1 f + t2 i with t1 = (256 / 8 - 1) / 255 and t2 =
// (256 / 8) / 255 (core Packing.hlsl:437-465 at 6363fa25), into a UNORM byte by the hardware; read
// back by UnpackFloatInt (:447-459): i = int(val / t2 + 1 / 255), f = saturate((val - t2 i) / t1).
// ==================================================================================================

TEST(LayerPackings, HdrpCoatMaskEqualsPackFloatInt8bit) {
    const Layout layout = gbl::loadLayout("hdrp-lit");
    const size_t target = targetIndex(layout, "GBuffer2");
    const float t1 = (256.0f / 8.0f - 1.0f) / 255.0f, t2 = (256.0f / 8.0f) / 255.0f;
    const uint32_t featureId = 0;  // GBUFFER_LIT_STANDARD (MaterialGBufferMacros.hlsl:29)
    Rng rng(1313);
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = glm::vec3(0, 1, 0);
        s.specularColor = glm::vec3(0.04f);
        s.coat = scalarInput(rng, i, 31, 1.0f);
        keep[i % kImage] = s;
        return s;
    };
    Tally mask;
    runCodec(layout, target, make, [&](size_t i, int, int, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        // coatMask is a [0, 1] material property (saturated before it reaches the G-buffer).
        const float val = t1 * clamp01(s.coat) + t2 * float(featureId);
        const HardwareCode c = hardwareUnorm(val, 8);
        ++mask.compared;
        if (c.nearTie) ++mask.nearTies;
        if (!accepts(c, w[0] >> 24u))
            mask.fail("coat " + std::to_string(s.coat) + ": gbufferlab byte " + std::to_string(w[0] >> 24u) +
                      ", HDRP " + std::to_string(c.nearest));
    });
    std::printf("[ hdrp     ] %zu coat-mask bytes (%zu within the hardware's latitude at a tie)\n", mask.compared, mask.nearTies);
    EXPECT_EQ(mask.mismatches, 0u);
    EXPECT_GT(mask.nearTies, 0u);            // the inputs reach the byte's ties (a seventh of them aim there) ...
    EXPECT_LT(mask.nearTies, kInputs / 5);   // ... and the rest are compared exactly

    // The read: every 5-bit mask, HDRP's UnpackFloatInt8bit against the codec's decode.
    const gbl::CpuCodec codec(layout);
    std::vector<Surface> all(32);
    for (int k = 0; k < 32; ++k) {
        all[size_t(k)].normal = glm::vec3(0, 1, 0);
        all[size_t(k)].coat = float(k) / 31.0f;
    }
    CpuGBuffer one;
    codec.encode(all, 32, 1, one);
    const std::vector<Surface> back = codec.decode(one);
    for (int k = 0; k < 32; ++k) {
        const float val = float(one.targetWords.at(target)[size_t(k)] >> 24u) / 255.0f;
        const uint32_t id = uint32_t(int(val / t2 + 1.0f / 255.0f));
        const float f = clamp01((-t2 * float(id) + val) / t1);
        EXPECT_EQ(id, featureId) << k;
        EXPECT_NEAR(back[size_t(k)].coat, f, 1e-6) << k;  // HDRP's division, not code / 31
        EXPECT_EQ(back[size_t(k)].coatRoughness, 0.1f) << k;  // CLEAR_COAT_ROUGHNESS 0.01, perceptual
    }
}

// ==================================================================================================
// HDRP 13, the anisotropic feature (GBUFFER_LIT_ANISOTROPIC = 4, MaterialGBufferMacros.hlsl:34 at
// c667268a), as EncodeIntoGBuffer writes it (Lit.hlsl:541-543, 575-634, 663-667) and
// DecodeFromGBuffer reads it (:770-905), written here from that text:
//   frame     = GetLocalFrame(normalWS) (core CommonLighting.hlsl:442-459 at 6363fa25): sz = FastSign(z)
//               (-0 as +1), a = 1 / (sz + z), x = (c x a - 1, sz b, c), y = (b, y ya - sz, y)
//   sinFrame  = dot(tangentWS, frame[1]), cosFrame = dot(tangentWS, frame[0]); quad2or4 = sin cos < 0
//   GBuffer2.r = (quad2or4 ? 255 - u : u) / 255, u = round(anisotropy * 127.5 + 127.5) (HLSL round:
//               ties to even)
//   GBuffer2.g = Remap01(min(|sin|, |cos|), sqrt(2) 256/255, 0.5/255) = saturate(x * s - 0.5/255)
//   GBuffer2.b = PackFloatInt8bit(metallic, storeSin, 8), storeSin = (|sin| < |cos|) != quad2or4
//   GBuffer2.a = PackFloatInt8bit(coatMask, 4, 8); GBuffer0.rgb = baseColor (sRGB target)
// read back: anisotropy = r * 2 - 1; sinOrCos = 0.5/256 rsqrt(2) + 255/256 rsqrt(2) g; the tangent
// sinFrame frame[1] + cosFrame frame[0] of the decoded normal's frame, the bitangent cross(n, t)
// (FillMaterialAnisotropy's T and B); metallic by UnpackFloatInt8bit, diffuse = base (1 - metallic),
// fresnel0 = lerp(0.04, base, metallic) (CommonMaterial.hlsl:267-275). HDRP's lobe with a signed
// anisotropy along (T, B) is gbufferlab's with strength |a| along T, or along B where a < 0
// (AnisoGGX(a, b, g) == AnisoGGX(b, a, g + pi/2), Lit.hlsl:585-596): the shading check below.
// ==================================================================================================

struct HdrpFrame {
    glm::vec3 x, y;
};

HdrpFrame hdrpGetLocalFrame(glm::vec3 n) {
    const float sz = std::copysign(1.0f, n.z) < 0.0f && n.z != 0.0f ? -1.0f : 1.0f;  // FastSign: -0 as +1
    const float a = 1.0f / (sz + n.z);
    const float ya = n.y * a, b = n.x * ya, c = n.x * sz;
    return {glm::vec3(c * n.x * a - 1.0f, sz * b, c), glm::vec3(b, n.y * ya - sz, n.y)};
}

float dot3(glm::vec3 a, glm::vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }  // unfused, in order

struct HdrpGBuffer2 {
    HardwareCode r, g, b, a;
};

HdrpGBuffer2 hdrpAnisotropicGBuffer2(glm::vec3 normal, glm::vec3 tangent, float anisotropy, float metallic, float coat) {
    const HdrpFrame f = hdrpGetLocalFrame(normal);
    const float sinFrame = dot3(tangent, f.y), cosFrame = dot3(tangent, f.x);
    const bool quad2or4 = sinFrame * cosFrame < 0.0f;
    float u = std::nearbyint(anisotropy * 127.5f + 127.5f);
    u = quad2or4 ? 255.0f - u : u;
    const bool storeSin = (std::fabs(sinFrame) < std::fabs(cosFrame)) != quad2or4;
    const float sinOrCos = std::min(std::fabs(sinFrame), std::fabs(cosFrame));
    const float rcpLength = std::sqrt(2.0f) * 256.0f / 255.0f, start = 0.5f / 255.0f;
    const float remapped = clamp01(sinOrCos * rcpLength - start);
    const float t1 = (256.0f / 8.0f - 1.0f) / 255.0f, t2 = (256.0f / 8.0f) / 255.0f;
    return {hardwareUnorm(u * (1.0f / 255.0f), 8), hardwareUnorm(remapped, 8),
            hardwareUnorm(t1 * clamp01(metallic) + t2 * (storeSin ? 1.0f : 0.0f), 8),
            hardwareUnorm(t1 * clamp01(coat) + t2 * 4.0f, 8)};
}

// KHR_materials_anisotropy's GGX D (at = mix(alpha, 1, strength^2), ab = alpha) for the half vector h
// in the frame (t, b, n): 1 / (pi at ab ((t.h / at)^2 + (b.h / ab)^2 + (n.h)^2)^2).
double anisotropicD(glm::dvec3 h, glm::dvec3 n, glm::dvec3 t, glm::dvec3 b, double strength, double alpha) {
    const double at = alpha + (1.0 - alpha) * strength * strength, ab = alpha;
    const double x = glm::dot(t, h) / at, y = glm::dot(b, h) / ab, z = glm::dot(n, h);
    const double d = x * x + y * y + z * z;
    return 1.0 / (3.141592653589793 * at * ab * d * d);
}

double srgbEncode(double x) {
    x = std::min(std::max(x, 0.0), 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

// The i-th anisotropic input: normals from the shared edges and random ones (a tenth near the
// equator, where GetLocalFrame's sign flips, a tenth within 1e-3 of +-z), tangents orthogonal to
// them at every quadrant boundary of the frame (k 45 degrees and the floats beside) or at random,
// anisotropy on the ties of u (j / 127.5) or uniform, metallic on PackFloatInt's ties, a coat on half.
Surface hdrpAnisotropicInput(Rng& rng, const std::vector<glm::vec3>& edges, size_t i) {
    Surface s;
    glm::vec3 n = normalInput(edges, rng, i / 2);
    if (i % 10 == 3) n = glm::normalize(glm::vec3(float(rng.u01() - 0.5) * 2e-3f, float(rng.u01() - 0.5) * 2e-3f, rng.u01() < 0.5 ? -1.0f : 1.0f));
    if (!(std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z) > 0.5f) || !(std::fabs(n.x) < 2.0f && std::fabs(n.y) < 2.0f && std::fabs(n.z) < 2.0f))
        n = glm::vec3(0.0f, 0.0f, 1.0f);  // the edge list's zero, huge and denormal vectors: a normal is unit here
    s.normal = n;
    const HdrpFrame f = hdrpGetLocalFrame(n);
    double angle = rng.u01() * 6.283185307179586;
    if (i % 4 == 1) {  // on a quadrant boundary (or the diagonal), or the float beside it
        angle = double((i / 4) % 8) * 0.7853981633974483;
        if (i % 3 == 1) angle = std::nextafter(angle, 10.0);
        if (i % 3 == 2) angle = std::nextafter(angle, -10.0);
    }
    s.anisotropyDirection = float(std::cos(angle)) * f.x + float(std::sin(angle)) * f.y;
    const size_t j = (i / 3) % 160;
    s.anisotropyStrength = j < 128 ? float(double(j + 1) / 127.5) : float(rng.u01());
    if (s.anisotropyStrength > 1.0f) s.anisotropyStrength = 1.0f;
    s.metallic = scalarInput(rng, (i * 7u) % 4093u, 31, 1.0f);
    s.baseColor = glm::vec3(float(rng.u01()), float(rng.u01()), float(rng.u01()));
    s.roughness = float(rng.u01());
    s.coat = i % 2 ? float(rng.u01()) : 0.0f;
    if (i % 16 == 0) s.anisotropyStrength = 0.0f;  // a standard pixel among them
    return s;
}

void checkHdrpAnisotropicRow(const std::string& name) {
    SCOPED_TRACE(name);
    const Layout layout = gbl::loadLayout(name);
    const size_t t0 = targetIndex(layout, "GBuffer0"), t2 = targetIndex(layout, "GBuffer2");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(4004);
    std::vector<Surface> keep(kImage), decoded;
    const CpuCodec codec(layout);
    Tally words, base, reads, lobe;
    size_t anisotropic = 0, standard = 0, coated = 0, flipped = 0, signFlips = 0;
    double worstAngle = 0.0, worstLobe = 0.0;
    runCodecAllTargets(layout, kInputs / 4, [&](size_t i) { return keep[i % kImage] = hdrpAnisotropicInput(rng, edges, i); },
                       [&](size_t i, const CpuGBuffer& g, size_t j) {
        const Surface& s = keep[j];
        if (j == 0) decoded = codec.decode(g);
        const uint32_t w2 = g.targetWords[t2][j], w0 = g.targetWords[t0][j];
        const std::string at = "input " + std::to_string(i) + " n " + vec(s.normal) + " t " + vec(s.anisotropyDirection) +
                               " a " + std::to_string(s.anisotropyStrength) + " m " + std::to_string(s.metallic);
        const Surface& o = decoded[j];
        if (!(s.anisotropyStrength > 0.0f)) {  // the standard feature: id 0 in the high 3 bits
            ++standard;
            if ((w2 >> 29u) != 0u) words.fail(at + ": standard pixel with feature " + std::to_string(w2 >> 29u));
            return;
        }
        ++anisotropic;
        coated += s.coat > 0.0f;
        const HdrpGBuffer2 h = hdrpAnisotropicGBuffer2(s.normal, s.anisotropyDirection, s.anisotropyStrength, s.metallic, s.coat);
        ++words.compared;
        if (h.g.nearTie || h.b.nearTie || h.a.nearTie) ++words.nearTies;
        if (!accepts(h.r, w2 & 0xFFu) || !accepts(h.g, (w2 >> 8u) & 0xFFu) || !accepts(h.b, (w2 >> 16u) & 0xFFu) ||
            !accepts(h.a, w2 >> 24u))
            words.fail(at + ": GBuffer2 " + hex(w2) + ", HDRP r " + std::to_string(h.r.nearest) + " g " +
                       std::to_string(h.g.nearest) + " b " + std::to_string(h.b.nearest) + " a " + std::to_string(h.a.nearest));
        signFlips += (w2 & 0xFFu) < 128u;
        // GBuffer0: the base colour itself (an sRGB target: the hardware's encode, half a step).
        ++base.compared;
        for (int c = 0; c < 3; ++c) {
            const HardwareCode e = hardwareUnorm(float(srgbEncode(double(s.baseColor[c]))), 8);
            const uint32_t code = (w0 >> (8u * uint32_t(c))) & 0xFFu;
            if (code + 1u < e.nearest || code > e.other + 1u) base.fail(at + ": GBuffer0 " + hex(w0) + " is not the base colour");
        }
        // HDRP's read of the words against the codec's decode.
        const float r = float(w2 & 0xFFu) / 255.0f, gv = float((w2 >> 8u) & 0xFFu) / 255.0f, bv = float((w2 >> 16u) & 0xFFu) / 255.0f;
        const float anisotropy = r * 2.0f - 1.0f;
        const float t1 = (256.0f / 8.0f - 1.0f) / 255.0f, tt2 = (256.0f / 8.0f) / 255.0f;
        const uint32_t flag = uint32_t(int(bv / tt2 + 1.0f / 255.0f));
        const float metallic = clamp01((-tt2 * float(flag) + bv) / t1);
        const float sinOrCos = (0.5f / 256.0f * (1.0f / std::sqrt(2.0f))) + (255.0f / 256.0f * (1.0f / std::sqrt(2.0f))) * gv;
        const float cosOrSin = std::sqrt(1.0f - sinOrCos * sinOrCos);
        const float sinF = flag != 0u ? sinOrCos : cosOrSin, cosF = flag != 0u ? cosOrSin : sinOrCos;
        const HdrpFrame f = hdrpGetLocalFrame(o.normal);
        const glm::vec3 T = sinF * f.y + cosF * f.x, B = glm::cross(o.normal, T);
        const glm::vec3 along = anisotropy >= 0.0f ? T : B;
        ++reads.compared;
        const bool ok = std::fabs(o.anisotropyStrength - std::fabs(anisotropy)) <= 1e-6f &&
                        std::fabs(std::fabs(glm::dot(o.anisotropyDirection, along)) - 1.0f) <= 1e-5f &&
                        std::fabs(o.metallic - metallic) <= 1e-6f && o.shadingModel == 4.0f &&
                        glm::all(glm::lessThanEqual(glm::abs(o.diffuseColor - o.baseColor * (1.0f - o.metallic)), glm::vec3(1e-6f))) &&
                        glm::all(glm::lessThanEqual(glm::abs(o.specularColor - (0.04f + (o.baseColor - 0.04f) * o.metallic)), glm::vec3(1e-6f))) &&
                        (s.coat > 0.0f ? o.coat > 0.0f || s.coat < 1.0f / 62.0f : o.coat == 0.0f);
        if (!ok)
            reads.fail(at + ": decoded strength " + std::to_string(o.anisotropyStrength) + " direction " + vec(o.anisotropyDirection) +
                       ", HDRP " + std::to_string(anisotropy) + " along " + vec(along) + ", metallic " + std::to_string(o.metallic) +
                       " / " + std::to_string(metallic));
        // The shading: HDRP's lobe (signed anisotropy along T, B) is gbufferlab's (|a| along the
        // decoded direction), and close to the input's lobe away from the equator.
        const glm::dvec3 n(o.normal), dd(o.anisotropyDirection), db = glm::cross(n, dd);
        const double alpha = 0.3 * 0.3;
        for (int k = 0; k < 4; ++k) {
            const glm::dvec3 hh = glm::normalize(n + glm::dvec3(randomDirection(rng)) * 0.6);
            const double hdrp = anisotropy >= 0.0f ? anisotropicD(hh, n, glm::dvec3(T), glm::dvec3(B), anisotropy, alpha)
                                                   : anisotropicD(hh, n, glm::dvec3(B), glm::dvec3(T), -anisotropy, alpha);
            const double ours = anisotropicD(hh, n, dd, db, o.anisotropyStrength, alpha);
            const double rel = std::fabs(hdrp - ours) / std::max(hdrp, 1e-12);
            worstLobe = std::max(worstLobe, rel);
            ++lobe.compared;
            if (rel > 1e-4) lobe.fail(at + ": HDRP's lobe " + std::to_string(hdrp) + ", the decoded one " + std::to_string(ours));
        }
        // The direction's loss, as the metric measures it (the angle between lines): within the
        // angle's cell and the normal's step, except within 0.01 of the equator (the frame's flip).
        if (std::fabs(s.normal.z) > 0.01f && std::fabs(glm::length(s.normal) - 1.0f) < 1e-3f) {
            const double c = std::fabs(glm::dot(glm::dvec3(o.anisotropyDirection), glm::dvec3(s.anisotropyDirection)));
            const double deg = std::acos(std::min(1.0, c)) * 57.29577951308232;
            worstAngle = std::max(worstAngle, deg);
            flipped += deg > 45.0;
        }
    });
    std::printf("[ %-15s] %zu anisotropic pixels (%zu coated, %zu with the anisotropy negated), %zu standard; %zu near a "
                "tie; worst direction error %.3f deg (|n.z| > 0.01), worst lobe difference %.2e\n",
                name.c_str(), anisotropic, coated, signFlips, standard, words.nearTies, worstAngle, worstLobe);
    EXPECT_EQ(words.mismatches, 0u);
    EXPECT_EQ(base.mismatches, 0u);
    EXPECT_EQ(reads.mismatches, 0u);
    EXPECT_EQ(lobe.mismatches, 0u);
    EXPECT_EQ(flipped, 0u);          // no axis relabelled by 90 degrees
    EXPECT_LT(worstAngle, 0.5);       // half a degree: the 8-bit angle and the 12:12 normal
    EXPECT_GT(signFlips, anisotropic / 4);  // the 2nd and 4th quadrants are reached ...
    EXPECT_LT(signFlips, anisotropic * 3 / 4);
    EXPECT_GT(coated, anisotropic / 3);  // ... and coated anisotropic pixels keep their coat
    EXPECT_GT(standard, 1000u);
}

TEST(LayerPackings, HdrpAnisotropicFeatureEqualsEncodeIntoGBuffer) {
    checkHdrpAnisotropicRow("hdrp-lit");
    checkHdrpAnisotropicRow("hdrp-lit-apv");
}

// ==================================================================================================
// UE 5.3.2, ClearCoat: SetGBufferForShadingModel writes CustomData.x = saturate(ClearCoat), .y =
// saturate(ClearCoatRoughness), .zw untouched (0) without CLEAR_COAT_BOTTOM_NORMAL
// (ShadingModelsMaterial.ush:85-117), GBufferD B8G8R8A8_UNORM (B in bits 0..7, G 8..15, R 16..23,
// A 24..31); GBufferB.a = SHADINGMODELID_CLEAR_COAT (4) | SKIP_VELOCITY_MASK (1 << 7).
// ==================================================================================================

TEST(LayerPackings, Ue5ClearCoatCustomDataEqualsSetGBufferForShadingModel) {
    const Layout layout = gbl::loadLayout("ue5-clearcoat");
    const size_t d = targetIndex(layout, "GBufferD");
    Rng rng(5324);
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = glm::vec3(0, 0, 1);
        s.coat = scalarInput(rng, i % 4096, 255, 1.0f);  // the ties in a fifth of each
        s.coatRoughness = scalarInput(rng, (i * 7919u) % 4093u, 255, 1.0f);
        keep[i % kImage] = s;
        return s;
    };
    Tally custom;
    runCodec(layout, d, make, [&](size_t i, int, int, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        const HardwareCode x = hardwareUnorm(clamp01(s.coat), 8), y = hardwareUnorm(clamp01(s.coatRoughness), 8);
        ++custom.compared;
        if (x.nearTie || y.nearTie) ++custom.nearTies;
        const uint32_t r = (w[0] >> 16u) & 0xFFu, g = (w[0] >> 8u) & 0xFFu;
        if (!accepts(x, r) || !accepts(y, g) || (w[0] & 0xFF0000FFu) != 0u)
            custom.fail("coat " + std::to_string(s.coat) + ", " + std::to_string(s.coatRoughness) + ": GBufferD " + hex(w[0]));
    });
    std::printf("[ ue5 cc   ] %zu CustomData words (%zu near a tie)\n", custom.compared, custom.nearTies);
    EXPECT_EQ(custom.mismatches, 0u);
    // GBufferB.a: the shading model id 4 with SKIP_VELOCITY_MASK, 0x84.
    const gbl::CpuCodec codec(layout);
    CpuGBuffer one;
    codec.encode(std::vector<Surface>(1, Surface{}), 1, 1, one);
    EXPECT_EQ(one.targetWords.at(targetIndex(layout, "GBufferB"))[0] >> 24u, 0x84u);
}

// ==================================================================================================
// UE 5.3.2, Cloth: CustomData.rgb = EncodeSubsurfaceColor(SubsurfaceColor) = sqrt(saturate(c))
// (ShadingModelsMaterial.ush:133-139, DeferredShadingCommon.ush:189-192) into UNORM bytes, read
// Square(CustomData.rgb) (:1031-1034); GBufferB.a = SHADINGMODELID_CLOTH (8) | 1 << 7.
// ==================================================================================================

TEST(LayerPackings, UnormSqrtThresholdsAreTheExactSquares) {
    // kUnormSqrtEncodeThresholds[k] >= (2k + 1)^2 / 260100 > the float below it; T * 260100 is exact
    // in double (24 + 18 bits).
    for (int k = 0; k < 255; ++k) {
        const double t = double(gbl::enc::kUnormSqrtEncodeThresholds[k]);
        const double below = double(std::nextafter(gbl::enc::kUnormSqrtEncodeThresholds[k], 0.0f));
        const double square = double((2 * k + 1) * (2 * k + 1));
        ASSERT_GE(t * 260100.0, square) << k;
        ASSERT_LT(below * 260100.0, square) << k;
    }
    EXPECT_EQ(gbl::enc::encodeUnormSqrt(-1.0f), 0u);
    EXPECT_EQ(gbl::enc::encodeUnormSqrt(2.0f), 255u);
    EXPECT_EQ(gbl::enc::decodeUnormSqrt(255u), 1.0f);
}

TEST(LayerPackings, Ue5ClothCustomDataEqualsEncodeSubsurfaceColor) {
    const Layout layout = gbl::loadLayout("ue5-cloth");
    const size_t d = targetIndex(layout, "GBufferD");
    Rng rng(8128);
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = glm::vec3(0, 0, 1);
        // sqrt's ties: c = ((k + 0.5) / 255)^2 and the floats beside it, then anything.
        auto one = [&](size_t j) {
            if (j < 255 * 3) {
                const float t = float(std::pow((double(j / 3) + 0.5) / 255.0, 2.0));
                return j % 3 == 0 ? t : j % 3 == 1 ? std::nextafter(t, -1.0f) : std::nextafter(t, 2.0f);
            }
            return float(rng.u01() * 1.2 - 0.1);
        };
        s.sheenColor = glm::vec3(one(i % 4096), one((i * 7919u) % 4093u), one(4096));  // ties in a fifth of r, g
        keep[i % kImage] = s;
        return s;
    };
    Tally custom;
    runCodec(layout, d, make, [&](size_t i, int, int, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        HardwareCode c[3];
        for (int k = 0; k < 3; ++k) c[k] = hardwareUnorm(std::sqrt(clamp01(s.sheenColor[k])), 8);
        ++custom.compared;
        if (c[0].nearTie || c[1].nearTie || c[2].nearTie) ++custom.nearTies;
        const uint32_t r = (w[0] >> 16u) & 0xFFu, g = (w[0] >> 8u) & 0xFFu, b = w[0] & 0xFFu;
        if (!accepts(c[0], r) || !accepts(c[1], g) || !accepts(c[2], b) || (w[0] >> 24u) != 0u)
            custom.fail("fuzz colour " + vec(s.sheenColor) + ": GBufferD " + hex(w[0]));
    });
    std::printf("[ ue5 cloth] %zu CustomData words (%zu near a tie)\n", custom.compared, custom.nearTies);
    EXPECT_EQ(custom.mismatches, 0u);
    EXPECT_GT(custom.nearTies, 0u);
    // The read: Square(code / 255) for every code, and GBufferB.a = 0x88.
    const gbl::CpuCodec codec(layout);
    std::vector<Surface> all(256);
    for (int k = 0; k < 256; ++k) all[size_t(k)].sheenColor = glm::vec3(float(k) / 255.0f * (float(k) / 255.0f));
    CpuGBuffer one;
    codec.encode(all, 256, 1, one);
    const std::vector<Surface> back = codec.decode(one);
    for (int k = 0; k < 256; ++k) {
        const uint32_t code = (one.targetWords.at(d)[size_t(k)] >> 16u) & 0xFFu;
        const float v = float(code) / 255.0f;
        EXPECT_EQ(back[size_t(k)].sheenColor.x, v * v) << k;
    }
    EXPECT_EQ(one.targetWords.at(targetIndex(layout, "GBufferB"))[0] >> 24u, 0x88u);
}

// ==================================================================================================
// UE 5.3.2, GBufferF: EncodeWorldTangentAndAnisotropy = (EncodeNormal(T), A * 0.5 + 0.5), EncodeNormal
// = N * 0.5 + 0.5 (DeferredShadingCommon.ush:122-125, 222-228; AnisotropyPassShader.usf:132-135),
// B8G8R8A8_UNORM; read back DecodeNormal = rgb * 2 - 1, normalised, and A = a * 2 - 1 (:1015-1022).
// ==================================================================================================

TEST(LayerPackings, Ue5GBufferFEqualsEncodeWorldTangentAndAnisotropy) {
    const Layout layout = gbl::loadLayout("ue5-anisotropy");
    const size_t f = targetIndex(layout, "GBufferF");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(6111);
    std::vector<Surface> keep(kImage);
    auto make = [&](size_t i) {
        Surface s;
        s.normal = glm::vec3(0, 0, 1);
        s.anisotropyDirection = i % 13 == 5 ? glm::vec3(0.0f) : normalInput(edges, rng, i);  // 0: no anisotropy
        s.anisotropyStrength = scalarInput(rng, i, 255, 1.0f) * 2.0f - 1.0f;  // UE's [-1, 1], ties of a * 0.5 + 0.5
        if (i % 17 == 3) s.anisotropyStrength = float(rng.u01());           // glTF's [0, 1]
        keep[i % kImage] = s;
        return s;
    };
    Tally words;
    size_t cleared = 0;
    runCodec(layout, f, make, [&](size_t i, int, int, const uint32_t* w) {
        const Surface& s = keep[i % kImage];
        // The anisotropy pass draws only anisotropic materials (the selector's id 17, strength > 0);
        // elsewhere GBufferF keeps its clear (UE reads it only under HAS_ANISOTROPY, dsc:1015-1018).
        if (!(s.anisotropyStrength > 0.0f)) {
            ++cleared;
            if (w[0] != 0x80808080u) words.fail("no anisotropy: GBufferF " + hex(w[0]) + ", not the clear");
            return;
        }
        const glm::vec3 t = s.anisotropyDirection * 0.5f + 0.5f;
        const HardwareCode r = hardwareUnorm(t.x, 8), g = hardwareUnorm(t.y, 8), b = hardwareUnorm(t.z, 8);
        const HardwareCode a = hardwareUnorm(s.anisotropyStrength * 0.5f + 0.5f, 8);
        ++words.compared;
        if (r.nearTie || g.nearTie || b.nearTie || a.nearTie) ++words.nearTies;
        if (!accepts(r, (w[0] >> 16u) & 0xFFu) || !accepts(g, (w[0] >> 8u) & 0xFFu) || !accepts(b, w[0] & 0xFFu) ||
            !accepts(a, w[0] >> 24u))
            words.fail("tangent " + vec(s.anisotropyDirection) + ", anisotropy " + std::to_string(s.anisotropyStrength) +
                       ": GBufferF " + hex(w[0]));
    });
    std::printf("[ ue5 F    ] %zu GBufferF words (%zu near a tie), %zu cleared\n", words.compared, words.nearTies, cleared);
    EXPECT_EQ(words.mismatches, 0u);
    EXPECT_GT(words.nearTies, 1000u);
    EXPECT_GT(cleared, 1000u);
    // No anisotropy writes UE's clear, 0.5 in every channel (code 128).
    const gbl::CpuCodec codec(layout);
    CpuGBuffer one;
    codec.encode(std::vector<Surface>(1, Surface{}), 1, 1, one);
    EXPECT_EQ(one.targetWords.at(f)[0], 0x80808080u);
    // The read: UE's DecodeNormal and a * 2 - 1 of the stored codes.
    std::vector<Surface> some(64);
    for (size_t i = 0; i < some.size(); ++i) {
        some[i].normal = glm::vec3(0, 0, 1);
        some[i].anisotropyDirection = normalInput(edges, rng, 1000 + i);
        some[i].anisotropyStrength = 0.01f + 0.99f * float(rng.u01());  // > 0: anisotropic pixels
    }
    codec.encode(some, 64, 1, one);
    const std::vector<Surface> back = codec.decode(one);
    for (size_t i = 0; i < some.size(); ++i) {
        const uint32_t w = one.targetWords.at(f)[i];
        const glm::vec3 rgb(float((w >> 16u) & 0xFFu) / 255.0f, float((w >> 8u) & 0xFFu) / 255.0f, float(w & 0xFFu) / 255.0f);
        const glm::vec3 tangent = glm::normalize(rgb * 2.0f - 1.0f);
        EXPECT_LT(glm::length(back[i].anisotropyDirection - tangent), 1e-6f) << i;
        EXPECT_EQ(back[i].anisotropyStrength, float(w >> 24u) / 255.0f * 2.0f - 1.0f) << i;
    }
}

// ==================================================================================================
// UE 5.3.2 with the shading model per pixel (ue5, ue5-anisotropy: the selector): GBufferB.a =
// EncodeShadingModelIdAndSelectiveOutputMask(id, mask) = ((id & 0xF) | mask) / 255 (DeferredShading-
// Common.ush:280-284; ids ShadingCommon.ush:20-34: Default Lit 1, ClearCoat 4, Cloth 8;
// HAS_ANISOTROPY_MASK 1 << 4, SKIP_VELOCITY_MASK 1 << 7, :38-41), and GBufferD = CustomData as
// SetGBufferForShadingModel writes it for the pixel's model (ShadingModelsMaterial.ush:12-140):
//   Default Lit  no branch (:37-40): CustomData keeps its zero initialisation (BasePassPixelShader.usf:986)
//   ClearCoat    .x = saturate(ClearCoat), .y = saturate(ClearCoatRoughness) (:85-91); .z, .w only
//                under CLEAR_COAT_BOTTOM_NORMAL (:96-116), 0 by default (r.ClearCoatNormal = 0,
//                DeferredShadingRenderer.cpp:114-120): 0; the base roughness clamped to 254/255 (:94)
//   Cloth        .rgb = EncodeSubsurfaceColor(fuzz colour) = sqrt(saturate(c)) (:133-139,
//                DeferredShadingCommon.ush:189-192), .a = saturate(cloth amount) (:137)
// The material's model (:33) is the row's mapping of the glTF layers (ue5.toml's header): a coated
// material is ClearCoat, a sheen-only one Cloth, the rest Default Lit, with HAS_ANISOTROPY where
// ue5-anisotropy's material has anisotropy (BasePassPixelShader.usf:737-753). Written here from that
// statement, not from the codec. The documented differences of the rows (each at its entry's
// `differs`) are counted apart: the cloth amount (no attribute holds it: 0, where UE stores the
// material's) and the ClearCoat roughness clamp (gbufferlab stores code 255 where UE stores 254).
// ==================================================================================================

struct UePixel {
    uint32_t id = 1;               // SHADINGMODELID_DEFAULT_LIT
    bool anisotropic = false;      // HAS_ANISOTROPY_MASK set
};

UePixel ueMaterialModel(const Surface& s, bool anisotropyPass) {
    UePixel p;
    if (s.coat > 0.0f) p.id = 4;  // SHADINGMODELID_CLEAR_COAT
    else if (s.sheenColor.x > 0.0f || s.sheenColor.y > 0.0f || s.sheenColor.z > 0.0f) p.id = 8;  // SHADINGMODELID_CLOTH
    else p.anisotropic = anisotropyPass && s.anisotropyStrength > 0.0f;
    return p;
}

// One input of each layer pattern (i % 8: bit 0 coat, 1 sheen, 2 anisotropy), the values on the
// ties of their 8-bit codes, and roughness on the ties of its own (254.5 / 255 among them).
Surface layeredInput(Rng& rng, const std::vector<glm::vec3>& edges, size_t i) {
    Surface s;
    s.normal = glm::vec3(0, 0, 1);
    const size_t k = i / 8;
    s.roughness = scalarInput(rng, (k * 31u) % 2039u, 255, 1.0f);
    if (i & 1u) {
        s.coat = scalarInput(rng, k % 4096, 255, 1.0f);
        s.coatRoughness = scalarInput(rng, (k * 7919u) % 4093u, 255, 1.0f);
    }
    if (i & 2u) {
        auto one = [&](size_t j) {  // sqrt's ties: ((j + 0.5) / 255)^2 and the floats beside it
            if (j < 255 * 3) {
                const float t = float(std::pow((double(j / 3) + 0.5) / 255.0, 2.0));
                return j % 3 == 0 ? t : j % 3 == 1 ? std::nextafter(t, -1.0f) : std::nextafter(t, 2.0f);
            }
            return float(rng.u01() * 1.2 - 0.1);
        };
        s.sheenColor = glm::vec3(one(k % 4096), one((k * 7919u) % 4093u), one(4096));
    }
    if (i & 4u) {
        s.anisotropyDirection = normalInput(edges, rng, k);
        s.anisotropyStrength = scalarInput(rng, (k * 13u) % 4091u, 255, 1.0f);
    }
    return s;
}

void checkUe5SelectorRow(const std::string& name, bool anisotropyPass) {
    SCOPED_TRACE(name);
    const Layout layout = gbl::loadLayout(name);
    const size_t b = targetIndex(layout, "GBufferB"), d = targetIndex(layout, "GBufferD");
    const size_t f = anisotropyPass ? targetIndex(layout, "GBufferF") : 0;
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(5401);
    std::vector<Surface> keep(kImage);
    std::vector<Surface> decoded;
    const CpuCodec codec(layout);
    Tally alpha, custom, rough, tangent, reads;
    size_t seen[32] = {}, clampedRoughness = 0, clothAmount = 0;
    runCodecAllTargets(layout, kInputs / 2, [&](size_t i) { return keep[i % kImage] = layeredInput(rng, edges, i); },
                       [&](size_t i, const CpuGBuffer& g, size_t j) {
        const Surface& s = keep[j];
        if (j == 0) decoded = codec.decode(g);
        const UePixel ue = ueMaterialModel(s, anisotropyPass);
        const uint32_t wb = g.targetWords[b][j], wd = g.targetWords[d][j];
        const std::string at = "input " + std::to_string(i) + " (layers " + std::to_string(i % 8) + ")";
        // GBufferB.a: (id | mask) / 255 into a UNORM byte is the integer itself.
        const uint32_t a = (ue.id & 0xFu) | (ue.anisotropic ? 1u << 4 : 0u) | 1u << 7;
        ++alpha.compared;
        ++seen[a & 31u];
        if ((wb >> 24u) != a) alpha.fail(at + ": GBufferB.a " + hex(wb >> 24u) + ", UE " + hex(a));
        // GBufferB.b: the base roughness, clamped to 254/255 on ClearCoat pixels by UE.
        const float r = ue.id == 4 ? std::min(clamp01(s.roughness), 254.0f / 255.0f) : clamp01(s.roughness);
        const HardwareCode rc = hardwareUnorm(r, 8);
        ++rough.compared;
        if (!accepts(rc, wb & 0xFFu)) {
            if (ue.id == 4 && (wb & 0xFFu) == 255u && rc.nearest == 254u) ++clampedRoughness;  // the row's `differs`
            else rough.fail(at + ": roughness " + std::to_string(s.roughness) + " code " + std::to_string(wb & 0xFFu));
        }
        // GBufferD: CustomData of the model (B8G8R8A8: x in R, bits 16..23; y in G; z in B; w in A).
        ++custom.compared;
        const uint32_t x = (wd >> 16u) & 0xFFu, y = (wd >> 8u) & 0xFFu, z = wd & 0xFFu, w = wd >> 24u;
        bool ok = true;
        if (ue.id == 4) {
            const HardwareCode cx = hardwareUnorm(clamp01(s.coat), 8), cy = hardwareUnorm(clamp01(s.coatRoughness), 8);
            if (cx.nearTie || cy.nearTie) ++custom.nearTies;
            ok = accepts(cx, x) && accepts(cy, y) && z == 0u && w == 0u;
        } else if (ue.id == 8) {
            HardwareCode c[3];
            for (int k = 0; k < 3; ++k) c[k] = hardwareUnorm(std::sqrt(clamp01(s.sheenColor[k])), 8);
            if (c[0].nearTie || c[1].nearTie || c[2].nearTie) ++custom.nearTies;
            ok = accepts(c[0], x) && accepts(c[1], y) && accepts(c[2], z) && w == 0u;  // .a: the cloth amount
            ++clothAmount;
        } else {
            ok = wd == 0u;
        }
        if (!ok) custom.fail(at + ": model " + std::to_string(ue.id) + ", GBufferD " + hex(wd));
        // GBufferF (ue5-anisotropy): EncodeWorldTangentAndAnisotropy on the anisotropic pixels, the
        // pass's clear 0.5 elsewhere (st:581-587), which UE does not read there (dsc:1015-1018).
        if (anisotropyPass) {
            const uint32_t wf = g.targetWords[f][j];
            ++tangent.compared;
            if (ue.anisotropic) {
                const glm::vec3 t = s.anisotropyDirection * 0.5f + 0.5f;
                const HardwareCode tr = hardwareUnorm(t.x, 8), tg = hardwareUnorm(t.y, 8), tb = hardwareUnorm(t.z, 8);
                const HardwareCode ta = hardwareUnorm(s.anisotropyStrength * 0.5f + 0.5f, 8);
                if (!accepts(tr, (wf >> 16u) & 0xFFu) || !accepts(tg, (wf >> 8u) & 0xFFu) || !accepts(tb, wf & 0xFFu) ||
                    !accepts(ta, wf >> 24u))
                    tangent.fail(at + ": GBufferF " + hex(wf));
            } else if (wf != 0x80808080u) {
                tangent.fail(at + ": GBufferF " + hex(wf) + " where UE keeps the clear");
            }
        }
        // UE's reads of the stored codes against the codec's decode: the coat from CustomData.xy
        // (ClearCoatCommon.ush:16-19), the fuzz colour Square(CustomData.rgb) (dsc:1031-1034) with
        // the base roughness as the cloth lobe's (ShadingModels.ush:766-767, 775), no layer where
        // the model holds none.
        const Surface& o = decoded[j];
        const float rd = float(wb & 0xFFu) / 255.0f;
        ++reads.compared;
        bool read = o.roughness == rd && o.shadingModel == float((wb >> 24u) & (anisotropyPass ? 31u : 15u));
        if (ue.id == 4) read = read && o.coat == float(x) / 255.0f && o.coatRoughness == float(y) / 255.0f &&
                               o.sheenColor == glm::vec3(0.0f);
        else if (ue.id == 8) {
            const glm::vec3 v(float(x) / 255.0f, float(y) / 255.0f, float(z) / 255.0f);
            read = read && o.sheenColor == v * v && o.sheenRoughness == o.roughness && o.coat == 0.0f;
        } else read = read && o.coat == 0.0f && o.sheenColor == glm::vec3(0.0f);
        if (anisotropyPass && !ue.anisotropic) read = read && o.anisotropyStrength == 0.0f;
        if (!read) reads.fail(at + ": decoded model " + std::to_string(o.shadingModel) + ", coat " + std::to_string(o.coat) +
                              ", sheen " + vec(o.sheenColor) + ", sheen roughness " + std::to_string(o.sheenRoughness));
    });
    std::printf("[ %-15s] %zu pixels: %zu Default Lit, %zu anisotropic, %zu ClearCoat, %zu Cloth; %zu near a tie; "
                "documented: %zu clamped roughness codes, %zu cloth amounts\n", name.c_str(), alpha.compared,
                seen[0x81 & 31], seen[0x91 & 31], seen[0x84 & 31], seen[0x88 & 31], custom.nearTies, clampedRoughness,
                clothAmount);
    EXPECT_EQ(alpha.mismatches, 0u);
    EXPECT_EQ(rough.mismatches, 0u);
    EXPECT_EQ(custom.mismatches, 0u);
    EXPECT_EQ(tangent.mismatches, 0u);
    EXPECT_EQ(reads.mismatches, 0u);
    // Every model of the row occurs, the ties are reached, and so is the documented clamp.
    for (uint32_t id : {0x81u, 0x84u, 0x88u}) EXPECT_GT(seen[id & 31u], 1000u) << hex(id);
    if (anisotropyPass) EXPECT_GT(seen[0x91 & 31], 1000u);
    else EXPECT_EQ(seen[0x91 & 31], 0u);  // ue5 without the anisotropy pass: no mask bit
    EXPECT_GT(custom.nearTies, 0u);
    EXPECT_GT(clampedRoughness, 0u);
}

TEST(LayerPackings, Ue5SelectorRowsWriteCustomDataAsSetGBufferForShadingModel) {
    checkUe5SelectorRow("ue5", false);
    checkUe5SelectorRow("ue5-anisotropy", true);
}

// ==================================================================================================
// UE 5.3.2's clear-coat bottom normal (CLEAR_COAT_BOTTOM_NORMAL, r.ClearCoatNormal = 1): CustomData.a
// and .z = (oct(bottom) - oct(top)) * 0.25 + 128/255 (ShadingModelsMaterial.ush:96-116), read back
// OctahedronToUnitVector((a, z) * 4 - 512/255 + oct(top)) (ClearCoatCommon.ush:5-14), with
// UnitVectorToOctahedron / OctahedronToUnitVector (OctahedralCommon.ush:18-34): the encoder and
// decoder held to UE's arithmetic here, the row ue5-clearcoat-normal below.
// ==================================================================================================

glm::vec2 ueUnitVectorToOctahedron(glm::vec3 n) {
    const float d = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);  // dot(1, abs(N))
    glm::vec2 xy(n.x / d, n.y / d);
    if (n.z <= 0.0f)
        xy = glm::vec2((1.0f - std::fabs(xy.y)) * (xy.x >= 0.0f ? 1.0f : -1.0f),
                       (1.0f - std::fabs(xy.x)) * (xy.y >= 0.0f ? 1.0f : -1.0f));
    return xy;
}

glm::vec3 ueOctahedronToUnitVector(glm::vec2 o) {
    glm::vec3 n(o.x, o.y, 1.0f - (std::fabs(o.x) + std::fabs(o.y)));
    const float t = std::max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return glm::normalize(n);
}

TEST(LayerPackings, Ue5ClearCoatBottomNormalDeltaEqualsShadingModelsMaterial) {
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(7711);
    Tally codes, reads;
    double worst = 0.0;
    for (size_t i = 0; i < kInputs / 4; ++i) {
        const glm::vec3 top = i < edges.size() ? edges[i] : glm::normalize(randomDirection(rng));
        // The bottom near the top (a normal map's perturbation), or anywhere.
        glm::vec3 bottom = i % 5 == 0 ? randomDirection(rng)
                                      : glm::normalize(top + 0.3f * glm::vec3(float(rng.u01()) - 0.5f, float(rng.u01()) - 0.5f,
                                                                              float(rng.u01()) - 0.5f));
        if (!(glm::length(bottom) > 0.5f)) bottom = top;
        const glm::vec2 o1 = ueUnitVectorToOctahedron(bottom), o2 = ueUnitVectorToOctahedron(top);
        const HardwareCode ca = hardwareUnorm((o1.x - o2.x) * 0.25f + 128.0f / 255.0f, 8);
        const HardwareCode cz = hardwareUnorm((o1.y - o2.y) * 0.25f + 128.0f / 255.0f, 8);
        const glm::uvec2 got = gbl::enc::encodeNormalOctahedralDeltaUe(bottom, top, 8u);
        ++codes.compared;
        if (ca.nearTie || cz.nearTie) ++codes.nearTies;
        if (!accepts(ca, got.x) || !accepts(cz, got.y))
            codes.fail("bottom " + vec(bottom) + " under " + vec(top) + ": codes (" + std::to_string(got.x) + ", " +
                       std::to_string(got.y) + "), UE (" + std::to_string(ca.nearest) + ", " + std::to_string(cz.nearest) + ")");
        // The read, from the stored codes (CustomData.a = code x / 255, .z = code y / 255).
        const glm::vec2 stored(float(got.x) / 255.0f, float(got.y) / 255.0f);
        const glm::vec3 ue = ueOctahedronToUnitVector(stored * 4.0f - 512.0f / 255.0f + o2);
        const glm::vec3 mine = gbl::enc::decodeNormalOctahedralDeltaUe(got, top, 8u);
        ++reads.compared;
        if (!(glm::length(ue - mine) < 1e-6f)) reads.fail("decode of " + vec(bottom) + ": " + vec(mine) + ", UE " + vec(ue));
        // The delta saturates beyond (oct(bottom) - oct(top)) of about +-2: the round trip is good
        // only for bottoms near the top, as UE intends (a coat over a perturbed base).
        if (i % 5 != 0) worst = std::max(worst, double(std::acos(std::min(1.0f, glm::dot(mine, bottom)))) * 57.29577951308232);
    }
    std::printf("[ ue5 cc n ] %zu bottom-normal deltas (%zu near a tie), worst near-top error %.3f deg\n", codes.compared,
                codes.nearTies, worst);
    EXPECT_EQ(codes.mismatches, 0u);
    EXPECT_EQ(reads.mismatches, 0u);
    EXPECT_LT(worst, 2.0);  // 8 bits over a delta range of 4: a step of 4/255 in the octahedron
    // The same normal above and below: the delta is 128/255 itself, code 128 each, and reads back.
    EXPECT_EQ(gbl::enc::encodeNormalOctahedralDeltaUe(glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), 8u), glm::uvec2(128u, 128u));
}

// ==================================================================================================
// ue5-clearcoat-normal (r.ClearCoatNormal = 1): on a ClearCoat pixel GBufferA = EncodeNormal of
// GBuffer.WorldNormal, the material's Normal input (ShadingModelsMaterial.ush:26), which is the
// coat's normal, n * 0.5 + 0.5 into A2B10G10R10_UNORM (R bits 0..9, G 10..19, B 20..29); CustomData
// .x, .y the coat as ue5's, .a = oct3.x, .z = oct3.y, oct3 = (oct(bottom) - oct(WorldNormal)) *
// 0.25 + 128/255 (:96-116) with the unquantised WorldNormal; GBufferD B8G8R8A8 puts .z in bits 0..7
// and .a in 24..31. Read back (DeferredLightingCommon.ush:320-325, ClearCoatCommon.ush:5-14):
// WorldNormal = normalize(code / 1023 * 2 - 1) (DeferredShadingCommon.ush:942-946), the base
// normal OctahedronToUnitVector((a, z) * 4 - 512/255 + UnitVectorToOctahedron(WorldNormal)).
// Every other pixel: GBufferA the (base) normal, GBufferD as ue5 (checkUe5SelectorRow).
// ==================================================================================================

struct CoatNormalPair {
    glm::vec3 top, bottom;
    int kind;  // 0: the bottom near the top (a normal-mapped base), 1: anywhere, 2: the same normal
};

// The i-th (coat normal, base normal): edge normals as the top first, then random ones.
CoatNormalPair coatNormalPair(Rng& rng, const std::vector<glm::vec3>& edges, size_t i) {
    CoatNormalPair p;
    p.top = i < edges.size() ? edges[i] : randomDirection(rng);
    if (!(glm::length(p.top) > 0.5f && glm::length(p.top) < 2.0f)) p.top = glm::vec3(0, 0, 1);  // edges' tiny and huge
    p.top = glm::normalize(p.top);
    p.kind = i % 7 == 3 ? 2 : i % 5 == 0 ? 1 : 0;
    const glm::vec3 jitter(float(rng.u01()) - 0.5f, float(rng.u01()) - 0.5f, float(rng.u01()) - 0.5f);
    p.bottom = p.kind == 2 ? p.top : p.kind == 1 ? randomDirection(rng) : glm::normalize(p.top + 0.3f * jitter);
    if (!(glm::length(p.bottom) > 0.5f)) p.bottom = p.top;
    return p;
}

// atan2(|a x b|, a.b) in double: acos of a float dot product reads 0.02 deg where two unit
// vectors differ in their last bits.
double degreesBetween(glm::vec3 a, glm::vec3 b) {
    const glm::dvec3 x(a), y(b);
    return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y)) * 57.29577951308232;
}

TEST(LayerPackings, Ue5ClearCoatNormalRowWritesTheCoatNormalAndTheBottomDelta) {
    const Layout layout = gbl::loadLayout("ue5-clearcoat-normal");
    const size_t a = targetIndex(layout, "GBufferA"), d = targetIndex(layout, "GBufferD");
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(4096), pairs(1357);
    std::vector<Surface> keep(kImage), decoded;
    std::vector<int> kinds(kImage);
    const CpuCodec codec(layout);
    Tally top, delta, reads, base;
    size_t coated = 0, same = 0, foldFlips = 0;
    double worstNear = 0.0, worstSame = 0.0;
    runCodecAllTargets(layout, kInputs / 2, [&](size_t i) {
        Surface s = layeredInput(rng, edges, i);
        const CoatNormalPair p = coatNormalPair(pairs, edges, i / 2);
        s.normal = p.bottom;
        if (i & 1u) s.coatNormal = p.top;  // a coat has its normal (material_eval.glsl), whatever its amount
        kinds[i % kImage] = p.kind;
        return keep[i % kImage] = s;
    }, [&](size_t i, const CpuGBuffer& g, size_t j) {
        const Surface& s = keep[j];
        if (j == 0) decoded = codec.decode(g);
        const bool clearCoat = ueMaterialModel(s, false).id == 4;
        const glm::vec3 world = clearCoat ? s.coatNormal : s.normal;  // GBuffer.WorldNormal
        const uint32_t wa = g.targetWords[a][j], wd = g.targetWords[d][j];
        const std::string at = "input " + std::to_string(i) + (clearCoat ? " (ClearCoat)" : "");
        ++top.compared;
        for (int k = 0; k < 3; ++k) {
            const HardwareCode c = hardwareUnorm(world[k] * 0.5f + 0.5f, 10);
            if (c.nearTie) ++top.nearTies;
            if (!accepts(c, (wa >> (10 * k)) & 1023u)) top.fail(at + ": GBufferA " + hex(wa) + " for " + vec(world));
        }
        const glm::vec3 ueWorld = glm::normalize(
            glm::vec3(float(wa & 1023u), float((wa >> 10) & 1023u), float((wa >> 20) & 1023u)) / 1023.0f * 2.0f - 1.0f);
        const Surface& o = decoded[j];
        if (!clearCoat) {  // ue5's pixel: GBufferD as checkUe5SelectorRow holds it; no coat normal
            ++reads.compared;
            if (!(glm::length(o.normal - ueWorld) < 1e-6f) || o.coatNormal != glm::vec3(0.0f))
                reads.fail(at + ": decoded normal " + vec(o.normal) + ", coat normal " + vec(o.coatNormal));
            return;
        }
        ++coated;
        const glm::vec2 o1 = ueUnitVectorToOctahedron(s.normal), o2 = ueUnitVectorToOctahedron(s.coatNormal);
        const HardwareCode cx = hardwareUnorm((o1.x - o2.x) * 0.25f + 128.0f / 255.0f, 8);
        const HardwareCode cz = hardwareUnorm((o1.y - o2.y) * 0.25f + 128.0f / 255.0f, 8);
        const HardwareCode coat = hardwareUnorm(clamp01(s.coat), 8), rough = hardwareUnorm(clamp01(s.coatRoughness), 8);
        ++delta.compared;
        if (cx.nearTie || cz.nearTie) ++delta.nearTies;
        const uint32_t ca = wd >> 24u, cb = wd & 0xFFu;
        if (!accepts(cx, ca) || !accepts(cz, cb) || !accepts(coat, (wd >> 16u) & 0xFFu) || !accepts(rough, (wd >> 8u) & 0xFFu))
            delta.fail(at + ": GBufferD " + hex(wd) + " for base " + vec(s.normal) + " under " + vec(s.coatNormal) +
                       ", UE (" + std::to_string(cx.nearest) + ", " + std::to_string(cz.nearest) + ")");
        // UE's reads of the stored words against the codec's decode.
        const glm::vec2 stored(float(ca) / 255.0f, float(cb) / 255.0f);
        const glm::vec3 ueBase = ueOctahedronToUnitVector(stored * 4.0f - 512.0f / 255.0f + ueUnitVectorToOctahedron(ueWorld));
        ++reads.compared;
        if (!(glm::length(o.coatNormal - ueWorld) < 1e-6f) || !(glm::length(o.normal - ueBase) < 1e-5f))
            reads.fail(at + ": decoded coat normal " + vec(o.coatNormal) + " (UE " + vec(ueWorld) + "), base " +
                       vec(o.normal) + " (UE " + vec(ueBase) + ")");
        // The round trip: near the top within the delta's steps; the same normal as the top's.
        ++base.compared;
        const int kind = kinds[j];
        // The delta is taken against the unquantised top and read against the decoded one: where the
        // top lies on a fold line of the lower half (x or y = 0, z < 0) within GBufferA's step, its
        // 10-bit code may fold it to the other side, and the base comes back far off, in UE as here.
        const bool onFold = s.coatNormal.z < 0.0f && std::min(std::fabs(s.coatNormal.x), std::fabs(s.coatNormal.y)) < 2e-3f;
        const double err = degreesBetween(o.normal, s.normal);
        if (kind == 0 && !onFold) worstNear = std::max(worstNear, err);
        if (kind == 0 && onFold && err >= 2.0) ++foldFlips;
        if (kind == 2) {
            ++same;
            worstSame = std::max(worstSame, degreesBetween(o.normal, o.coatNormal));
            if (ca != 128u || cb != 128u) base.fail(at + ": the same normal stores (" + std::to_string(ca) + ", " +
                                                    std::to_string(cb) + "), not (128, 128)");
        }
    });
    std::printf("[ ue5 ccn  ] %zu pixels, %zu ClearCoat (%zu near a delta tie, %zu base = coat); worst near-top base "
                "error %.3f deg off the fold lines (%zu flipped on them), base = coat read back within %.2e deg\n",
                top.compared, coated, delta.nearTies, same, worstNear, foldFlips, worstSame);
    EXPECT_EQ(top.mismatches, 0u);
    EXPECT_EQ(delta.mismatches, 0u);
    EXPECT_EQ(reads.mismatches, 0u);
    EXPECT_EQ(base.mismatches, 0u);
    EXPECT_GT(coated, kInputs / 8);  // about 3/8 of the inputs are coated (a coat amount > 0)
    EXPECT_GT(same, 1000u);
    EXPECT_LT(worstNear, 2.0);   // 8 bits over a delta range of 4, after the top's 10-bit quantisation
    EXPECT_LT(worstSame, 0.01);  // code (128, 128): oct(decoded top) itself, unfolded again
}

}  // namespace
