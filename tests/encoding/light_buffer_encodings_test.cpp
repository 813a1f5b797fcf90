// The light-buffer encodings' stated ranges and errors (shaders/light_buffer_encodings.glsl,
// src/encoding/light_buffer_encodings.h): float7e3 (the Xbox 360's A2B10G10R10F colour channels)
// and RGBK in RGBA8 (the PS3's). float16 / float11 / float10 are scalar_encodings_test's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "light_buffer_encodings.h"

namespace gbl::enc {
namespace {

TEST(Float7e3, EveryCodeDecodesAndReencodesToItself) {
    float previous = -1.0f;
    for (uint code = 0; code < 1024u; ++code) {
        const float x = decodeFloat7e3(code);
        EXPECT_EQ(encodeFloat7e3(x), code) << code;
        EXPECT_GT(x, previous) << code;  // strictly increasing: no duplicate or special codes
        previous = x;
    }
    EXPECT_EQ(decodeFloat7e3(0x3ffu), 31.875f);  // the range's top
    EXPECT_EQ(decodeFloat7e3(1u), 1.0f / 512.0f);  // the smallest denormal
    EXPECT_EQ(decodeFloat7e3(0x80u), 0.25f);       // the smallest normal
}

TEST(Float7e3, RangeClampsAndErrorBoundsHold) {
    EXPECT_EQ(encodeFloat7e3(-1.0f), 0u);
    EXPECT_EQ(encodeFloat7e3(-0.0f), 0u);
    EXPECT_EQ(encodeFloat7e3(31.9375f), 0x3ffu);
    EXPECT_EQ(encodeFloat7e3(1e30f), 0x3ffu);
    EXPECT_EQ(encodeFloat7e3(INFINITY), 0x3ffu);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> e(-14.0f, 4.99f);
    for (int i = 0; i < 200000; ++i) {
        const float x = std::exp2(e(rng));
        const float d = decodeFloat7e3(encodeFloat7e3(x));
        if (x >= 0.25f)
            ASSERT_LE(std::abs(d - x), x * std::exp2(-8.0f)) << x;
        else
            ASSERT_LE(std::abs(d - x), std::exp2(-10.0f)) << x;
    }
}

TEST(Float7e3, RoundsToNearestEven) {
    // 1 + 1/256 lies halfway between 1 (mantissa 0) and 1 + 1/128 (mantissa 1): even wins.
    EXPECT_EQ(decodeFloat7e3(encodeFloat7e3(1.0f + 1.0f / 256.0f)), 1.0f);
    EXPECT_EQ(decodeFloat7e3(encodeFloat7e3(1.0f + 3.0f / 256.0f)), 1.0f + 2.0f / 128.0f);
}

TEST(Rgbk, ErrorBoundHoldsWithinTheRangeAndBrighterLightClamps) {
    for (float range : {6.0f, 32.0f, 1000.0f}) {
        const float unit = float(double(range) / 65025.0);
        std::mt19937 rng{uint32_t(range)};
        std::uniform_real_distribution<float> e(-16.0f, std::log2(range));
        for (int i = 0; i < 100000; ++i) {
            const vec3 x(std::exp2(e(rng)), std::exp2(e(rng)), std::exp2(e(rng)));
            const glm::uvec4 c = encodeRgbk(x, unit);
            ASSERT_GE(c.w, 1u);
            const vec3 d = decodeRgbk(c, unit);
            const float m = std::max(x.x, std::max(x.y, x.z));
            const float bound = m / 510.0f + range / 130050.0f;
            for (int k = 0; k < 3; ++k) ASSERT_LE(std::abs(d[k] - x[k]), bound * 1.0001f) << range << " " << x[k];
        }
        const vec3 top = decodeRgbk(encodeRgbk(vec3(range * 4.0f, 0.0f, -1.0f), unit), unit);
        EXPECT_NEAR(top.x, range, range * 1e-6f);
        EXPECT_EQ(top.y, 0.0f);
        EXPECT_EQ(top.z, 0.0f);
    }
}

TEST(Rgbk, MultiplierIsTheSmallestThatFits) {
    const float unit = float(32.0 / 65025.0);
    for (float m : {1e-6f, 0.1f, 0.5f, 1.0f, 3.3f, 31.9f}) {
        const uint k = rgbkMultiplier(m, unit);
        EXPECT_GE(float(255u * k) * unit, m);
        if (k > 1u) {
            EXPECT_LT(float(255u * (k - 1u)) * unit, m);
        }
    }
}

TEST(LightLuminance, Rec709Weights) {
    EXPECT_NEAR(lightLuminance(vec3(1.0f)), 1.0f, 1e-6f);
    EXPECT_NEAR(lightLuminance(vec3(0.0f, 1.0f, 0.0f)), 0.7152f, 1e-7f);
}

}  // namespace
}  // namespace gbl::enc
