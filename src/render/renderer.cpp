#include "renderer.h"

#include "sheen_albedo.h"

#include "cpu_decode.h"
#include "decode_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "error.h"
#include "host_profile.h"
#include "memory_budget.h"
#include "ibl_cache.h"
#include "parallel_invoke.h"
#include "renderer_passes.h"
#include "sheen_albedo.h"
#include "stage_clock.h"
#include "warm_up_times.h"
#include "wiring_plan.h"

namespace gbl {


void validateResolution(const VulkanContext& ctx, uint32_t width, uint32_t height, const std::string& flag,
                        uint32_t bandRows, const std::string& advice) {
    const uint32_t maxDim = ctx.properties.limits.maxImageDimension2D;
    if (width == 0 || height == 0)
        throwUserError(flag + " " + std::to_string(width) + "x" + std::to_string(height) +
                       ": width and height must be at least 1 (e.g. 1920x1080)");
    if (width > maxDim || height > maxDim)
        throwUserError(flag + " " + std::to_string(width) + "x" + std::to_string(height) + ": the device '" +
                       ctx.info.name + "' allows at most " + std::to_string(maxDim) + " pixels per side");
    requireRenderMemory(width, height, bandRows, flag, advice);
}

void requireRenderMemory(uint32_t width, uint32_t height, uint32_t bandRows, const std::string& flag,
                         const std::string& advice) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    requireMemory(renderMemoryBytes(width, height, bandRows),
                  flag + " " + size + (bandRows ? " in bands of " + std::to_string(bandRows) + " rows" : ""),
                  bandRows ? "give a smaller --size" : advice);
}

RenderBand renderBand(const RenderSettings& settings) {
    RenderBand b;
    const uint32_t h = settings.height;
    if (settings.bandRows == 0) {
        b.rows = b.rasterRows = h;
        return b;
    }
    if (settings.bandFirstRow >= h || settings.bandRows > h - settings.bandFirstRow)
        throwUserError("band of rows " + std::to_string(settings.bandFirstRow) + ".." +
                       std::to_string(uint64_t(settings.bandFirstRow) + settings.bandRows) +
                       ": outside the frame's " + std::to_string(h) + " rows");
    // The ground truth's batch count follows its mean noise over the frame (GroundTruthStats): a
    // band's would follow the band's, another image.
    if (settings.specularIbl == IblMode::GroundTruth)
        throwUserError("band of rows " + std::to_string(settings.bandFirstRow) +
                       "..: the ground truth converges over the whole frame; render it whole");
    b.first = settings.bandFirstRow;
    b.rows = settings.bandRows;
    // A halo of one row each side: checkerboard chroma (color_encodings.glsl reconstructChroma)
    // reads the 4 direct neighbours of a pixel. The G-buffer's images are the frame's (its pass
    // draws only these rows), not band-sized ones behind a viewport shifted by the band's first
    // row: llvmpipe's attribute interpolation (plane equations from the window coordinates)
    // rounds differently then, and depth, G-buffer codes and HDR values came out up to a few
    // ulps (a code or a checkerboard edge decision: more) off the whole frame's.
    b.rasterFirst = b.first == 0 ? 0u : b.first - 1;
    b.rasterRows = std::min(h, b.first + b.rows + 1) - b.rasterFirst;
    return b;
}

CameraMatrices computeCameraMatrices(const Camera& camera, float aspect, bool reversedZ) {
    CameraMatrices m;
    m.view = glm::lookAt(camera.position, camera.target, camera.up);
    m.proj = glm::perspective(camera.yFovRadians, aspect, camera.zNear, camera.zFar);
    m.proj[1][1] *= -1.0f;  // Vulkan's framebuffer y points down: keep row 0 at the top of the image
    if (reversedZ) {
        glm::mat4 flipDepth(1.0f);  // z' = w - z: near -> 1, far -> 0
        flipDepth[2][2] = -1.0f;
        flipDepth[3][2] = 1.0f;
        m.proj = flipDepth * m.proj;
    }
    m.viewProj = m.proj * m.view;
    m.invViewProj = glm::inverse(m.viewProj);
    return m;
}

void applyJitter(CameraMatrices& m, float dx, float dy, uint32_t width, uint32_t height) {
    // NDC spans 2 over the frame; clip w = -z_view (proj[2][3] = -1), so adding -offset to the
    // z column adds offset x w to clip x / y. Framebuffer y is NDC y here (the flip is in proj).
    m.proj[2][0] -= 2.0f * dx / float(width);
    m.proj[2][1] -= 2.0f * dy / float(height);
    m.viewProj = m.proj * m.view;
    m.invViewProj = glm::inverse(m.viewProj);
}

Renderer::Renderer(const VulkanContext& ctx, const Scene& scene, const EnvironmentMap& environment)
    : ctx_(ctx), scene_(scene), pipelines_(ownPipelines_) {
    ScopedStage timed(Stage::Precompute);
    init(environment, loadOrComputeIbl(ctx, environment, IblSettings{}));
}

Renderer::Renderer(const VulkanContext& ctx, const Scene& scene, const EnvironmentMap& environment,
                   const IblMaps& ibl, PipelineMemo* sharedPipelines)
    : ctx_(ctx), scene_(scene), pipelines_(sharedPipelines ? *sharedPipelines : ownPipelines_) {
    ScopedStage timed(Stage::Precompute);
    init(environment, ibl);
}

