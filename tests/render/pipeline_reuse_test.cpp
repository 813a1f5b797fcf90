// A Renderer builds each layout's pipelines once (issue 14: compare --views 3 built 92 pipelines
// where 32 do): later renders of the same layout, from another camera, under another prepared IBL
// mode or at another size, create no pipeline, and render exactly what a fresh Renderer renders.
#include <gtest/gtest.h>

#include <cstring>

#include "layout_catalog.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "shader_cache.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class PipelineReuseTest : public test::VulkanTest {};

// The process-wide count of vkCreate*Pipelines calls (vk_pipeline.cpp counts each one), not the
// renderer's own memo: what the driver was asked to build.
int pipelinesCreated() { return shaderCacheCounters().pipelines.load(); }

RenderSettings settingsAt(uint32_t w, uint32_t h, IblMode mode, const std::optional<Camera>& camera) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.specularIbl = mode;
    s.splitSumShaderSamples = 16;
    s.decodeSurfaces = true;  // the decode pass's pipeline too
    s.readTargetWords = false;
    s.camera = camera;
    return s;
}

Camera movedCamera(const Scene& scene) {
    Camera c = scene.camera;
    c.position = scene.camera.position + glm::vec3(1.5f, 0.5f, -0.5f);
    return c;
}

void expectSameImage(const Image& a, const Image& b, const char* what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.height, b.height) << what;
    ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
    EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0) << what;
}

// One renderer builds everything once: preparePipelines builds every pipeline up front (on worker
// threads; with several IBL modes one generic lighting pipeline per layout), then renders of
// those layouts from other cameras, under those IBL modes and at other sizes build none. A wiring
// whose shader does not compile is skipped by preparePipelines and fails in its render, as before. (One test: every new pipeline costs llvmpipe seconds of JIT.)
TEST_F(PipelineReuseTest, ViewsModesAndSizesReuseEachLayoutsPipelines) {
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    const GBufferWiring ue4 = generateWiring(loadLayout("ue4"));
    // Deferred lighting: G-buffer, material pass, lighting, decode.
    const GBufferWiring slim = generateWiring(loadLayout("crysis2-slim"));
    GBufferWiring broken = ue4;
    broken.layoutName = "broken";
    broken.glsl += "\nthis is not GLSL;\n";
    const Camera other = movedCamera(scene);

    Renderer prepared(test::sharedContext(), scene, sky);
    const int before = pipelinesCreated();
    EXPECT_NO_THROW(prepared.preparePipelines({slim, ue4, broken}, settingsAt(96, 64, IblMode::SplitSum, std::nullopt),
                                              {IblMode::SplitSum, IblMode::SplitSumShader}));
    // ue4: G-buffer, lighting (one generic pipeline for the two IBL modes), decode; crysis2-slim
    // adds its material pass; nothing of the broken wiring (its shaders fail to compile).
    EXPECT_EQ(pipelinesCreated() - before, 4 + 3);
    EXPECT_EQ(prepared.pipelineCount(), size_t(4 + 3));
    prepared.render(slim, settingsAt(96, 64, IblMode::SplitSum, std::nullopt));
    prepared.render(slim, settingsAt(96, 64, IblMode::SplitSum, other));
    const RenderOutput slimOther = prepared.render(slim, settingsAt(96, 64, IblMode::SplitSumShader, other));
    prepared.render(slim, settingsAt(80, 48, IblMode::SplitSumShader, scene.camera));
    const RenderOutput ue4Out = prepared.render(ue4, settingsAt(96, 64, IblMode::SplitSum, std::nullopt));
    EXPECT_EQ(pipelinesCreated() - before, 4 + 3) << "a render built a pipeline preparePipelines had built";
    EXPECT_EQ(prepared.pipelineCount(), size_t(4 + 3));
    EXPECT_THROW(prepared.render(broken, settingsAt(96, 64, IblMode::SplitSum, std::nullopt)), ShaderCompileError);

    // Built one by one, at first render: one layout's pipelines, then the other's (different
    // layouts share nothing), and the same images as the prepared, reused ones. These lighting
    // pipelines are specialised for their IBL mode (no preparePipelines of several modes), the
    // prepared ones generic: the same pixels to the bit (renderer_passes.h LightingVariant).
    Renderer oneByOne(test::sharedContext(), scene, sky);
    const RenderOutput slimFresh = oneByOne.render(slim, settingsAt(96, 64, IblMode::SplitSumShader, other));
    EXPECT_EQ(oneByOne.pipelineCount(), 4u);
    const RenderOutput ue4Fresh = oneByOne.render(ue4, settingsAt(96, 64, IblMode::SplitSum, std::nullopt));
    EXPECT_EQ(oneByOne.pipelineCount(), 4u + 3u);
    expectSameImage(slimOther.hdr, slimFresh.hdr, "crysis2-slim, third render vs first");
    expectSameImage(slimOther.surfaces.normal, slimFresh.surfaces.normal, "decoded normals");
    expectSameImage(slimOther.surfaces.baseColor, slimFresh.surfaces.baseColor, "decoded base colour");
    EXPECT_EQ(slimOther.depth, slimFresh.depth);
    expectSameImage(ue4Out.hdr, ue4Fresh.hdr, "ue4 after crysis2-slim vs alone");
}

// Only the pipelines a render uses are built (issue 14: every unused pipeline is llvmpipe JIT
// time). With the read-back on the CPU codec (decodeOnCpu) no decode pass is built for a wiring
// the codec decodes, but still for one it cannot (a visibility buffer); with the surfaces kept on
// the device, the decode pass's to-images variant is built, not the band variant it never runs.
TEST_F(PipelineReuseTest, PreparesNoDecodePassTheRendersDoNotRun) {
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    const GBufferWiring ue4 = generateWiring(loadLayout("ue4"));
    const GBufferWiring slim = generateWiring(loadLayout("crysis2-slim"));
    const GBufferWiring visibility = generateWiring(loadLayout("visibility-32"));
    Renderer renderer(test::sharedContext(), scene, sky);
    RenderSettings cpu = settingsAt(96, 64, IblMode::SplitSum, std::nullopt);
    cpu.decodeOnCpu = true;
    const int before = pipelinesCreated();
    renderer.preparePipelines({slim, ue4, visibility}, cpu, {IblMode::SplitSum});
    // crysis2-slim: G-buffer, material, lighting; ue4: G-buffer, lighting; the visibility
    // buffer: G-buffer, lighting and the decode pass.
    EXPECT_EQ(pipelinesCreated() - before, 3 + 2 + 3);
    RenderSettings device = cpu;
    device.keepOnDevice = true;  // --eval gpu: decodeSurfacesOnDevice's variant, for all three
    renderer.preparePipelines({slim, ue4, visibility}, device, {IblMode::SplitSum});
    EXPECT_EQ(pipelinesCreated() - before, 3 + 2 + 3 + 3);
    RenderSettings bands = cpu;
    bands.decodeOnCpu = false;  // the band variant: new for the two the codec decoded
    renderer.preparePipelines({slim, ue4, visibility}, bands, {IblMode::SplitSum});
    EXPECT_EQ(pipelinesCreated() - before, 3 + 2 + 3 + 3 + 2);
    EXPECT_EQ(renderer.pipelineCount(), size_t(3 + 2 + 3 + 3 + 2));
}

}  // namespace
}  // namespace gbl
