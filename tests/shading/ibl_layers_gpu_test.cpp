// The layers' GLSL (shaders/brdf_layers.glsl, shaders/ibl_layers.glsl) against their C++ twins
// (src/shading/brdf_layers.cpp, ibl_layers.cpp) on lavapipe: the layered direct light, the
// layered ground truth, and the per-pixel first sums of split-sum-shader, for random layered
// materials. The C++ twins are held to the specifications in brdf_layers_test and ibl_layers_test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "brdf.h"
#include "brdf_layers.h"
#include "environment_map.h"
#include "ibl_layers.h"
#include "ibl_math.h"
#include "ibl_precompute.h"
#include "image.h"
#include "shader_compiler.h"
#include "vk_pipeline.h"
#include "vk_resources.h"
#include "vk_test_support.h"

namespace gbl {
namespace {

class LayersGpuTest : public test::VulkanTest {};

// The same smooth radiance and sheen albedo function on both sides (any will do: what is tested
// is that the two implementations compute the same thing with them).
glm::vec3 smoothRadiance(glm::vec3 d) {
    return {1.0f + 0.5f * d.x + 0.3f * d.y * d.y, 0.8f + 0.2f * d.z + 0.6f * std::max(d.y, 0.0f), 1.2f - 0.4f * d.y};
}
float testAlbedo(float NoX, float r) { return 0.05f + 0.25f * r * (1.0f - 0.5f * NoX); }

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        glm::vec3 v(n(rng), n(rng), n(rng));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

struct Case {
    glm::vec3 N, V, L, diffuse, f0;
    float roughness;
    shading::Layers ly;
    glm::vec4 shiftA, shiftB;
};

// Packed as 12 vec4 per case, read back as 4 vec4 (direct, ground truth, sheen first sum,
// anisotropic first sum).
const char* kShader = R"(#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
layout(std430, set = 0, binding = 0) readonly buffer EnvironmentSampling { float environmentSampling[]; };
layout(std430, set = 0, binding = 1) readonly buffer Cases { vec4 cases[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push { uint samples; } pc;
#include "brdf.glsl"
#include "brdf_layers.glsl"
#include "environment_map.glsl"
vec3 sampleEnvironmentLod(vec3 d, float lod) {
    return vec3(1.0 + 0.5 * d.x + 0.3 * d.y * d.y, 0.8 + 0.2 * d.z + 0.6 * max(d.y, 0.0), 1.2 - 0.4 * d.y);
}
float sheenAlbedo(float NoX, float r) { return 0.05 + 0.25 * r * (1.0 - 0.5 * NoX); }
#define GBL_IBL_HAS_ENVIRONMENT
#include "environment_sampling.glsl"
#define GBL_IBL_HAS_ENVIRONMENT_SAMPLING
#define GBL_IBL_HAS_SHEEN_ALBEDO
#include "ibl_math.glsl"
#include "ibl_layers.glsl"
void main() {
    uint c = gl_GlobalInvocationID.x;
    uint b = 12u * c;
    vec3 N = cases[b].xyz, V = cases[b + 1u].xyz, L = cases[b + 2u].xyz;
    vec3 diffuse = cases[b + 3u].xyz, f0 = cases[b + 4u].xyz;
    float roughness = cases[b].w;
    Layers ly;
    ly.coat = cases[b + 5u].x; ly.coatRoughness = cases[b + 5u].y; ly.sheenRoughness = cases[b + 5u].z;
    ly.anisotropy = cases[b + 5u].w;
    ly.coatNormal = cases[b + 6u].xyz;
    ly.sheenColor = cases[b + 7u].xyz;
    ly.anisotropyT = cases[b + 8u].xyz;
    ly.anisotropyB = cases[b + 9u].xyz;
    vec4 shiftA = cases[b + 10u], shiftB = cases[b + 11u];
    float sheenV = sheenAlbedo(clamp(dot(N, V), 0.0, 1.0), ly.sheenRoughness);
    float sheenL = sheenAlbedo(clamp(dot(N, L), 0.0, 1.0), ly.sheenRoughness);
    results[4u * c] = vec4(evaluateDirectLightLayeredMode(N, V, L, diffuse, f0, roughness, ly, sheenV, sheenL,
                                                          vec3(2.0, 1.5, 1.0), FRESNEL_KARIS), 0.0);
    results[4u * c + 1u] = vec4(iblGroundTruthLayeredMis(diffuse, f0, roughness, N, V, ly, pc.samples, shiftA, shiftB), 0.0);
    results[4u * c + 2u] = vec4(sheenRadianceInShader(N, V, ly.sheenRoughness, 64u), 0.0);
    results[4u * c + 3u] = vec4(prefilteredRadianceInShaderAnisotropic(N, V, ly.anisotropyT, ly.anisotropyB,
                                                                       anisotropicAlphaT(roughness, ly.anisotropy),
                                                                       roughness * roughness, 64u), 0.0);
}
)";

double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// 24 random layered materials (coat, sheen, anisotropy, each on in about two thirds of them),
// random N, V, L, tilted coat normals. Tolerances (relative, on luminance): the direct light 1e-4
// (a driver's pow and exp against glibc's, amplified by the Charlie exponent as in
// brdf_layers_test's float-against-double bound; lavapipe: 1.6e-7); the ground truth's 256 steps
// 2e-3 with a smooth radiance (the same directions up to rounding: a sample's path may flip at a
// branch, as GroundTruthMisMatchesCpuTwin states for the base estimator; lavapipe: 5.8e-4); the
// first sums 1e-5 (lavapipe: 2.8e-7).
TEST_F(LayersGpuTest, LayeredShadingMatchesCpuTwins) {
    gbl::Image equirect(64, 32, 3);
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 64; ++i) {
            const glm::vec3 r = smoothRadiance(equirectUvToDirection(glm::vec2((i + 0.5f) / 64.0f, (j + 0.5f) / 32.0f)));
            for (int c = 0; c < 3; ++c) equirect.at(i, j, c) = r[c];
        }
    const std::vector<float> table = buildEnvironmentSampling(equirect);
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Case> cases;
    for (int k = 0; k < 24; ++k) {
        Case c;
        c.N = randomUnit(rng);
        c.V = randomUnit(rng);
        if (glm::dot(c.V, c.N) < 0.1f) c.V = glm::normalize(c.V + c.N * (0.1f - glm::dot(c.V, c.N) + 0.2f));
        c.L = randomUnit(rng);
        c.diffuse = glm::vec3(u(rng), u(rng), u(rng)) * 0.8f;
        c.f0 = k % 2 ? glm::vec3(0.04f) : glm::vec3(0.9f, 0.6f, 0.5f);
        c.roughness = 0.15f + 0.85f * u(rng);
        if (k % 3 != 0) {
            c.ly.coat = 0.2f + 0.8f * u(rng);
            c.ly.coatRoughness = 0.05f + 0.9f * u(rng);
        }
        c.ly.coatNormal = glm::normalize(c.N + 0.3f * randomUnit(rng));
        if (k % 3 != 1) c.ly.sheenColor = glm::vec3(u(rng), u(rng), u(rng));
        c.ly.sheenRoughness = 0.1f + 0.9f * u(rng);
        const glm::vec3 T = glm::normalize(glm::cross(c.N, randomUnit(rng)));
        c.ly.anisotropyT = T;
        c.ly.anisotropyB = glm::cross(c.N, T);
        if (k % 3 != 2) c.ly.anisotropy = u(rng);
        c.shiftA = glm::vec4(shading::randomShift(uint32_t(k), 5u, 0u), shading::randomShift(uint32_t(k), 5u, 1u));
        c.shiftB = glm::vec4(shading::randomShift(uint32_t(k), 5u, 2u), shading::randomShift(uint32_t(k), 5u, 3u));
        cases.push_back(c);
    }
    std::vector<glm::vec4> in;
    for (const Case& c : cases) {
        in.push_back(glm::vec4(c.N, c.roughness));
        in.push_back(glm::vec4(c.V, 0.0f));
        in.push_back(glm::vec4(c.L, 0.0f));
        in.push_back(glm::vec4(c.diffuse, 0.0f));
        in.push_back(glm::vec4(c.f0, 0.0f));
        in.push_back(glm::vec4(c.ly.coat, c.ly.coatRoughness, c.ly.sheenRoughness, c.ly.anisotropy));
        in.push_back(glm::vec4(c.ly.coatNormal, 0.0f));
        in.push_back(glm::vec4(c.ly.sheenColor, 0.0f));
        in.push_back(glm::vec4(c.ly.anisotropyT, 0.0f));
        in.push_back(glm::vec4(c.ly.anisotropyB, 0.0f));
        in.push_back(c.shiftA);
        in.push_back(c.shiftB);
    }
    const uint32_t n = uint32_t(cases.size()), samples = 256;
    VulkanContext& vk = ctx();
    Buffer tableBuf = createBufferWithData(vk, table.data(), table.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer casesBuf = createBufferWithData(vk, in.data(), in.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer out = createBuffer(vk, 4 * n * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    const std::vector<Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                           {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                           {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    VkDescriptorSetLayout setLayout = createSetLayout(vk.device, bindings, VK_SHADER_STAGE_COMPUTE_BIT);
    VkPipelineLayout pipelineLayout = createPipelineLayout(vk.device, {setLayout}, 4, VK_SHADER_STAGE_COMPUTE_BIT);
    VkDescriptorPool pool = createPoolFor(vk.device, {bindings});
    VkDescriptorSet set = allocateSet(vk.device, pool, setLayout);
    DescriptorWriter()
        .buffer(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, tableBuf.buffer)
        .buffer(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, casesBuf.buffer)
        .buffer(set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out.buffer)
        .flush(vk.device);
    ShaderSource cs{"layers_twin.comp", kShader, VK_SHADER_STAGE_COMPUTE_BIT, {}, {}};
    VkShaderModule module = createShaderModule(vk.device, compileGlsl(cs));
    VkPipeline pipeline = createComputePipeline(vk, pipelineLayout, module);
    vkDestroyShaderModule(vk.device, module, nullptr);
    vk.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout, 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &samples);
        vkCmdDispatch(cmd, n, 1, 1);
        fullBarrier(cmd);
    });
    const glm::vec4* gpu = static_cast<const glm::vec4*>(out.mapped);
    const shading::EnvironmentLodFn env = [](glm::vec3 d, float) { return smoothRadiance(d); };
    const shading::SheenAlbedoFn albedo = [](float x, float r) { return testAlbedo(x, r); };
    double worst[4] = {0, 0, 0, 0};
    for (uint32_t k = 0; k < n; ++k) {
        const Case& c = cases[k];
        const float sheenV = testAlbedo(std::clamp(glm::dot(c.N, c.V), 0.0f, 1.0f), c.ly.sheenRoughness);
        const float sheenL = testAlbedo(std::clamp(glm::dot(c.N, c.L), 0.0f, 1.0f), c.ly.sheenRoughness);
        const glm::vec3 cpu[4] = {
            shading::evaluateDirectLightLayeredMode(c.N, c.V, c.L, c.diffuse, c.f0, c.roughness, c.ly, sheenV, sheenL,
                                                    glm::vec3(2.0f, 1.5f, 1.0f), shading::FRESNEL_KARIS),
            shading::iblGroundTruthLayeredMis(env, table, albedo, c.diffuse, c.f0, c.roughness, c.N, c.V, c.ly, samples,
                                              c.shiftA, c.shiftB),
            shading::sheenRadianceInShader(env, c.N, c.V, c.ly.sheenRoughness, 64),
            shading::prefilteredRadianceInShaderAnisotropic(env, c.N, c.V, c.ly.anisotropyT, c.ly.anisotropyB,
                                                            shading::anisotropicAlphaT(c.roughness, c.ly.anisotropy),
                                                            c.roughness * c.roughness, 64)};
        const double tolerance[4] = {1e-4, 2e-3, 1e-5, 1e-5};
        for (int q = 0; q < 4; ++q) {
            const glm::vec3 g(gpu[4 * k + uint32_t(q)]);
            const double yc = luminance(cpu[q]), yg = luminance(g);
            EXPECT_TRUE(std::isfinite(yg)) << "case " << k << " output " << q;
            const double rel = std::abs(yg - yc) / std::max(std::abs(yc), 1e-4);
            worst[q] = std::max(worst[q], rel);
            EXPECT_LT(rel, tolerance[q]) << "case " << k << " output " << q << ": CPU " << yc << " GPU " << yg;
        }
    }
    std::printf("  worst relative difference GPU vs CPU: direct %.2e, ground truth %.2e, sheen sum %.2e, anisotropic sum %.2e\n",
                worst[0], worst[1], worst[2], worst[3]);
    vkDestroyPipeline(vk.device, pipeline, nullptr);
    vkDestroyPipelineLayout(vk.device, pipelineLayout, nullptr);
    vkDestroyDescriptorPool(vk.device, pool, nullptr);
    vkDestroyDescriptorSetLayout(vk.device, setLayout, nullptr);
    destroyBuffer(vk, tableBuf);
    destroyBuffer(vk, casesBuf);
    destroyBuffer(vk, out);
}

}  // namespace
}  // namespace gbl