void Renderer::init(const EnvironmentMap& environment, const IblMaps& ibl) {
    ibl_ = createIblGpu(ctx_, environment, ibl);
    gpuScene_ = uploadScene(ctx_, scene_);
    const Image& env = environment.image;
    std::vector<float> rgba(size_t(env.width) * env.height * 4, 1.0f);
    for (size_t i = 0; i < env.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = env.pixels[i * env.channels + c];
    ImageDesc d;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = uint32_t(env.width);
    d.height = uint32_t(env.height);
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    environmentTexture_ = createImage(ctx_, d);
    uploadImage(ctx_, environmentTexture_, rgba.data(), rgba.size() * sizeof(float),
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
    environmentSampler_ = createSampler(ctx_, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                        VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    nearestSampler_ = createSampler(ctx_, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                    VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    // The sheen's albedo table (lighting_pass.comp.glsl binding 12): built (once per process) only
    // for a scene with sheen; otherwise a 1 x 1 zero that no pass reads.
    {
        ImageDesc t;
        t.format = VK_FORMAT_R32_SFLOAT;
        t.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        const float zero = 0.0f;
        const float* texels = &zero;
        t.width = t.height = 1;
        if (gpuScene_.layers & kLayerSheen) {
            const shading::SheenAlbedoTable& table = shading::sheenAlbedoTable();
            t.width = t.height = uint32_t(table.size);
            texels = table.values.data();
        }
        sheenAlbedo_ = createImage(ctx_, t);
        uploadImage(ctx_, sheenAlbedo_, texels, VkDeviceSize(t.width) * t.height * sizeof(float),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
    }
    codecTables_.codecTables = createCodecTablesBuffer(ctx_);
    // The binding is in every G-buffer pass's set layout; a shader without best-fit normals never
    // reads it, so any valid buffer serves.
    const uint32_t zeros[4] = {};
    bestFitPlaceholder_ = createBufferWithData(ctx_, zeros, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

CodecTableBuffers Renderer::tablesFor(const GBufferWiring& wiring) {
    if (!wiring.bestFitTable) return {bestFitPlaceholder_, codecTables_.codecTables};
    std::lock_guard lock(tablesMutex_);
    if (!codecTables_.bestFitTable.buffer) codecTables_.bestFitTable = createBestFitTableBuffer(ctx_);
    return codecTables_;
}

Renderer::~Renderer() {
    vkDeviceWaitIdle(ctx_.device);
    destroyGpuScene(ctx_, gpuScene_);
    destroyImage(ctx_, environmentTexture_);
    destroyImage(ctx_, sheenAlbedo_);
    destroyIblGpu(ctx_, ibl_);
    vkDestroySampler(ctx_.device, environmentSampler_, nullptr);
    vkDestroySampler(ctx_.device, nearestSampler_, nullptr);
    destroyCodecTableBuffers(ctx_, codecTables_);
    destroyBuffer(ctx_, bestFitPlaceholder_);
    ownPipelines_.destroy(ctx_.device);  // a shared memo is its owner's to destroy
}

bool Renderer::decodesOnCpu(const GBufferWiring& wiring, const RenderSettings& settings) {
    // A band keeps the decode pass: the codec decodes whole frames (checkerboard chroma reads the
    // rows beyond a band's edge, and pixel-dependent decodes need the frame's row).
    return settings.decodeSurfaces && settings.decodeOnCpu && !settings.keepOnDevice && settings.bandRows == 0 &&
           wiring.cpuDecoder != nullptr;
}

void Renderer::preparePipelines(const std::vector<GBufferWiring>& wirings, const RenderSettings& settings,
                                 const std::vector<IblMode>& iblModes) {
    const int fresnelMode = settings.fresnelMode;
    ScopedStage timed(Stage::ShaderCompile);
    std::vector<GBufferWiring> materials(wirings.size());
    std::vector<std::function<void()>> tasks;
    // One mode: its specialised lighting pipelines; several: one generic pipeline per wiring
    // serves them all (LightingVariant), and later renders build the same.
    specialiseLighting_ = iblModes.size() <= 1;
    const std::vector<IblMode> lightingModes =
        specialiseLighting_ ? iblModes : std::vector<IblMode>{iblModes.front()};
    for (size_t i = 0; i < wirings.size(); ++i) {
        tasks.push_back([&, i] { gbufferPassPipeline(ctx_, wirings[i], gpuScene_, pipelines_); });
        if (wirings[i].materialPass) {
            materials[i] = materialPassWiring(wirings[i]);
            tasks.push_back([&, i] { gbufferPassPipeline(ctx_, materials[i], gpuScene_, pipelines_); });
        }
        const TargetReadScene readScene = targetReadScene(ctx_, wirings[i], gpuScene_);
        for (IblMode mode : lightingModes)
            tasks.push_back([&, i, readScene, mode] {
                lightingPassPipeline(ctx_, wirings[i], readScene,
                                     LightingVariant{mode, fresnelMode, settings.brdf, specialiseLighting_}, pipelines_);
            });
        if (settings.decodeSurfaces && !decodesOnCpu(wirings[i], settings))  // no pipeline a render does not use
            tasks.push_back([&, i, readScene] {
                decodePassPipeline(ctx_, wirings[i], readScene, pipelines_, settings.keepOnDevice);
            });
    }
    for (auto& task : tasks)
        task = [run = std::move(task)] {
            try {
                run();
            } catch (const std::exception&) {
                // left for render(), which reports it as that run's failure
            }
        };
    parallelInvoke(tasks);
}

}  // namespace gbl
