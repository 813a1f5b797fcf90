// BRDF_GLTF's GLSL (shaders/brdf.glsl evaluateDirectLightGltf, brdf_layers.glsl
// evaluateDirectLightLayeredGltf, lightRangeWindow) against its C++ twin (src/shading/brdf.cpp,
// brdf_layers.cpp) on lavapipe, for random materials with and without layers. The C++ is held to
// the specification's text in brdf_gltf_test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "brdf.h"
#include "brdf_layers.h"
#include "shader_compiler.h"
#include "vk_pipeline.h"
#include "vk_resources.h"
#include "vk_test_support.h"

namespace gbl {
namespace {

class BrdfGltfGpuTest : public test::VulkanTest {};

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        glm::vec3 v(n(rng), n(rng), n(rng));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

float testAlbedo(float NoX, float r) { return 0.05f + 0.25f * r * (1.0f - 0.5f * NoX); }

// 10 vec4 per case in, 3 vec4 out (base, layered, the range window under each BRDF).
const char* kShader = R"(#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
layout(std430, set = 0, binding = 0) readonly buffer Cases { vec4 cases[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { vec4 results[]; };
#include "brdf.glsl"
#include "brdf_layers.glsl"
float sheenAlbedo(float NoX, float r) { return 0.05 + 0.25 * r * (1.0 - 0.5 * NoX); }
void main() {
    uint c = gl_GlobalInvocationID.x;
    uint b = 10u * c;
    vec3 N = cases[b].xyz, V = cases[b + 1u].xyz, L = cases[b + 2u].xyz;
    vec3 diffuse = cases[b + 3u].xyz, f0 = cases[b + 4u].xyz;
    float roughness = cases[b].w, dielectricF0 = cases[b + 1u].w, d2 = cases[b + 2u].w, range = cases[b + 3u].w;
    Layers ly;
    ly.coat = cases[b + 5u].x; ly.coatRoughness = cases[b + 5u].y; ly.sheenRoughness = cases[b + 5u].z;
    ly.anisotropy = cases[b + 5u].w;
    ly.coatNormal = cases[b + 6u].xyz;
    ly.sheenColor = cases[b + 7u].xyz;
    ly.anisotropyT = cases[b + 8u].xyz;
    ly.anisotropyB = cases[b + 9u].xyz;
    float sheenV = sheenAlbedo(clamp(dot(N, V), 0.0, 1.0), ly.sheenRoughness);
    float sheenL = sheenAlbedo(clamp(dot(N, L), 0.0, 1.0), ly.sheenRoughness);
    vec3 E = vec3(2.0, 1.5, 1.0);
    results[3u * c] = vec4(evaluateDirectLightGltf(N, V, L, diffuse, f0, dielectricF0, roughness, E), 0.0);
    results[3u * c + 1u] = vec4(evaluateDirectLightLayeredGltf(N, V, L, diffuse, f0, dielectricF0, roughness, ly,
                                                               sheenV, sheenL, E) + coatedEmissionGltf(vec3(0.3), ly, V), 0.0);
    results[3u * c + 2u] = vec4(lightRangeWindow(d2, range, BRDF_GLTF), lightRangeWindow(d2, range, BRDF_UE4), 0.0, 0.0);
}
)";

double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// 64 random cases: roughness 0 to 1 (a third at 0, the kMinGltfRoughness floor), each layer on in
// about two thirds. Tolerance 1e-4 relative on luminance (a driver's pow / exp / sqrt against
// glibc's, amplified by the Charlie exponent as in ibl_layers_gpu_test; the window: 1e-6 absolute).
TEST_F(BrdfGltfGpuTest, GltfDirectLightMatchesCpuTwin) {
    std::mt19937 rng(4545);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    struct Case {
        glm::vec3 N, V, L, diffuse, f0;
        float roughness, dielectricF0, d2, range;
        shading::Layers ly;
    };
    std::vector<Case> cases;
    for (int k = 0; k < 64; ++k) {
        Case c;
        c.N = randomUnit(rng);
        c.V = randomUnit(rng);
        if (glm::dot(c.V, c.N) < 0.1f) c.V = glm::normalize(c.V + c.N * (0.1f - glm::dot(c.V, c.N) + 0.2f));
        c.L = randomUnit(rng);
        if (glm::dot(c.L, c.N) < 0.05f) c.L = glm::normalize(c.L + c.N * (0.05f - glm::dot(c.L, c.N) + 0.3f));
        const float metallic = k % 4 == 0 ? 1.0f : u(rng);
        const glm::vec3 base(u(rng), u(rng), u(rng));
        c.diffuse = base * (1.0f - metallic);
        c.f0 = glm::mix(glm::vec3(0.04f), base, metallic);
        c.dielectricF0 = 0.04f;
        c.roughness = k % 3 == 0 ? 0.0f : u(rng);
        c.d2 = 4.0f * u(rng);
        c.range = k % 5 == 0 ? 0.0f : 0.5f + 1.5f * u(rng);
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
        cases.push_back(c);
    }
    std::vector<glm::vec4> in;
    for (const Case& c : cases) {
        in.push_back(glm::vec4(c.N, c.roughness));
        in.push_back(glm::vec4(c.V, c.dielectricF0));
        in.push_back(glm::vec4(c.L, c.d2));
        in.push_back(glm::vec4(c.diffuse, c.range));
        in.push_back(glm::vec4(c.f0, 0.0f));
        in.push_back(glm::vec4(c.ly.coat, c.ly.coatRoughness, c.ly.sheenRoughness, c.ly.anisotropy));
        in.push_back(glm::vec4(c.ly.coatNormal, 0.0f));
        in.push_back(glm::vec4(c.ly.sheenColor, 0.0f));
        in.push_back(glm::vec4(c.ly.anisotropyT, 0.0f));
        in.push_back(glm::vec4(c.ly.anisotropyB, 0.0f));
    }
    const uint32_t n = uint32_t(cases.size());
    VulkanContext& vk = ctx();
    Buffer casesBuf = createBufferWithData(vk, in.data(), in.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer out = createBuffer(vk, 3 * n * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    const std::vector<Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    VkDescriptorSetLayout setLayout = createSetLayout(vk.device, bindings, VK_SHADER_STAGE_COMPUTE_BIT);
    VkPipelineLayout pipelineLayout = createPipelineLayout(vk.device, {setLayout}, 0, VK_SHADER_STAGE_COMPUTE_BIT);
    VkDescriptorPool pool = createPoolFor(vk.device, {bindings});
    VkDescriptorSet set = allocateSet(vk.device, pool, setLayout);
    DescriptorWriter()
        .buffer(set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, casesBuf.buffer)
        .buffer(set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out.buffer)
        .flush(vk.device);
    ShaderSource cs{"brdf_gltf_twin.comp", kShader, VK_SHADER_STAGE_COMPUTE_BIT, {}, {}};
    VkShaderModule module = createShaderModule(vk.device, compileGlsl(cs));
    VkPipeline pipeline = createComputePipeline(vk, pipelineLayout, module);
    vkDestroyShaderModule(vk.device, module, nullptr);
    vk.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(cmd, n, 1, 1);
        fullBarrier(cmd);
    });
    const glm::vec4* gpu = static_cast<const glm::vec4*>(out.mapped);
    double worst[2] = {0, 0};
    for (uint32_t k = 0; k < n; ++k) {
        const Case& c = cases[k];
        const glm::vec3 E(2.0f, 1.5f, 1.0f);
        const float sheenV = testAlbedo(std::clamp(glm::dot(c.N, c.V), 0.0f, 1.0f), c.ly.sheenRoughness);
        const float sheenL = testAlbedo(std::clamp(glm::dot(c.N, c.L), 0.0f, 1.0f), c.ly.sheenRoughness);
        const glm::vec3 cpu[2] = {
            shading::evaluateDirectLightGltf(c.N, c.V, c.L, c.diffuse, c.f0, c.dielectricF0, c.roughness, E),
            shading::evaluateDirectLightLayeredGltf(c.N, c.V, c.L, c.diffuse, c.f0, c.dielectricF0, c.roughness, c.ly,
                                                    sheenV, sheenL, E) +
                shading::coatedEmissionGltf(glm::vec3(0.3f), c.ly, c.V)};
        for (int q = 0; q < 2; ++q) {
            const glm::vec3 g(gpu[3 * k + uint32_t(q)]);
            const double yc = luminance(cpu[q]), yg = luminance(g);
            EXPECT_TRUE(std::isfinite(yg)) << "case " << k << " output " << q;
            const double rel = std::abs(yg - yc) / std::max(std::abs(yc), 1e-4);
            worst[q] = std::max(worst[q], rel);
            EXPECT_LT(rel, 1e-4) << "case " << k << " output " << q << ": CPU " << yc << " GPU " << yg;
        }
        const glm::vec4 w = gpu[3 * k + 2];
        EXPECT_NEAR(w.x, shading::lightRangeWindow(c.d2, c.range, shading::BRDF_GLTF), 1e-6) << "case " << k;
        EXPECT_NEAR(w.y, shading::lightRangeWindow(c.d2, c.range, shading::BRDF_UE4), 1e-6) << "case " << k;
    }
    std::printf("  worst relative difference GPU vs CPU: base %.2e, layered %.2e\n", worst[0], worst[1]);
    vkDestroyPipeline(vk.device, pipeline, nullptr);
    vkDestroyPipelineLayout(vk.device, pipelineLayout, nullptr);
    vkDestroyDescriptorPool(vk.device, pool, nullptr);
    vkDestroyDescriptorSetLayout(vk.device, setLayout, nullptr);
    destroyBuffer(vk, casesBuf);
    destroyBuffer(vk, out);
}

}  // namespace
}  // namespace gbl
