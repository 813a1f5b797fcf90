#pragma once
// Renders one scene, under one environment, through any G-buffer wiring: the G-buffer raster
// pass, then the lighting compute pass, timed with timestamp queries, then read back.
#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "environment_map.h"
#include "gbuffer_wiring.h"
#include "gpu_scene.h"
#include "ibl_precompute.h"
#include "image.h"
#include "pipeline_memo.h"
#include "renderer_passes.h"
#include "scene.h"
#include "surface_images.h"

namespace gbl {

struct RenderBand;
class HostScope;

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    int fresnelMode = 1;              // brdf.glsl FRESNEL_* (1 = Karis' exp2 form, UE4's)
    int brdf = 0;                     // brdf.glsl BRDF_* of the direct lights (0 UE4's, 1 the glTF specification's)
    float environmentIntensity = 1.0f;
    // Image-based light (ibl_precompute.h): the specular approximation, and the samples per pixel
    // of the two in-shader modes (ground-truth, split-sum-shader). Diffuse IBL (SH9 irradiance)
    // applies to every mode unless diffuseIbl is off.
    IblMode specularIbl = IblMode::SplitSum;
    // Ground truth: batches of groundTruthSamples steps per pixel (each step one GGX and one
    // environment sample, combined by MIS: ibl_math.glsl specularIBLGroundTruthMis), run until the
    // mean relative noise over covered pixels (GroundTruthStats) is at most groundTruthNoiseTarget,
    // with at least groundTruthMinBatches (the noise estimate needs a few) and at most
    // groundTruthMaxBatches.
    int groundTruthSamples = 64;
    int splitSumShaderSamples = 1024;  // samples per pixel of split-sum-shader (the seed's NumSamples)
    double groundTruthNoiseTarget = 0.002;
    int groundTruthMinBatches = 8;
    int groundTruthMaxBatches = 256;
    int groundTruthSeed = 0;  // another seed, other random rotations (an independent estimate); < 256
    bool diffuseIbl = true;
    // Also run the layout's readGBuffer() over every pixel and return the Surface as floats
    // (RenderOutput::surfaces): what attribute errors are measured on.
    bool decodeSurfaces = false;
    // Copy each target's raw words to RenderOutput::targetWords (bit tests need them; compare
    // only needs the decoded surfaces, and skipping the copy saves up to 80 bytes per pixel).
    bool readTargetWords = true;
    // Keep the HDR image and (with decodeSurfaces) the decoded surfaces in device memory
    // (RenderOutput::device) instead of reading them back (RenderOutput::hdr, ::surfaces and
    // ::depth stay empty; a ground truth still reads its HDR image for the noise): the GPU
    // evaluation (src/evaluate/) measures them there.
    bool keepOnDevice = false;
    // Rows per read-back band of the decode pass (a multiple of 8); 0: as many as fit in 64 MiB.
    uint32_t decodeBandRows = 0;
    // A band of rows of the frame (bounded memory at 4K): rows [bandFirstRow, bandFirstRow +
    // bandRows) of the width x height frame, as the whole frame's render has them (rendered with
    // the frame's viewport and a halo of rows: render_band_test). Every output (HDR, noise, depth,
    // stencil, target and light-buffer words, surfaces, device images) holds the band's rows only.
    // bandRows 0: the whole frame. Not with IblMode::GroundTruth (UserError: it converges over the
    // whole frame).
    uint32_t bandFirstRow = 0;
    uint32_t bandRows = 0;
    // With decodeSurfaces (and not keepOnDevice): read the targets' raw words back and decode
    // them on the host with the layout's CPU codec (GBufferWiring::cpuDecoder; cpu_decode.h)
    // instead of running the decode pass, where the wiring has one; a visibility buffer or
    // --native-formats targets still run the pass (Renderer::decodesOnCpu says which).
    bool decodeOnCpu = false;
    // The camera to render from; unset: the scene's (compare --views renders several).
    std::optional<Camera> camera;
    // compare --temporal N (image/temporal_resolve.h): the frame's sub-pixel jitter in pixels (the
    // image of the scene moves by it, x right, y down; applyJitter) and its index in the sequence,
    // which an encoding whose dither moves with time reads (a field's dither_per_frame). Zero: the
    // projection and the G-buffer codes of a render without them, bit for bit.
    float jitterX = 0.0f, jitterY = 0.0f;
    uint32_t frameIndex = 0;
    // Called once per G-buffer target (a visibility buffer's: its id target) with the target's raw
    // words as read back (RenderOutput::targetWords' layout) for the rows [firstRow, firstRow +
    // rows) of the frame (a band's rows, its halo included), before the decode: what the
    // framebuffer-compression model (measure/framebuffer_compression.h) measures. Set, the words
    // are read back even where the decode does not need them, and freed after the call unless
    // readTargetWords. Not with keepOnDevice's GPU decode only: there too the words are read back.
    std::function<void(size_t target, uint32_t firstRow, uint32_t rows, const std::vector<uint32_t>& words)> onTargetWords;
};

