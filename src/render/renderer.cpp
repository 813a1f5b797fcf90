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

namespace {

// An RGBA32F image read back straight into an Image: one copy out of the staging buffer's memory
// (downloadImageWith), no zero-filled byte vector and pixel vector in between.
Image downloadRgba32f(const VulkanContext& ctx, const GpuImage& image, VkImageLayout layout, uint32_t firstRow = 0,
                      uint32_t rowCount = 0) {
    Image out;
    out.width = int(image.extent.width);
    out.height = int(rowCount ? rowCount : image.extent.height);
    out.channels = 4;
    downloadImageWith(
        ctx, image, layout,
        [&](const uint8_t* bytes, size_t size) {
            if (size != out.pixelCount() * 16) throw std::logic_error("downloadRgba32f: not an RGBA32F image");
            const float* f = reinterpret_cast<const float*>(bytes);  // mapped memory: aligned for any texel
            out.pixels.assign(f, f + size / 4);
        },
        0, 0, firstRow, rowCount);
    return out;
}

// A target's raw words (texelsToWords' layout: texels of 4 bytes or more as they are, 1- and
// 2-byte texels widened to a word each) straight from the staging buffer's memory.
std::vector<uint32_t> downloadWords(const VulkanContext& ctx, const GpuImage& image, size_t pixels, uint32_t firstRow = 0,
                                    uint32_t rowCount = 0) {
    std::vector<uint32_t> words;
    downloadImageWith(
        ctx, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
        [&](const uint8_t* bytes, size_t size) {
            if (pixels && size % pixels == 0 && size / pixels >= 4 && (size / pixels) % 4 == 0) {
                const uint32_t* w = reinterpret_cast<const uint32_t*>(bytes);
                words.assign(w, w + size / 4);
            } else {
                words = texelsToWords(std::vector<uint8_t>(bytes, bytes + size), pixels);
            }
        },
        0, 0, firstRow, rowCount);
    return words;
}

}  // namespace

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
                                     LightingVariant{mode, fresnelMode, specialiseLighting_}, pipelines_);
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

