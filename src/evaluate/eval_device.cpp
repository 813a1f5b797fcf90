#include "eval_device.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "color_map.h"
#include "env_flag.h"
#include "error.h"
#include "eval_profile.h"
#include "histogram.h"
#include "shader_compiler.h"
#include "vk_pipeline.h"

namespace gbl::evaluate {

namespace {

constexpr size_t kConstantFloats = 8192;  // room for the colour constants and every FLIP kernel

// The profile's kinds: each pass, the separable ones' rows and columns apart (flags bit 0), the
// attribute statistics apart from the normal-error image (mode 1, 2).
constexpr uint32_t kKinds = 2 * uint32_t(Pass::Count);
uint32_t profileKind(Pass p, const Push& push) {
    const bool split = p == Pass::FlipFilter || p == Pass::FlipFeatures;
    if (p == Pass::Attributes) return 2 * uint32_t(p) + (push.mode != 0 ? 1u : 0u);
    return 2 * uint32_t(p) + (split ? (push.flags & 1u) : 0u);
}
std::vector<std::string> profileKinds() {
    const char* names[] = {"Image", "Reduce", "FlipOpponent", "FlipFilter", "FlipLab", "FlipFeatures", "FlipCombine",
                           "FlipStats", "Attributes", "Tiles", "Luminance", "NormalMap", "Layers"};
    static_assert(std::size(names) == size_t(Pass::Count));
    std::vector<std::string> k(kKinds);
    for (uint32_t p = 0; p < uint32_t(Pass::Count); ++p) {
        const bool split = Pass(p) == Pass::FlipFilter || Pass(p) == Pass::FlipFeatures;
        k[2 * p] = std::string(names[p]) + (split ? " rows" : "");
        k[2 * p + 1] = std::string(names[p]) + (Pass(p) == Pass::Attributes ? " image" : " cols");
    }
    k[kKinds - 1] = "clear histograms";
    return k;
}

const char* shaderFile(Pass p) {
    switch (p) {
        case Pass::Image: return "eval_image.comp.glsl";
        case Pass::Reduce: return "eval_reduce.comp.glsl";
        case Pass::FlipOpponent: return "flip_opponent.comp.glsl";
        case Pass::FlipFilter: return "flip_filter.comp.glsl";
        case Pass::FlipLab: return "flip_lab.comp.glsl";
        case Pass::FlipFeatures: return "flip_features.comp.glsl";
        case Pass::FlipCombine: return "flip_combine.comp.glsl";
        case Pass::FlipStats: return "eval_flip_stats.comp.glsl";
        case Pass::Attributes: return "eval_attributes.comp.glsl";
        case Pass::Tiles: return "eval_tiles.comp.glsl";
        case Pass::Luminance: return "eval_luminance.comp.glsl";
        case Pass::NormalMap: return "eval_normal_map.comp.glsl";
        case Pass::Layers: return "eval_layers.comp.glsl";
        case Pass::Count: break;
    }
    throw std::logic_error("evaluate: no shader for this pass");
}

std::vector<Binding> bindings() {
    return {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
            {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4},      {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4},
            {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kPlaneCount}, {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},        {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kOut8Count},
            {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},        {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},       {11, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4},
            {12, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4}};
}

}  // namespace

uint32_t EvalDevice::kHistBinsTotal() { return kHistBins; }

namespace {
bool cpuDevice(const VulkanContext& c) { return c.info.type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
uint32_t groupsFor(const VulkanContext& c) {
    if (const std::optional<long> n = envLong("GBL_EVAL_GROUPS"); n && *n >= 1 && *n <= 65535) return uint32_t(*n);
    return cpuDevice(c) ? kCpuGroups : kGpuGroups;
}
// Subgroup vote and ballot in compute shaders (eval_common.glsl histAdd).
bool subgroupVoteAndBallot(const VulkanContext& c) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(c.physicalDevice, &properties);
    const VkSubgroupFeatureFlags needed =
        VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
    return (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) && (subgroup.supportedOperations & needed) == needed;
}
}  // namespace

EvalDevice::EvalDevice(const VulkanContext& c, uint32_t w, uint32_t h, uint32_t rows)
    : ctx(c), width(w), height(h), planeRows(rows == 0 ? h : std::min(rows, h)), groups(groupsFor(c)) {
    setWholeFrameView();
    if (!ctx.shaderFloat64)
        throwUserError("--eval gpu: the Vulkan device '" + ctx.info.name +
                       "' has no 64-bit float shaders (shaderFloat64), which the GPU evaluation's sums need; "
                       "use --eval cpu");
    const std::vector<Binding> b = bindings();
    setLayout_ = createSetLayout(ctx.device, b, VK_SHADER_STAGE_COMPUTE_BIT);
    pipelineLayout_ = createPipelineLayout(ctx.device, {setLayout_}, sizeof(Push), VK_SHADER_STAGE_COMPUTE_BIT);
    pool_ = createPoolFor(ctx.device, {b});
    set_ = allocateSet(ctx.device, pool_, setLayout_);
    const bool subgroupHist = subgroupVoteAndBallot(ctx) && !envFlag("GBL_EVAL_NO_SUBGROUPS");
    for (size_t p = 0; p < size_t(Pass::Count); ++p) {
        ShaderSource s = loadShaderFile(shaderFile(Pass(p)));
        if (subgroupHist) s.defines.push_back({"EVAL_SUBGROUP_HIST", "1"});
        s.defines.push_back({"EVAL_PLANE_COUNT", std::to_string(kPlaneCount)});
        s.defines.push_back({"EVAL_OUT8_COUNT", std::to_string(kOut8Count)});
        s.defines.push_back({"EVAL_HIST_BINS", std::to_string(kHistBins) + "u"});
        s.defines.push_back({"EVAL_LAYER_HIST", std::to_string(kHistLayers) + "u"});
        VkShaderModule module = createShaderModule(ctx.device, compileGlsl(s));
        pipelines_[p] = createComputePipeline(ctx, pipelineLayout_, module);
        vkDestroyShaderModule(ctx.device, module, nullptr);
    }
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    dummy_ = createBuffer(ctx, 256, storage, false);
    // Stage-1 records, then room for the chunk sums of a chunked reduction.
    partials_ = createBuffer(ctx, VkDeviceSize(groups * 64 + kReduceChunks) * kMaxFields * sizeof(double), storage, false);
    const VkDeviceSize histogramBytes = VkDeviceSize(kHistCount) * kHistBins * 4;
    const VkDeviceSize constantBytes = 256 * 4 + kConstantFloats * 4;
    histograms_ = createBuffer(ctx, histogramBytes, storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    histogramsHost_ = createBuffer(ctx, histogramBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    constants_ = createBuffer(ctx, constantBytes, storage, false);
    constantsHost_ = createBuffer(ctx, constantBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memset(constantsHost_.mapped, 0, size_t(constantBytes));
    result_ = createBuffer(ctx, 4 * kMaxFields * sizeof(double), storage, true);
    uint32_t* table = static_cast<uint32_t*>(constantsHost_.mapped);
    const auto& viridis = viridisTable();
    for (size_t i = 0; i < 256; ++i) table[i] = viridis[i].r | (uint32_t(viridis[i].g) << 8) | (uint32_t(viridis[i].b) << 16);
    uploadConstants();
    rebindBuffers();
    if (EvalProfile::wanted()) profile_ = std::make_unique<EvalProfile>(profileKinds(), ctx.info.name);
}

EvalDevice::~EvalDevice() {
    profile_.reset();
    for (Buffer& p : planes_) destroyBuffer(ctx, p);
    for (Buffer& p : out8_) destroyBuffer(ctx, p);
    for (Buffer* b : {&dummy_, &partials_, &histograms_, &histogramsHost_, &constants_, &constantsHost_, &result_, &tiles_})
        destroyBuffer(ctx, *b);
    for (VkPipeline p : pipelines_) vkDestroyPipeline(ctx.device, p, nullptr);
    vkDestroyPipelineLayout(ctx.device, pipelineLayout_, nullptr);
    vkDestroyDescriptorSetLayout(ctx.device, setLayout_, nullptr);
    vkDestroyDescriptorPool(ctx.device, pool_, nullptr);
}

void EvalDevice::rebindBuffers() {
    auto orDummy = [&](const Buffer& b) { return b.buffer ? b.buffer : dummy_.buffer; };
    DescriptorWriter w;
    for (uint32_t i = 0; i < kPlaneCount; ++i) w.buffer(set_, 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, orDummy(planes_[i]), i);
    w.buffer(set_, 5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, partials_.buffer);
    w.buffer(set_, 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, histograms_.buffer);
    for (uint32_t i = 0; i < kOut8Count; ++i) w.buffer(set_, 7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, orDummy(out8_[i]), i);
    w.buffer(set_, 8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, constants_.buffer);
    w.buffer(set_, 9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, result_.buffer);
    w.buffer(set_, 10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, orDummy(tiles_));
    w.flush(ctx.device);
}

void EvalDevice::bindImages(const GpuImage& refHdr, const GpuImage& testHdr, const GpuImage* const refSurfaces[4],
                            const GpuImage* const testSurfaces[4], const GpuImage* const refLayers[4],
                            const GpuImage* const testLayers[4]) {
    DescriptorWriter w;
    auto image = [&](uint32_t binding, const GpuImage& im, uint32_t element) {
        w.image(set_, binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, im.view, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL,
                element);
    };
    image(0, refHdr, 0);
    image(1, testHdr, 0);
    for (uint32_t k = 0; k < 4; ++k) {
        image(2, refSurfaces && refSurfaces[k] ? *refSurfaces[k] : refHdr, k);
        image(3, testSurfaces && testSurfaces[k] ? *testSurfaces[k] : testHdr, k);
        image(11, refLayers && refLayers[k] ? *refLayers[k] : refHdr, k);
        image(12, testLayers && testLayers[k] ? *testLayers[k] : testHdr, k);
    }
    w.flush(ctx.device);
}

void EvalDevice::setView(uint32_t imageRows, uint32_t countedFirst, uint32_t countedRows) {
    if (imageRows > planeRows || countedFirst + countedRows > imageRows)
        throw std::logic_error("evaluate: the view exceeds the planes or its image");
    viewRows_ = imageRows;
    countedFirst_ = countedFirst;
    countedRows_ = countedRows;
}

void EvalDevice::ensurePlane(uint32_t slot) {
    if (planes_[slot].buffer) return;
    planes_[slot] = createBuffer(ctx, VkDeviceSize(width) * planeRows * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    rebindBuffers();
}

void EvalDevice::releasePlane(uint32_t slot) {
    if (!planes_[slot].buffer) return;
    destroyBuffer(ctx, planes_[slot]);
    planes_[slot] = {};
    rebindBuffers();
}

void EvalDevice::uploadPlane(uint32_t slot, const float* values) {
    destroyBuffer(ctx, planes_[slot]);
    planes_[slot] = createBuffer(ctx, VkDeviceSize(width) * planeRows * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    std::memcpy(planes_[slot].mapped, values, size_t(width) * planeRows * 4);
    rebindBuffers();
}

float* EvalDevice::hostPlane(uint32_t slot) {
    if (!planes_[slot].mapped) {
        destroyBuffer(ctx, planes_[slot]);
        planes_[slot] = createBuffer(ctx, VkDeviceSize(width) * planeRows * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        rebindBuffers();
    }
    return static_cast<float*>(planes_[slot].mapped);
}

void EvalDevice::ensureOut8() {
    if (out8_[0].buffer) return;
    for (Buffer& b : out8_) b = createBuffer(ctx, VkDeviceSize(width) * planeRows * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    rebindBuffers();
}

std::vector<Buffer> EvalDevice::detachOut8() {
    std::vector<Buffer> out(out8_.begin(), out8_.end());
    out8_ = {};
    rebindBuffers();
    return out;
}

void EvalDevice::releaseOut8() {
    if (!out8_[0].buffer) return;
    for (Buffer& b : out8_) destroyBuffer(ctx, b);
    rebindBuffers();
}

void EvalDevice::ensureTiles(size_t count) {
    if (tiles_.buffer && tiles_.size >= count * 4) return;
    destroyBuffer(ctx, tiles_);
    tiles_ = createBuffer(ctx, VkDeviceSize(std::max<size_t>(count, 1)) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    rebindBuffers();
}

void EvalDevice::setKernels(const std::vector<float>& kernels) {
    if (kernels.size() > kConstantFloats) throw std::logic_error("evaluate: FLIP kernels exceed the constants buffer");
    std::memcpy(static_cast<uint32_t*>(constantsHost_.mapped) + 256, kernels.data(), kernels.size() * 4);
    uploadConstants();
}

void EvalDevice::uploadConstants() {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, constantsHost_.size};
        vkCmdCopyBuffer(cmd, constantsHost_.buffer, constants_.buffer, 1, &region);
        fullBarrier(cmd);
    });
}

const uint32_t* EvalDevice::histogram(uint32_t slot) const {
    if (histogramsDirty_) {
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            fullBarrier(cmd);
            const VkBufferCopy region{0, 0, histograms_.size};
            vkCmdCopyBuffer(cmd, histograms_.buffer, histogramsHost_.buffer, 1, &region);
            fullBarrier(cmd);
        });
        histogramsDirty_ = false;
    }
    return static_cast<const uint32_t*>(histogramsHost_.mapped) + size_t(slot) * kHistBinsTotal();
}

void EvalDevice::dispatch(VkCommandBuffer cmd, Pass pass, const Push& push, uint32_t groupCount) const {
    const uint32_t count = groupCount ? groupCount : groups;
    histogramsDirty_ = true;  // any pass may add to them
    Push p = push;
    p.width = width;
    p.height = viewRows_;
    p.rowFirst = countedFirst_;
    p.rowCount = countedRows_;
    auto record = [&](VkCommandBuffer c) {
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[size_t(pass)]);
        vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set_, 0, nullptr);
        vkCmdPushConstants(c, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push), &p);
        vkCmdDispatch(c, count, 1, 1);
        fullBarrier(c);
    };
    if (profile_) return profiled(profileKind(pass, p), record);
    record(cmd);
}

void EvalDevice::profiled(uint32_t kind, const std::function<void(VkCommandBuffer)>& record) const {
    // Submitted now, in recording order: the caller's command buffer holds only evaluation
    // commands (every one goes through here), so it is left empty and nothing is reordered.
    const auto start = std::chrono::steady_clock::now();
    ctx.submitAndWait(record);
    profile_->add(kind, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

void EvalDevice::reduce(VkCommandBuffer cmd, uint32_t fields, const std::array<uint32_t, 4>& maxMask,
                        uint32_t resultOffset) const {
    if (fields > kMaxFields || resultOffset + fields > 4 * kMaxFields) throw std::logic_error("evaluate: too many fields");
    Push p;
    p.u[0] = fields;
    for (int k = 0; k < 4; ++k) p.u[1 + k] = maxMask[size_t(k)];
    p.u[6] = resultOffset;
    const uint32_t records = groups * 64;
    if (records <= kReduceChunkAbove) {  // one invocation per field walks every record (lavapipe)
        p.u[5] = records;
        dispatch(cmd, Pass::Reduce, p, (fields + 63) / 64);
        return;
    }
    // Chunks: field f of chunk c folds records [c R / C, (c + 1) R / C) into record R + c; then
    // the C chunk records are folded as above.
    p.mode = 1;
    p.flags = kReduceChunks;
    p.u[5] = records;
    dispatch(cmd, Pass::Reduce, p, (fields * kReduceChunks + 63) / 64);
    p.mode = 0;
    p.u[5] = kReduceChunks;
    p.u[7] = records;
    dispatch(cmd, Pass::Reduce, p, (fields + 63) / 64);
}

void EvalDevice::clearHistograms(VkCommandBuffer cmd) const {
    histogramsDirty_ = true;
    auto record = [&](VkCommandBuffer c) {
        vkCmdFillBuffer(c, histograms_.buffer, 0, VK_WHOLE_SIZE, 0);
        fullBarrier(c);
    };
    if (profile_) return profiled(kKinds - 1, record);  // Layers never splits: its second slot is free
    record(cmd);
}

}  // namespace gbl::evaluate
