#include "decode_pass.h"

#include <algorithm>
#include <cstring>
#include <span>

#include "parallel_for.h"
#include "shader_compiler.h"
#include "stage_clock.h"
#include "vk_pipeline.h"
#include "warm_up_times.h"

namespace gbl {

namespace {
constexpr int kFloatsPerPixel = 20;  // five vec4, see DecodedPixel in decode_pass.comp.glsl
constexpr int kLayerFloatsPerPixel = 36;  // nine with GBL_LAYERS (a scene with material layers)
// Rows per band: the read-back buffer holds one band, not the frame (at 3840x2160 the whole
// frame would be 663 MB on top of the SurfaceImages it is copied into). A multiple of the
// shader's 8-row workgroups.
constexpr size_t kBandBytes = size_t(64) << 20;
uint32_t bandRows(uint32_t width, uint32_t height, int floatsPerPixel) {
    const size_t rowBytes = size_t(width) * size_t(floatsPerPixel) * sizeof(float);
    const uint32_t rows = uint32_t(std::max<size_t>(8, kBandBytes / rowBytes / 8 * 8));
    return std::min(rows, (height + 7) / 8 * 8);
}
// `layers`: the scene's GBL_LAYERS variant writes eight images (the layers' four after the surfaces').
std::vector<Binding> decodeToImagesSet0(bool layers) {
    return {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, layers ? 8u : 4u},
    };
}
std::vector<Binding> decodeSet0() {
    return {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
    };
}
}  // namespace

