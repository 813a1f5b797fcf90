// The material layers through the renderer on lavapipe, on the sphere grid with layers added to
// some of its materials (clear coat, sheen, anisotropy; the rest keep none): every IBL mode shades
// them, approximating the ground truth; a layout that does not store them drops them, shading as
// the scene without layers does, bit for bit; the forward mask covers the transmissive draws.
// Small images (the layers' code is in the same shaders as everything else).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "facing_quad.h"
#include "forward_mask.h"
#include "gbuffer_wiring.h"
#include "ibl_precompute.h"
#include "layered_scene.h"
#include "layout_catalog.h"
#include "layout_files.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "scene.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class LayersRenderTest : public test::VulkanTest {};

using test::constantEnvironment;

// The sphere grid; of its spheres, every fourth from the second gets a coat, from the third a
// sheen, from the fourth anisotropy (the first and the ground none).
Scene layeredGrid(bool layers) {
    Scene scene = makeSphereGridScene();
    scene.lights.clear();
    if (!layers) return scene;
    test::addLayersToSphereGrid(scene);
    return scene;
}

double meanAbsCovered(const Image& a, const Image& b) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < a.pixelCount(); ++i) {
        if (a.pixels[i * 4 + 3] < 0.5f) continue;
        for (int c = 0; c < 3; ++c) sum += std::abs(double(a.pixels[i * 4 + c]) - b.pixels[i * 4 + c]);
        n += 3;
    }
    return n ? sum / double(n) : 0.0;
}


// The pixels of the materials `pick` selects, labelled by the forward mask (a visibility buffer of
// the scene, render/forward_mask.h) of a copy whose picked materials are marked forward.
template <class Pick>
std::vector<uint8_t> pixelsOf(Renderer& renderer, const Scene& scene, const RenderSettings& rs, Pick pick) {
    Scene marked = scene;
    for (size_t i = 0; i < marked.materials.size(); ++i)
        if (pick(i)) marked.materials[i].forward = "label";
    return renderForwardMask(renderer, marked, rs);
}

