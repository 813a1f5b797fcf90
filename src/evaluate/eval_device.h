#pragma once
// The evaluation passes' shared machinery (internal to gbl_evaluate): one descriptor set layout for
// every pass (shaders/eval_common.glsl), the pipelines, the planes and read-back buffers, and the
// dispatch / two-stage reduction helpers.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vk_context.h"
#include "vk_resources.h"

namespace gbl::evaluate {

class EvalProfile;

// Plane slots (binding 4): FLIP's prepared reference (L, a, b, edge, point) and test, its five
// working planes, the LDR- and HDR-FLIP maps, the reference's noise, and the host-visible plane a
// band's per-pixel values come back through (banded runs: the reference's luminance, the normal
// angles).
enum PlaneSlot : uint32_t {
    kRefPrepared = 0,
    kTestPrepared = 5,
    kWork = 10,  // yy, cx, cz, lum, tmp
    kFlipMap = 15,
    kHdrFlipMap = 16,
    kNoise = 17,
    kBandOut = 18,
    kPlaneCount = 19,
};
enum Out8Slot : uint32_t { kOutRender = 0, kOutDifference, kOutHeat, kOutFlip, kOutNormal, kOutReference, kOut8Count };
// Histograms (binding 6).
enum HistSlot : uint32_t { kHistAbsLinear = 0, kHistFlip = 1, kHistAttributes = 2 /* + 2 attribute + class */,
                           kHistLuminance = 18, kHistRefine = 19,
                           kHistLayers = 20 /* + 2 layer attribute + class (eval_layers.comp.glsl) */, kHistCount = 34 };
// Workgroups of 64 per grid-stride pass. On a CPU device (lavapipe) 128 groups, 8192 invocations:
// a few per core, each walking many pixels. A GPU holds far more (an H200: 270,336 resident
// invocations), so it gets kGpuGroups. Measured on the H200 at 4K: no change in the evaluation's
// time while its histograms were in host memory (their atomics were the cost); not measured
// apart since. GBL_EVAL_GROUPS overrides both, for measurements.
inline constexpr uint32_t kCpuGroups = 128;
inline constexpr uint32_t kGpuGroups = 2048;
inline constexpr uint32_t kMaxFields = 96;
// Above this many stage-1 records the reduction folds them in kReduceChunks fixed chunks first
// (one invocation per field and chunk), then the chunks: the same order on every run.
inline constexpr uint32_t kReduceChunkAbove = 8192;
inline constexpr uint32_t kReduceChunks = 256;

struct Push {
    uint32_t width = 0, height = 0, mode = 0, flags = 0;
    float f0 = 0, f1 = 0, f2 = 0, f3 = 0;
    uint32_t u[8] = {};
    uint32_t rowFirst = 0, rowCount = 0;  // set by dispatch from the view (eval_common.glsl)
};

enum class Pass { Image, Reduce, FlipOpponent, FlipFilter, FlipLab, FlipFeatures, FlipCombine, FlipStats, Attributes,
                  Tiles, Luminance, NormalMap, Layers, Count };

class EvalDevice {
public:
    // planeRows: the rows of every plane and 8-bit output buffer (0: height, a whole frame); a
    // banded evaluation's bands hold at most that many rows.
    EvalDevice(const VulkanContext& ctx, uint32_t width, uint32_t height, uint32_t planeRows = 0);
    ~EvalDevice();
    EvalDevice(const EvalDevice&) = delete;
    EvalDevice& operator=(const EvalDevice&) = delete;

    const VulkanContext& ctx;
    const uint32_t width, height;  // the frame
    const uint32_t planeRows;
    const uint32_t groups;  // of every grid-stride pass (kCpuGroups / kGpuGroups)

    // What the passes see: bound images of width x imageRows (imageRows <= planeRows), of which
    // rows [countedFirst, countedFirst + countedRows) count. The default view is the whole frame.
    void setView(uint32_t imageRows, uint32_t countedFirst, uint32_t countedRows);
    // Back to the whole frame (the view outside a band; only whole-frame evaluators dispatch in it).
    void setWholeFrameView() { viewRows_ = countedRows_ = height, countedFirst_ = 0; }
    uint32_t viewRows() const { return viewRows_; }

    // Binds the images (RGBA32F, GENERAL) of binding 0-3 and the layers' of 11-12; surfaces and
    // layers may be null (the HDR image is bound in their place and the passes reading them must
    // not run).
    void bindImages(const GpuImage& refHdr, const GpuImage& testHdr, const GpuImage* const refSurfaces[4],
                    const GpuImage* const testSurfaces[4], const GpuImage* const refLayers[4] = nullptr,
                    const GpuImage* const testLayers[4] = nullptr);
    // Allocates plane `slot` (width x planeRows floats) if not yet there (and rebinds).
    void ensurePlane(uint32_t slot);
    void ensureOut8();   // the 8-bit output images (host visible)
    void releaseOut8();
    // Hands the 8-bit output buffers over (kOut8Count, Out8Slot order); the next ensureOut8
    // allocates new ones.
    std::vector<Buffer> detachOut8();
    void ensureTiles(size_t count);
    // Writes the kernels region of the constants buffer (binding 8) after the colour map.
    void setKernels(const std::vector<float>& kernels);

    // groupCount 0: `groups`.
    void dispatch(VkCommandBuffer cmd, Pass pass, const Push& push, uint32_t groupCount = 0) const;
    // Stage 2: result[offset + f] = sum (max where bit f of maxMask) over the stage-1 records.
    void reduce(VkCommandBuffer cmd, uint32_t fields, const std::array<uint32_t, 4>& maxMask, uint32_t resultOffset) const;
    void clearHistograms(VkCommandBuffer cmd) const;

    const double* result() const { return static_cast<const double*>(result_.mapped); }
    // The histograms as the passes recorded so far left them: copied from the device when a pass
    // ran since the last copy (one small submission).
    const uint32_t* histogram(uint32_t slot) const;
    const uint32_t* out8(uint32_t slot) const { return static_cast<const uint32_t*>(out8_[slot].mapped); }
    const float* tiles() const { return static_cast<const float*>(tiles_.mapped); }
    bool hasPlane(uint32_t slot) const { return planes_[slot].buffer != VK_NULL_HANDLE; }
    void releasePlane(uint32_t slot);
    // Plane `slot` holding `values` (width x planeRows floats), host visible.
    void uploadPlane(uint32_t slot, const float* values);
    // Plane `slot` made host visible (allocated if needed, contents undefined), and its memory.
    float* hostPlane(uint32_t slot);

private:
    static uint32_t kHistBinsTotal();
    void rebindBuffers();
    void profiled(uint32_t kind, const std::function<void(VkCommandBuffer)>& record) const;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::array<VkPipeline, size_t(Pass::Count)> pipelines_{};
    std::array<Buffer, kPlaneCount> planes_{};
    std::array<Buffer, kOut8Count> out8_{};
    // Histograms and constants live in device memory (binding 6, 8): in host memory every
    // histogram atomic crossed the bus (on an H200 at 4K the three histogram passes took 10-28 ms
    // each, the others ~1 ms). Their host twins: the read-back and the upload staging.
    Buffer dummy_, partials_, histograms_, histogramsHost_, constants_, constantsHost_, result_, tiles_;
    mutable bool histogramsDirty_ = false;
    void uploadConstants();
    uint32_t viewRows_ = 0, countedFirst_ = 0, countedRows_ = 0;
    std::unique_ptr<EvalProfile> profile_;  // null unless GBL_EVAL_PROFILE
};

}  // namespace gbl::evaluate
