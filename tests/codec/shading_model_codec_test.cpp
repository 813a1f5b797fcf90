// The CPU codec on a layout with a shading-model selector (tests/layout/data/shading-models.toml),
// held to what layouts/README.md, "Shading models: the selector", states, computed here from the
// statement and not from the codec: the id each pixel's layers give it (the first of clear coat,
// cloth, anisotropic that it carries, UE's ids 4, 8 and the layout's 13; default 1), the bits of
// the model's own fields in the shared target, nothing of the other models' fields, and on decode
// each layer where the pixel's model holds it, 0 ("no layer") where it does not, the fallback of an
// attribute the model does not store. (GPU against this mirror: tests/codec/gpu_cpu_bits_test.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cpu_codec.h"
#include "layout_files.h"
#include "surface_support.h"

namespace gbl {
namespace {

constexpr int kW = 64, kH = 16;

// The statement's rule, restated: the model's id in the test layout.
uint32_t expectedId(unsigned layers) {
    if (layers & 1u) return 4;  // clear_coat
    if (layers & 2u) return 8;  // cloth
    if (layers & 4u) return 13;  // anisotropic
    return 1;  // default
}

uint32_t unorm8(float x) { return uint32_t(std::floor(std::clamp(x, 0.0f, 1.0f) * 255.0f + 0.5f)); }

uint32_t byteOf(uint32_t word, int k) { return (word >> (8 * k)) & 0xffu; }

TEST(ShadingModelCodec, EachPixelStoresItsModelsIdAndOnlyItsModelsFields) {
    const Layout layout = test::testLayout("shading-models");
    std::vector<Surface> surfaces = test::randomSurfaces(size_t(kW * kH), 41);
    test::assignLayerPatterns(surfaces);
    const CpuGBuffer g = encodeGBuffer(layout, surfaces, kW, kH);
    ASSERT_EQ(g.targetWords.size(), 4u);
    int seen[16] = {};
    for (size_t i = 0; i < surfaces.size(); ++i) {
        SCOPED_TRACE("pixel " + std::to_string(i) + ", layers " + std::to_string(test::layerPattern(i)));
        const Surface& s = surfaces[i];
        const uint32_t id = expectedId(test::layerPattern(i));
        ++seen[id];
        const uint32_t b = g.targetWords[1][i], c = g.targetWords[2][i], d = g.targetWords[3][i];
        EXPECT_EQ(byteOf(b, 3) & 0xfu, id);  // B.a[0:3]: the selector
        EXPECT_EQ(byteOf(b, 3) >> 4, 5u);    // B.a[4:7]: selective_output_mask = 5
        EXPECT_EQ(byteOf(c, 3) & 0x7u, id == 4 ? 3u : 0u);  // C.a[0:2]: flags = 3 under clear_coat only
        switch (id) {
            case 4:  // clear_coat: coat, coat roughness in D.r, D.g (the coat normal in D.b, D.a)
                EXPECT_EQ(byteOf(d, 0), unorm8(s.coat));
                EXPECT_EQ(byteOf(d, 1), unorm8(s.coatRoughness));
                EXPECT_EQ(byteOf(c, 1), 0u);  // no specular field under clear_coat
                break;
            case 8:  // cloth: the sheen in D
                EXPECT_EQ(byteOf(d, 0), unorm8(s.sheenColor.x));
                EXPECT_EQ(byteOf(d, 1), unorm8(s.sheenColor.y));
                EXPECT_EQ(byteOf(d, 2), unorm8(s.sheenColor.z));
                EXPECT_EQ(byteOf(d, 3), unorm8(s.sheenRoughness));
                EXPECT_EQ(byteOf(c, 1), unorm8(s.specular));
                break;
            case 13:  // anisotropic: strength in D.r, specular in D.a[0:5] (6 bits), the top 2 bits free
                EXPECT_EQ(byteOf(d, 0), unorm8(s.anisotropyStrength));
                EXPECT_EQ(byteOf(d, 3), uint32_t(std::floor(std::clamp(s.specular, 0.0f, 1.0f) * 63.0f + 0.5f)));
                EXPECT_EQ(byteOf(c, 1), 0u);
                break;
            default:  // default: custom_data's constant (0.25, 0.5, 0.75, 1.0) in D
                EXPECT_EQ(d, unorm8(0.25f) | unorm8(0.5f) << 8 | unorm8(0.75f) << 16 | unorm8(1.0f) << 24);
                EXPECT_EQ(byteOf(c, 1), unorm8(s.specular));
                break;
        }
    }
    for (uint32_t id : {1u, 4u, 8u, 13u}) EXPECT_GT(seen[id], 0) << "id " << id;
}

TEST(ShadingModelCodec, ALayerTheModelCannotHoldDecodesAsNoLayer) {
    const Layout layout = test::testLayout("shading-models");
    std::vector<Surface> surfaces = test::randomSurfaces(size_t(kW * kH), 42);
    test::assignLayerPatterns(surfaces);
    const std::vector<Surface> out = decodeGBuffer(layout, encodeGBuffer(layout, surfaces, kW, kH));
    const float step = 0.5f / 255.0f + 1e-6f;
    for (size_t i = 0; i < surfaces.size(); ++i) {
        SCOPED_TRACE("pixel " + std::to_string(i) + ", layers " + std::to_string(test::layerPattern(i)));
        const Surface& s = surfaces[i];
        const Surface& o = out[i];
        const uint32_t id = expectedId(test::layerPattern(i));
        EXPECT_EQ(o.shadingModel, float(id));
        EXPECT_NEAR(o.coat, id == 4 ? s.coat : 0.0f, step);
        EXPECT_NEAR(o.coatRoughness, id == 4 ? s.coatRoughness : 0.0f, step);
        if (id != 4) {
            EXPECT_EQ(o.coatNormal, glm::vec3(0.0f));
        }
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(o.sheenColor[c], id == 8 ? s.sheenColor[c] : 0.0f, step);
        EXPECT_NEAR(o.anisotropyStrength, id == 13 ? s.anisotropyStrength : 0.0f, step);
        if (id != 13) {
            EXPECT_EQ(o.anisotropyDirection, glm::vec3(0.0f));
        }
        // specular: 8 bits under default and cloth, 6 under anisotropic, the fallback 0.5 under clear_coat
        const float spec = id == 4 ? 0.5f : s.specular;
        EXPECT_NEAR(o.specular, spec, id == 13 ? 0.5f / 63.0f + 1e-6f : (id == 4 ? 0.0f : step));
        // specular_color = "ue4" reads the decoded (or fallen-back) specular
        const glm::vec3 f0 = glm::mix(glm::vec3(0.08f * o.specular), o.baseColor, o.metallic);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(o.specularColor[c], f0[c], 1e-6f);
        // unconditional fields are untouched by the models
        EXPECT_NEAR(o.metallic, s.metallic, step);
        EXPECT_NEAR(o.occlusion, s.occlusion, step);
    }
}

TEST(ShadingModelCodec, ACleanedPixelIsOfTheDefaultModel) {
    const Layout layout = test::testLayout("shading-models");
    const auto clear = clearWords(layout);
    ASSERT_EQ(clear.size(), 4u);
    EXPECT_EQ(byteOf(clear[1][0], 3), 1u | 5u << 4);  // default's id 1, the mask 5
    EXPECT_EQ(clear[3][0], unorm8(0.25f) | unorm8(0.5f) << 8 | unorm8(0.75f) << 16 | unorm8(1.0f) << 24);
}

// HDRP's shape (fresnel0 under its standard feature, metallic under anisotropy, each derived where
// the other is stored): on a pixel of a model storing metallic, specular_color is derived from the
// decoded metallic; where specular_color is stored, metallic from it; the fallbacks' order
// (wiring_plan.h orderedFallbacks) works for every model.
TEST(ShadingModelCodec, FallbacksDeriveEachOtherPerModel) {
    const Layout layout = test::selectorLayoutDerivingEachOther();
    std::vector<Surface> surfaces = test::randomSurfaces(size_t(kW * kH), 43);
    test::assignLayerPatterns(surfaces);
    const std::vector<Surface> out = decodeGBuffer(layout, encodeGBuffer(layout, surfaces, kW, kH));
    const float step = 0.5f / 255.0f + 1e-6f;
    for (size_t i = 0; i < surfaces.size(); ++i) {
        SCOPED_TRACE("pixel " + std::to_string(i));
        const uint32_t id = expectedId(test::layerPattern(i));
        const Surface& s = surfaces[i];
        const Surface& o = out[i];
        if (id == 4 || id == 13) {  // metallic stored; specular_color = ue4 of it
            EXPECT_NEAR(o.metallic, s.metallic, step);
            const glm::vec3 f0 = glm::mix(glm::vec3(0.08f * o.specular), o.baseColor, o.metallic);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(o.specularColor[c], f0[c], 1e-6f);
        } else {  // specular_color stored; metallic from it (Unity's reflectivity convention)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(o.specularColor[c], s.specularColor[c], step);
            const float m = std::clamp((std::max({o.specularColor.x, o.specularColor.y, o.specularColor.z}) - 0.04f) / 0.96f,
                                       0.0f, 1.0f);
            EXPECT_NEAR(o.metallic, m, 1e-6f);
        }
    }
}

}  // namespace
}  // namespace gbl
