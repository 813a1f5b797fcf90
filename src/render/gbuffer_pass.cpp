#include "renderer_passes.h"

#include <algorithm>

#include "best_fit_normals.h"
#include "codec_tables.h"
#include "error.h"
#include "shader_compiler.h"
#include "stage_clock.h"
#include "visibility_wiring.h"
#include "vk_pipeline.h"

namespace gbl {

namespace {

constexpr VkFormat kEmissiveFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

bool isStencilFormat(VkFormat f) {
    return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D16_UNORM_S8_UINT;
}

}  // namespace

static std::vector<size_t> drawTriangleCounts(const GpuScene& scene) {
    std::vector<size_t> triangles;
    for (const Draw& d : scene.drawRanges) triangles.push_back(d.indexCount / 3);
    return triangles;
}

void checkVisibilityBufferSupport(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene) {
    const std::string problem = visibilityCapacityProblem(wiring, drawTriangleCounts(scene));
    if (!problem.empty()) throwUserError(problem);
    if (!ctx.primitiveIdInFragment)
        throwUserError("layout '" + wiring.layoutName + "': the device '" + ctx.info.name +
                       "' lacks geometryShader (gl_PrimitiveID in the id pass), which a visibility buffer needs; "
                       "choose another device (--device) or a G-buffer layout");
}

bool writesStencil(const GBufferWiring& wiring) {
    return isStencilFormat(wiring.depthFormat) && wiring.stencilWriteMask != 0;
}

VkPipeline createGBufferPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, VkPipelineLayout layout,
                                 const ShaderSource& vs, ShaderSource fs, bool sceneVertices) {
    fs.virtualFiles["gbuffer_wiring.glsl"] = wiring.glsl;
    addSpaceDefines(fs, wiring);
    // Both compiled before either module exists: a shader that fails to compile leaks nothing.
    const std::vector<uint32_t> vsSpirv = compileGlsl(vs), fsSpirv = compileGlsl(fs);
    return createGBufferPipelineSpirv(ctx, wiring, layout, vsSpirv, fsSpirv, sceneVertices);
}

VkPipeline createGBufferPipelineSpirv(const VulkanContext& ctx, const GBufferWiring& wiring, VkPipelineLayout layout,
                                      const std::vector<uint32_t>& vsSpirv, const std::vector<uint32_t>& fsSpirv,
                                      bool sceneVertices) {
    VkShaderModule vsModule = createShaderModule(ctx.device, vsSpirv);
    VkShaderModule fsModule = createShaderModule(ctx.device, fsSpirv);

    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vsModule;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fsModule;
    stages[1].pName = "main";

    VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[5] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
        {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
        {4, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv1)},
    };
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (sceneVertices) {
        vertexInput.vertexBindingDescriptionCount = 1;
        vertexInput.pVertexBindingDescriptions = &binding;
        vertexInput.vertexAttributeDescriptionCount = 5;
        vertexInput.pVertexAttributeDescriptions = attributes;
    }

    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;  // glTF double-sided materials; single-sided back faces are hidden by depth
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = wiring.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
    // The layout's targets, then (emissive = forward) the RGBA32F scene-colour emissive.
    std::vector<VkFormat> colorFormats = wiring.targetFormats;
    if (wiring.emissiveForward && !wiring.materialPass) colorFormats.push_back(kEmissiveFormat);
    std::vector<VkPipelineColorBlendAttachmentState> blend(colorFormats.size());
    for (auto& b : blend) b.colorWriteMask = 0xF;  // UINT targets: no blending
    VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    colorBlend.attachmentCount = uint32_t(blend.size());
    colorBlend.pAttachments = blend.data();
    // Stencil extras (scene pipelines only: the bit tests draw without them): every fragment that
    // passes the depth test replaces the layout's stencil bits with the draw's reference.
    const bool stencil = sceneVertices && writesStencil(wiring);
    if (stencil) {
        depth.stencilTestEnable = VK_TRUE;
        VkStencilOpState op{};
        op.failOp = VK_STENCIL_OP_KEEP;
        op.passOp = VK_STENCIL_OP_REPLACE;
        op.depthFailOp = VK_STENCIL_OP_KEEP;
        op.compareOp = VK_COMPARE_OP_ALWAYS;
        op.compareMask = 0xFF;
        op.writeMask = wiring.stencilWriteMask;
        depth.front = depth.back = op;
    }
    VkDynamicState dynamicStates[3] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                       VK_DYNAMIC_STATE_STENCIL_REFERENCE};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = stencil ? 3 : 2;
    dynamic.pDynamicStates = dynamicStates;

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(colorFormats.size());
    rendering.pColorAttachmentFormats = colorFormats.data();
    rendering.depthAttachmentFormat = wiring.depthFormat;
    rendering.stencilAttachmentFormat = isStencilFormat(wiring.depthFormat) ? wiring.depthFormat : VK_FORMAT_UNDEFINED;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &colorBlend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    VkPipeline pipeline = createGraphicsPipeline(ctx, info);
    vkDestroyShaderModule(ctx.device, vsModule, nullptr);
    vkDestroyShaderModule(ctx.device, fsModule, nullptr);
    return pipeline;
}