namespace {

// The decode pass's pipeline, from `memo`: writing the band buffer (set 0 binding 2; the host
// read-back), or `toImages`, the GBL_DECODE_TO_IMAGES variant writing four RGBA32F images (set 0
// binding 3; the GPU evaluation's input). Views and IBL modes after the first compile nothing.
PassPipeline decodePipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const TargetReadScene& scene,
                            PipelineMemo& memo, bool toImages) {
    const size_t materialTargets = wiring.materialPass ? wiring.materialTargetFormats.size() : 0;
    const uint32_t setCount = wiring.materialPass ? 3 : 2;
    ShaderSource cs = loadShaderFile("decode_pass.comp.glsl");
    cs.virtualFiles["gbuffer_wiring.glsl"] = wiring.glsl;
    addSpaceDefines(cs, wiring);
    addTargetReadDefines(cs, scene);  // a visibility buffer's TEXTURE_COUNT: in the key below
    if (toImages) cs.defines.push_back({"GBL_DECODE_TO_IMAGES", "1"});
    cs.name = "decode_pass.comp.glsl (layout " + wiring.layoutName + (toImages ? ", to images)" : ")");
    const std::string key = std::string(toImages ? "decode-images|" : "decode|") + shaderMemoKey(cs) + "|targets " +
                            std::to_string(wiring.targetFormats.size()) + " " + std::to_string(materialTargets) +
                            " sets " + std::to_string(setCount);
    return memo.getOrBuild(ctx.device, key, [&] {
        const std::vector<uint32_t> spirv = compileGlsl(cs);  // first: a failed compile leaks nothing
        std::vector<Binding> materialBindings;
        for (uint32_t i = 0; i < materialTargets; ++i)
            materialBindings.push_back({i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
        MemoPipeline p;
        p.setLayouts = {createSetLayout(ctx.device, toImages ? decodeToImagesSet0(scene.layers != 0) : decodeSet0(),
                                        VK_SHADER_STAGE_COMPUTE_BIT),
                        createSetLayout(ctx.device, targetReadBindings(wiring.targetFormats.size(), scene),
                                        VK_SHADER_STAGE_COMPUTE_BIT)};
        if (wiring.materialPass)
            p.setLayouts.push_back(createSetLayout(ctx.device, materialBindings, VK_SHADER_STAGE_COMPUTE_BIT));
        p.layout = createPipelineLayout(ctx.device, p.setLayouts, 4, VK_SHADER_STAGE_COMPUTE_BIT);
        VkShaderModule module = createShaderModule(ctx.device, spirv);
        p.pipeline = createComputePipeline(ctx, p.layout, module);
        vkDestroyShaderModule(ctx.device, module, nullptr);
        return p;
    });
}

// One dispatch's descriptor sets: a pool and `layouts`' sets, with set 0's frame constants
// (binding 0) and depth (1), set 1 the G-buffer, set 2 the material pass written into `writer`;
// the caller adds its output binding (2: the band buffer, 3: the four images) and flushes.
struct DecodeSets {
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> sets;
};
DecodeSets writeDecodeSets(const VulkanContext& ctx, const std::vector<VkDescriptorSetLayout>& layouts,
                           const std::vector<Binding>& set0, const GBufferPass& gbuffer,
                           const GBufferPass* materialPass, const Buffer& frameConstants, VkSampler nearestSampler,
                           DescriptorWriter& writer) {
    const std::vector<Binding> set1 = targetReadBindings(gbuffer);
    const std::vector<Binding> set2 = materialPass ? targetReadBindings(*materialPass) : std::vector<Binding>{};
    DecodeSets d;
    d.pool = createPoolFor(ctx.device, {set0, set1, set2});
    for (VkDescriptorSetLayout l : layouts) d.sets.push_back(allocateSet(ctx.device, d.pool, l));
    writer.buffer(d.sets[0], 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, frameConstants.buffer)
        .image(d.sets[0], 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, gbuffer.depth.view, nearestSampler,
               VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    writeTargetReadSet(writer, d.sets[1], gbuffer, nearestSampler);
    if (materialPass)
        for (uint32_t i = 0; i < materialPass->targets.size(); ++i)
            writer.image(d.sets[2], i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, materialPass->targets[i].view,
                         nearestSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return d;
}

}  // namespace

PassPipeline decodePassPipeline(const VulkanContext& ctx, const GBufferWiring& wiring, const TargetReadScene& scene,
                                PipelineMemo& memo, bool toImages) {
    return decodePipeline(ctx, wiring, scene, memo, toImages);
}

std::array<GpuImage, 8> decodeSurfacesOnDevice(const VulkanContext& ctx, const GBufferWiring& wiring,
                                               const GBufferPass& gbuffer, const Buffer& frameConstants,
                                               VkSampler nearestSampler, const GBufferPass* materialPass,
                                               uint32_t rows, PipelineMemo& memo) {
    const uint32_t w = gbuffer.depth.extent.width, h = rows;
    const TargetReadScene readScene = targetReadScene(gbuffer);
    const uint32_t count = readScene.layers != 0 ? 8u : 4u;  // the layers' four in a scene with them
    std::array<GpuImage, 8> all;
    const std::span<GpuImage> images(all.data(), count);
    for (GpuImage& im : images) {
        ImageDesc desc;
        desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        desc.width = w;
        desc.height = h;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        im = createImage(ctx, desc);
    }
    const PassPipeline built = decodePipeline(ctx, wiring, readScene, memo, true);
    DescriptorWriter writer;
    DecodeSets d = writeDecodeSets(ctx, built.entry->setLayouts, decodeToImagesSet0(count == 8), gbuffer, materialPass,
                                   frameConstants, nearestSampler, writer);
    std::vector<VkDescriptorSet>& sets = d.sets;
    for (uint32_t k = 0; k < count; ++k)
        writer.image(sets[0], 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, images[k].view, VK_NULL_HANDLE,
                     VK_IMAGE_LAYOUT_GENERAL, k);
    writer.flush(ctx.device);
    const uint32_t firstRow = 0;
    auto record = [&](VkCommandBuffer cmd, uint32_t groupsX, uint32_t groupsY) {
        for (const GpuImage& im : images) transitionImage(cmd, im, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, built.entry->pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, built.entry->layout, 0, uint32_t(sets.size()),
                                sets.data(), 0, nullptr);
        vkCmdPushConstants(cmd, built.entry->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &firstRow);
        vkCmdDispatch(cmd, groupsX, groupsY, 1);
        fullBarrier(cmd);
    };
    if (memo.firstUse(built.entry)) {
        // llvmpipe compiles at first dispatch: timed as the compile it is (renderer.cpp's warm-up).
        ScopedStage timed(Stage::ShaderCompile);
        ScopedWarmUp warmUp("decode", "decode to images (layout " + wiring.layoutName + ")");
        ctx.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, 1, 1); });
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, (w + 7) / 8, (h + 7) / 8); });
    vkDestroyDescriptorPool(ctx.device, d.pool, nullptr);
    return all;
}