struct PassTimings {
    double gbufferMs = 0.0;
    double lightingMs = 0.0;
};

// The ground truth's convergence (RenderSettings::groundTruth*). Noise: the standard error of a
// pixel's luminance (CIE Y of linear sRGB), sqrt(s^2 / K) with s^2 the sample variance of its K
// batch means; relative: divided by max(Y, floor), floor = 1e-2 x the image's mean luminance (the
// denominator of measure/run_metrics.h relativeLuminanceError, so noise and errors share a unit).
struct GroundTruthStats {
    int batches = 0;
    int samplesPerPixel = 0;         // batches x steps x 2 (one GGX + one environment sample per step)
    double meanRelativeNoise = 0.0;  // over pixels with geometry
    double targetRelativeNoise = 0.0;
    bool targetMet = false;
    double lightingMs = 0.0;         // GPU time of all batches (timestamps)
};

// A render kept in device memory (RenderSettings::keepOnDevice); destroys its images.
struct DeviceRenderImages {
    explicit DeviceRenderImages(const VulkanContext& c) : ctx(c) {}
    ~DeviceRenderImages();
    DeviceRenderImages(const DeviceRenderImages&) = delete;
    DeviceRenderImages& operator=(const DeviceRenderImages&) = delete;
    // The HDR image read back (RGBA float), e.g. for render.exr.
    Image downloadHdr() const;
    const VulkanContext& ctx;
    GpuImage hdr;  // RGBA32F, GENERAL: linear radiance, alpha 1 where geometry covers the pixel
    std::array<GpuImage, 4> surfaces{};  // decode_pass.h decodeSurfacesOnDevice; empty without decodeSurfaces
    std::array<GpuImage, 4> layers{};    // its layers' images in a scene with layers; else empty
};

struct RenderOutput {
    Image hdr;  // RGBA float: linear radiance, alpha 1 where geometry covers the pixel
    std::vector<std::vector<uint32_t>> targetWords;  // per target, row-major, texel size / 4 words per pixel
                                                     // (empty unless RenderSettings::readTargetWords)
    std::vector<float> depth;                        // row-major depth-buffer values
    // Row-major stencil values where the depth format has stencil (the per-draw references the
    // layout's stencil extras make, gbuffer_pass.cpp), else empty.
    std::vector<uint8_t> stencil;
    // Deferred lighting: the light buffers' words, row-major, GBufferWiring::lightBufferWordsPerPixel
    // per pixel, buffers in layout order (empty unless RenderSettings::readTargetWords).
    std::vector<uint32_t> lightBufferWords;
    PassTimings timings;
    SurfaceImages surfaces;  // filled when RenderSettings::decodeSurfaces (and not keepOnDevice)
    std::shared_ptr<DeviceRenderImages> device;  // RenderSettings::keepOnDevice
    // Ground truth only: per-pixel standard error of the luminance (1 channel, absolute, 0 where no
    // geometry), and how it converged.
    Image noise;
    GroundTruthStats groundTruth;
};

// Mean of noise / max(Y(hdr), floor) over the pixels where hdr's alpha >= 0.5 (GroundTruthStats).
double meanRelativeNoise(const Image& hdr, const Image& noise);