// Under the procedural sky, in every IBL mode: each layer changes its spheres (the mean absolute
// change over their pixels, relative to their mean radiance, above 1 %, in 2/3 of their pixels;
// what the layer adds there printed beside what it adds in the ground truth: the modes'
// approximations of the layers, measured), and every other pixel is bit for bit the scene's
// without layers (but in the ground truth, whose layered estimator draws its samples otherwise).
// Measured at 96 x 54 (relative radiance the layer adds; ground truth / split-sum-shader /
// split-sum / envbrdf-approx / bo2): coat +0.004 / +0.017 / +0.024 / +0.022 / +0.017, sheen
// +0.079 / +0.128 / -0.027 / -0.027 / -0.028, anisotropy -0.024 / +0.127 / +2.04 / +1.77 / +1.83
// (the specification's bent-normal look-up aims a smooth, strongly anisotropic lobe at the sky
// behind the viewer).
TEST_F(LayersRenderTest, EveryIblModeShadesTheLayers) {
    const EnvironmentMap sky = makeProceduralSky(64);
    IblSettings s;
    s.sourceFaceSize = 32;
    s.prefilteredFaceSize = 32;
    const IblMaps maps = computeIblMaps(ctx(), sky, s);
    const Scene layered = layeredGrid(true), bare = layeredGrid(false);
    Renderer withLayers(ctx(), layered, sky, maps), without(ctx(), bare, sky, maps);
    RenderSettings rs;
    rs.width = 96;
    rs.height = 54;
    rs.groundTruthSamples = 64;
    rs.groundTruthMaxBatches = 32;
    rs.splitSumShaderSamples = 128;
    const char* names[3] = {"coat", "sheen", "anisotropy"};
    std::vector<uint8_t> masks[3];
    for (size_t t = 0; t < 3; ++t)
        masks[t] = pixelsOf(without, bare, rs, [&](size_t i) { return i + 1 < bare.materials.size() && i % 4 == t + 1; });
    auto effect = [&](const Image& a, const Image& b, const std::vector<uint8_t>& mask) {
        double diff = 0.0, sum = 0.0;
        for (size_t i = 0; i < mask.size(); ++i) {
            if (!mask[i]) continue;
            for (int c = 0; c < 3; ++c) {
                diff += a.pixels[i * 4 + c] - b.pixels[i * 4 + c];
                sum += b.pixels[i * 4 + c];
            }
        }
        return diff / sum;  // signed: what the layer adds, relative
    };
    double truthEffect[3] = {0, 0, 0};
    for (IblMode mode : {IblMode::GroundTruth, IblMode::SplitSumShader, IblMode::SplitSum, IblMode::EnvBrdfApprox, IblMode::Bo2}) {
        rs.specularIbl = mode;
        const RenderOutput a = withLayers.render(makeReferenceWiring(), rs);
        const RenderOutput b = without.render(makeReferenceWiring(), rs);
        std::printf("  %-16s", iblModeName(mode).c_str());
        for (size_t t = 0; t < 3; ++t) {
            size_t changed = 0, count = 0;
            for (size_t i = 0; i < masks[t].size(); ++i)
                if (masks[t][i]) {
                    ++count;
                    changed += std::memcmp(&a.hdr.pixels[i * 4], &b.hdr.pixels[i * 4], 3 * sizeof(float)) != 0 ? 1 : 0;
                }
            double meanAbs = 0.0, meanRef = 0.0;
            for (size_t i = 0; i < masks[t].size(); ++i)
                if (masks[t][i])
                    for (int c = 0; c < 3; ++c) {
                        meanAbs += std::abs(double(a.hdr.pixels[i * 4 + c]) - b.hdr.pixels[i * 4 + c]);
                        meanRef += b.hdr.pixels[i * 4 + c];
                    }
            const double e = effect(a.hdr, b.hdr, masks[t]);
            if (mode == IblMode::GroundTruth) truthEffect[t] = e;
            std::printf("  %s %+.4f (ground truth %+.4f)", names[t], e, truthEffect[t]);
            EXPECT_GT(count, 20u) << names[t];
            EXPECT_GT(meanAbs / meanRef, 0.01) << iblModeName(mode) << ", " << names[t];
            // (envbrdf-approx drops the specular of its fully rough spheres, anisotropic or not.)
            EXPECT_GT(changed, count * 2 / 3) << iblModeName(mode) << ", " << names[t];
        }
        std::printf("\n");
        // The pixels without layers.
        size_t others = 0, same = 0;
        for (size_t i = 0; i < masks[0].size(); ++i) {
            if (masks[0][i] || masks[1][i] || masks[2][i] || a.hdr.pixels[i * 4 + 3] < 0.5f) continue;
            ++others;
            same += std::memcmp(&a.hdr.pixels[i * 4], &b.hdr.pixels[i * 4], 3 * sizeof(float)) == 0 ? 1 : 0;
        }
        if (mode != IblMode::GroundTruth) {
            EXPECT_EQ(same, others) << iblModeName(mode) << ": pixels without layers changed";
        }
        EXPECT_GT(others, 200u);
    }
}

