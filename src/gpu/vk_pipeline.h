#pragma once
// Small helpers for descriptor sets and pipelines, so each pass reads as what it binds.
#include <vector>

#include "vk_context.h"

namespace gbl {

struct Binding {
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count = 1;
};

VkDescriptorSetLayout createSetLayout(VkDevice device, const std::vector<Binding>& bindings, VkShaderStageFlags stages);
VkPipelineLayout createPipelineLayout(VkDevice device, const std::vector<VkDescriptorSetLayout>& sets,
                                      uint32_t pushConstantBytes, VkShaderStageFlags pushStages);
// A pool big enough for `sets` sets of the given bindings (counted per type).
VkDescriptorPool createPoolFor(VkDevice device, const std::vector<std::vector<Binding>>& sets);
VkDescriptorSet allocateSet(VkDevice device, VkDescriptorPool pool, VkDescriptorSetLayout layout);

// Descriptor writes collected and flushed in one vkUpdateDescriptorSets call.
class DescriptorWriter {
public:
    DescriptorWriter& buffer(VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                             uint32_t arrayElement = 0);
    DescriptorWriter& image(VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkImageView view,
                            VkSampler sampler, VkImageLayout layout, uint32_t arrayElement = 0);
    void flush(VkDevice device);

private:
    std::vector<VkDescriptorBufferInfo> buffers_;
    std::vector<VkDescriptorImageInfo> images_;
    struct Pending {
        VkWriteDescriptorSet write;
        bool isImage;
        size_t index;
    };
    std::vector<Pending> pending_;
};

// Both go through the context's persistent VkPipelineCache (shader_cache.h) and count the
// pipeline and its cache hit in shaderCacheCounters().
VkPipeline createComputePipeline(const VulkanContext& ctx, VkPipelineLayout layout, VkShaderModule module);
VkPipeline createGraphicsPipeline(const VulkanContext& ctx, VkGraphicsPipelineCreateInfo info);

}  // namespace gbl
