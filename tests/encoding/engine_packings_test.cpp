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

#include "engine_packing_support.h"
#include "layout_catalog.h"
#include "layout_text.h"

namespace {

using namespace gbl::test::packing;

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
std::string unityLayout(const std::string& name, const std::string& normalEncoding) {
    const std::string roughness = name == "hdrp" ? "unorm" : "gloss";
    return gbl::test::LayoutText(name, "normal buffer", R"({ engine = "Unity", talk = "unit test", year = 2021 })")
        .target("normals", "R8G8B8A8_UNORM",
                {R"(attribute = "normal",    encoding = ")" + normalEncoding + R"(", at = ["r + b[0:3]", "g + b[4:7]"])",
                 R"(attribute = "roughness", encoding = ")" + roughness + R"(", at = "a")"});
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

std::string hdrpFresnelLayout() {
    return gbl::test::LayoutText("hdrp-fresnel0", "HDRP's GBuffer1 and GBuffer2", gbl::test::kHdrpSource)
        .target(gbl::test::hdrpGBuffer1())
        .target(gbl::test::hdrpGBuffer2())
        .clear("specular_color = 0.0");
}

TEST(EnginePackings, HdrpFresnel0EqualsFastLinearToSrgbAndItsCubic) {
    const Layout layout = gbl::parseLayout(hdrpFresnelLayout(), "hdrp-fresnel0.toml");
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

// Occlusion rides in GBuffer3 (the AO tag): no fallback for it.
std::string hdrpGBuffer3Layout() {
    return gbl::test::LayoutText("hdrp-gbuffer3", "HDRP's GBuffer3 with its AO tag", gbl::test::kHdrpSource)
        .target(gbl::test::hdrpGBuffer1())
        .target(gbl::test::hdrpGBuffer3())
        .noFallback("occlusion")
        .clear("emissive = 0.0")
        .clear("occlusion = 1.0");
}

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
    const Layout layout = gbl::parseLayout(hdrpGBuffer3Layout(), "hdrp-gbuffer3.toml");
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

TEST(EnginePackings, UrpSnormNormalsEqualTheHardwareConversion) {
    const Layout layout = gbl::loadLayout("urp-deferred");  // the shipped row: its GBuffer2
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2804);
    std::vector<Surface> keep(kImage);
    Tally t;
    runCodec(layout, targetIndex(layout, "GBuffer2"),
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

TEST(EnginePackings, NiagaraNormalsEqualEncodeOctWithItsDeband) {
    const Layout layout = gbl::loadLayout("niagara");  // the shipped row: its gbuffer1
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2805);
    std::vector<Surface> keep(kImage);
    Tally t;
    runCodec(layout, targetIndex(layout, "gbuffer1"),
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

TEST(EnginePackings, GraniteNormalsEqualHalfNormalPlusHalf) {
    const Layout layout = gbl::loadLayout("granite");  // the shipped row: its normal target
    const std::vector<glm::vec3> edges = edgeNormals();
    Rng rng(2806);
    std::vector<Surface> keep(kImage);
    Tally t;
    runCodec(layout, targetIndex(layout, "normal"),
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
