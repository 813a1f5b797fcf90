// The material layers' metrics on the device evaluator (shaders/eval_layers.comp.glsl) against the
// CPU oracle (measure/run_metrics.h "Material layers") on a real layered render: the sphere grid
// with clear coat, sheen and anisotropy on some spheres, measured for ue4 (which stores none of
// them, so it drops every layer). Also: the device decode's layer images (GBL_DECODE_TO_IMAGES)
// give what the host read-back's give, the host decode on the CPU codec fills the same layer
// images as the decode pass, and a scene without layers measures none (absent, not zero).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "gpu_evaluator.h"
#include "layered_scene.h"
#include "layout_catalog.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "run_metrics.h"
#include "scene.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class GpuEvaluatorLayersTest : public test::VulkanTest {};

constexpr double kFlipTol = 1e-4;  // gpu_evaluator_test's
constexpr double kQuantileRel = 1.0 / 1024.0 + 1e-6;

void expectStats(const ClassStats& g, const ClassStats& c, double meanRel, const std::string& what) {
    ASSERT_EQ(g.error.count, c.error.count) << what;
    if (c.error.count == 0) return;
    auto near = [&](double a, double b, double rel, double abs, const char* field) {
        EXPECT_NEAR(a, b, std::max(abs, rel * std::abs(b))) << what << " " << field;
    };
    near(g.error.mean, c.error.mean, meanRel, 1e-7, "mean");
    near(g.error.rms, c.error.rms, meanRel, 1e-7, "rms");
    near(g.error.max, c.error.max, meanRel, 1e-6, "max");
    near(g.error.p99, c.error.p99, kQuantileRel + meanRel, 1e-6, "p99");
    near(g.rmse, c.rmse, 1e-6, 1e-9, "rmse");
}

// The sphere grid with its layers (layered_scene.h), or without.
Scene layeredGrid(bool layers) {
    Scene scene = makeSphereGridScene();
    if (!layers) return scene;
    test::addLayersToSphereGrid(scene);
    return scene;
}

DeviceRender deviceRender(const RenderOutput& r) {
    DeviceRender d;
    d.hdr = &r.device->hdr;
    for (size_t k = 0; k < 4; ++k) d.surfaces[k] = &r.device->surfaces[k];
    if (r.device->layers[0].image)
        for (size_t k = 0; k < 4; ++k) d.layers[k] = &r.device->layers[k];
    return d;
}