RenderOutput Renderer::render(const GBufferWiring& wiring, const RenderSettings& settings) {
    ScopedStage timedRender(Stage::Render);  // pass set-up and the frame; compiles and read-back nest
    validateResolution(ctx_, settings.width, settings.height, "--size", settings.bandRows);
    if (wiring.visibilityBuffer) checkVisibilityBufferSupport(ctx_, wiring, gpuScene_);
    const uint32_t w = settings.width, h = settings.height;
    const RenderBand band = renderBand(settings);
    const uint32_t rows = band.rows;  // of every output
    const Camera& camera = settings.camera ? *settings.camera : scene_.camera;
    CameraMatrices cam = computeCameraMatrices(camera, float(w) / float(h), wiring.reversedZ);
    if (settings.jitterX != 0.0f || settings.jitterY != 0.0f) applyJitter(cam, settings.jitterX, settings.jitterY, w, h);
    gpu::FrameConstants frame{};
    frame.view = cam.view;
    frame.proj = cam.proj;
    frame.viewProj = cam.viewProj;
    frame.invViewProj = cam.invViewProj;
    frame.cameraPosition = glm::vec4(camera.position, 1.0f);
    frame.extent = glm::uvec4(w, h, gpuScene_.lightCount, wiring.reversedZ ? 1u : 0u);
    if (settings.groundTruthSamples < 1 || settings.splitSumShaderSamples < 1)
        throwUserError("--ibl-samples " + std::to_string(std::min(settings.groundTruthSamples, settings.splitSumShaderSamples)) +
                       ": must be at least 1");
    frame.environment = glm::vec4(settings.environmentIntensity, float(ibl_.prefilteredMips),
                                  float(int(settings.specularIbl)), settings.diffuseIbl ? 1.0f : 0.0f);
    const int iblSamples = settings.specularIbl == IblMode::GroundTruth ? settings.groundTruthSamples
                                                                         : settings.splitSumShaderSamples;
    frame.ibl = glm::vec4(float(iblSamples), float(ibl_.sourceFaceSize), float(settings.groundTruthSeed), 0.0f);
    for (int k = 0; k < 9; ++k) frame.irradianceSh[k] = glm::vec4(ibl_.irradianceSh[k], 0.0f);
    frame.shading = glm::vec4(float(settings.fresnelMode), wiring.reversedZ ? 0.0f : 1.0f, 0.0f, 0.0f);
    frame.band = glm::uvec4(band.first, band.rows, settings.frameIndex, 0u);
    // Every pipeline this render needs, first (from the memo, or built now): a shader that does not
    // compile fails the render before anything is allocated for it.
    gbufferPassPipeline(ctx_, wiring, gpuScene_, pipelines_);
    if (wiring.materialPass) gbufferPassPipeline(ctx_, materialPassWiring(wiring), gpuScene_, pipelines_);
    const TargetReadScene readScene = targetReadScene(ctx_, wiring, gpuScene_);
    const LightingVariant variant{settings.specularIbl, settings.fresnelMode, specialiseLighting_};
    lightingPassPipeline(ctx_, wiring, readScene, variant, pipelines_);
    const bool cpuDecode = decodesOnCpu(wiring, settings);
    if (settings.decodeSurfaces && !cpuDecode)
        decodePassPipeline(ctx_, wiring, readScene, pipelines_, settings.keepOnDevice);
    Buffer frameBuffer = createBufferWithData(ctx_, &frame, sizeof(frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);

    GBufferPass gbuffer =
        createGBufferPass(ctx_, wiring, gpuScene_, frameBuffer, w, h, pipelines_, tablesFor(wiring));
    gbuffer.renderFirstRow = band.rasterFirst;
    gbuffer.renderRows = settings.bandRows ? band.rasterRows : 0;
    // Deferred lighting: the second geometry pass writes the material attributes the slim
    // G-buffer leaves out, at full precision (the same generated GLSL, MATERIAL_PASS_WRITE).
    GBufferPass materialPass;
    if (wiring.materialPass) {
        const GBufferWiring materialWiring = materialPassWiring(wiring);
        materialPass = createGBufferPass(ctx_, materialWiring, gpuScene_, frameBuffer, w, h, pipelines_,
                                         tablesFor(materialWiring));
        materialPass.renderFirstRow = band.rasterFirst;
        materialPass.renderRows = settings.bandRows ? band.rasterRows : 0;
    }
    const GBufferPass* material = wiring.materialPass ? &materialPass : nullptr;
    // Deferred lighting: the light buffers, as the words their formats hold.
    Buffer lightBuffers;
    if (wiring.lightBufferWordsPerPixel > 0)
        lightBuffers = createBuffer(ctx_, VkDeviceSize(w) * rows * uint32_t(wiring.lightBufferWordsPerPixel) * 4,
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, settings.readTargetWords);
    const bool groundTruth = settings.specularIbl == IblMode::GroundTruth;
    LightingInputs inputs{&frameBuffer, &gpuScene_.lights, &gbuffer, &environmentTexture_, environmentSampler_,
                          nearestSampler_, &ibl_, &sheenAlbedo_, material,
                          lightBuffers.buffer ? &lightBuffers : nullptr, groundTruth, variant};
    LightingPass lighting = createLightingPass(ctx_, wiring, inputs, w, rows, pipelines_);
    if (gbuffer.needsWarmUp || (material && material->needsWarmUp) || lighting.needsWarmUp) {
        // New pipelines: one draw clipped to a pixel and one workgroup each, so that a driver that
        // compiles at first use (llvmpipe JIT-compiles a shader variant at its first draw or
        // dispatch, keyed by the bound formats and samplers, hence with the frame's own resources)
        // does it here, timed as shader compile, and the frame below times the frame alone.
        // One submission per pass, each timed as its pass kind's warm-up (gpu/warm_up_times.h:
        // which shaders a first run's compile is spent on). A pass whose pipeline was warmed
        // before still runs (it leaves the targets in the layout the next pass reads them in),
        // uncounted.
        ScopedStage timedCompile(Stage::ShaderCompile);
        const std::string of = " (layout " + wiring.layoutName + ")";
        {
            ScopedWarmUp timed("gbuffer", "gbuffer" + of, gbuffer.needsWarmUp);
            ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordGBufferWarmUp(cmd, gbuffer, gpuScene_); });
        }
        if (material) {
            ScopedWarmUp timed("material", "material" + of, material->needsWarmUp);
            ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordGBufferWarmUp(cmd, *material, gpuScene_); });
        }
        ScopedWarmUp timed("lighting", "lighting (layout " + wiring.layoutName + ", " + iblModeName(settings.specularIbl) + ")",
                           lighting.needsWarmUp);
        ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordLightingWarmUp(cmd, lighting); });
    }

    const std::vector<double> passMs = submitTimedSegments(
        ctx_, {[&](VkCommandBuffer cmd) {
                   recordGBufferPass(cmd, gbuffer, gpuScene_);
                   if (material) recordGBufferPass(cmd, *material, gpuScene_);  // timed with the geometry passes
               },
               [&](VkCommandBuffer cmd) { recordLightingPass(cmd, lighting, 0); }});
    RenderOutput out;
    out.timings.gbufferMs = passMs[0];
    out.timings.lightingMs = passMs[1];
    auto readHdr = [&] {
        HostScope scope("read-back: HDR image");
        out.hdr = downloadRgba32f(ctx_, lighting.hdr, VK_IMAGE_LAYOUT_GENERAL);
    };
    if (groundTruth) {
        // Progressive: more batches until the noise target is met (or the batch limit is reached).
        if (settings.groundTruthMinBatches < 2 || settings.groundTruthMaxBatches < settings.groundTruthMinBatches ||
            !(settings.groundTruthNoiseTarget > 0.0))
            throwUserError("ground truth: needs at least 2 batches, max >= min, and a noise target > 0");
        GroundTruthStats& gt = out.groundTruth;
        gt.targetRelativeNoise = settings.groundTruthNoiseTarget;
        gt.lightingMs = passMs[1];
        int done = 1;
        int next = settings.groundTruthMinBatches;
        for (;;) {
            if (next > done) {
                std::vector<std::function<void(VkCommandBuffer)>> segment = {[&, from = done, to = next](VkCommandBuffer cmd) {
                    for (int b = from; b < to; ++b) recordLightingPass(cmd, lighting, uint32_t(b));
                }};
                gt.lightingMs += submitTimedSegments(ctx_, segment)[0];
                done = next;
            }
            ScopedStage timedReadback(Stage::Readback);
            readHdr();
            const std::vector<uint8_t> accBytes = downloadImage(ctx_, lighting.accumulation, VK_IMAGE_LAYOUT_GENERAL);
            const float* acc = reinterpret_cast<const float*>(accBytes.data());
            out.noise = Image(int(w), int(rows), 1);
            for (size_t i = 0; i < out.noise.pixelCount(); ++i) {
                if (out.hdr.pixels[i * 4 + 3] < 0.5f) continue;
                const double m2 = std::max(0.0, double(acc[i * 4 + 3]));
                out.noise.pixels[i] = float(std::sqrt(m2 / (double(done) * double(done - 1))));
            }
            gt.batches = done;
            gt.meanRelativeNoise = meanRelativeNoise(out.hdr, out.noise);
            gt.targetMet = gt.meanRelativeNoise <= settings.groundTruthNoiseTarget;
            if (gt.targetMet || done >= settings.groundTruthMaxBatches) break;
            // Noise ~ 1 / sqrt(batches): aim 10% past the batches the target needs.
            const double ratio = gt.meanRelativeNoise / settings.groundTruthNoiseTarget;
            const double needed = std::ceil(double(done) * ratio * ratio * 1.1);
            next = int(std::clamp(needed, double(done + 1), double(settings.groundTruthMaxBatches)));
        }
        gt.samplesPerPixel = gt.batches * settings.groundTruthSamples * 2;
        out.timings.lightingMs = gt.lightingMs;
    }

    ScopedStage timedReadback(Stage::Readback);
    if (settings.keepOnDevice) {
        out.device = std::make_shared<DeviceRenderImages>(ctx_);
        out.device->hdr = lighting.hdr;  // moved out: destroyLightingPass leaves it alone
        lighting.hdr = GpuImage{};
    } else if (!groundTruth) {
        readHdr();
    }
    // Free what the decode does not read before it allocates (peak memory at 4K).
    destroyLightingPass(ctx_, lighting);
    if (lightBuffers.buffer) {
        if (settings.readTargetWords) {
            out.lightBufferWords.resize(size_t(w) * rows * size_t(wiring.lightBufferWordsPerPixel));
            std::memcpy(out.lightBufferWords.data(), lightBuffers.mapped, out.lightBufferWords.size() * 4);
        }
        destroyBuffer(ctx_, lightBuffers);
    }
    std::optional<HostScope> wordsScope(std::in_place, "read-back: G-buffer words, depth (and a decode pass)");
    for (const GpuImage& t : gbuffer.targets) {
        if (!settings.readTargetWords && !cpuDecode && !settings.onTargetWords) break;
        out.targetWords.push_back(downloadWords(ctx_, t, size_t(w) * rows, band.first, band.rows));  // R8 / R16 widened
    }
    if (settings.onTargetWords) {
        wordsScope.reset();
        HostScope scope("read-back: G-buffer words to the compression model");
        for (size_t i = 0; i < out.targetWords.size(); ++i) settings.onTargetWords(i, band.first, band.rows, out.targetWords[i]);
        if (!settings.readTargetWords && !cpuDecode) out.targetWords.clear();
        wordsScope.emplace("read-back: G-buffer words, depth (and a decode pass)");
    }
    if (settings.keepOnDevice) {
        if (settings.decodeSurfaces) {
            const std::array<GpuImage, 8> images =
                decodeSurfacesOnDevice(ctx_, wiring, gbuffer, frameBuffer, nearestSampler_, material, rows, pipelines_);
            std::copy(images.begin(), images.begin() + 4, out.device->surfaces.begin());
            std::copy(images.begin() + 4, images.end(), out.device->layers.begin());
        }
        if (material) destroyGBufferPass(ctx_, materialPass);
        destroyGBufferPass(ctx_, gbuffer);
        destroyBuffer(ctx_, frameBuffer);
        return out;
    }
    out.depth.resize(size_t(w) * rows);
    // Converted straight from the staging buffer's memory (downloadImageWith).
    downloadImageWith(
        ctx_, gbuffer.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
        [&](const uint8_t* depthBytes, size_t size) {
            const size_t n = out.depth.size();
            const size_t texel = wiring.depthFormat == VK_FORMAT_D16_UNORM ? 2 : 4;
            if (size != n * texel) throw std::logic_error("render: depth read-back of unexpected size");
            if (wiring.depthFormat == VK_FORMAT_D32_SFLOAT || wiring.depthFormat == VK_FORMAT_D32_SFLOAT_S8_UINT) {
                std::memcpy(out.depth.data(), depthBytes, n * 4);
            } else if (wiring.depthFormat == VK_FORMAT_D16_UNORM) {
                for (size_t i = 0; i < n; ++i) {
                    uint16_t v;
                    std::memcpy(&v, depthBytes + i * 2, 2);
                    out.depth[i] = float(v) / 65535.0f;
                }
            } else {  // D24: 24 bits in the low bits of a 32-bit word
                for (size_t i = 0; i < n; ++i) {
                    uint32_t v;
                    std::memcpy(&v, depthBytes + i * 4, 4);
                    out.depth[i] = float(double(v & 0xFFFFFFu) / 16777215.0);
                }
            }
        },
        0, VK_IMAGE_ASPECT_DEPTH_BIT, band.first, band.rows);
    if (settings.readTargetWords && (gbuffer.depth.aspect & VK_IMAGE_ASPECT_STENCIL_BIT))
        out.stencil = downloadImage(ctx_, gbuffer.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, 0,
                                    VK_IMAGE_ASPECT_STENCIL_BIT, band.first, band.rows);
    if (cpuDecode) {
        // The decode pass's work on the host (RenderSettings::decodeOnCpu): the raw words (read
        // above), the material pass's, then the G-buffer's images are freed before the decode.
        CpuGBuffer words;
        words.width = int(w);
        words.height = int(rows);  // decodesOnCpu: never a band, so rows == h
        words.targetWords = std::move(out.targetWords);
        for (const GpuImage& t : materialPass.targets) words.materialWords.push_back(downloadWords(ctx_, t, size_t(w) * rows));
        if (material) destroyGBufferPass(ctx_, materialPass);
        destroyGBufferPass(ctx_, gbuffer);
        destroyBuffer(ctx_, frameBuffer);
        wordsScope.reset();
        HostScope scope("read-back: decode on the host");
        out.surfaces = decodeSurfacesOnCpu(*wiring.cpuDecoder, words, out.depth, frame, wiring.normalSpace, wiring.depthFormat,
                                           wiring.storesDepth, gpuScene_.layers != 0);
        out.targetWords.clear();
        if (settings.readTargetWords) out.targetWords = std::move(words.targetWords);
        return out;
    }
    if (settings.decodeSurfaces)
        out.surfaces = decodeSurfaces(ctx_, wiring, gbuffer, frameBuffer, nearestSampler_, out.depth, material,
                                      settings.decodeBandRows, pipelines_);
    if (material) destroyGBufferPass(ctx_, materialPass);
    destroyGBufferPass(ctx_, gbuffer);
    destroyBuffer(ctx_, frameBuffer);
    return out;
}

