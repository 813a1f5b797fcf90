#include "renderer_passes.h"

#include "shader_compiler.h"
#include "vk_pipeline.h"

namespace gbl {

std::vector<Binding> targetReadBindings(const GBufferPass& pass) {
    std::vector<Binding> bindings;
    for (uint32_t i = 0; i < pass.targets.size(); ++i) bindings.push_back({i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
    if (const GpuScene* scene = pass.visibilityScene) {
        for (uint32_t b = 1; b <= 4; ++b) bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        bindings.push_back({5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(scene->textures.size())});
    }
    return bindings;
}

void writeTargetReadSet(DescriptorWriter& writer, VkDescriptorSet set, const GBufferPass& pass, VkSampler nearestSampler) {
    for (uint32_t i = 0; i < pass.targets.size(); ++i)
        writer.image(set, i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pass.targets[i].view, nearestSampler,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const GpuScene* scene = pass.visibilityScene;
    if (!scene) return;
    writer.buffer(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->vertices.buffer)
        .buffer(set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->indices.buffer)
        .buffer(set, 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->drawTable.buffer)
        .buffer(set, 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->materials.buffer);
    for (uint32_t i = 0; i < scene->textures.size(); ++i)  // sampled as the G-buffer pass samples them
        writer.image(set, 5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, scene->textures[i].view, scene->textureSampler,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, i);
}

void addTargetReadDefines(ShaderSource& s, const GBufferPass& pass) {
    if (!pass.visibilityScene) return;
    s.defines.push_back({"TEXTURE_COUNT", std::to_string(pass.visibilityScene->textures.size())});
    if (pass.nonUniformTextureIndexing) s.defines.push_back({"GBL_NONUNIFORM_TEXTURE_INDEXING", "1"});
}

LightingPass createLightingPass(const VulkanContext& ctx, const GBufferWiring& wiring, const LightingInputs& in,
                                uint32_t width, uint32_t height) {
    LightingPass pass;
    pass.width = width;
    pass.height = height;
    ImageDesc d;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = width;
    d.height = height;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    pass.hdr = createImage(ctx, d);
    ImageDesc a = d;
    if (!in.accumulate) a.width = a.height = 1;
    a.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    pass.accumulation = createImage(ctx, a);

    std::vector<Binding> set0 = {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
        {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},  // emissive = forward: scene-colour emissive (else depth)
        {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},  // ground truth: the environment's sampling table
        {11, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},   // ground truth: the progressive accumulation
    };
    const bool lightPrePass = !wiring.lightBufferGlsl.empty();
    if (lightPrePass) set0.push_back({9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});  // the light buffers' words
    const std::vector<Binding> set1 = targetReadBindings(*in.gbuffer);
    const std::vector<Binding> set2 = in.materialPass ? targetReadBindings(*in.materialPass) : std::vector<Binding>{};
    pass.setCount = in.materialPass ? 3 : 2;
    pass.setLayouts[0] = createSetLayout(ctx.device, set0, VK_SHADER_STAGE_COMPUTE_BIT);
    pass.setLayouts[1] = createSetLayout(ctx.device, set1, VK_SHADER_STAGE_COMPUTE_BIT);
    if (in.materialPass) pass.setLayouts[2] = createSetLayout(ctx.device, set2, VK_SHADER_STAGE_COMPUTE_BIT);
    pass.pipelineLayout = createPipelineLayout(
        ctx.device, std::vector<VkDescriptorSetLayout>(pass.setLayouts, pass.setLayouts + pass.setCount), sizeof(uint32_t),
        VK_SHADER_STAGE_COMPUTE_BIT);
    pass.pool = createPoolFor(ctx.device, {set0, set1, set2});
    for (uint32_t i = 0; i < pass.setCount; ++i) pass.sets[i] = allocateSet(ctx.device, pass.pool, pass.setLayouts[i]);

    DescriptorWriter writer;
    writer.buffer(pass.sets[0], 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, in.frameConstants->buffer)
        .buffer(pass.sets[0], 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, in.lights->buffer)
        .image(pass.sets[0], 2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.gbuffer->depth.view, in.nearestSampler,
               VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
        .image(pass.sets[0], 3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.environment->view,
               in.environmentSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .image(pass.sets[0], 4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pass.hdr.view, VK_NULL_HANDLE,
               VK_IMAGE_LAYOUT_GENERAL)
        .image(pass.sets[0], 5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.ibl->environmentCube.view,
               in.ibl->cubeSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .image(pass.sets[0], 6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.ibl->prefiltered.view,
               in.ibl->cubeSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .image(pass.sets[0], 7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.ibl->brdfLut.view, in.ibl->lutSampler,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .buffer(pass.sets[0], 10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, in.ibl->environmentSampling.buffer)
        .image(pass.sets[0], 11, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pass.accumulation.view, VK_NULL_HANDLE,
               VK_IMAGE_LAYOUT_GENERAL);
    const bool emissive = in.gbuffer->emissive.image != VK_NULL_HANDLE;
    writer.image(pass.sets[0], 8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                 emissive ? in.gbuffer->emissive.view : in.gbuffer->depth.view, in.nearestSampler,
                 emissive ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    if (lightPrePass) writer.buffer(pass.sets[0], 9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, in.lightBufferWords->buffer);
    writeTargetReadSet(writer, pass.sets[1], *in.gbuffer, in.nearestSampler);
    if (in.materialPass)
        for (uint32_t i = 0; i < in.materialPass->targets.size(); ++i)
            writer.image(pass.sets[2], i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.materialPass->targets[i].view,
                         in.nearestSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    writer.flush(ctx.device);

    ShaderSource cs = loadShaderFile("lighting_pass.comp.glsl");
    cs.virtualFiles["gbuffer_wiring.glsl"] = wiring.glsl;
    addSpaceDefines(cs, wiring);
    addTargetReadDefines(cs, *in.gbuffer);
    if (lightPrePass) {
        cs.virtualFiles["light_buffers.glsl"] = wiring.lightBufferGlsl;
        cs.defines.push_back({"LIGHT_PRE_PASS", "1"});
    }
    cs.name = "lighting_pass.comp.glsl (layout " + wiring.layoutName + ")";
    if (emissive) cs.defines.push_back({"EMISSIVE_FORWARD", "1"});
    VkShaderModule module = createShaderModule(ctx.device, compileGlsl(cs));
    pass.pipeline = createComputePipeline(ctx, pass.pipelineLayout, module);
    vkDestroyShaderModule(ctx.device, module, nullptr);
    return pass;
}

void recordLightingPass(VkCommandBuffer cmd, const LightingPass& pass, uint32_t batch) {
    if (batch == 0) {
        transitionImage(cmd, pass.hdr, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        transitionImage(cmd, pass.accumulation, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipelineLayout, 0, pass.setCount, pass.sets, 0,
                            nullptr);
    vkCmdPushConstants(cmd, pass.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(batch), &batch);
    vkCmdDispatch(cmd, (pass.width + 7) / 8, (pass.height + 7) / 8, 1);
    fullBarrier(cmd);
}

void destroyLightingPass(const VulkanContext& ctx, LightingPass& pass) {
    destroyImage(ctx, pass.hdr);
    destroyImage(ctx, pass.accumulation);
    if (pass.pipeline) vkDestroyPipeline(ctx.device, pass.pipeline, nullptr);
    if (pass.pipelineLayout) vkDestroyPipelineLayout(ctx.device, pass.pipelineLayout, nullptr);
    for (auto& l : pass.setLayouts)
        if (l) vkDestroyDescriptorSetLayout(ctx.device, l, nullptr);
    if (pass.pool) vkDestroyDescriptorPool(ctx.device, pass.pool, nullptr);
    pass = LightingPass{};
}

}  // namespace gbl