void createGBufferImages(const VulkanContext& ctx, const GBufferWiring& wiring, uint32_t width, uint32_t height,
                         GBufferPass& pass) {
    pass.clearDepth = wiring.reversedZ ? 0.0f : 1.0f;
    pass.clearWords = wiring.targetClearWords;
    pass.clearWords.resize(wiring.targetFormats.size(), std::array<uint32_t, 4>{0, 0, 0, 0});
    for (VkFormat format : wiring.targetFormats) {
        ImageDesc d;
        d.format = format;
        d.width = width;
        d.height = height;
        d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        pass.targets.push_back(createImage(ctx, d));
    }
    if (wiring.emissiveForward && !wiring.materialPass) {
        ImageDesc e;
        e.format = kEmissiveFormat;
        e.width = width;
        e.height = height;
        e.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        pass.emissive = createImage(ctx, e);
    }
    ImageDesc dd;
    dd.format = wiring.depthFormat;
    dd.width = width;
    dd.height = height;
    dd.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    dd.aspect = VK_IMAGE_ASPECT_DEPTH_BIT | (isStencilFormat(wiring.depthFormat) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    dd.viewAspect = VK_IMAGE_ASPECT_DEPTH_BIT;  // sampled as depth only
    pass.depth = createImage(ctx, dd);
}

GBufferWiring materialPassWiring(const GBufferWiring& wiring) {
    GBufferWiring material = wiring;
    material.layoutName = wiring.layoutName + " material pass";
    material.targetFormats = wiring.materialTargetFormats;
    material.targetClearWords.assign(wiring.materialTargetFormats.size(), std::array<uint32_t, 4>{0, 0, 0, 0});
    material.glsl = "#define MATERIAL_PASS_WRITE 1\n" + wiring.glsl;
    return material;
}

namespace {

std::vector<Binding> gbufferBindings(uint32_t textureCount) {
    return {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textureCount},
        {enc::kBestFitTableBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {enc::kCodecTablesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},  // codec_tables.glsl, set 0 here
    };
}
constexpr VkShaderStageFlags kGBufferStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

// What each material slot samples in the G-buffer pass (material.glsl's GBL_MATERIAL_SLOT_<slot>):
// nothing where no material binds a texture to the slot, the one texture by a constant index
// where one is bound there, the material's index where several are. Why: lavapipe runs a
// branch's both sides under a lane mask, so a slot's sample ran for every pixel, bound or not;
// on the built-in scene (4 of 7 slots bound, 3 of them to one texture) ue4's G-buffer pass took
// 268-315 ms at 1080p with every slot sampled, 247-259 ms so (gpu_pass_bench, alternated; the
// material's index in single-texture slots too: 254-287 ms). Every material's index in a slot is
// one of its listed textures or GBL_NO_TEXTURE (then the fallback is taken): the same texels.
// With KHR_texture_transform in the scene (`gradients`), every sample takes the slot's own
// gradients (material.glsl gblUvDx, gblUvDy; material_eval.glsl materialSlotUv says why).
void addMaterialSlotDefines(ShaderSource& fs, const MaterialTextureSlots& slots, bool gradients) {
    fs.defines.push_back({"GBL_MATERIAL_SLOTS", "1"});
    const std::string tail = gradients ? ", uv, gblUvDx, gblUvDy)" : ", uv)";
    const std::string call = gradients ? "textureGrad(" : "texture(";
    for (size_t k = 0; k < kMaterialTextureSlotCount; ++k) {
        const std::vector<uint32_t>& t = slots[k];
        const std::string sample = t.empty()       ? "vec4(0.0)"
                                   : t.size() == 1 ? call + "textures[" + std::to_string(t[0]) + "]" + tail
                                                   : call + "textures[index]" + tail;
        fs.defines.push_back({std::string("GBL_MATERIAL_SLOT_") + kMaterialTextureSlotNames[k] + "(index, uv)", sample});
    }
}

}  // namespace

PassPipeline gbufferPassPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene,
                                 PipelineMemo& memo) {
    const uint32_t textureCount = uint32_t(scene.textures.size());
    const ShaderSource vs = loadShaderFile("gbuffer_pass.vert.glsl");
    ShaderSource fs = loadShaderFile("gbuffer_pass.frag.glsl");
    fs.defines.push_back({"TEXTURE_COUNT", std::to_string(textureCount)});
    addMaterialSlotDefines(fs, scene.texturesBySlot, scene.uvTransforms);
    addSceneFeatureDefines(fs, scene.layers, scene.uvTransforms);  // material_eval.glsl
    // The encoders' threshold tables from GBufferPass::codecTables, not constant arrays: llvmpipe
    // JIT-compiles their binary searches far faster so (codec_tables.glsl).
    fs.defines.push_back({"GBL_CODEC_TABLES_SET", "0"});
    fs.defines.push_back({"GBL_CODEC_TABLES_BINDING", std::to_string(enc::kCodecTablesBinding)});
    fs.name = "gbuffer_pass.frag.glsl (layout " + wiring.layoutName + ")";
    // The key: the shaders' input as createGBufferPipeline compiles them (the wiring's GLSL and
    // [space] go in as a virtual file and defines) and every piece of fixed-function state it
    // reads from the wiring.
    ShaderSource keyed = fs;
    keyed.virtualFiles["gbuffer_wiring.glsl"] = wiring.glsl;
    addSpaceDefines(keyed, wiring);
    std::string key = "gbuffer|" + shaderMemoKey(vs) + "|" + shaderMemoKey(keyed) + "|formats";
    for (VkFormat f : wiring.targetFormats) key += " " + std::to_string(int(f));
    key += "|depth " + std::to_string(int(wiring.depthFormat)) + " reversed " + std::to_string(wiring.reversedZ) +
           " stencil " + std::to_string(writesStencil(wiring) ? int(wiring.stencilWriteMask) : 0) + " emissive " +
           std::to_string(wiring.emissiveForward && !wiring.materialPass);
    return memo.getOrBuild(ctx.device, key, [&] {
        MemoPipeline p;
        p.setLayouts = {createSetLayout(ctx.device, gbufferBindings(textureCount), kGBufferStages)};
        p.layout = createPipelineLayout(ctx.device, p.setLayouts, sizeof(gpu::DrawConstants), kGBufferStages);
        try {
            p.pipeline = createGBufferPipeline(ctx, wiring, p.layout, vs, fs, true);
        } catch (...) {  // a shader that does not compile: leave nothing behind
            vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
            vkDestroyDescriptorSetLayout(ctx.device, p.setLayouts[0], nullptr);
            throw;
        }
        return p;
    });
}