// A layout that stores no layer (ue4) decodes "no layer" and shades the layered scene exactly as
// the scene without layers, bit for bit, in every mode but the ground truth (whose layered
// estimator draws its samples otherwise): the layer dropped as an engine without it drops it. The
// reference keeps them (its image differs on the layered spheres only).
TEST_F(LayersRenderTest, ALayoutWithoutLayersDropsThem) {
    const EnvironmentMap white = constantEnvironment(1.0f);
    IblSettings s;
    s.sourceFaceSize = 32;
    s.prefilteredFaceSize = 32;
    const IblMaps maps = computeIblMaps(ctx(), white, s);
    Scene layered = layeredGrid(true), bare = layeredGrid(false);
    layered.lights.push_back(defaultSun());
    bare.lights.push_back(defaultSun());
    Renderer withLayers(ctx(), layered, white, maps), without(ctx(), bare, white, maps);
    const GBufferWiring ue4 = generateWiring(loadLayout("ue4"));
    RenderSettings rs;
    rs.width = 96;
    rs.height = 54;
    rs.splitSumShaderSamples = 16;
    for (IblMode mode : {IblMode::SplitSumShader, IblMode::SplitSum, IblMode::EnvBrdfApprox, IblMode::Bo2}) {
        rs.specularIbl = mode;
        const RenderOutput a = withLayers.render(ue4, rs), b = without.render(ue4, rs);
        ASSERT_EQ(a.hdr.pixels.size(), b.hdr.pixels.size());
        EXPECT_EQ(std::memcmp(a.hdr.pixels.data(), b.hdr.pixels.data(), a.hdr.pixels.size() * sizeof(float)), 0)
            << iblModeName(mode);
    }
    rs.specularIbl = IblMode::SplitSum;
    const RenderOutput ra = withLayers.render(makeReferenceWiring(), rs), rb = without.render(makeReferenceWiring(), rs);
    EXPECT_GT(meanAbsCovered(ra.hdr, rb.hdr), 1e-3);
}

// The reference of a scene stores only the layers its materials have (loadReferenceLayout): a
// scene without layers gets the five targets of a reference without them (48 bytes a pixel fewer),
// and the image is the full reference's bit for bit, in a scene without layers and in one whose
// materials have a coat only (the sheen and anisotropy targets dropped, the coat's kept).
TEST_F(LayersRenderTest, TheReferenceStoresOnlyTheScenesLayers) {
    const Layout full = loadLayout("reference"), bare = loadReferenceLayout(0), coat = loadReferenceLayout(kLayerCoat);
    EXPECT_EQ(full.targets.size(), 8u);
    EXPECT_EQ(bare.targets.size(), 5u);
    EXPECT_EQ(bytesPerPixel(full) - bytesPerPixel(bare), 48);
    EXPECT_EQ(coat.targets.size(), 6u);
    for (const AttributeInfo& a : listAttributes()) {
        if (!isShadingAttribute(a.id)) continue;
        const int bit = attributeLayerBit(a.id);
        EXPECT_EQ(bare.stores(a.id), bit == 0) << a.name;
        EXPECT_EQ(coat.stores(a.id), bit == 0 || bit == kLayerCoat) << a.name;
        EXPECT_EQ(loadReferenceLayout(kLayerCoat | kLayerSheen | kLayerAnisotropy).stores(a.id), full.stores(a.id)) << a.name;
    }
    EXPECT_EQ(attributeLayerBit(Attribute::SheenRoughness), kLayerSheen);
    EXPECT_EQ(attributeLayerBit(Attribute::AnisotropyDirection), kLayerAnisotropy);

    const EnvironmentMap sky = makeProceduralSky(64);
    IblSettings s;
    s.sourceFaceSize = 32;
    s.prefilteredFaceSize = 32;
    const IblMaps maps = computeIblMaps(ctx(), sky, s);
    Scene plain = layeredGrid(false), coated = layeredGrid(true);
    plain.lights.push_back(defaultSun());
    coated.lights.push_back(defaultSun());
    for (Material& m : coated.materials) m.sheenColorFactor = glm::vec3(0.0f), m.anisotropyStrength = 0.0f;
    RenderSettings rs;
    rs.width = 96;
    rs.height = 54;
    rs.splitSumShaderSamples = 16;
    for (Scene* scene : {&plain, &coated}) {
        Renderer renderer(ctx(), *scene, sky, maps);
        ASSERT_EQ(renderer.sceneLayers(), scene == &plain ? 0 : kLayerCoat);
        for (IblMode mode : {IblMode::SplitSumShader, IblMode::SplitSum, IblMode::Bo2}) {
            rs.specularIbl = mode;
            const RenderOutput a = renderer.render(makeReferenceWiring(), rs);
            const RenderOutput b = renderer.render(makeReferenceWiring(renderer.sceneLayers()), rs);
            ASSERT_EQ(a.hdr.pixels.size(), b.hdr.pixels.size());
            EXPECT_EQ(std::memcmp(a.hdr.pixels.data(), b.hdr.pixels.data(), a.hdr.pixels.size() * sizeof(float)), 0)
                << iblModeName(mode) << (scene == &plain ? ", no layers" : ", coat only");
        }
    }
}