SurfaceImages decodeSurfaces(const VulkanContext& ctx, const GBufferWiring& wiring, const GBufferPass& gbuffer,
                             const Buffer& frameConstants, VkSampler nearestSampler,
                             const std::vector<float>& depthValues, const GBufferPass* materialPass,
                             uint32_t bandRowsWanted, PipelineMemo& memo) {
    const uint32_t w = gbuffer.depth.extent.width, h = uint32_t(depthValues.size() / w);
    const size_t pixels = size_t(w) * h;
    const TargetReadScene readScene = targetReadScene(gbuffer);
    const bool layers = readScene.layers != 0;  // the shader's DecodedPixel has the layers' vec4s
    const int floatsPerPixel = layers ? kLayerFloatsPerPixel : kFloatsPerPixel;
    const uint32_t band = bandRowsWanted ? std::max(8u, bandRowsWanted / 8 * 8) : bandRows(w, h, floatsPerPixel);
    Buffer output = createBuffer(ctx, size_t(w) * band * size_t(floatsPerPixel) * sizeof(float),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);

    const PassPipeline built = decodePassPipeline(ctx, wiring, readScene, memo);
    const uint32_t setCount = uint32_t(built.entry->setLayouts.size());
    const VkPipelineLayout pipelineLayout = built.entry->layout;
    const VkPipeline pipeline = built.entry->pipeline;
    DescriptorWriter writer;
    DecodeSets d = writeDecodeSets(ctx, built.entry->setLayouts, decodeSet0(), gbuffer, materialPass, frameConstants,
                                   nearestSampler, writer);
    std::vector<VkDescriptorSet>& sets = d.sets;
    writer.buffer(sets[0], 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, output.buffer);
    writer.flush(ctx.device);

    auto record = [&](VkCommandBuffer cmd, uint32_t firstRow, uint32_t groupsX, uint32_t groupsY) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout, 0, setCount, sets.data(), 0,
                                nullptr);
        vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &firstRow);
        vkCmdDispatch(cmd, groupsX, groupsY, 1);
        fullBarrier(cmd);
    };
    if (memo.firstUse(built.entry)) {
        // A driver that compiles at first use (llvmpipe) compiles here, timed as the compile it is
        // (renderer.cpp's warm-up); the band's dispatch below rewrites the one workgroup's pixels.
        ScopedStage timed(Stage::ShaderCompile);
        ScopedWarmUp warmUp("decode", "decode (layout " + wiring.layoutName + ")");
        ctx.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, 0, 1, 1); });
    }

    SurfaceImages s;
    const int iw = int(w), ih = int(h);
    s.normal = Image(iw, ih, 3);
    s.baseColor = Image(iw, ih, 3);
    s.diffuseColor = Image(iw, ih, 3);
    s.specularColor = Image(iw, ih, 3);
    s.emissive = Image(iw, ih, 3);
    s.roughness = Image(iw, ih, 1);
    s.metallic = Image(iw, ih, 1);
    s.occlusion = Image(iw, ih, 1);
    s.viewDepth = Image(iw, ih, 1);
    s.depth = Image(iw, ih, 1);
    s.coverage.assign(pixels, 0);
    if (layers) s.allocateLayers(iw, ih);
    const float clearDepth = gbuffer.clearDepth;
    for (uint32_t firstRow = 0; firstRow < h; firstRow += band) {
        const uint32_t rows = std::min(band, h - firstRow);
        ctx.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, firstRow, (w + 7) / 8, (rows + 7) / 8); });
        const float* src = static_cast<const float*>(output.mapped);
        const size_t first = size_t(firstRow) * w;
        // Split across threads: much of this loop's time is the kernel faulting in fresh pages.
        parallelFor(int64_t(rows), 0, [&](int64_t y0, int64_t y1) {
            for (size_t i = first + size_t(y0) * w; i < first + size_t(y1) * w; ++i) {
                const float* p = src + (i - first) * size_t(floatsPerPixel);
                for (int c = 0; c < 3; ++c) {
                    s.normal.pixels[i * 3 + c] = p[0 + c];
                    s.baseColor.pixels[i * 3 + c] = p[4 + c];
                    s.diffuseColor.pixels[i * 3 + c] = p[8 + c];
                    s.specularColor.pixels[i * 3 + c] = p[12 + c];
                    s.emissive.pixels[i * 3 + c] = p[16 + c];
                }
                s.roughness.pixels[i] = p[3];
                s.metallic.pixels[i] = p[7];
                s.occlusion.pixels[i] = p[11];
                s.viewDepth.pixels[i] = p[19];
                s.depth.pixels[i] = depthValues[i];
                s.coverage[i] = depthValues[i] != clearDepth;
                if (!layers) continue;
                for (int c = 0; c < 3; ++c) {
                    s.coatNormal.pixels[i * 3 + c] = p[20 + c];
                    s.sheenColor.pixels[i * 3 + c] = p[24 + c];
                    s.anisotropyDirection.pixels[i * 3 + c] = p[28 + c];
                }
                s.coat.pixels[i] = p[23];
                s.sheenRoughness.pixels[i] = p[27];
                s.anisotropyStrength.pixels[i] = p[31];
                s.coatRoughness.pixels[i] = p[32];
            }
        });
    }

    destroyBuffer(ctx, output);
    vkDestroyDescriptorPool(ctx.device, d.pool, nullptr);
    return s;
}

}  // namespace gbl
