// Deferred lighting's light buffers, GPU against CPU: the generated light_buffers.glsl of every
// shipped deferred-lighting layout (and of layouts written here for the encodings they do not
// use) encodes random light on the GPU; src/codec/light_buffer_wiring.h does the same on the CPU.
// Words must agree to the bit, and the decoded values exactly (decoders are exact). Two checks:
//   1. each buffer's encode / decode of random channel values, ranges chosen to hit every case
//      (zero, denormals, normals, the top of each range, beyond it, negative);
//   2. accumulateLight over four lights, as the lighting pass runs it (quantised light by light).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "layout_catalog.h"
#include "light_buffer_wiring.h"
#include "shader_compiler.h"
#include "layout_files.h"
#include "vk_test_support.h"

namespace gbl {
namespace {

constexpr uint32_t kItems = 4096;
constexpr int kLights = 4;

// A light value: a mix of magnitudes across every encoding's cases.
float randomLight(std::mt19937& rng) {
    static const float special[] = {0.0f, -1.0f, 1e-9f, 0.001953125f, 0.24f, 0.25f, 1.0f, 31.875f, 31.9f, 31.9375f,
                                    32.0f, 40.0f, 1000.0f, 65504.0f, 1e6f};
    std::uniform_int_distribution<int> pick(0, 9);
    const int p = pick(rng);
    if (p == 0) return special[std::uniform_int_distribution<int>(0, 14)(rng)];
    const float e = std::uniform_real_distribution<float>(-12.0f, 8.0f)(rng);
    return std::exp2(e) * (p == 1 ? -1.0f : 1.0f);
}

std::string shaderText(const Layout& layout) {
    std::string s = "#version 450\n#extension GL_GOOGLE_include_directive : require\n#include \"light_buffers.glsl\"\n"
                    "layout(local_size_x = 64) in;\n"
                    "layout(set = 0, binding = 0) readonly buffer In { vec4 values[]; };\n"
                    "layout(set = 0, binding = 1) writeonly buffer Words { uint words[]; };\n"
                    "layout(set = 0, binding = 2) writeonly buffer Decoded { vec4 decoded[]; };\n"
                    "void main() {\n    uint i = gl_GlobalInvocationID.x;\n    uint w[LIGHT_BUFFER_WORDS];\n"
                    "    for (int k = 0; k < LIGHT_BUFFER_WORDS; ++k) w[k] = 0u;\n";
    // 1. each buffer alone, on values[i * B + b]
    const size_t B = layout.lightBuffers.size();
    for (size_t b = 0; b < B; ++b) {
        s += "    encodeLightBuffer" + std::to_string(b) + "(values[i * " + std::to_string(B) + "u + " +
             std::to_string(b) + "u], w);\n";
        s += "    decoded[i * " + std::to_string(2 * B) + "u + " + std::to_string(b) + "u] = decodeLightBuffer" +
             std::to_string(b) + "(w);\n";
    }
    s += "    for (int k = 0; k < LIGHT_BUFFER_WORDS; ++k) words[i * uint(2 * LIGHT_BUFFER_WORDS) + uint(k)] = w[k];\n";
    // 2. accumulateLight over kLights lights: diffuse, specular from the values after the first block
    s += "    vec4 ch[LIGHT_BUFFER_COUNT];\n    for (int b = 0; b < LIGHT_BUFFER_COUNT; ++b) ch[b] = vec4(0.0);\n"
         "    for (int k = 0; k < LIGHT_BUFFER_WORDS; ++k) w[k] = 0u;\n";
    s += "    uint base = " + std::to_string(kItems * B) + "u + i * " + std::to_string(2 * kLights) + "u;\n";
    s += "    for (uint l = 0u; l < " + std::to_string(kLights) +
         "u; ++l) accumulateLight(ch, w, values[base + 2u * l].xyz, values[base + 2u * l + 1u].xyz);\n";
    s += "    for (int k = 0; k < LIGHT_BUFFER_WORDS; ++k) words[i * uint(2 * LIGHT_BUFFER_WORDS) + "
         "uint(LIGHT_BUFFER_WORDS + k)] = w[k];\n";
    for (size_t b = 0; b < B; ++b)
        s += "    decoded[i * " + std::to_string(2 * B) + "u + " + std::to_string(B + b) + "u] = ch[" +
             std::to_string(b) + "];\n";
    s += "}\n";
    return s;
}

bool sameFloat(float a, float b) {
    uint32_t x, y;
    std::memcpy(&x, &a, 4);
    std::memcpy(&y, &b, 4);
    return x == y || (a == 0.0f && b == 0.0f);
}

class LightBufferBits : public test::VulkanTest {
protected:
    void check(const Layout& layout, uint32_t seed) {
        VulkanContext& c = ctx();
        const size_t B = layout.lightBuffers.size();
        const int W = lightBufferWordsPerPixel(layout);
        std::mt19937 rng(seed);
        std::vector<glm::vec4> values(kItems * B + size_t(kItems) * 2 * kLights);
        for (glm::vec4& v : values) {
            v = {randomLight(rng), randomLight(rng), randomLight(rng), randomLight(rng)};
            // grey and near-grey light too (RGBK's ties between channels)
            if (std::uniform_int_distribution<int>(0, 7)(rng) == 0) v.y = v.z = v.x;
        }
        // accumulation: physical light (non-negative, below 1e4)
        for (size_t i = kItems * B; i < values.size(); ++i)
            for (int k = 0; k < 4; ++k) values[i][k] = std::min(std::abs(values[i][k]), 1e4f);

        const test::TestBuffer in = test::TestBuffer::holding(c, values);
        const test::TestBuffer words(c, size_t(kItems) * 2 * W * 4);
        const test::TestBuffer decoded(c, size_t(kItems) * 2 * B * sizeof(glm::vec4));
        ShaderSource cs{"light_buffer_bits.comp (layout " + layout.name + ")", shaderText(layout),
                        VK_SHADER_STAGE_COMPUTE_BIT, {}, {{"light_buffers.glsl", generateLightBufferGlsl(layout)}}};
        test::ComputeKernel(c, cs, {{test::storage(in), test::storage(words), test::storage(decoded)}}).dispatch(kItems / 64);
        const uint32_t* gw = words.mapped<const uint32_t>();
        const glm::vec4* gd = decoded.mapped<const glm::vec4>();

        size_t mismatches = 0, compared = 0;
        auto report = [&](bool ok, const std::string& what) {
            ++compared;
            if (!ok && mismatches++ < 8) ADD_FAILURE() << layout.name << ": " << what;
        };
        std::vector<uint32_t> cw(static_cast<size_t>(W));
        for (uint32_t i = 0; i < kItems; ++i) {
            // 1. each buffer alone
            std::fill(cw.begin(), cw.end(), 0u);
            uint32_t* w = cw.data();
            for (size_t b = 0; b < B; ++b) {
                const LightBuffer& lb = layout.lightBuffers[b];
                const glm::vec4 v = values[i * B + b];
                encodeLightBuffer(lb, v, w);
                const glm::vec4 d = decodeLightBuffer(lb, w);
                const glm::vec4 g = gd[i * 2 * B + b];
                for (int k = 0; k < 4; ++k)
                    report(sameFloat(d[k], g[k]), "item " + std::to_string(i) + " buffer " + lb.name + " channel " +
                                                      std::to_string(k) + " of " + std::to_string(v[k]) +
                                                      ": cpu decodes " + std::to_string(d[k]) + ", gpu " +
                                                      std::to_string(g[k]));
                w += lightBufferWords(lb);
            }
            for (int k = 0; k < W; ++k)
                report(cw[size_t(k)] == gw[size_t(i) * 2 * W + size_t(k)],
                       "item " + std::to_string(i) + " word " + std::to_string(k) + ": cpu " +
                           std::to_string(cw[size_t(k)]) + ", gpu " + std::to_string(gw[size_t(i) * 2 * W + size_t(k)]));
            // 2. accumulation
            std::vector<glm::vec4> ch(B, glm::vec4(0.0f));
            std::fill(cw.begin(), cw.end(), 0u);
            const size_t base = kItems * B + size_t(i) * 2 * kLights;
            for (int l = 0; l < kLights; ++l)
                accumulateLight(layout, ch, cw.data(), glm::vec3(values[base + 2 * l]), glm::vec3(values[base + 2 * l + 1]));
            for (int k = 0; k < W; ++k)
                report(cw[size_t(k)] == gw[size_t(i) * 2 * W + size_t(W + k)],
                       "accumulated item " + std::to_string(i) + " word " + std::to_string(k));
            for (size_t b = 0; b < B; ++b)
                for (int k = 0; k < 4; ++k)
                    report(sameFloat(ch[b][k], gd[i * 2 * B + B + b][k]),
                           "accumulated item " + std::to_string(i) + " buffer " + std::to_string(b));
        }
        EXPECT_EQ(mismatches, 0u) << layout.name << ": " << mismatches << " of " << compared << " differ";
        EXPECT_GT(compared, size_t(kItems) * 4);
    }
};

TEST_F(LightBufferBits, ShippedDeferredLightingLayoutsAgreeWithTheCpuMirror) {
    int checked = 0;
    uint32_t seed = 11;
    for (const Layout& layout : test::shippedLayouts()) {
        if (layout.pipeline != Pipeline::DeferredLighting) continue;
        SCOPED_TRACE(layout.name);
        check(layout, seed++);
        ++checked;
    }
    EXPECT_GE(checked, 3);  // crysis2-slim (float16), -x360 (float7e3), -ps3 (rgbk)
}

// The encodings and channel orders no shipped layout uses: R11G11B10F, RGBK in B8G8R8A8 with
// another range, and Engel's light pre-pass (one buffer: diffuse RGB + specular luminance).
TEST_F(LightBufferBits, OtherEncodingsAndEngelsLuminanceAgreeWithTheCpuMirror) {
    const Layout base = test::shippedLayout("crysis2-slim");
    auto variant = [&](std::vector<LightBuffer> buffers) {
        Layout l = base;
        l.lightBuffers = std::move(buffers);
        return l;
    };
    LightBuffer d, s;
    d.name = "diffuse";
    d.holds = {LightQuantity::DiffuseRgb};
    s.name = "specular";
    s.holds = {LightQuantity::SpecularRgb};
    d.format = s.format = "B10G11R11_UFLOAT_PACK32";
    d.encoding = s.encoding = LightBufferEncoding::Float111110;
    check(variant({d, s}), 101);
    d.format = s.format = "B8G8R8A8_UNORM";
    d.encoding = s.encoding = LightBufferEncoding::Rgbk;
    d.range = 6.0;
    s.range = 1000.0;
    check(variant({d, s}), 102);
    LightBuffer engel;
    engel.name = "light";
    engel.format = "R16G16B16A16_SFLOAT";
    engel.encoding = LightBufferEncoding::Float16;
    engel.holds = {LightQuantity::DiffuseRgb, LightQuantity::SpecularLuminance};
    check(variant({engel}), 103);
}

}  // namespace
}  // namespace gbl
