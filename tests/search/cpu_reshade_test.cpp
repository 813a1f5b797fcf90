// The search's CPU re-shade and fast evaluation, without Vulkan: cube addressing against the IBL
// pre-computation's own texel directions, the split-sum under a constant environment against its
// closed form, depth quantisation against the formats' definitions, and the evaluation's sense
// (the reference scores zero, fewer bits score worse).
#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "brdf.h"
#include "cpu_reshade.h"
#include "sheen_albedo.h"
#include "fast_eval.h"
#include "ibl_math.h"
#include "layout.h"
#include "layout_catalog.h"
#include "search_test_scene.h"

namespace gbl::search {
namespace {

TEST(CpuReshade, CubeAddressingInvertsTheTexelDirections) {
    // ibl_precompute.cpp's cubeTexelDirection is how the cube was filled; reading it back must
    // land on the same face and texel centre.
    for (uint32_t size : {1u, 4u, 16u})
        for (uint32_t f = 0; f < 6; ++f)
            for (uint32_t y = 0; y < size; ++y)
                for (uint32_t x = 0; x < size; ++x) {
                    const glm::vec3 d = cubeTexelDirection(f, float(x), float(y), size);
                    uint32_t face;
                    float u, v;
                    CpuIbl::cubeCoordinates(glm::normalize(d) * 3.0f, size, face, u, v);
                    ASSERT_EQ(face, f);
                    EXPECT_NEAR(u, float(x) + 0.5f, 1e-4f);
                    EXPECT_NEAR(v, float(y) + 0.5f, 1e-4f);
                }
}

TEST(CpuReshade, ConstantEnvironmentGivesTheSplitSumClosedForm) {
    // A constant environment L: every pre-filtered mip is L, the SH irradiance is pi L (only the
    // DC term: sh0 = pi L / 0.282095), so IBL radiance = albedo L + L (F0 A + B) with (A, B) the LUT.
    const glm::vec3 L(0.7f, 0.9f, 1.3f);
    IblMaps maps = test::syntheticIbl();
    for (CubeMip& m : maps.prefiltered)
        for (size_t i = 0; i < m.rgba.size(); i += 4)
            for (int c = 0; c < 3; ++c) m.rgba[i + size_t(c)] = L[c];
    maps.irradianceSh = {};
    maps.irradianceSh[0] = L * (shading::kPi / 0.282095f);
    const CpuIbl ibl(maps);
    Surface s;
    s.normal = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    s.diffuseColor = glm::vec3(0.5f, 0.3f, 0.2f);
    s.specularColor = glm::vec3(0.04f);
    s.roughness = 0.4f;
    s.occlusion = 0.8f;
    const glm::vec3 camera(0.0f, 3.0f, 4.0f);
    const glm::vec3 got = shadePixel(s, glm::vec3(0.0f), camera, {}, ibl, glm::vec3(0.25f));
    const float NoV = glm::dot(s.normal, glm::normalize(camera));
    // The LUT texel by hand: bilinear at (NoV, roughness) between texel centres.
    const Image& lut = maps.brdfLut;
    const float fx = NoV * 16.0f - 0.5f, fy = 0.4f * 16.0f - 0.5f;
    const int x0 = int(fx), y0 = int(fy);
    const float tx = fx - float(x0), ty = fy - float(y0);
    glm::vec2 ab(0.0f);
    for (int c = 0; c < 2; ++c)
        ab[c] = (lut.at(x0, y0, c) * (1 - tx) + lut.at(x0 + 1, y0, c) * tx) * (1 - ty) +
                (lut.at(x0, y0 + 1, c) * (1 - tx) + lut.at(x0 + 1, y0 + 1, c) * tx) * ty;
    // UE4's EnvBRDF with the 2 % rule: saturate(50 F0.g) = 1 here.
    const glm::vec3 expected = (s.diffuseColor * L + L * (s.specularColor * ab.x + ab.y)) * s.occlusion + 0.25f;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 2e-5f * expected[c]) << c;
}

// The layers in the search's re-shade, as the lighting pass layers them (image_based_light.glsl
// evaluateImageBasedLightLayered, split-sum): on a constant environment L every look-up is L, so
// the pixel is, written out from the glTF layering: the sheen's c E(NoV) L over the base scaled
// by 1 - max3(c) E(NoV), under the coat's weight clearcoat * fc(NcoV) with its lobe L (A + B) at
// (NcoV, coat roughness), all of it times occlusion; emission under the coat. A pixel with the same
// base and no layer shades
// as before the layers (the base's closed form of the test above).
TEST(CpuReshade, LayersOnAConstantEnvironment) {
    const glm::vec3 L(0.7f, 0.9f, 1.3f);
    IblMaps maps = test::syntheticIbl();
    for (CubeMip& m : maps.prefiltered)
        for (size_t i = 0; i < m.rgba.size(); i += 4)
            for (int c = 0; c < 3; ++c) m.rgba[i + size_t(c)] = L[c];
    maps.irradianceSh = {};
    maps.irradianceSh[0] = L * (shading::kPi / 0.282095f);
    const CpuIbl ibl(maps);
    Surface s;
    s.normal = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    s.diffuseColor = glm::vec3(0.5f, 0.3f, 0.2f);
    s.specularColor = glm::vec3(0.04f);
    s.roughness = 0.4f;
    s.occlusion = 0.8f;
    s.emissive = glm::vec3(0.1f, 0.2f, 0.3f);
    const glm::vec3 camera(0.0f, 3.0f, 4.0f), V = glm::normalize(camera);
    const glm::vec3 bare = shadePixel(s, glm::vec3(0.0f), camera, {}, ibl, glm::vec3(0.0f));
    s.coat = 0.75f;
    s.coatRoughness = 0.3f;
    s.coatNormal = glm::normalize(glm::vec3(0.0f, 1.0f, 0.3f));
    s.sheenColor = glm::vec3(0.8f, 0.4f, 0.2f);
    s.sheenRoughness = 0.5f;
    const glm::vec3 got = shadePixel(s, glm::vec3(0.0f), camera, {}, ibl, glm::vec3(0.0f));
    const float NoV = glm::dot(s.normal, V), NcoV = glm::dot(s.coatNormal, V);
    const float E = shading::sheenAlbedoTable().lookup(NoV, s.sheenRoughness);
    const glm::vec2 ab = ibl.lut(NcoV, s.coatRoughness);
    const float fc = s.coat * (0.04f + 0.96f * std::pow(1.0f - NcoV, 5.0f));
    const glm::vec3 base = (bare - s.emissive) / s.occlusion;  // the base's IBL, checked in closed form above
    const glm::vec3 sheened = s.sheenColor * E * L + base * (1.0f - 0.8f * E);
    // Occlusion darkens the whole indirect light, the layers' included.
    const glm::vec3 expected = (sheened * (1.0f - fc) + fc * L * (ab.x + ab.y)) * s.occlusion + s.emissive * (1.0f - fc);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5f + 2e-5f * expected[c]) << c;
    EXPECT_GT(E, 0.05f);  // the sheen takes part
    // No layer: the base alone, bit for bit.
    Surface none = s;
    none.coat = 0.0f;
    none.sheenColor = glm::vec3(0.0f);
    const glm::vec3 again = shadePixel(none, glm::vec3(0.0f), camera, {}, ibl, glm::vec3(0.0f));
    EXPECT_EQ(std::memcmp(&again, &bare, sizeof(bare)), 0);
}