// A layout with a shading-model selector (tests/layout/data/shading-models.toml: each layer in 8
// bits, under its model, all in one shared target) carries the layers through the renderer: on the
// layered grid (one layer per material, so none is dropped) its image is far nearer the reference's
// than that of a layout without layers (ue4), in every IBL mode's split-sum path.
TEST_F(LayersRenderTest, ASelectorLayoutCarriesTheLayers) {
    const EnvironmentMap white = constantEnvironment(1.0f);
    IblSettings s;
    s.sourceFaceSize = 32;
    s.prefilteredFaceSize = 32;
    const IblMaps maps = computeIblMaps(ctx(), white, s);
    Scene layered = layeredGrid(true);
    layered.lights.push_back(defaultSun());
    Renderer renderer(ctx(), layered, white, maps);
    RenderSettings rs;
    rs.width = 96;
    rs.height = 54;
    rs.specularIbl = IblMode::SplitSum;
    const RenderOutput ref = renderer.render(makeReferenceWiring(), rs);
    const RenderOutput selector = renderer.render(generateWiring(test::testLayout("shading-models")), rs);
    const RenderOutput ue4 = renderer.render(generateWiring(loadLayout("ue4")), rs);
    const double kept = meanAbsCovered(selector.hdr, ref.hdr), dropped = meanAbsCovered(ue4.hdr, ref.hdr);
    std::printf("  mean |layout - reference|: shading-models %.5f, ue4 (no layers) %.5f\n", kept, dropped);
    EXPECT_LT(kept, 0.25 * dropped);
}

// The forward mask is the pixels of the transmissive material's draws: every pixel where the
// reference decodes that material's (unique) base colour, and no other.
TEST_F(LayersRenderTest, ForwardMaskCoversTheTransmissiveDraws) {
    const EnvironmentMap white = constantEnvironment(1.0f);
    IblSettings s;
    s.sourceFaceSize = 32;
    s.prefilteredFaceSize = 32;
    const IblMaps maps = computeIblMaps(ctx(), white, s);
    Scene scene = layeredGrid(false);
    const glm::vec3 marker(0.123f, 0.456f, 0.789f);
    scene.materials[5].baseColorFactor = glm::vec4(marker, 1.0f);
    scene.materials[5].forward = "KHR_materials_transmission";
    EXPECT_TRUE(hasForwardMaterials(scene));
    Renderer renderer(ctx(), scene, white, maps);
    RenderSettings rs;
    rs.width = 96;
    rs.height = 54;
    rs.decodeSurfaces = true;
    const std::vector<uint8_t> mask = renderForwardMask(renderer, scene, rs);
    const RenderOutput ref = renderer.render(makeReferenceWiring(), rs);
    ASSERT_EQ(mask.size(), size_t(rs.width) * rs.height);
    size_t masked = 0, agree = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        const float* c = &ref.surfaces.baseColor.pixels[i * 3];
        const bool isMarker = ref.surfaces.coverage[i] && std::abs(c[0] - marker.x) < 1e-6f &&
                              std::abs(c[1] - marker.y) < 1e-6f && std::abs(c[2] - marker.z) < 1e-6f;
        masked += mask[i] ? 1 : 0;
        agree += (mask[i] != 0) == isMarker ? 1 : 0;
    }
    std::printf("  %zu of %zu pixels forward\n", masked, mask.size());
    EXPECT_GT(masked, 20u);
    EXPECT_EQ(agree, mask.size());
    scene.materials[5].forward.clear();
    EXPECT_TRUE(renderForwardMask(renderer, scene, rs).empty());  // none: no render, no mask
}