// The host memory a width x height render takes at its peak, whole (bandRows 0) or in bands of
// bandRows rows (RenderSettings::bandRows), on a CPU device, whose device memory is host memory:
// in bands, what stays frame-sized (the HDR result and the PNG made from it) per pixel of the
// frame, the rest per pixel of a band. (A band's G-buffer targets are the frame's size, but only
// the band's rows of them are ever touched.) Constants measured in renderer_memory.cpp.
double renderMemoryBytes(uint32_t width, uint32_t height, uint32_t bandRows);

// Checks a requested resolution against the device's limits, and the render's memory
// (renderMemoryBytes, with `bandRows`) against the budget (memory_budget.h); throws UserError
// naming `flag`.
// `advice`: the fix the refusal of whole frames gives; it names only flags the command has and
// accepts with its other flags (render: bands; search and compare --temporal: none).
inline constexpr const char* kRenderInBandsAdvice = "give a smaller --size, or render in bands (--band-rows 64)";
void validateResolution(const VulkanContext& ctx, uint32_t width, uint32_t height, const std::string& flag,
                        uint32_t bandRows = 0, const std::string& advice = kRenderInBandsAdvice);
// The budget half alone, before a device exists (render checks it before loading anything).
void requireRenderMemory(uint32_t width, uint32_t height, uint32_t bandRows, const std::string& flag,
                         const std::string& advice = kRenderInBandsAdvice);

class Renderer {
public:
    // Pre-computes the IBL of `environment` through the disk cache (ibl_cache.h, default settings).
    Renderer(const VulkanContext& ctx, const Scene& scene, const EnvironmentMap& environment);
    // Uses pre-computed IBL maps (from loadOrComputeIbl / computeIblMaps of the same environment).
    // `sharedPipelines`, when given, holds the pipelines instead of the renderer's own memo: the
    // renderers of several scenes (compare --scene A --scene B) then build each pipeline once,
    // those that do not depend on the scene (lighting, decode; a G-buffer pass's key holds the
    // scene's texture count) serving them all. Its owner destroys it after the renderers.
    Renderer(const VulkanContext& ctx, const Scene& scene, const EnvironmentMap& environment, const IblMaps& ibl,
             PipelineMemo* sharedPipelines = nullptr);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    RenderOutput render(const GBufferWiring& wiring, const RenderSettings& settings);

    // Builds the pipelines render(wiring, settings) uses for every wiring (G-buffer, material,
    // lighting, and the decode pass's variant where it runs one: none when decodesOnCpu) side by
    // side on worker threads (vkCreate*Pipelines may be called from several threads; the
    // VkPipelineCache is internally synchronised, created without EXTERNALLY_SYNCHRONIZED), timed
    // as shader compile, so the renders of these wirings under these IBL modes (and Fresnel,
    // RenderSettings::fresnelMode) build nothing. With one mode the lighting pipelines are
    // specialised for it (render/renderer_passes.h LightingVariant), with several they are generic
    // and serve them all, and so are those of later renders. A wiring whose pipeline cannot be
    // built is skipped here: its render() fails with the error, as it would have. An empty
    // `iblModes` builds no lighting pipeline. Of the settings only the decode choices
    // (decodeSurfaces, keepOnDevice, decodeOnCpu, bandRows) and fresnelMode matter.
    void preparePipelines(const std::vector<GBufferWiring>& wirings, const RenderSettings& settings,
                          const std::vector<IblMode>& iblModes);

    // Whether render(wiring, settings) decodes the surfaces on the host with the wiring's CPU
    // codec (RenderSettings::decodeOnCpu) rather than with the decode pass.
    static bool decodesOnCpu(const GBufferWiring& wiring, const RenderSettings& settings);

