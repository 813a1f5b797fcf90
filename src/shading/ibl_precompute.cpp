#include "ibl_precompute.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "error.h"
#include "shader_compiler.h"
#include "vk_pipeline.h"

namespace gbl {

std::vector<std::string> iblModeNames() {
    return {"ground-truth", "split-sum-shader", "split-sum", "envbrdf-approx", "bo2"};
}

std::string iblModeName(IblMode mode) { return iblModeNames().at(size_t(mode)); }

IblMode parseIblMode(const std::string& text) {
    const auto names = iblModeNames();
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == text) return IblMode(i);
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throwUserError("--ibl " + text + ": unknown IBL mode; known modes: " + known);
}

std::vector<std::string> brdfLutVariantNames() { return {"converged", "seed"}; }

void applyBrdfLutVariant(const std::string& text, IblSettings& settings) {
    if (text == "converged") {
        settings.lutEstimator = shading::BrdfLutEstimator::VisibleNormals;
        settings.lutSamples = shading::kBrdfLutConvergedSamples;
    } else if (text == "seed") {
        settings.lutEstimator = shading::BrdfLutEstimator::Seed;
        settings.lutSamples = shading::kBrdfLutSeedSamples;
    } else {
        throwUserError("--brdf-lut " + text + ": unknown BRDF LUT; known: converged (visible-normal sampling, " +
                       std::to_string(shading::kBrdfLutConvergedSamples) + " samples, the default), seed (the " +
                       "seed's IntegrateBRDF, " + std::to_string(shading::kBrdfLutSeedSamples) + " samples)");
    }
}

std::string brdfLutVariantName(const IblSettings& settings) {
    if (settings.lutEstimator == shading::BrdfLutEstimator::VisibleNormals &&
        settings.lutSamples == shading::kBrdfLutConvergedSamples)
        return "converged";
    if (settings.lutEstimator == shading::BrdfLutEstimator::Seed && settings.lutSamples == shading::kBrdfLutSeedSamples)
        return "seed";
    return std::string(settings.lutEstimator == shading::BrdfLutEstimator::Seed ? "seed" : "visible-normals") + ", " +
           std::to_string(settings.lutSamples) + " samples";
}

