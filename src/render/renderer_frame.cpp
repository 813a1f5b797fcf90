// Renderer::render: one frame of one wiring, as the sequence of its passes (G-buffer, material,
// lighting, the ground truth's further batches, read-back and decode), each a step of one job.
#include "renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "cpu_decode.h"
#include "decode_pass.h"
#include "error.h"
#include "host_profile.h"
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

// What one frame's passes hold from their creation to the read-back: the frame's constants on the
// device, the G-buffer pass, the material pass (deferred lighting's second geometry pass), the
// light buffers (deferred lighting's accumulation, as their formats' words) and the lighting pass.
struct Renderer::FramePasses {
    Buffer frameBuffer;
    GBufferPass gbuffer;
    GBufferPass materialPass;
    bool hasMaterialPass = false;
    Buffer lightBuffers;
    LightingPass lighting;
    const GBufferPass* material() const { return hasMaterialPass ? &materialPass : nullptr; }
};

gpu::FrameConstants Renderer::frameConstants(const GBufferWiring& wiring, const RenderSettings& settings,
                                             const RenderBand& band) const {
    const uint32_t w = settings.width, h = settings.height;
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
    frame.shading = glm::vec4(float(settings.fresnelMode), wiring.reversedZ ? 0.0f : 1.0f, float(settings.brdf), 0.0f);
    frame.band = glm::uvec4(band.first, band.rows, settings.frameIndex, 0u);
    return frame;
}

// Every pipeline this render needs, first (from the memo, or built now): a shader that does not
// compile fails the render before anything is allocated for it.
Renderer::FramePipelines Renderer::framePipelines(const GBufferWiring& wiring, const RenderSettings& settings) {
    gbufferPassPipeline(ctx_, wiring, gpuScene_, pipelines_);
    if (wiring.materialPass) gbufferPassPipeline(ctx_, materialPassWiring(wiring), gpuScene_, pipelines_);
    FramePipelines p{targetReadScene(ctx_, wiring, gpuScene_),
                     LightingVariant{settings.specularIbl, settings.fresnelMode, settings.brdf, specialiseLighting_},
                     decodesOnCpu(wiring, settings)};
    lightingPassPipeline(ctx_, wiring, p.readScene, p.variant, pipelines_);
    if (settings.decodeSurfaces && !p.cpuDecode)
        decodePassPipeline(ctx_, wiring, p.readScene, pipelines_, settings.keepOnDevice);
    return p;
}