    const Scene& scene() const { return scene_; }
    const IblGpu& ibl() const { return ibl_; }
    // The material layers some material of the scene has (GpuScene::layers, kLayer* bits).
    int sceneLayers() const { return gpuScene_.layers; }
    // Pipelines built so far (G-buffer, material, lighting, decode): each layout's are built at its
    // first render and reused by every later one, whatever the camera or size; the lighting
    // pass's once per IBL mode (and Fresnel).
    size_t pipelineCount() const { return pipelines_.size(); }

private:
    void init(const EnvironmentMap& environment, const IblMaps& ibl);
    // render()'s steps (renderer_frame.cpp), in the order it runs them.
    struct FramePasses;
    struct FramePipelines {
        TargetReadScene readScene;
        LightingVariant variant;
        bool cpuDecode = false;  // decodesOnCpu
    };
    gpu::FrameConstants frameConstants(const GBufferWiring& wiring, const RenderSettings& settings,
                                       const RenderBand& band) const;
    FramePipelines framePipelines(const GBufferWiring& wiring, const RenderSettings& settings);
    void createFramePasses(FramePasses& passes, const GBufferWiring& wiring, const RenderSettings& settings,
                           const RenderBand& band, const gpu::FrameConstants& frame, const FramePipelines& pipes);
    void warmUpFramePasses(const GBufferWiring& wiring, const RenderSettings& settings, FramePasses& passes);
    PassTimings drawFrame(FramePasses& passes);
    void convergeGroundTruth(const RenderSettings& settings, FramePasses& passes, RenderOutput& out);
    void readHdr(const FramePasses& passes, RenderOutput& out);
    void readLightBufferWords(const GBufferWiring& wiring, const RenderSettings& settings, const RenderBand& band,
                              FramePasses& passes, RenderOutput& out);
    void readTargetWords(const RenderSettings& settings, const RenderBand& band, bool cpuDecode,
                         const FramePasses& passes, RenderOutput& out, std::optional<HostScope>& wordsScope);
    void readDepth(const GBufferWiring& wiring, const RenderSettings& settings, const RenderBand& band,
                   const FramePasses& passes, RenderOutput& out);
    void decodeOnHost(const GBufferWiring& wiring, const RenderSettings& settings, const gpu::FrameConstants& frame,
                      FramePasses& passes, RenderOutput& out, std::optional<HostScope>& wordsScope);
    void destroyGeometryPasses(FramePasses& passes);
    const VulkanContext& ctx_;
    const Scene& scene_;
    GpuScene gpuScene_;
    GpuImage environmentTexture_;
    VkSampler environmentSampler_ = VK_NULL_HANDLE;
    VkSampler nearestSampler_ = VK_NULL_HANDLE;
    IblGpu ibl_;
    GpuImage sheenAlbedo_;  // shading::sheenAlbedoTable() as R32F (1 x 1 zero without sheen)
    PipelineMemo ownPipelines_;
    PipelineMemo& pipelines_;  // ownPipelines_, or the memo shared by several renderers
    // The tables a G-buffer pass binds (tablesFor): the encodings' (uploaded at init) and the
    // best-fit normal table (uploaded at the first render of a wiring that reads it: generating it
    // is the largest part of a small compare's set-up, and most layouts never read it; compare
    // starts its generation early, prefetchBestFitNormalTable).
    CodecTableBuffers tablesFor(const GBufferWiring& wiring);
    CodecTableBuffers codecTables_;
    Buffer bestFitPlaceholder_;  // bound where the table would be for the other wirings
    std::mutex tablesMutex_;
    // Lighting pipelines specialised per IBL mode and Fresnel: until preparePipelines is given
    // several modes (LightingVariant).
    bool specialiseLighting_ = true;
};

// The rows a render covers (RenderSettings::bandFirstRow, ::bandRows): its outputs' rows
// [first, first + rows) and the rows its G-buffer pass draws, [rasterFirst, rasterFirst +
// rasterRows) (the band and a halo of a row each side) of frame-sized images. A whole frame: 0
// and the height. Throws UserError for a band outside the frame.
struct RenderBand {
    uint32_t first = 0, rows = 0;
    uint32_t rasterFirst = 0, rasterRows = 0;
};
RenderBand renderBand(const RenderSettings& settings);

// Camera matrices for the frame, with Vulkan's y-down flip and optional reversed Z.
struct CameraMatrices {
    glm::mat4 view, proj, viewProj, invViewProj;
};
CameraMatrices computeCameraMatrices(const Camera& camera, float aspect, bool reversedZ);
// Moves the image by (dx, dy) pixels of a width x height frame (x right, y down: clip-space x and
// y gain offset x w, which a perspective projection's w = -z_view makes a translation of the
// projection's third column), and recomputes viewProj and invViewProj. As UE's TAA jitters its
// projection (ViewMatrices.HackAddTemporalAAProjectionJitter).
void applyJitter(CameraMatrices& m, float dx, float dy, uint32_t width, uint32_t height);

}  // namespace gbl