namespace {

uint32_t floorPow2(uint32_t v) {
    uint32_t p = 1;
    while (p * 2 <= v) p *= 2;
    return p;
}

// One compute pipeline with one descriptor set layout and a push-constant block.
struct Kernel {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
};

Kernel createKernel(const VulkanContext& ctx, const std::string& shaderFile, const std::vector<Binding>& bindings,
                    uint32_t pushBytes, uint32_t maxSets) {
    Kernel k;
    k.setLayout = createSetLayout(ctx.device, bindings, VK_SHADER_STAGE_COMPUTE_BIT);
    k.layout = createPipelineLayout(ctx.device, {k.setLayout}, pushBytes, VK_SHADER_STAGE_COMPUTE_BIT);
    k.pool = createPoolFor(ctx.device, std::vector<std::vector<Binding>>(maxSets, bindings));
    VkShaderModule module = createShaderModule(ctx.device, compileGlsl(loadShaderFile(shaderFile)));
    k.pipeline = createComputePipeline(ctx, k.layout, module);
    vkDestroyShaderModule(ctx.device, module, nullptr);
    return k;
}

void destroyKernel(const VulkanContext& ctx, Kernel& k) {
    vkDestroyPipeline(ctx.device, k.pipeline, nullptr);
    vkDestroyPipelineLayout(ctx.device, k.layout, nullptr);
    vkDestroyDescriptorSetLayout(ctx.device, k.setLayout, nullptr);
    vkDestroyDescriptorPool(ctx.device, k.pool, nullptr);
    k = Kernel{};
}

// Submits `record` between two timestamps; returns the GPU time in ms.
double submitTimed(const VulkanContext& ctx, const std::function<void(VkCommandBuffer)>& record) {
    return submitTimedSegments(ctx, {record})[0];
}

VkSampler cubeSamplerFor(const VulkanContext& ctx) {
    return createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                         VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

GpuImage createCubeImage(const VulkanContext& ctx, uint32_t size, uint32_t mips, VkImageUsageFlags extra) {
    ImageDesc d;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = d.height = size;
    d.mipLevels = mips;
    d.layers = 6;
    d.cube = true;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | extra;
    return createImage(ctx, d);
}

}  // namespace

IblSettings resolveIblSettings(const IblSettings& in, const EnvironmentMap& environment) {
    IblSettings s = in;
    if (s.sourceFaceSize == 0)
        s.sourceFaceSize = std::clamp(floorPow2(uint32_t(std::max(environment.image.width / 4, 1))), 32u, 512u);
    s.prefilteredFaceSize = std::clamp(s.prefilteredFaceSize, 1u, s.sourceFaceSize);
    s.prefilteredMips = std::clamp(s.prefilteredMips, 1u, mipCountFor(s.prefilteredFaceSize, s.prefilteredFaceSize));
    s.prefilterSamples = std::max(s.prefilterSamples, 1u);
    s.bruteForceSamples = std::max(s.bruteForceSamples, 1u);
    s.lutSize = std::max(s.lutSize, 1u);
    s.lutSamples = std::max(s.lutSamples, 1u);
    return s;
}

glm::vec3 cubeTexelDirection(uint32_t face, float x, float y, uint32_t size) {
    const float s = (x + 0.5f) / float(size) * 2.0f - 1.0f, t = (y + 0.5f) / float(size) * 2.0f - 1.0f;
    switch (face) {
        case 0: return {1.0f, -t, -s};
        case 1: return {-1.0f, -t, s};
        case 2: return {s, 1.0f, t};
        case 3: return {s, -1.0f, -t};
        case 4: return {s, -t, 1.0f};
        default: return {-s, -t, -1.0f};
    }
}

GpuImage createEnvironmentCube(const VulkanContext& ctx, const EnvironmentMap& environment, uint32_t faceSize,
                               double* gpuMs) {
    const Image& env = environment.image;
    std::vector<float> rgba(env.pixelCount() * 4, 1.0f);
    for (size_t i = 0; i < env.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = env.pixels[i * env.channels + c];
    ImageDesc ed;
    ed.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    ed.width = uint32_t(env.width);
    ed.height = uint32_t(env.height);
    ed.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    GpuImage equirect = createImage(ctx, ed);
    uploadImage(ctx, equirect, rgba.data(), rgba.size() * sizeof(float), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                false);
    VkSampler equirectSampler = createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                              VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);

    const uint32_t mips = mipCountFor(faceSize, faceSize);
    GpuImage cube = createCubeImage(ctx, faceSize, mips, VK_IMAGE_USAGE_STORAGE_BIT);
    std::vector<VkImageView> mipViews;
    for (uint32_t m = 0; m < mips; ++m) mipViews.push_back(createMipView(ctx, cube, m, true));

    const std::vector<Binding> toCube = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    const std::vector<Binding> down = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    Kernel k0 = createKernel(ctx, "ibl_equirect_to_cube.comp.glsl", toCube, 4, 1);
    Kernel k1 = createKernel(ctx, "ibl_downsample.comp.glsl", down, 4, std::max(mips, 1u));
    VkDescriptorSet set0 = allocateSet(ctx.device, k0.pool, k0.setLayout);
    DescriptorWriter w;
    w.image(set0, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, equirect.view, equirectSampler,
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .image(set0, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, mipViews[0], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    std::vector<VkDescriptorSet> downSets;
    for (uint32_t m = 1; m < mips; ++m) {
        VkDescriptorSet s = allocateSet(ctx.device, k1.pool, k1.setLayout);
        w.image(s, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, mipViews[m - 1], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL)
            .image(s, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, mipViews[m], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
        downSets.push_back(s);
    }
    w.flush(ctx.device);

    const double ms = submitTimed(ctx, [&](VkCommandBuffer cmd) {
        transitionImage(cmd, cube, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k0.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k0.layout, 0, 1, &set0, 0, nullptr);
        vkCmdPushConstants(cmd, k0.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &faceSize);
        vkCmdDispatch(cmd, (faceSize + 7) / 8, (faceSize + 7) / 8, 6);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k1.pipeline);
        for (uint32_t m = 1; m < mips; ++m) {
            fullBarrier(cmd);
            const uint32_t size = std::max(faceSize >> m, 1u);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k1.layout, 0, 1, &downSets[m - 1], 0,
                                    nullptr);
            vkCmdPushConstants(cmd, k1.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &size);
            vkCmdDispatch(cmd, (size + 7) / 8, (size + 7) / 8, 6);
        }
        transitionImage(cmd, cube, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    if (gpuMs) *gpuMs = ms;

    destroyKernel(ctx, k0);
    destroyKernel(ctx, k1);
    for (VkImageView v : mipViews) vkDestroyImageView(ctx.device, v, nullptr);
    vkDestroySampler(ctx.device, equirectSampler, nullptr);
    destroyImage(ctx, equirect);
    return cube;
}

GpuImage prefilterEnvironment(const VulkanContext& ctx, const GpuImage& sourceCube, const PrefilterParams& p,
                              double* gpuMs) {
    if (p.faceSize == 0 || p.mipCount == 0 || p.samples == 0 || p.mipCount > mipCountFor(p.faceSize, p.faceSize))
        throw std::invalid_argument("prefilterEnvironment: bad face size / mip count / samples");
    GpuImage out = createCubeImage(ctx, p.faceSize, p.mipCount, VK_IMAGE_USAGE_STORAGE_BIT);
    std::vector<VkImageView> views;
    for (uint32_t m = 0; m < p.mipCount; ++m) views.push_back(createMipView(ctx, out, m, true));
    VkSampler sampler = cubeSamplerFor(ctx);
    const std::vector<Binding> b = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    struct Push {
        float roughness;
        uint32_t numSamples;
        float sourceFaceSize;
        float maxLod;
        uint32_t outputSize;
        uint32_t filtered;
        float lodBias;
    };
    Kernel k = createKernel(ctx, "ibl_prefilter.comp.glsl", b, sizeof(Push), p.mipCount);
    std::vector<VkDescriptorSet> sets;
    DescriptorWriter w;
    for (uint32_t m = 0; m < p.mipCount; ++m) {
        VkDescriptorSet s = allocateSet(ctx.device, k.pool, k.setLayout);
        w.image(s, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, sourceCube.view, sampler,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .image(s, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, views[m], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
        sets.push_back(s);
    }
    w.flush(ctx.device);
    const double ms = submitTimed(ctx, [&](VkCommandBuffer cmd) {
        transitionImage(cmd, out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.pipeline);
        for (uint32_t m = 0; m < p.mipCount; ++m) {
            const uint32_t size = std::max(p.faceSize >> m, 1u);
            Push push{};
            push.roughness = p.mipCount > 1 ? float(m) / float(p.mipCount - 1) : 0.0f;  // roughnessFromMip
            push.numSamples = p.samples;
            push.sourceFaceSize = float(sourceCube.extent.width);
            push.maxLod = float(sourceCube.mipLevels - 1);
            push.outputSize = size;
            push.filtered = p.filtered ? 1u : 0u;
            push.lodBias = p.filtered ? p.lodBias : 0.0f;
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.layout, 0, 1, &sets[m], 0, nullptr);
            vkCmdPushConstants(cmd, k.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, (size + 7) / 8, (size + 7) / 8, 6);
        }
        transitionImage(cmd, out, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    if (gpuMs) *gpuMs = ms;
    destroyKernel(ctx, k);
    for (VkImageView v : views) vkDestroyImageView(ctx.device, v, nullptr);
    vkDestroySampler(ctx.device, sampler, nullptr);
    return out;
}

GpuImage computeBrdfLutGpu(const VulkanContext& ctx, uint32_t size, uint32_t samples,
                           shading::BrdfLutEstimator estimator, double* gpuMs) {
    if (size == 0 || samples == 0) throw std::invalid_argument("computeBrdfLutGpu: size and samples must be >= 1");
    ImageDesc d;
    d.format = VK_FORMAT_R32G32_SFLOAT;
    d.width = d.height = size;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    GpuImage lut = createImage(ctx, d);
    const std::vector<Binding> b = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    Kernel k = createKernel(ctx, "ibl_brdf_lut.comp.glsl", b, 12, 1);
    VkDescriptorSet s = allocateSet(ctx.device, k.pool, k.setLayout);
    DescriptorWriter w;
    w.image(s, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, lut.view, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL).flush(ctx.device);
    const uint32_t push[3] = {size, samples, uint32_t(estimator)};
    const double ms = submitTimed(ctx, [&](VkCommandBuffer cmd) {
        transitionImage(cmd, lut, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k.layout, 0, 1, &s, 0, nullptr);
        vkCmdPushConstants(cmd, k.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
        vkCmdDispatch(cmd, (size + 7) / 8, (size + 7) / 8, 1);
        transitionImage(cmd, lut, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    if (gpuMs) *gpuMs = ms;
    destroyKernel(ctx, k);
    return lut;
}

std::vector<CubeMip> downloadCube(const VulkanContext& ctx, const GpuImage& cube) {
    std::vector<CubeMip> mips;
    for (uint32_t m = 0; m < cube.mipLevels; ++m) {
        auto bytes = downloadImage(ctx, cube, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m);
        CubeMip mip;
        mip.size = std::max(cube.extent.width >> m, 1u);
        mip.rgba.resize(bytes.size() / sizeof(float));
        std::memcpy(mip.rgba.data(), bytes.data(), bytes.size());
        mips.push_back(std::move(mip));
    }
    return mips;
}

Image downloadBrdfLut(const VulkanContext& ctx, const GpuImage& lut) {
    auto bytes = downloadImage(ctx, lut, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    Image img(int(lut.extent.width), int(lut.extent.height), 2);
    std::memcpy(img.pixels.data(), bytes.data(), bytes.size());
    return img;
}

namespace {
void shBasis(glm::vec3 d, float y[9]) {
    y[0] = 0.282095f;
    y[1] = 0.488603f * d.y;
    y[2] = 0.488603f * d.z;
    y[3] = 0.488603f * d.x;
    y[4] = 1.092548f * d.x * d.y;
    y[5] = 1.092548f * d.y * d.z;
    y[6] = 0.315392f * (3.0f * d.z * d.z - 1.0f);
    y[7] = 1.092548f * d.x * d.z;
    y[8] = 0.546274f * (d.x * d.x - d.y * d.y);
}
}  // namespace

std::array<glm::vec3, 9> projectIrradianceSh(const CubeMip& mip) {
    std::array<glm::dvec3, 9> acc{};
    double totalWeight = 0.0;
    const uint32_t n = mip.size;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                const glm::vec3 d = cubeTexelDirection(f, float(x), float(y), n);
                const float len2 = glm::dot(d, d);
                // Texel solid angle ~ (2/n)^2 / |d|^3 (d on the unit cube).
                const double w = double(4.0f / (float(n) * float(n))) / (double(len2) * std::sqrt(double(len2)));
                const glm::vec3 dir = d / std::sqrt(len2);
                const size_t i = ((size_t(f) * n + y) * n + x) * 4;
                const glm::dvec3 L(mip.rgba[i], mip.rgba[i + 1], mip.rgba[i + 2]);
                float b[9];
                shBasis(dir, b);
                for (int k = 0; k < 9; ++k) acc[k] += L * (double(b[k]) * w);
                totalWeight += w;
            }
    // Normalise the discrete solid angles to 4 pi, then convolve with the clamped cosine:
    // A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 [Ramamoorthi & Hanrahan 2001].
    const double norm = 4.0 * M_PI / totalWeight;
    const double band[9] = {M_PI, 2 * M_PI / 3, 2 * M_PI / 3, 2 * M_PI / 3, M_PI / 4,
                            M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4};
    std::array<glm::vec3, 9> sh{};
    for (int k = 0; k < 9; ++k) sh[k] = glm::vec3(acc[k] * (norm * band[k]));
    return sh;
}

glm::vec3 evalIrradianceSh(const std::array<glm::vec3, 9>& sh, glm::vec3 n) {
    float b[9];
    shBasis(n, b);
    glm::vec3 e(0.0f);
    for (int k = 0; k < 9; ++k) e += sh[k] * b[k];
    return e;
}

IblMaps computeIblMaps(const VulkanContext& ctx, const EnvironmentMap& environment, const IblSettings& settings) {
    IblMaps maps;
    maps.settings = resolveIblSettings(settings, environment);
    const IblSettings& s = maps.settings;
    GpuImage cube = createEnvironmentCube(ctx, environment, s.sourceFaceSize, &maps.cubeMs);
    PrefilterParams p;
    p.faceSize = s.prefilteredFaceSize;
    p.mipCount = s.prefilteredMips;
    p.samples = s.bruteForce ? s.bruteForceSamples : s.prefilterSamples;
    p.filtered = !s.bruteForce;
    GpuImage pre = prefilterEnvironment(ctx, cube, p, &maps.prefilterMs);
    GpuImage lut = computeBrdfLutGpu(ctx, s.lutSize, s.lutSamples, s.lutEstimator, &maps.lutMs);
    maps.prefiltered = downloadCube(ctx, pre);
    maps.brdfLut = downloadBrdfLut(ctx, lut);
    // SH from a cube mip of at most 32 texels a side (box-filtered: the irradiance is smooth).
    const uint32_t shMip = cube.extent.width > 32 ? uint32_t(std::log2(double(cube.extent.width) / 32.0)) : 0u;
    auto bytes = downloadImage(ctx, cube, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, shMip);
    CubeMip m;
    m.size = std::max(cube.extent.width >> shMip, 1u);
    m.rgba.resize(bytes.size() / 4);
    std::memcpy(m.rgba.data(), bytes.data(), bytes.size());
    maps.irradianceSh = projectIrradianceSh(m);
    destroyImage(ctx, cube);
    destroyImage(ctx, pre);
    destroyImage(ctx, lut);
    return maps;
}

std::vector<float> buildEnvironmentSampling(const Image& env) {
    const int W = env.width, H = env.height;
    if (W < 1 || H < 1 || env.channels < 3) throw std::invalid_argument("buildEnvironmentSampling: need an RGB image");
    std::vector<double> lum(size_t(W) * H);
    double mean = 0.0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const float* p = &env.pixels[(size_t(j) * W + i) * env.channels];
            const double y = std::max(0.0, 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
            lum[size_t(j) * W + i] = std::isfinite(y) ? y : 0.0;
            mean += lum[size_t(j) * W + i];
        }
    mean /= double(lum.size());
    const double eps = mean > 0.0 ? 1e-3 * mean : 1.0;
    std::vector<double> weight(lum.size());
    for (int j = 0; j < H; ++j) {
        const double sinTheta = std::sin(M_PI * (j + 0.5) / H);
        for (int i = 0; i < W; ++i) {
            double m = 0.0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int jj = std::clamp(j + dj, 0, H - 1), ii = (i + di + W) % W;  // wraps in u
                    m = std::max(m, lum[size_t(jj) * W + ii]);
                }
            weight[size_t(j) * W + i] = (m + eps) * sinTheta;
        }
    }
    const size_t marginal = 4, conditional = marginal + H + 1, pdfs = conditional + size_t(H) * (W + 1);
    std::vector<float> t(pdfs + size_t(W) * H, 0.0f);
    t[0] = float(W);
    t[1] = float(H);
    std::vector<double> rowSum(H, 0.0);
    double total = 0.0;
    for (int j = 0; j < H; ++j) {
        for (int i = 0; i < W; ++i) rowSum[j] += weight[size_t(j) * W + i];
        total += rowSum[j];
    }
    double acc = 0.0;
    for (int j = 0; j < H; ++j) {
        t[marginal + j] = float(acc / total);
        acc += rowSum[j];
        double rowAcc = 0.0;
        const size_t row = conditional + size_t(j) * (W + 1);
        for (int i = 0; i < W; ++i) {
            t[row + i] = float(rowAcc / rowSum[j]);
            rowAcc += weight[size_t(j) * W + i];
            t[pdfs + size_t(j) * W + i] = float(weight[size_t(j) * W + i] / total * double(W) * double(H));
        }
        t[row + W] = 1.0f;
    }
    t[marginal + H] = 1.0f;
    return t;
}

double environmentSamplingPdf(const std::vector<float>& t, glm::vec3 d) {
    const int W = int(t.at(0)), H = int(t.at(1));
    const glm::vec2 uv = directionToEquirectUv(glm::normalize(d));
    const int i = std::min(int(uv.x * W), W - 1), j = std::min(int(uv.y * H), H - 1);
    const glm::vec3 n = glm::normalize(d);
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - double(n.y) * n.y));
    const double pUv = t.at(4 + size_t(H) + 1 + size_t(H) * (W + 1) + size_t(j) * W + i);
    return sinTheta > 0.0 ? pUv / (2.0 * M_PI * M_PI * sinTheta) : 0.0;
}

IblGpu createIblGpu(const VulkanContext& ctx, const EnvironmentMap& environment, const IblMaps& maps) {
    IblGpu g;
    {
        const std::vector<float> table = buildEnvironmentSampling(environment.image);
        g.environmentSampling = createBufferWithData(ctx, table.data(), table.size() * sizeof(float),
                                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    }
    g.sourceFaceSize = maps.settings.sourceFaceSize;
    g.prefilteredMips = uint32_t(maps.prefiltered.size());
    g.irradianceSh = maps.irradianceSh;
    g.environmentCube = createEnvironmentCube(ctx, environment, maps.settings.sourceFaceSize);
    if (maps.prefiltered.empty()) throw std::invalid_argument("createIblGpu: no pre-filtered mips");
    const uint32_t face = maps.prefiltered[0].size;
    g.prefiltered = createCubeImage(ctx, face, g.prefilteredMips, VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    ImageDesc ld;
    ld.format = VK_FORMAT_R32G32_SFLOAT;
    ld.width = uint32_t(maps.brdfLut.width);
    ld.height = uint32_t(maps.brdfLut.height);
    ld.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    g.brdfLut = createImage(ctx, ld);
    uploadImage(ctx, g.brdfLut, maps.brdfLut.pixels.data(), maps.brdfLut.pixels.size() * sizeof(float),
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false);
    // All pre-filtered mips in one staging buffer, one region per mip.
    VkDeviceSize total = 0;
    for (const CubeMip& m : maps.prefiltered) total += m.rgba.size() * sizeof(float);
    Buffer staging = createBuffer(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize offset = 0;
    for (uint32_t m = 0; m < g.prefilteredMips; ++m) {
        const CubeMip& mip = maps.prefiltered[m];
        if (mip.size != std::max(face >> m, 1u) || mip.rgba.size() != size_t(mip.size) * mip.size * 24)
            throw std::invalid_argument("createIblGpu: pre-filtered mip " + std::to_string(m) + " has the wrong size");
        std::memcpy(static_cast<char*>(staging.mapped) + offset, mip.rgba.data(), mip.rgba.size() * sizeof(float));
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 6};
        r.imageExtent = {mip.size, mip.size, 1};
        regions.push_back(r);
        offset += mip.rgba.size() * sizeof(float);
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        transitionImage(cmd, g.prefiltered, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, staging.buffer, g.prefiltered.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        transitionImage(cmd, g.prefiltered, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    destroyBuffer(ctx, staging);
    g.cubeSampler = cubeSamplerFor(ctx);
    g.lutSampler = createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                 VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    return g;
}

void destroyIblGpu(const VulkanContext& ctx, IblGpu& g) {
    destroyImage(ctx, g.environmentCube);
    destroyImage(ctx, g.prefiltered);
    destroyImage(ctx, g.brdfLut);
    destroyBuffer(ctx, g.environmentSampling);
    if (g.cubeSampler) vkDestroySampler(ctx.device, g.cubeSampler, nullptr);
    if (g.lutSampler) vkDestroySampler(ctx.device, g.lutSampler, nullptr);
    g = IblGpu{};
}

}  // namespace gbl
