#include "vk_pipeline.h"

#include "shader_cache.h"
#include "stage_clock.h"

#include <map>

namespace gbl {

VkDescriptorSetLayout createSetLayout(VkDevice device, const std::vector<Binding>& bindings, VkShaderStageFlags stages) {
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (const Binding& x : bindings) b.push_back({x.binding, x.type, x.count, stages, nullptr});
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = uint32_t(b.size());
    info.pBindings = b.data();
    VkDescriptorSetLayout layout;
    VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout));
    return layout;
}

VkPipelineLayout createPipelineLayout(VkDevice device, const std::vector<VkDescriptorSetLayout>& sets,
                                      uint32_t pushConstantBytes, VkShaderStageFlags pushStages) {
    VkPushConstantRange range{pushStages, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = uint32_t(sets.size());
    info.pSetLayouts = sets.data();
    info.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout;
    VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
    return layout;
}

VkDescriptorPool createPoolFor(VkDevice device, const std::vector<std::vector<Binding>>& sets) {
    std::map<VkDescriptorType, uint32_t> counts;
    for (const auto& set : sets)
        for (const Binding& b : set) counts[b.type] += b.count;
    std::vector<VkDescriptorPoolSize> sizes;
    for (auto [type, count] : counts) sizes.push_back({type, count});
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = uint32_t(sets.size());
    info.poolSizeCount = uint32_t(sizes.size());
    info.pPoolSizes = sizes.data();
    VkDescriptorPool pool;
    VK_CHECK(vkCreateDescriptorPool(device, &info, nullptr, &pool));
    return pool;
}

VkDescriptorSet allocateSet(VkDevice device, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(device, &info, &set));
    return set;
}

DescriptorWriter& DescriptorWriter::buffer(VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkBuffer b,
                                           uint32_t arrayElement) {
    buffers_.push_back({b, 0, VK_WHOLE_SIZE});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = binding;
    w.dstArrayElement = arrayElement;
    w.descriptorCount = 1;
    w.descriptorType = type;
    pending_.push_back({w, false, buffers_.size() - 1});
    return *this;
}

DescriptorWriter& DescriptorWriter::image(VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                                          VkImageView view, VkSampler sampler, VkImageLayout layout,
                                          uint32_t arrayElement) {
    images_.push_back({sampler, view, layout});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = binding;
    w.dstArrayElement = arrayElement;
    w.descriptorCount = 1;
    w.descriptorType = type;
    pending_.push_back({w, true, images_.size() - 1});
    return *this;
}

void DescriptorWriter::flush(VkDevice device) {
    std::vector<VkWriteDescriptorSet> writes;
    for (Pending& p : pending_) {  // pointers taken only now: the vectors no longer grow
        if (p.isImage) p.write.pImageInfo = &images_[p.index];
        else p.write.pBufferInfo = &buffers_[p.index];
        writes.push_back(p.write);
    }
    vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
    pending_.clear();
    images_.clear();
    buffers_.clear();
}

namespace {

// Counts the pipeline, and whether the driver found it in the pipeline cache (Vulkan 1.3 core,
// VkPipelineCreationFeedback: VK_PIPELINE_CREATION_FEEDBACK_APPLICATION_PIPELINE_CACHE_HIT_BIT;
// a driver that does not report it leaves the VALID bit clear and counts as no hit).
void countPipeline(const VkPipelineCreationFeedback& feedback) {
    ShaderCacheCounters& c = shaderCacheCounters();
    ++c.pipelines;
    if ((feedback.flags & VK_PIPELINE_CREATION_FEEDBACK_VALID_BIT) &&
        (feedback.flags & VK_PIPELINE_CREATION_FEEDBACK_APPLICATION_PIPELINE_CACHE_HIT_BIT))
        ++c.pipelineCacheHits;
}

}  // namespace

VkPipeline createComputePipeline(const VulkanContext& ctx, VkPipelineLayout layout, VkShaderModule module) {
    VkPipelineCreationFeedback feedback{};
    VkPipelineCreationFeedbackCreateInfo feedbackInfo{VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO};
    feedbackInfo.pPipelineCreationFeedback = &feedback;
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, &feedbackInfo};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline;
    ScopedStage timed(Stage::ShaderCompile);  // the driver compiles the shader here (or finds it in the cache)
    VK_CHECK(vkCreateComputePipelines(ctx.device, ctx.pipelineCache(), 1, &info, nullptr, &pipeline));
    countPipeline(feedback);
    return pipeline;
}

VkPipeline createGraphicsPipeline(const VulkanContext& ctx, VkGraphicsPipelineCreateInfo info) {
    VkPipelineCreationFeedback feedback{};
    VkPipelineCreationFeedbackCreateInfo feedbackInfo{VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO};
    feedbackInfo.pPipelineCreationFeedback = &feedback;
    feedbackInfo.pNext = info.pNext;
    info.pNext = &feedbackInfo;
    VkPipeline pipeline;
    ScopedStage timed(Stage::ShaderCompile);  // the driver compiles the shaders here (or finds them in the cache)
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device, ctx.pipelineCache(), 1, &info, nullptr, &pipeline));
    countPipeline(feedback);
    return pipeline;
}

}  // namespace gbl