void Renderer::createFramePasses(FramePasses& passes, const GBufferWiring& wiring, const RenderSettings& settings,
                                 const RenderBand& band, const gpu::FrameConstants& frame, const FramePipelines& pipes) {
    const uint32_t w = settings.width, h = settings.height, rows = band.rows;
    passes.frameBuffer = createBufferWithData(ctx_, &frame, sizeof(frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    passes.gbuffer = createGBufferPass(ctx_, wiring, gpuScene_, passes.frameBuffer, w, h, pipelines_, tablesFor(wiring));
    passes.gbuffer.renderFirstRow = band.rasterFirst;
    passes.gbuffer.renderRows = settings.bandRows ? band.rasterRows : 0;
    // Deferred lighting: the second geometry pass writes the material attributes the slim
    // G-buffer leaves out, at full precision (the same generated GLSL, MATERIAL_PASS_WRITE).
    if (wiring.materialPass) {
        const GBufferWiring materialWiring = materialPassWiring(wiring);
        passes.materialPass = createGBufferPass(ctx_, materialWiring, gpuScene_, passes.frameBuffer, w, h, pipelines_,
                                                tablesFor(materialWiring));
        passes.materialPass.renderFirstRow = band.rasterFirst;
        passes.materialPass.renderRows = settings.bandRows ? band.rasterRows : 0;
        passes.hasMaterialPass = true;
    }
    // Deferred lighting: the light buffers, as the words their formats hold.
    if (wiring.lightBufferWordsPerPixel > 0)
        passes.lightBuffers =
            createBuffer(ctx_, VkDeviceSize(w) * rows * uint32_t(wiring.lightBufferWordsPerPixel) * 4,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, settings.readTargetWords);
    const bool groundTruth = settings.specularIbl == IblMode::GroundTruth;
    LightingInputs inputs{&passes.frameBuffer, &gpuScene_.lights, &passes.gbuffer, &environmentTexture_,
                          environmentSampler_, nearestSampler_, &ibl_, &sheenAlbedo_, passes.material(),
                          passes.lightBuffers.buffer ? &passes.lightBuffers : nullptr, groundTruth, pipes.variant};
    passes.lighting = createLightingPass(ctx_, wiring, inputs, w, rows, pipelines_);
}

// New pipelines: one draw clipped to a pixel and one workgroup each, so that a driver that
// compiles at first use (llvmpipe JIT-compiles a shader variant at its first draw or dispatch,
// keyed by the bound formats and samplers, hence with the frame's own resources) does it here,
// timed as shader compile, and the frame times the frame alone. One submission per pass, each
// timed as its pass kind's warm-up (gpu/warm_up_times.h: which shaders a first run's compile is
// spent on). A pass whose pipeline was warmed before still runs (it leaves the targets in the
// layout the next pass reads them in), uncounted.
void Renderer::warmUpFramePasses(const GBufferWiring& wiring, const RenderSettings& settings, FramePasses& passes) {
    const GBufferPass* material = passes.material();
    if (!passes.gbuffer.needsWarmUp && !(material && material->needsWarmUp) && !passes.lighting.needsWarmUp) return;
    ScopedStage timedCompile(Stage::ShaderCompile);
    const std::string of = " (layout " + wiring.layoutName + ")";
    {
        ScopedWarmUp timed("gbuffer", "gbuffer" + of, passes.gbuffer.needsWarmUp);
        ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordGBufferWarmUp(cmd, passes.gbuffer, gpuScene_); });
    }
    if (material) {
        ScopedWarmUp timed("material", "material" + of, material->needsWarmUp);
        ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordGBufferWarmUp(cmd, *material, gpuScene_); });
    }
    ScopedWarmUp timed("lighting", "lighting (layout " + wiring.layoutName + ", " + iblModeName(settings.specularIbl) + ")",
                       passes.lighting.needsWarmUp);
    ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordLightingWarmUp(cmd, passes.lighting); });
}

// The frame: the geometry passes, then the lighting pass, each timed (timestamp queries).
PassTimings Renderer::drawFrame(FramePasses& passes) {
    const GBufferPass* material = passes.material();
    const std::vector<double> passMs = submitTimedSegments(
        ctx_, {[&](VkCommandBuffer cmd) {
                   recordGBufferPass(cmd, passes.gbuffer, gpuScene_);
                   if (material) recordGBufferPass(cmd, *material, gpuScene_);  // timed with the geometry passes
               },
               [&](VkCommandBuffer cmd) { recordLightingPass(cmd, passes.lighting, 0); }});
    PassTimings t;
    t.gbufferMs = passMs[0];
    t.lightingMs = passMs[1];
    return t;
}

void Renderer::readHdr(const FramePasses& passes, RenderOutput& out) {
    HostScope scope("read-back: HDR image");
    out.hdr = downloadRgba32f(ctx_, passes.lighting.hdr, VK_IMAGE_LAYOUT_GENERAL);
}