// KHR_texture_transform on the GPU, in the G-buffer pass (the rasteriser's derivatives) and in a
// visibility buffer's resolve (the slot's gradients through the transform): a quad facing the
// camera, uv (0, 0) at its top left, textured with four quadrants (top left red, top right green,
// bottom left blue, bottom right white), seen at the centres of its quarters. Identity: the
// quadrants as they are; offset (0.5, 0): left and right swap; rotation pi/2, the README's
// "counter-clockwise" in UV space (scene.h: (u, v) -> (v, -u)): uv (0.25, 0.25) reads (0.25,
// 0.75), the top left quarter shows blue; texCoord 1 with TEXCOORD_1 = (1 - u, v): mirrored. The
// centres of the quarters lie on the quad's diagonal, where a pixel quad straddles its two
// triangles: the implicit derivatives of a transformed uv read a 1 x 1 mip there on lavapipe
// (material_eval.glsl materialSlotUv), which the explicit gradients avoid.
TEST_F(LayersRenderTest, TextureTransformMovesWhatEachPixelSamples) {
    Scene scene = test::facingQuad("texture transform quad", {glm::vec2(1, 0), glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1)});
    Texture quadrants;
    quadrants.name = "quadrants";
    quadrants.width = quadrants.height = 64;
    quadrants.rgba.resize(64 * 64 * 4);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const uint8_t c[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255}};
            std::memcpy(&quadrants.rgba[size_t(y * 64 + x) * 4], c[(y >= 32 ? 2 : 0) + (x >= 32 ? 1 : 0)], 4);
        }
    scene.textures.push_back(quadrants);
    const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
    struct Case {
        const char* name;
        TextureTransform transform;
        glm::vec3 topLeft, topRight, bottomLeft, bottomRight;
    };
    TextureTransform offset, rotation, set1;
    offset.offset = glm::vec2(0.5f, 0.0f);
    rotation.rotation = 1.5707963f;
    set1.texCoord = 1;
    const Case cases[] = {{"identity", TextureTransform{}, red, green, blue, white},
                          {"offset (0.5, 0)", offset, green, red, white, blue},
                          {"rotation pi/2", rotation, blue, red, white, green},
                          {"texCoord 1", set1, green, red, white, blue}};
    const EnvironmentMap white1 = constantEnvironment(1.0f);
    const IblMaps maps = test::smallIblMaps(ctx(), white1);
    for (const Case& c : cases) {
        Material m;
        m.baseColorTexture = 0;
        m.uvTransforms[size_t(TextureSlot::BaseColor)] = c.transform;
        scene.materials = {m};
        Renderer renderer(ctx(), scene, white1, maps);
        RenderSettings rs;
        rs.width = rs.height = 64;
        rs.decodeSurfaces = true;
        for (const char* layout : {"reference", "visibility-32"}) {
            const GBufferWiring wiring = std::string(layout) == "reference" ? makeReferenceWiring() : generateWiring(loadLayout(layout));
            const RenderOutput out = renderer.render(wiring, rs);
            // The quarters' centres, world (+-0.5, +-0.5): about 14.7 pixels from the image's centre.
            auto at = [&](int x, int y) {
                const float* p = &out.surfaces.baseColor.pixels[size_t(y * 64 + x) * 3];
                return glm::vec3(p[0], p[1], p[2]);
            };
            const std::pair<glm::vec3, glm::vec3> checks[] = {
                {at(17, 17), c.topLeft}, {at(46, 17), c.topRight}, {at(17, 46), c.bottomLeft}, {at(46, 46), c.bottomRight}};
            for (const auto& [got, want] : checks)
                EXPECT_LT(glm::length(got - want), 0.02f) << c.name << ", " << layout << ": (" << got.x << ", " << got.y
                                                          << ", " << got.z << ")";
        }
    }
}

}  // namespace
}  // namespace gbl