DeviceRenderImages::~DeviceRenderImages() {
    destroyImage(ctx, hdr);
    for (GpuImage& s : surfaces) destroyImage(ctx, s);
    for (GpuImage& l : layers) destroyImage(ctx, l);
}

Image DeviceRenderImages::downloadHdr() const { return downloadRgba32f(ctx, hdr, VK_IMAGE_LAYOUT_GENERAL); }

double meanRelativeNoise(const Image& hdr, const Image& noise) {
    if (noise.empty() || hdr.pixelCount() != noise.pixelCount() || hdr.channels < 4) return 0.0;
    double sum = 0.0;
    size_t finite = 0;
    for (size_t i = 0; i < hdr.pixelCount(); ++i) {
        const float* p = &hdr.pixels[i * size_t(hdr.channels)];
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        if (std::isfinite(y) && y > 0.0) sum += y;
        finite += std::isfinite(y) ? 1 : 0;
    }
    const double floor = std::max(1e-2 * (finite ? sum / double(finite) : 0.0), 1e-6);
    double total = 0.0;
    size_t covered = 0;
    for (size_t i = 0; i < hdr.pixelCount(); ++i) {
        const float* p = &hdr.pixels[i * size_t(hdr.channels)];
        if (p[3] < 0.5f) continue;
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        total += double(noise.pixels[i]) / std::max(std::isfinite(y) ? y : 0.0, floor);
        ++covered;
    }
    return covered ? total / double(covered) : 0.0;
}

}  // namespace gbl
