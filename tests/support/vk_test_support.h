#pragma once
// The Vulkan tests' scaffolding: one Vulkan context per test binary (device creation costs ~40 ms
// with validation) and a check that the test which ran did not raise a validation error; buffers
// freed with their object; compute kernels over storage buffers and images, dispatched and waited
// for; the words of a render target read back; the settings of a frame whose Surfaces are decoded.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "renderer.h"
#include "shader_compiler.h"
#include "vk_context.h"
#include "vk_resources.h"

namespace gbl::test {

// lavapipe unless GBL_TEST_DEVICE names another device as --device does ("gpu", an index, a
// name): the GPU-against-CPU tests then check a real driver's arithmetic against the CPU oracle.
std::string testDeviceName();

VulkanContext& sharedContext();

// Fails the current test when validation errors were reported during it.
class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    VulkanContext& ctx() { return sharedContext(); }

private:
    int errorsBefore_ = 0;
};

// A storage buffer, destroyed with the object: host-visible and mapped for results, or a device
// buffer holding data (createBufferWithData).
class TestBuffer {
public:
    TestBuffer(const VulkanContext& ctx, VkDeviceSize bytes);
    TestBuffer(const VulkanContext& ctx, const void* data, VkDeviceSize bytes);
    template <class T>
    static TestBuffer holding(const VulkanContext& ctx, const std::vector<T>& values) {
        return TestBuffer(ctx, values.data(), values.size() * sizeof(T));
    }
    ~TestBuffer();
    TestBuffer(const TestBuffer&) = delete;
    TestBuffer& operator=(const TestBuffer&) = delete;

    operator const Buffer&() const { return buffer_; }
    // The contents of a host-visible buffer.
    template <class T>
    T* mapped() const {
        return static_cast<T*>(buffer_.mapped);
    }

private:
    const VulkanContext& ctx_;
    Buffer buffer_;
};

// One descriptor of a set, bound at its position in the set.
struct Resource {
    VkDescriptorType type;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
};
Resource storage(const Buffer& buffer);
// An image in SHADER_READ_ONLY_OPTIMAL, sampled without a sampler (texelFetch) or with one.
Resource sampledImage(const GpuImage& image);
Resource combinedImage(const GpuImage& image, VkSampler sampler);

// Descriptor sets holding `sets` (set i, binding j: sets[i][j]) for `stages`, and their pipeline
// layout with `pushConstantBytes` of push constants, destroyed with the object.
class DescriptorSets {
public:
    DescriptorSets(const VulkanContext& ctx, VkShaderStageFlags stages, const std::vector<std::vector<Resource>>& sets,
                   uint32_t pushConstantBytes = 0);
    ~DescriptorSets();
    DescriptorSets(const DescriptorSets&) = delete;
    DescriptorSets& operator=(const DescriptorSets&) = delete;

    std::vector<VkDescriptorSetLayout> setLayouts;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> sets;
    uint32_t pushConstantBytes = 0;

private:
    const VulkanContext& ctx_;
};

// A compute pipeline over `sets` (DescriptorSets), destroyed with the object.
class ComputeKernel {
public:
    ComputeKernel(const VulkanContext& ctx, const std::vector<uint32_t>& spirv,
                  const std::vector<std::vector<Resource>>& sets, uint32_t pushConstantBytes = 0);
    // `source` through compileGlsl (the shader cache).
    ComputeKernel(const VulkanContext& ctx, const ShaderSource& source, const std::vector<std::vector<Resource>>& sets,
                  uint32_t pushConstantBytes = 0);
    ~ComputeKernel();
    ComputeKernel(const ComputeKernel&) = delete;
    ComputeKernel& operator=(const ComputeKernel&) = delete;

    // x * y * z work groups, with `push` as the push constants when given; a full barrier after
    // them, and waits: the results are in the buffers when it returns.
    void dispatch(uint32_t x, uint32_t y = 1, uint32_t z = 1, const void* push = nullptr) const;

private:
    const VulkanContext& ctx_;
    DescriptorSets sets_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// The text of a compute shader over a layout's generated wiring (the virtual file
// gbuffer_wiring.glsl), 64 invocations a group, reading `uvec4 inputs[]` (set 0, binding 0) and
// writing `uvec4 outputs[]` (binding 1): `body` is its main's after `uint i = gl_GlobalInvocationID.x;`.
std::string wiringKernel(const std::string& body);

// A full-screen triangle's vertex shader (depth 0.5: it passes LESS and reversed-Z GREATER).
extern const char* const kFullScreenTriangleVertex;

// The settings of a width x height frame.
RenderSettings frame(uint32_t width, uint32_t height);
// A width x height frame whose decoded Surfaces come back (decodeSurfaces) without the targets'
// raw words (readTargetWords off).
RenderSettings decodedFrame(uint32_t width, uint32_t height);
// The built-in default scene under the built-in sky (makeProceduralSky(64)), rendered with
// `settings` through each of `wirings` in turn by one Renderer.
std::vector<RenderOutput> renderDefaultScene(const RenderSettings& settings, const std::vector<GBufferWiring>& wirings);

// The words of a render target in SHADER_READ_ONLY_OPTIMAL, `pixels` texels: one word per texel
// for R8 / R16 targets (texelsToWords).
std::vector<uint32_t> targetWords(const VulkanContext& ctx, const GpuImage& target, size_t pixels);

}  // namespace gbl::test