TEST(CpuReshade, DepthQuantisationFollowsTheFormats) {
    Depth d16;
    d16.depthBits = 16;
    EXPECT_FLOAT_EQ(quantizeDepth(0.5f, false, d16), float(std::round(0.5 * 65535) / 65535));
    Depth d24;
    d24.depthBits = 24;
    const float d = 0.987654321f;
    EXPECT_FLOAT_EQ(quantizeDepth(d, false, d24), float(std::round(double(d) * 16777215.0) / 16777215.0));
    EXPECT_LE(std::abs(quantizeDepth(d, false, d24) - d), 0.5f / 16777215.0f + 1e-7f);
    Depth f32;
    f32.floatDepth = true;
    EXPECT_EQ(quantizeDepth(d, false, f32), d);
    f32.reversedZ = true;  // 1 - d in float32 near 0 is finer than d near 1: returns d within an ulp
    EXPECT_NEAR(quantizeDepth(d, false, f32), d, 1.2e-7f);
    // A reversed-Z reference: the same convention is exact, the other one rounds 1 - d.
    EXPECT_EQ(quantizeDepth(d, true, f32), d);
    const float near0 = 3.0e-4f;  // a far point in reversed Z
    d24.reversedZ = false;
    EXPECT_FLOAT_EQ(quantizeDepth(near0, true, d24),
                    float(1.0 - std::round((1.0 - double(near0)) * 16777215.0) / 16777215.0));
    d24.reversedZ = true;
    EXPECT_FLOAT_EQ(quantizeDepth(near0, true, d24), float(std::round(double(near0) * 16777215.0) / 16777215.0));
}