// Progressive: more lighting batches until the mean relative noise meets its target (or the batch
// limit is reached); the HDR image and its per-pixel noise are read back after each round.
void Renderer::convergeGroundTruth(const RenderSettings& settings, FramePasses& passes, RenderOutput& out) {
    if (settings.groundTruthMinBatches < 2 || settings.groundTruthMaxBatches < settings.groundTruthMinBatches ||
        !(settings.groundTruthNoiseTarget > 0.0))
        throwUserError("ground truth: needs at least 2 batches, max >= min, and a noise target > 0");
    GroundTruthStats& gt = out.groundTruth;
    gt.targetRelativeNoise = settings.groundTruthNoiseTarget;
    gt.lightingMs = out.timings.lightingMs;
    int done = 1;
    int next = settings.groundTruthMinBatches;
    for (;;) {
        if (next > done) {
            std::vector<std::function<void(VkCommandBuffer)>> segment = {[&, from = done, to = next](VkCommandBuffer cmd) {
                for (int b = from; b < to; ++b) recordLightingPass(cmd, passes.lighting, uint32_t(b));
            }};
            gt.lightingMs += submitTimedSegments(ctx_, segment)[0];
            done = next;
        }
        ScopedStage timedReadback(Stage::Readback);
        readHdr(passes, out);
        const std::vector<uint8_t> accBytes = downloadImage(ctx_, passes.lighting.accumulation, VK_IMAGE_LAYOUT_GENERAL);
        const float* acc = reinterpret_cast<const float*>(accBytes.data());
        out.noise = Image(out.hdr.width, out.hdr.height, 1);
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

// Deferred lighting's light buffers: their words where asked, then freed.
void Renderer::readLightBufferWords(const GBufferWiring& wiring, const RenderSettings& settings, const RenderBand& band,
                                    FramePasses& passes, RenderOutput& out) {
    if (!passes.lightBuffers.buffer) return;
    if (settings.readTargetWords) {
        out.lightBufferWords.resize(size_t(settings.width) * band.rows * size_t(wiring.lightBufferWordsPerPixel));
        std::memcpy(out.lightBufferWords.data(), passes.lightBuffers.mapped, out.lightBufferWords.size() * 4);
    }
    destroyBuffer(ctx_, passes.lightBuffers);
}

// The G-buffer's words: for the caller, for the host decode, or handed to
// RenderSettings::onTargetWords (the compression model) band by band, timed apart.
void Renderer::readTargetWords(const RenderSettings& settings, const RenderBand& band, bool cpuDecode,
                               const FramePasses& passes, RenderOutput& out, std::optional<HostScope>& wordsScope) {
    for (const GpuImage& t : passes.gbuffer.targets) {
        if (!settings.readTargetWords && !cpuDecode && !settings.onTargetWords) break;
        out.targetWords.push_back(downloadWords(ctx_, t, size_t(settings.width) * band.rows, band.first, band.rows));  // R8 / R16 widened
    }
    if (settings.onTargetWords) {
        wordsScope.reset();
        HostScope scope("read-back: G-buffer words to the compression model");
        for (size_t i = 0; i < out.targetWords.size(); ++i) settings.onTargetWords(i, band.first, band.rows, out.targetWords[i]);
        if (!settings.readTargetWords && !cpuDecode) out.targetWords.clear();
        wordsScope.emplace("read-back: G-buffer words, depth (and a decode pass)");
    }
}

// The depth buffer as floats in [0, 1], converted straight from the staging buffer's memory
// (downloadImageWith); and the stencil where the words are asked for.
void Renderer::readDepth(const GBufferWiring& wiring, const RenderSettings& settings, const RenderBand& band,
                         const FramePasses& passes, RenderOutput& out) {
    out.depth.resize(size_t(settings.width) * band.rows);
    downloadImageWith(
        ctx_, passes.gbuffer.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
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
    if (settings.readTargetWords && (passes.gbuffer.depth.aspect & VK_IMAGE_ASPECT_STENCIL_BIT))
        out.stencil = downloadImage(ctx_, passes.gbuffer.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, 0,
                                    VK_IMAGE_ASPECT_STENCIL_BIT, band.first, band.rows);
}

void Renderer::destroyGeometryPasses(FramePasses& passes) {
    if (passes.hasMaterialPass) destroyGBufferPass(ctx_, passes.materialPass);
    destroyGBufferPass(ctx_, passes.gbuffer);
    destroyBuffer(ctx_, passes.frameBuffer);
}

// The decode pass's work on the host (RenderSettings::decodeOnCpu): the raw words (read before),
// the material pass's, then the G-buffer's images are freed before the decode.
void Renderer::decodeOnHost(const GBufferWiring& wiring, const RenderSettings& settings, const gpu::FrameConstants& frame,
                            FramePasses& passes, RenderOutput& out, std::optional<HostScope>& wordsScope) {
    CpuGBuffer words;
    words.width = int(settings.width);
    words.height = int(settings.height);  // decodesOnCpu: never a band
    words.targetWords = std::move(out.targetWords);
    for (const GpuImage& t : passes.materialPass.targets)
        words.materialWords.push_back(downloadWords(ctx_, t, size_t(settings.width) * settings.height));
    destroyGeometryPasses(passes);
    wordsScope.reset();
    HostScope scope("read-back: decode on the host");
    out.surfaces = decodeSurfacesOnCpu(*wiring.cpuDecoder, words, out.depth, frame, wiring.normalSpace, wiring.depthFormat,
                                       wiring.storesDepth, gpuScene_.layers != 0);
    out.targetWords.clear();
    if (settings.readTargetWords) out.targetWords = std::move(words.targetWords);
}

RenderOutput Renderer::render(const GBufferWiring& wiring, const RenderSettings& settings) {
    ScopedStage timedRender(Stage::Render);  // pass set-up and the frame; compiles and read-back nest
    validateResolution(ctx_, settings.width, settings.height, "--size", settings.bandRows);
    if (wiring.visibilityBuffer) checkVisibilityBufferSupport(ctx_, wiring, gpuScene_);
    const RenderBand band = renderBand(settings);
    const gpu::FrameConstants frame = frameConstants(wiring, settings, band);
    const FramePipelines pipes = framePipelines(wiring, settings);
    FramePasses passes;
    createFramePasses(passes, wiring, settings, band, frame, pipes);
    warmUpFramePasses(wiring, settings, passes);
    RenderOutput out;
    out.timings = drawFrame(passes);
    const bool groundTruth = settings.specularIbl == IblMode::GroundTruth;
    if (groundTruth) convergeGroundTruth(settings, passes, out);

    ScopedStage timedReadback(Stage::Readback);
    if (settings.keepOnDevice) {
        out.device = std::make_shared<DeviceRenderImages>(ctx_);
        out.device->hdr = passes.lighting.hdr;  // moved out: destroyLightingPass leaves it alone
        passes.lighting.hdr = GpuImage{};
    } else if (!groundTruth) {
        readHdr(passes, out);
    }
    // Free what the decode does not read before it allocates (peak memory at 4K).
    destroyLightingPass(ctx_, passes.lighting);
    readLightBufferWords(wiring, settings, band, passes, out);
    std::optional<HostScope> wordsScope(std::in_place, "read-back: G-buffer words, depth (and a decode pass)");
    readTargetWords(settings, band, pipes.cpuDecode, passes, out, wordsScope);
    if (settings.keepOnDevice) {
        if (settings.decodeSurfaces) {
            const std::array<GpuImage, 8> images = decodeSurfacesOnDevice(
                ctx_, wiring, passes.gbuffer, passes.frameBuffer, nearestSampler_, passes.material(), band.rows, pipelines_);
            std::copy(images.begin(), images.begin() + 4, out.device->surfaces.begin());
            std::copy(images.begin() + 4, images.end(), out.device->layers.begin());
        }
        destroyGeometryPasses(passes);
        return out;
    }
    readDepth(wiring, settings, band, passes, out);
    if (pipes.cpuDecode) {
        decodeOnHost(wiring, settings, frame, passes, out, wordsScope);
        return out;
    }
    if (settings.decodeSurfaces)
        out.surfaces = decodeSurfaces(ctx_, wiring, passes.gbuffer, passes.frameBuffer, nearestSampler_, out.depth,
                                      passes.material(), settings.decodeBandRows, pipelines_);
    destroyGeometryPasses(passes);
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
