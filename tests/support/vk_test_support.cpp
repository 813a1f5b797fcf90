#include "vk_test_support.h"

#include <cstdlib>
#include <memory>

#include "procedural_sky.h"
#include "vk_pipeline.h"
#include "wiring_plan.h"

namespace gbl::test {

std::string testDeviceName() {
    const char* d = std::getenv("GBL_TEST_DEVICE");
    return d ? d : "";
}

VulkanContext& sharedContext() {
    static std::unique_ptr<VulkanContext> ctx = std::make_unique<VulkanContext>(DeviceOptions{testDeviceName(), true});
    return *ctx;
}

void VulkanTest::SetUp() { errorsBefore_ = sharedContext().validationErrorCount(); }

void VulkanTest::TearDown() {
    EXPECT_EQ(sharedContext().validationErrorCount(), errorsBefore_)
        << "Vulkan validation error: " << sharedContext().firstValidationError();
}

TestBuffer::TestBuffer(const VulkanContext& ctx, VkDeviceSize bytes)
    : ctx_(ctx), buffer_(createBuffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true)) {}

TestBuffer::TestBuffer(const VulkanContext& ctx, const void* data, VkDeviceSize bytes)
    : ctx_(ctx), buffer_(createBufferWithData(ctx, data, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)) {}

TestBuffer::~TestBuffer() { destroyBuffer(ctx_, buffer_); }

Resource storage(const Buffer& buffer) { return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer.buffer}; }

Resource sampledImage(const GpuImage& image) {
    return {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, VK_NULL_HANDLE, image.view, VK_NULL_HANDLE};
}

Resource combinedImage(const GpuImage& image, VkSampler sampler) {
    return {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, image.view, sampler};
}

DescriptorSets::DescriptorSets(const VulkanContext& ctx, VkShaderStageFlags stages,
                               const std::vector<std::vector<Resource>>& resources, uint32_t pushBytes)
    : pushConstantBytes(pushBytes), ctx_(ctx) {
    std::vector<std::vector<Binding>> bindings;
    for (const std::vector<Resource>& set : resources) {
        bindings.emplace_back();
        for (uint32_t j = 0; j < set.size(); ++j) bindings.back().push_back({j, set[j].type});
        setLayouts.push_back(createSetLayout(ctx.device, bindings.back(), stages));
    }
    pipelineLayout = createPipelineLayout(ctx.device, setLayouts, pushBytes, pushBytes ? stages : 0);
    pool = createPoolFor(ctx.device, bindings);
    DescriptorWriter writer;
    for (size_t i = 0; i < resources.size(); ++i) {
        sets.push_back(allocateSet(ctx.device, pool, setLayouts[i]));
        for (uint32_t j = 0; j < resources[i].size(); ++j) {
            const Resource& r = resources[i][j];
            if (r.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
                writer.buffer(sets[i], j, r.type, r.buffer);
            else
                writer.image(sets[i], j, r.type, r.view, r.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
    }
    writer.flush(ctx.device);
}

DescriptorSets::~DescriptorSets() {
    vkDestroyPipelineLayout(ctx_.device, pipelineLayout, nullptr);
    vkDestroyDescriptorPool(ctx_.device, pool, nullptr);
    for (VkDescriptorSetLayout l : setLayouts) vkDestroyDescriptorSetLayout(ctx_.device, l, nullptr);
}

ComputeKernel::ComputeKernel(const VulkanContext& ctx, const std::vector<uint32_t>& spirv,
                             const std::vector<std::vector<Resource>>& sets, uint32_t pushConstantBytes)
    : ctx_(ctx), sets_(ctx, VK_SHADER_STAGE_COMPUTE_BIT, sets, pushConstantBytes) {
    VkShaderModule module = createShaderModule(ctx.device, spirv);
    pipeline_ = createComputePipeline(ctx, sets_.pipelineLayout, module);
    vkDestroyShaderModule(ctx.device, module, nullptr);
}

ComputeKernel::ComputeKernel(const VulkanContext& ctx, const ShaderSource& source,
                             const std::vector<std::vector<Resource>>& sets, uint32_t pushConstantBytes)
    : ComputeKernel(ctx, compileGlsl(source), sets, pushConstantBytes) {}

ComputeKernel::~ComputeKernel() { vkDestroyPipeline(ctx_.device, pipeline_, nullptr); }

void ComputeKernel::dispatch(uint32_t x, uint32_t y, uint32_t z, const void* push) const {
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sets_.pipelineLayout, 0, uint32_t(sets_.sets.size()),
                                sets_.sets.data(), 0, nullptr);
        if (push)
            vkCmdPushConstants(cmd, sets_.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sets_.pushConstantBytes, push);
        vkCmdDispatch(cmd, x, y, z);
        fullBarrier(cmd);
    });
}

std::string wiringKernel(const std::string& body) {
    return R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "gbuffer_wiring.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer In { uvec4 inputs[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Out { uvec4 outputs[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
)" + body + "}\n";
}

const char* const kFullScreenTriangleVertex = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.5, 1.0);  // depth 0.5 passes LESS and reversed-Z GREATER
}
)";

RenderSettings frame(uint32_t width, uint32_t height) {
    RenderSettings s;
    s.width = width;
    s.height = height;
    return s;
}

RenderSettings decodedFrame(uint32_t width, uint32_t height) {
    RenderSettings s = frame(width, height);
    s.decodeSurfaces = true;
    s.readTargetWords = false;
    return s;
}

std::vector<RenderOutput> renderDefaultScene(const RenderSettings& settings, const std::vector<GBufferWiring>& wirings) {
    const Scene scene = makeDefaultScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(sharedContext(), scene, sky);
    std::vector<RenderOutput> out;
    for (const GBufferWiring& w : wirings) out.push_back(renderer.render(w, settings));
    return out;
}

std::vector<uint32_t> targetWords(const VulkanContext& ctx, const GpuImage& target, size_t pixels) {
    return texelsToWords(downloadImage(ctx, target, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), pixels);
}

}  // namespace gbl::test