const FastEvaluator& evaluator(Objective o) {
    static const FastEvaluator flip({test::syntheticView(48, 32)}, test::syntheticLights(), test::syntheticIbl(),
                                    Objective::Flip);
    static const FastEvaluator psnr({test::syntheticView(48, 32)}, test::syntheticLights(), test::syntheticIbl(),
                                    Objective::Psnr);
    static const FastEvaluator attributes({test::syntheticView(48, 32)}, test::syntheticLights(),
                                          test::syntheticIbl(), Objective::Attributes);
    return o == Objective::Flip ? flip : o == Objective::Psnr ? psnr : attributes;
}

TEST(FastEval, TheReferenceScoresZeroAndThinLayoutsScoreWorse) {
    const Layout reference = loadLayout("reference");
    const Layout ue4 = loadLayout("ue4");
    const Layout thin = loadLayout("crysis3-thin");
    for (Objective o : {Objective::Flip, Objective::Psnr, Objective::Attributes}) {
        const Evaluation r = evaluator(o).evaluate(reference), u = evaluator(o).evaluate(ue4),
                         t = evaluator(o).evaluate(thin);
        if (o == Objective::Flip) {
            EXPECT_EQ(r.flip, 0.0);
            EXPECT_GT(u.flip, 0.0);
            EXPECT_GT(t.flip, u.flip) << "crysis3-thin (12 B/px) should lose more than ue4 (25 B/px)";
        }
        if (o == Objective::Psnr) {
            EXPECT_GT(-u.error, -t.error);
        }
        if (o == Objective::Attributes) {
            EXPECT_LT(r.attributes, 1e-3);  // float32 storage: rounding only
            EXPECT_GT(t.attributes, u.attributes);
        }
    }
}

// Every metric is measured whatever the objective: the reference's storage loses (almost)
// nothing; Crysis 3's checkerboard chroma and 7-bit gloss lose more colour and roughness than
// UE4's sRGB8 and 8-bit roughness.
TEST(FastEval, EveryMetricWhateverTheObjective) {
    const Layout reference = loadLayout("reference"), ue4 = loadLayout("ue4"), thin = loadLayout("crysis3-thin");
    for (Objective o : {Objective::Flip, Objective::Psnr, Objective::Attributes}) {
        const Evaluation r = evaluator(o).evaluate(reference), u = evaluator(o).evaluate(ue4),
                         t = evaluator(o).evaluate(thin);
        EXPECT_EQ(r.flip, 0.0);
        EXPECT_LT(r.normalDeg, 0.01);
        EXPECT_LT(r.baseColorDe + r.diffuseColorDe + r.specularColorDe, 1e-3);
        EXPECT_LT(r.roughness + r.metallic + r.occlusion, 1e-5);
        EXPECT_GT(u.flip, 0.0);
        EXPECT_GT(t.diffuseColorDe, u.diffuseColorDe);
        EXPECT_GT(t.roughness, u.roughness);
        EXPECT_GT(u.psnr, t.psnr);
    }
}

// A stored window depth (Bevy on WebGL2) is what the re-shade lights from, as the lighting pass
// does: without its depth field the same layout lights from the reference's depth. The images
// differ, and by no more than moving each point by a 20-bit depth step can.
TEST(FastEval, AStoredDepthIsWhatTheLightingReads) {
    const Layout webgl2 = loadLayout("bevy-deferred-webgl2");
    Layout attachment = webgl2;
    for (Target& t : attachment.targets)
        t.fields.erase(std::remove_if(t.fields.begin(), t.fields.end(),
                                      [](const Field& f) { return f.attribute == Attribute::Depth; }),
                       t.fields.end());
    ASSERT_FALSE(attachment.stores(Attribute::Depth));
    const Image a = evaluator(Objective::Flip).renderLayout(webgl2, 0, 1);
    const Image b = evaluator(Objective::Flip).renderLayout(attachment, 0, 1);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    size_t differ = 0;
    double worst = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        differ += a.pixels[i] != b.pixels[i];
        worst = std::max(worst, std::abs(double(a.pixels[i]) - b.pixels[i]) / std::max(std::abs(double(b.pixels[i])), 1e-3));
    }
    std::printf("[ depth    ] %zu of %zu values moved by the 20-bit depth, at most %.3g relative\n", differ, a.pixels.size(),
                worst);
    EXPECT_GT(differ, a.pixels.size() / 10);
    EXPECT_LT(worst, 1e-3);
}

TEST(FastEval, DeferredLightingIsRefusedInOneLine) {
    const Layout slim = loadLayout("crysis2-slim");
    try {
        evaluator(Objective::Flip).evaluate(slim);
        FAIL();
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("crysis2-slim"), std::string::npos);
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

}  // namespace
}  // namespace gbl::search
