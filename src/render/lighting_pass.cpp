#include "renderer_passes.h"

#include <stdexcept>

#include "codec_tables.h"
#include "shader_compiler.h"
#include "vk_pipeline.h"

namespace gbl {

std::vector<Binding> targetReadBindings(size_t targetCount, const TargetReadScene& scene) {
    std::vector<Binding> bindings;
    for (uint32_t i = 0; i < targetCount; ++i) bindings.push_back({i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
    bindings.push_back({enc::kCodecTablesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    if (scene.visibility) {
        for (uint32_t b = 1; b <= 4; ++b) bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        bindings.push_back({5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, scene.textureCount});
        if (scene.clusters) bindings.push_back({6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    }
    return bindings;
}

TargetReadScene targetReadScene(const GBufferPass& pass) {
    TargetReadScene s;
    s.layers = pass.sceneLayers;
    s.uvTransforms = pass.sceneUvTransforms;
    if (const GpuScene* scene = pass.visibilityScene) {
        s.visibility = true;
        s.textureCount = uint32_t(scene->textures.size());
        s.nonUniformIndexing = pass.nonUniformTextureIndexing;
        s.texturesBySlot = scene->texturesBySlot;
        s.clusters = pass.clusterTable.buffer != VK_NULL_HANDLE;
    }
    return s;
}

TargetReadScene targetReadScene(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene) {
    TargetReadScene s;
    s.layers = scene.layers;
    s.uvTransforms = scene.uvTransforms;
    if (!wiring.visibilityBuffer) return s;
    s.visibility = true;
    s.textureCount = uint32_t(scene.textures.size());
    s.nonUniformIndexing = ctx.nonUniformSampledImageIndexing;
    s.texturesBySlot = scene.texturesBySlot;
    s.clusters = wiring.visibilityIds.clusterTriangles > 0;
    return s;
}

std::vector<Binding> targetReadBindings(const GBufferPass& pass) {
    return targetReadBindings(pass.targets.size(), targetReadScene(pass));
}

void writeTargetReadSet(DescriptorWriter& writer, VkDescriptorSet set, const GBufferPass& pass, VkSampler nearestSampler) {
    if (!pass.codecTables.buffer)
        throw std::logic_error("writeTargetReadSet: the G-buffer pass has no codec tables (createGBufferPass makes them)");
    writer.buffer(set, enc::kCodecTablesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pass.codecTables.buffer);
    for (uint32_t i = 0; i < pass.targets.size(); ++i)
        writer.image(set, i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pass.targets[i].view, nearestSampler,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const GpuScene* scene = pass.visibilityScene;
    if (!scene) return;
    writer.buffer(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->vertices.buffer)
        .buffer(set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->indices.buffer)
        .buffer(set, 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->drawTable.buffer)
        .buffer(set, 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene->materials.buffer);
    if (pass.clusterTable.buffer) writer.buffer(set, 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pass.clusterTable.buffer);
    for (uint32_t i = 0; i < scene->textures.size(); ++i)  // sampled as the G-buffer pass samples them
        writer.image(set, 5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, scene->textures[i].view, scene->textureSampler,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, i);
}

void addSceneFeatureDefines(ShaderSource& s, int layers, bool uvTransforms) {
    // Only what the scene has: a scene without layers or uv transforms compiles the passes as
    // before them (no define at all, so the shader text and its memo key are unchanged).
    if (layers != 0) s.defines.push_back({"GBL_LAYERS", std::to_string(layers)});
    if (uvTransforms) s.defines.push_back({"GBL_UV_TRANSFORMS", "1"});
}

void addTargetReadDefines(ShaderSource& s, const TargetReadScene& scene) {
    // The encodings' tables from the storage buffer, not constant arrays (codec_tables.glsl).
    s.defines.push_back({"GBL_CODEC_TABLES_SET", "1"});
    s.defines.push_back({"GBL_CODEC_TABLES_BINDING", std::to_string(enc::kCodecTablesBinding)});
    addSceneFeatureDefines(s, scene.layers, scene.uvTransforms);
    if (!scene.visibility) return;
    s.defines.push_back({"TEXTURE_COUNT", std::to_string(scene.textureCount)});
    if (scene.nonUniformIndexing) {
        s.defines.push_back({"GBL_NONUNIFORM_TEXTURE_INDEXING", "1"});
        return;
    }
    // The waterfall's candidates, a test per texture some material binds to the slot
    // (visibility_resolve.glsl); an empty list leaves the slot's texel zero, as no pixel reads it.
    for (size_t k = 0; k < kMaterialTextureSlotCount; ++k) {
        std::string tries;
        for (uint32_t i : scene.texturesBySlot[k]) tries += "GBL_RESOLVE_TRY(" + std::to_string(i) + ") ";
        s.defines.push_back({std::string("GBL_RESOLVE_SLOT_") + kMaterialTextureSlotNames[k], tries});
    }
}

namespace {

// Set 0's bindings; binding 9 (the light buffers' words) with a light pre-pass only.
std::vector<Binding> lightingSet0(bool lightPrePass) {
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
        {12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},  // the sheen's albedo table (1 x 1 without sheen)
    };
    if (lightPrePass) set0.push_back({9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    return set0;
}

std::vector<Binding> samplerBindings(size_t count) {
    std::vector<Binding> bindings;
    for (uint32_t i = 0; i < count; ++i) bindings.push_back({i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
    return bindings;
}

}  // namespace

PassPipeline lightingPassPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const TargetReadScene& scene,
                                  const LightingVariant& variant, PipelineMemo& memo) {
    const bool lightPrePass = !wiring.lightBufferGlsl.empty();
    const bool emissive = wiring.emissiveForward && !wiring.materialPass;  // createGBufferImages' rule
    const size_t materialTargets = wiring.materialPass ? wiring.materialTargetFormats.size() : 0;
    const uint32_t setCount = wiring.materialPass ? 3 : 2;
    ShaderSource cs = loadShaderFile("lighting_pass.comp.glsl");
    cs.virtualFiles["gbuffer_wiring.glsl"] = wiring.glsl;
    addSpaceDefines(cs, wiring);
    addTargetReadDefines(cs, scene);
    if (lightPrePass) {
        cs.virtualFiles["light_buffers.glsl"] = wiring.lightBufferGlsl;
        cs.defines.push_back({"LIGHT_PRE_PASS", "1"});
    }
    cs.name = "lighting_pass.comp.glsl (layout " + wiring.layoutName + ")";
    if (emissive) cs.defines.push_back({"EMISSIVE_FORWARD", "1"});
    // Specialised: one IBL mode and one Fresnel per pipeline (in the key through the defines);
    // without them the shader holds every mode behind run-time branches, all of which llvmpipe
    // compiles, and the pipeline serves every mode (LightingVariant).
    if (variant.specialised) {
        cs.defines.push_back({"GBL_IBL_MODE", std::to_string(int(variant.ibl))});
        cs.defines.push_back({"GBL_FRESNEL_MODE", std::to_string(variant.fresnelMode)});
        // Only a non-default BRDF adds its define: a UE4 pipeline's source (and memo key) stays as it was.
        if (variant.brdf != 0) cs.defines.push_back({"GBL_BRDF_MODEL", std::to_string(variant.brdf)});
    }
    // The shader's input and the set layouts (set 0 follows LIGHT_PRE_PASS, set 1 a visibility
    // buffer's TEXTURE_COUNT, both already in the key).
    const std::string key = "lighting|" + shaderMemoKey(cs) + "|targets " +
                            std::to_string(wiring.targetFormats.size()) + " " + std::to_string(materialTargets) +
                            " sets " + std::to_string(setCount);
    return memo.getOrBuild(ctx.device, key, [&] {
        const std::vector<uint32_t> spirv = compileGlsl(cs);  // first: a failed compile leaks nothing
        MemoPipeline p;
        p.setLayouts = {createSetLayout(ctx.device, lightingSet0(lightPrePass), VK_SHADER_STAGE_COMPUTE_BIT),
                        createSetLayout(ctx.device, targetReadBindings(wiring.targetFormats.size(), scene),
                                        VK_SHADER_STAGE_COMPUTE_BIT)};
        if (wiring.materialPass)
            p.setLayouts.push_back(
                createSetLayout(ctx.device, samplerBindings(materialTargets), VK_SHADER_STAGE_COMPUTE_BIT));
        p.layout = createPipelineLayout(ctx.device, p.setLayouts, sizeof(uint32_t), VK_SHADER_STAGE_COMPUTE_BIT);
        VkShaderModule module = createShaderModule(ctx.device, spirv);
        p.pipeline = createComputePipeline(ctx, p.layout, module);
        vkDestroyShaderModule(ctx.device, module, nullptr);
        return p;
    });
}

LightingPass createLightingPass(const VulkanContext& ctx, const GBufferWiring& wiring, const LightingInputs& in,
                                uint32_t width, uint32_t height, PipelineMemo& memo) {
    if (in.gbuffer->targets.size() != wiring.targetFormats.size() || (in.materialPass != nullptr) != wiring.materialPass ||
        (in.materialPass && in.materialPass->targets.size() != wiring.materialTargetFormats.size()))
        throw std::logic_error("createLightingPass: the G-buffer passes given are not the wiring's");
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

    const bool lightPrePass = !wiring.lightBufferGlsl.empty();
    const std::vector<Binding> set0 = lightingSet0(lightPrePass);
    const std::vector<Binding> set1 = targetReadBindings(*in.gbuffer);
    const std::vector<Binding> set2 = in.materialPass ? targetReadBindings(*in.materialPass) : std::vector<Binding>{};
    const bool emissive = in.gbuffer->emissive.image != VK_NULL_HANDLE;
    const PassPipeline pipeline = lightingPassPipeline(ctx, wiring, targetReadScene(*in.gbuffer), in.variant, memo);
    pass.setCount = uint32_t(pipeline.entry->setLayouts.size());
    for (uint32_t i = 0; i < pass.setCount; ++i) pass.setLayouts[i] = pipeline.entry->setLayouts[i];
    pass.pipelineLayout = pipeline.entry->layout;
    pass.pipeline = pipeline.entry->pipeline;
    pass.needsWarmUp = memo.firstUse(pipeline.entry);
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
               VK_IMAGE_LAYOUT_GENERAL)
        .image(pass.sets[0], 12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, in.sheenAlbedo->view, in.ibl->lutSampler,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
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

void recordLightingWarmUp(VkCommandBuffer cmd, const LightingPass& pass) {
    transitionImage(cmd, pass.hdr, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    transitionImage(cmd, pass.accumulation, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipelineLayout, 0, pass.setCount, pass.sets, 0,
                            nullptr);
    const uint32_t batch = 0;
    vkCmdPushConstants(cmd, pass.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(batch), &batch);
    vkCmdDispatch(cmd, 1, 1, 1);
    fullBarrier(cmd);
}

void destroyLightingPass(const VulkanContext& ctx, LightingPass& pass) {
    destroyImage(ctx, pass.hdr);
    destroyImage(ctx, pass.accumulation);
    // The pipeline and its layouts belong to the PipelineMemo.
    if (pass.pool) vkDestroyDescriptorPool(ctx.device, pass.pool, nullptr);
    pass = LightingPass{};
}

}  // namespace gbl