TEST_F(GpuEvaluatorLayersTest, AgreesWithTheCpuOracleOnALayeredRender) {
    const EnvironmentMap sky = makeProceduralSky(64);
    const Scene scene = layeredGrid(true);  // the renderer keeps a reference to it
    Renderer renderer(ctx(), scene, sky);
    const RenderSettings rs = test::decodedFrame(160, 90);
    const RenderOutput ref = renderer.render(makeReferenceWiring(), rs);
    const RenderOutput ue4 = renderer.render(generateWiring(loadLayout("ue4")), rs);
    ASSERT_TRUE(ref.surfaces.hasLayers());
    ASSERT_TRUE(ue4.surfaces.hasLayers());  // decoded as 0: ue4 stores no layer

    const float exposure = 1.0f;
    RunMetricsOptions cpuOptions;
    cpuOptions.hdrFlip = false;
    const RunMetrics c = computeRunMetrics(ref.surfaces, ue4.surfaces, ref.hdr, ue4.hdr, exposure, cpuOptions);
    ASSERT_TRUE(c.layers.has_value());
    ASSERT_TRUE(c.image.layerClasses.has_value());
    for (LayerClass k : kLayerClasses)
        std::printf("%s: %zu pixels\n", layerClassName(k), (*c.image.layerClasses)[size_t(k)].pixels);
    // ue4 drops the coat: its coat error is the reference's coat amount, 1 on every coated pixel.
    const ClassStats& coat = (*c.layers)[LayerAttribute::Coat].all;
    ASSERT_GT(coat.error.count, 100u);
    EXPECT_NEAR(coat.error.mean, 1.0, 1e-6);
    EXPECT_GT((*c.layers)[LayerAttribute::SheenColor].all.error.mean, 1.0);  // a dropped sheen: far from black
    EXPECT_NEAR((*c.layers)[LayerAttribute::AnisotropyStrength].all.error.mean, 0.8, 1e-6);

    const uint32_t w = uint32_t(ref.hdr.width), h = uint32_t(ref.hdr.height);
    UploadedRender r(ctx(), ref.hdr, &ref.surfaces), t(ctx(), ue4.hdr, &ue4.surfaces);
    GpuEvaluator evaluator(ctx(), w, h);
    evaluator.setReference(r.view(), exposure);
    GpuEvalOptions options;
    options.hdrFlip = false;
    const RunMetrics g = evaluator.evaluate(t.view(), options);
    ASSERT_TRUE(g.layers.has_value());
    ASSERT_TRUE(g.image.layerClasses.has_value());
    const char* names[] = {"coat", "coat roughness", "coat normal", "sheen colour", "sheen roughness",
                           "anisotropy strength", "anisotropy direction"};
    for (size_t k = 0; k < kLayerAttributeCount; ++k) {
        // Float angles and CIEDE2000 against the CPU's double: 1e-4 relative on means (as the others).
        const bool floatMaths = k == 2 || k == 3 || k == 6;
        const double rel = floatMaths ? 1e-4 : 1e-6;
        const AttributeMetrics& ga = g.layers->byAttribute[k];
        const AttributeMetrics& ca = c.layers->byAttribute[k];
        expectStats(ga.all, ca.all, rel, std::string(names[k]) + " all");
        expectStats(ga.metal, ca.metal, rel, std::string(names[k]) + " metal");
        expectStats(ga.dielectric, ca.dielectric, rel, std::string(names[k]) + " dielectric");
        EXPECT_EQ(ga.skipped, ca.skipped) << names[k];
    }
    for (LayerClass k : kLayerClasses) {
        const ClassImageErrors& gc = (*g.image.layerClasses)[size_t(k)];
        const ClassImageErrors& cc = (*c.image.layerClasses)[size_t(k)];
        EXPECT_EQ(gc.pixels, cc.pixels) << layerClassName(k);
        EXPECT_GT(cc.pixels, 0u) << layerClassName(k);
        EXPECT_NEAR(gc.relLuminanceMean, cc.relLuminanceMean, std::max(1e-9, 1e-6 * cc.relLuminanceMean))
            << layerClassName(k);
        EXPECT_NEAR(gc.rmseLinear, cc.rmseLinear, 1e-9 * cc.rmseLinear) << layerClassName(k);
        EXPECT_NEAR(gc.flipMean, cc.flipMean, kFlipTol) << layerClassName(k);
    }
    // The coated class loses most where the coat is dropped (a sanity check that the classes differ).
    EXPECT_GT((*c.image.layerClasses)[size_t(LayerClass::Coated)].flipMean,
              (*c.image.layerClasses)[size_t(LayerClass::Plain)].flipMean);

    // The device decode's layer images: the same numbers as the read-back's, uploaded.
    RenderSettings device = rs;
    device.keepOnDevice = true;
    const RenderOutput refDevice = renderer.render(makeReferenceWiring(), device);
    const RenderOutput ue4Device = renderer.render(generateWiring(loadLayout("ue4")), device);
    ASSERT_TRUE(refDevice.device && refDevice.device->layers[0].image);
    GpuEvaluator onDevice(ctx(), w, h);
    onDevice.setReference(deviceRender(refDevice), exposure);
    const RunMetrics d = onDevice.evaluate(deviceRender(ue4Device), options);
    ASSERT_TRUE(d.layers.has_value());
    for (size_t k = 0; k < kLayerAttributeCount; ++k) {
        EXPECT_EQ(d.layers->byAttribute[k].all.error.count, g.layers->byAttribute[k].all.error.count) << names[k];
        EXPECT_NEAR(d.layers->byAttribute[k].all.error.mean, g.layers->byAttribute[k].all.error.mean, 1e-12) << names[k];
    }

    // The host decode on the CPU codec fills the layer images as the decode pass does.
    RenderSettings onCpu = rs;
    onCpu.decodeOnCpu = true;
    const RenderOutput ue4Cpu = renderer.render(generateWiring(loadLayout("ue4")), onCpu);
    const RenderOutput refCpu = renderer.render(makeReferenceWiring(), onCpu);
    ASSERT_TRUE(refCpu.surfaces.hasLayers());
    const RunMetrics cc = computeRunMetrics(refCpu.surfaces, ue4Cpu.surfaces, ref.hdr, ue4.hdr, exposure, cpuOptions);
    ASSERT_TRUE(cc.layers.has_value());
    for (size_t k = 0; k < kLayerAttributeCount; ++k) {
        EXPECT_EQ(cc.layers->byAttribute[k].all.error.count, c.layers->byAttribute[k].all.error.count) << names[k];
        EXPECT_NEAR(cc.layers->byAttribute[k].all.error.mean, c.layers->byAttribute[k].all.error.mean,
                    1e-5 * std::max(1.0, c.layers->byAttribute[k].all.error.mean))
            << names[k];
    }
}

TEST_F(GpuEvaluatorLayersTest, ASceneWithoutLayersMeasuresNone) {
    const std::vector<RenderOutput> o =
        test::renderDefaultScene(test::decodedFrame(64, 36), {makeReferenceWiring(), generateWiring(loadLayout("ue4"))});
    EXPECT_FALSE(o[0].surfaces.hasLayers());
    const RunMetrics c = computeRunMetrics(o[0].surfaces, o[1].surfaces, o[0].hdr, o[1].hdr, 1.0f);
    EXPECT_FALSE(c.layers.has_value());
    EXPECT_FALSE(c.image.layerClasses.has_value());
    UploadedRender r(ctx(), o[0].hdr, &o[0].surfaces), t(ctx(), o[1].hdr, &o[1].surfaces);
    GpuEvaluator evaluator(ctx(), 64, 36);
    evaluator.setReference(r.view(), 1.0f);
    GpuEvalOptions options;
    options.hdrFlip = false;
    const RunMetrics g = evaluator.evaluate(t.view(), options);
    EXPECT_FALSE(g.layers.has_value());
    EXPECT_FALSE(g.image.layerClasses.has_value());
}

}  // namespace
}  // namespace gbl
