// The engine layer encodings' GLSL (shaders/engine_encodings.glsl) against their C++ twins
// (src/encoding/engine_encodings.h) on lavapipe, bit for bit, on the inputs random Surfaces
// rarely reach: the exact ties where roundEven (unorm_round_even, coat_roughness_bevy) and
// floor(x + 0.5) part, the floats either side of every unorm_sqrt threshold, and UE's clear-coat
// bottom-normal delta, which no row stores yet (so gpu_cpu_bits_test does not run it). The C++
// twins are held to the engines' arithmetic in layer_packings_test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "encodings.h"
#include "layout_catalog.h"
#include "shader_compiler.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class LayerEncodingsGpu : public test::VulkanTest {};

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

float fromBits(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Scalars: x -> (unorm_round_even at 4 bits, coat_roughness_bevy at 4 bits, unorm_sqrt, unorm_signed
// at 8 bits), and their decodes' bits.
TEST_F(LayerEncodingsGpu, ScalarCodesAndDecodesEqualTheCpuTwins) {
    std::vector<float> xs;
    for (int k = 0; k <= 30; ++k) {  // every tie of x * 15 and x * 30, and the floats beside them
        for (double steps : {15.0, 30.0}) {
            const float t = float((k + 0.5) / steps);
            xs.insert(xs.end(), {t, std::nextafter(t, 0.0f), std::nextafter(t, 1.0f)});
        }
    }
    for (int k = 0; k < 255; ++k) {  // unorm_sqrt's thresholds and the floats beside them
        const float t = enc::kUnormSqrtEncodeThresholds[k];
        xs.insert(xs.end(), {t, std::nextafter(t, 0.0f), std::nextafter(t, 1.0f)});
    }
    std::mt19937 rng(40);
    std::uniform_real_distribution<float> u(-0.2f, 1.2f);
    for (float e : {0.0f, -0.0f, 1.0f, 0.5f, -1.0f, 2.0f}) xs.push_back(e);
    while (xs.size() % 64 != 0 || xs.size() < 4096) xs.push_back(u(rng));
    const size_t n = xs.size();
    std::vector<uint32_t> in(n * 4, 0u);
    for (size_t i = 0; i < n; ++i) in[i * 4] = bits(xs[i]);

    VulkanContext& c = ctx();
    const GBufferWiring w = generateWiring(loadLayout("bevy-deferred-clearcoat"));
    const test::TestBuffer input = test::TestBuffer::holding(c, in);
    const test::TestBuffer codes(c, n * 4 * sizeof(uint32_t));
    const std::string source = test::wiringKernel(R"(    float x = uintBitsToFloat(inputs[i].x);
    outputs[i] = uvec4(quantizeUnormRoundEven(x, 4u), encodeCoatRoughnessBevy(x, 4u), encodeUnormSqrt(x),
                       quantizeUnormSigned(x * 2.0 - 1.0, 8u));
)");
    ShaderSource cs{"layer_encodings.comp (test)", source, VK_SHADER_STAGE_COMPUTE_BIT, {}, {{"gbuffer_wiring.glsl", w.glsl}}};
    test::ComputeKernel(c, cs, {{test::storage(input), test::storage(codes)}}).dispatch(uint32_t(n / 64));
    const uint32_t* got = codes.mapped<const uint32_t>();
    size_t mismatches = 0, evenTies = 0;
    for (size_t i = 0; i < n; ++i) {
        const float x = xs[i];
        const uint32_t want[4] = {enc::quantizeUnormRoundEven(x, 4u), enc::encodeCoatRoughnessBevy(x, 4u),
                                  enc::encodeUnormSqrt(x), enc::quantizeUnormSigned(x * 2.0f - 1.0f, 8u)};
        const float t15 = std::fmin(std::fmax(x, 0.0f), 1.0f) * 15.0f;
        evenTies += t15 - std::floor(t15) == 0.5f && want[0] != enc::quantizeUnorm(x, 4u);
        for (int k = 0; k < 4; ++k)
            if (got[i * 4 + k] != want[k] && mismatches++ < 8)
                ADD_FAILURE() << "x " << x << " code " << k << ": GPU " << got[i * 4 + k] << ", CPU " << want[k];
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(evenTies, 3u);  // ties where roundEven and floor(x + 0.5) part were compared

    // The decodes of every code.
    std::vector<uint32_t> cin(256 * 4, 0u);
    for (uint32_t k = 0; k < 256; ++k) cin[k * 4] = k;
    const test::TestBuffer cinput = test::TestBuffer::holding(c, cin);
    const test::TestBuffer decoded(c, 256 * 4 * sizeof(uint32_t));
    const std::string dsource = test::wiringKernel(R"(    uint k = inputs[i].x;
    outputs[i] = uvec4(floatBitsToUint(decodeCoatRoughnessBevy(k & 15u, 4u)), floatBitsToUint(decodeUnormSqrt(k)),
                       floatBitsToUint(dequantizeUnormSigned(k, 8u)), 0u);
)");
    ShaderSource ds{"layer_decodes.comp (test)", dsource, VK_SHADER_STAGE_COMPUTE_BIT, {}, {{"gbuffer_wiring.glsl", w.glsl}}};
    test::ComputeKernel(c, ds, {{test::storage(cinput), test::storage(decoded)}}).dispatch(4);
    const uint32_t* dg = decoded.mapped<const uint32_t>();
    for (uint32_t k = 0; k < 256; ++k) {
        EXPECT_EQ(dg[k * 4], bits(enc::decodeCoatRoughnessBevy(k & 15u, 4u))) << k;
        EXPECT_EQ(dg[k * 4 + 1], bits(enc::decodeUnormSqrt(k))) << k;
        EXPECT_EQ(dg[k * 4 + 2], bits(enc::dequantizeUnormSigned(k, 8u))) << k;
    }
    std::printf("[ layers   ] %zu scalars (%zu ties rounded to even) and 256 codes: GPU = CPU\n", n, evenTies);
}

// UE's clear-coat bottom normal: the delta's codes exactly, the decoded normal within 4 ulp (the
// GLSL normalize is the driver's).
TEST_F(LayerEncodingsGpu, ClearCoatBottomNormalDeltaEqualsTheCpuTwin) {
    std::mt19937 rng(41);
    std::normal_distribution<float> g(0.0f, 1.0f);
    auto unit = [&] {
        glm::vec3 v(g(rng), g(rng), g(rng));
        return glm::normalize(v);
    };
    constexpr size_t n = 1u << 14;
    std::vector<glm::vec3> top(n), bottom(n);
    const glm::vec3 axes[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.6f, 0.0f, -0.8f}};
    for (size_t i = 0; i < n; ++i) {
        top[i] = i < 5 ? axes[i] : unit();
        bottom[i] = i % 4 == 0 ? unit() : glm::normalize(top[i] + 0.3f * unit());
    }
    std::vector<uint32_t> in(n * 8);
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            in[i * 8 + size_t(k)] = bits(bottom[i][k]);
            in[i * 8 + 4 + size_t(k)] = bits(top[i][k]);
        }
    VulkanContext& c = ctx();
    const GBufferWiring w = generateWiring(loadLayout("ue5"));
    const test::TestBuffer input = test::TestBuffer::holding(c, in);
    const test::TestBuffer out(c, n * 2 * 4 * sizeof(uint32_t));
    const std::string source = test::wiringKernel(R"(    vec3 bottom = uintBitsToFloat(inputs[2u * i].xyz);
    vec3 top = uintBitsToFloat(inputs[2u * i + 1u].xyz);
    uvec2 code = encodeNormalOctahedralDeltaUe(bottom, top, 8u);
    vec3 back = decodeNormalOctahedralDeltaUe(code, top, 8u);
    outputs[2u * i] = uvec4(code, 0u, 0u);
    outputs[2u * i + 1u] = uvec4(floatBitsToUint(back), 0u);
)");
    ShaderSource cs{"ue_bottom_normal.comp (test)", source, VK_SHADER_STAGE_COMPUTE_BIT, {}, {{"gbuffer_wiring.glsl", w.glsl}}};
    test::ComputeKernel(c, cs, {{test::storage(input), test::storage(out)}}).dispatch(uint32_t(n / 64));
    const uint32_t* got = out.mapped<const uint32_t>();
    size_t codeMismatches = 0;
    float worst = 0.0f;
    for (size_t i = 0; i < n; ++i) {
        const glm::uvec2 want = enc::encodeNormalOctahedralDeltaUe(bottom[i], top[i], 8u);
        if ((got[i * 8] != want.x || got[i * 8 + 1] != want.y) && codeMismatches++ < 8)
            ADD_FAILURE() << "pair " << i << ": GPU (" << got[i * 8] << ", " << got[i * 8 + 1] << "), CPU (" << want.x << ", "
                          << want.y << ")";
        const glm::vec3 cpu = enc::decodeNormalOctahedralDeltaUe(want, top[i], 8u);
        for (int k = 0; k < 3; ++k) worst = std::fmax(worst, std::fabs(fromBits(got[i * 8 + 4 + size_t(k)]) - cpu[k]));
    }
    EXPECT_EQ(codeMismatches, 0u);
    EXPECT_LE(worst, 4.0f * 0x1.0p-24f);
    std::printf("[ layers   ] %zu bottom-normal deltas: codes GPU = CPU, decode within %.3g\n", n, double(worst));
}

}  // namespace
}  // namespace gbl