GBufferPass createGBufferPass(const VulkanContext& ctx, const GBufferWiring& wiring, const GpuScene& scene,
                              const Buffer& frameConstants, uint32_t width, uint32_t height, PipelineMemo& memo,
                              const CodecTableBuffers& tables) {
    GBufferPass pass;
    const uint32_t textureCount = uint32_t(scene.textures.size());
    const PassPipeline pipeline = gbufferPassPipeline(ctx, wiring, scene, memo);
    pass.setLayout = pipeline.entry->setLayouts.at(0);
    pass.pipelineLayout = pipeline.entry->layout;
    pass.pipeline = pipeline.entry->pipeline;
    pass.needsWarmUp = memo.firstUse(pipeline.entry);
    createGBufferImages(ctx, wiring, width, height, pass);
    const std::vector<Binding> bindings = gbufferBindings(textureCount);
    pass.pool = createPoolFor(ctx.device, {bindings});
    pass.set = allocateSet(ctx.device, pass.pool, pass.setLayout);
    pass.bestFitTable = tables.bestFitTable;
    pass.codecTables = tables.codecTables;
    pass.tablesBorrowed = true;
    DescriptorWriter writer;
    writer.buffer(pass.set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, frameConstants.buffer)
        .buffer(pass.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene.materials.buffer)
        .buffer(pass.set, enc::kBestFitTableBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pass.bestFitTable.buffer)
        .buffer(pass.set, enc::kCodecTablesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pass.codecTables.buffer);
    for (uint32_t i = 0; i < textureCount; ++i)
        writer.image(pass.set, 2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, scene.textures[i].view,
                     scene.textureSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, i);
    writer.flush(ctx.device);
    pass.pipelineFromMemo = true;
    pass.sceneLayers = scene.layers;
    pass.sceneUvTransforms = scene.uvTransforms;
    pass.writesStencil = writesStencil(wiring);
    pass.wiring.stencilFields = wiring.stencilFields;
    if (wiring.visibilityBuffer) {
        pass.visibilityScene = &scene;
        pass.nonUniformTextureIndexing = ctx.nonUniformSampledImageIndexing;
        if (const uint32_t n = wiring.visibilityIds.clusterTriangles) {
            const std::vector<size_t> triangles = drawTriangleCounts(scene);
            pass.drawFirstIds = visibilityFirstIds(wiring.visibilityIds, triangles);
            std::vector<std::array<uint32_t, 2>> table = visibilityClusterTable(n, triangles);
            if (table.empty()) table.push_back({0, 0});  // the binding is never empty
            pass.clusterTable = createBufferWithData(ctx, table.data(), table.size() * sizeof(table[0]),
                                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        }
    }
    return pass;
}

void beginGBufferPass(VkCommandBuffer cmd, const GBufferPass& pass) {
    const VkExtent2D extent = pass.depth.extent;
    for (const GpuImage& t : pass.targets)
        transitionImage(cmd, t, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    transitionImage(cmd, pass.depth, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);

    std::vector<VkRenderingAttachmentInfo> colors;
    for (size_t i = 0; i < pass.targets.size(); ++i) {
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = pass.targets[i].view;
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        // The layout's [clear] values, encoded as written values are (UINT targets: the words
        // themselves; material and native targets: 0).
        for (int k = 0; k < 4; ++k)
            a.clearValue.color.uint32[k] = i < pass.clearWords.size() ? pass.clearWords[i][size_t(k)] : 0u;
        colors.push_back(a);
    }
    if (pass.emissive.image) {
        transitionImage(cmd, pass.emissive, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = pass.emissive.view;
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // no geometry: no emission
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colors.push_back(a);
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = pass.depth.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {pass.clearDepth, 0};
    VkRenderingAttachmentInfo stencil = depth;

    // A band (renderRows): only its rows are cleared, drawn and so ever written. On a device whose
    // memory is host memory committed at first write (lavapipe), the rows outside it cost nothing.
    VkRect2D area{{0, 0}, extent};
    if (pass.renderRows) area = {{0, int32_t(pass.renderFirstRow)}, {extent.width, pass.renderRows}};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = area;
    info.layerCount = 1;
    info.colorAttachmentCount = uint32_t(colors.size());
    info.pColorAttachments = colors.data();
    info.pDepthAttachment = &depth;
    info.pStencilAttachment = (pass.depth.aspect & VK_IMAGE_ASPECT_STENCIL_BIT) ? &stencil : nullptr;
    vkCmdBeginRendering(cmd, &info);
    VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass.pipelineLayout, 0, 1, &pass.set, 0, nullptr);
}

void endGBufferPass(VkCommandBuffer cmd, const GBufferPass& pass) {
    vkCmdEndRendering(cmd);
    for (const GpuImage& t : pass.targets)
        transitionImage(cmd, t, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (pass.emissive.image)
        transitionImage(cmd, pass.emissive, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    transitionImage(cmd, pass.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
}

void recordGBufferPass(VkCommandBuffer cmd, const GBufferPass& pass, const GpuScene& scene) {
    beginGBufferPass(cmd, pass);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &scene.vertices.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (size_t i = 0; i < scene.draws.size(); ++i) {
        gpu::DrawConstants c = scene.draws[i];
        if (i < pass.drawFirstIds.size()) c.material.y = int32_t(pass.drawFirstIds[i]);  // clusters: first cluster
        vkCmdPushConstants(cmd, pass.pipelineLayout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(gpu::DrawConstants), &c);
        const Draw& d = scene.drawRanges[i];
        if (pass.writesStencil) {
            static const std::vector<std::pair<std::string, uint32_t>> none;
            const auto& values = size_t(d.material) < scene.materialStencilValues.size()
                                     ? scene.materialStencilValues[size_t(d.material)]
                                     : none;
            vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, stencilReference(pass.wiring, values));
        }
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
    }
    endGBufferPass(cmd, pass);
}

void recordGBufferWarmUp(VkCommandBuffer cmd, const GBufferPass& pass, const GpuScene& scene) {
    beginGBufferPass(cmd, pass);
    const VkRect2D onePixel{{0, int32_t(pass.renderFirstRow)}, {1, 1}};
    vkCmdSetScissor(cmd, 0, 1, &onePixel);
    if (!scene.drawRanges.empty()) {
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &scene.vertices.buffer, &offset);
        vkCmdBindIndexBuffer(cmd, scene.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        vkCmdPushConstants(cmd, pass.pipelineLayout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(gpu::DrawConstants), &scene.draws[0]);
        if (pass.writesStencil) vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
        const Draw& d = scene.drawRanges[0];
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
    }
    endGBufferPass(cmd, pass);
}

Buffer createCodecTablesBuffer(const VulkanContext& ctx) {
    const std::vector<float>& floats = enc::codecTableFloats();
    return createBufferWithData(ctx, floats.data(), floats.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

Buffer createBestFitTableBuffer(const VulkanContext& ctx) {
    const std::vector<uint32_t>& table = enc::bestFitNormalTable();
    return createBufferWithData(ctx, table.data(), table.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

void destroyCodecTableBuffers(const VulkanContext& ctx, CodecTableBuffers& tables) {
    if (tables.bestFitTable.buffer) destroyBuffer(ctx, tables.bestFitTable);
    if (tables.codecTables.buffer) destroyBuffer(ctx, tables.codecTables);
}

void destroyGBufferPass(const VulkanContext& ctx, GBufferPass& pass) {
    if (!pass.tablesBorrowed) {
        if (pass.bestFitTable.buffer) destroyBuffer(ctx, pass.bestFitTable);
        if (pass.codecTables.buffer) destroyBuffer(ctx, pass.codecTables);
    }
    pass.bestFitTable = Buffer{};
    pass.codecTables = Buffer{};
    for (auto& t : pass.targets) destroyImage(ctx, t);
    pass.targets.clear();
    if (pass.clusterTable.buffer) destroyBuffer(ctx, pass.clusterTable);
    pass.clusterTable = Buffer{};
    pass.drawFirstIds.clear();
    if (pass.emissive.image) destroyImage(ctx, pass.emissive);
    destroyImage(ctx, pass.depth);
    if (!pass.pipelineFromMemo) {
        if (pass.pipeline) vkDestroyPipeline(ctx.device, pass.pipeline, nullptr);
        if (pass.pipelineLayout) vkDestroyPipelineLayout(ctx.device, pass.pipelineLayout, nullptr);
        if (pass.setLayout) vkDestroyDescriptorSetLayout(ctx.device, pass.setLayout, nullptr);
    }
    if (pass.pool) vkDestroyDescriptorPool(ctx.device, pass.pool, nullptr);
    pass = GBufferPass{};
}

}  // namespace gbl
