// Tests for the colour, chroma, roughness and depth encodings (src/encoding/encodings.h, mirror of
// shaders/encodings.glsl), against references written independently here.
#include "encodings_test_support.h"

namespace {

using namespace gbl::enc;
using namespace gbl::enc_test;

// ---------------------------------------------------------------------------------------------
// Colour
// ---------------------------------------------------------------------------------------------

TEST(Color, TransformsInvertAndHitKnownValues) {
    Rng rng(50);
    double worst = 0.0, worstSqrt = 0.0, worstCoCg = 0.0;
    for (int i = 0; i < 500000; ++i) {
        glm::vec3 c(float(rng.u01()), float(rng.u01()), float(rng.u01()));
        glm::vec3 y = rgbToYCbCr(c);
        ASSERT_GE(y.x, 0.0f);
        ASSERT_LE(y.x, 1.0f);
        ASSERT_GE(std::min(y.y, y.z), -1e-6f);
        ASSERT_LE(std::max(y.y, y.z), 1.0f + 1e-6f);
        ASSERT_EQ(y.x, lumaBt601(c));
        glm::vec3 o = rgbToYCoCg(c);
        ASSERT_GE(std::min({o.x, o.y, o.z}), 0.0f);
        ASSERT_LE(std::max({o.x, o.y, o.z}), 1.0f);
        worst = std::max(worst, double(glm::length(yCbCrToRgb(y) - c)));
        worstSqrt = std::max(worstSqrt, double(glm::length(yCbCrSqrtToRgb(rgbToYCbCrSqrt(c)) - c)));
        worstCoCg = std::max(worstCoCg, double(glm::length(yCoCgToRgb(o) - c)));
    }
    std::printf("[measured] unquantised round trip: ycbcr %.3g, ycbcr_sqrt %.3g, ycocg %.3g\n", worst, worstSqrt,
                worstCoCg);
    EXPECT_LT(worst, 1e-6);
    EXPECT_LT(worstSqrt, 1e-6);
    EXPECT_LT(worstCoCg, 1e-6);
    glm::vec3 white = rgbToYCbCr(glm::vec3(1.0f));
    EXPECT_NEAR(white.x, 1.0f, 1e-6f);
    EXPECT_NEAR(white.y, 0.5f, 1e-6f);
    EXPECT_NEAR(white.z, 0.5f, 1e-6f);
    glm::vec3 red = rgbToYCbCr(glm::vec3(1, 0, 0));
    EXPECT_NEAR(red.x, 0.299f, 1e-6f);
    EXPECT_NEAR(red.y, 0.5f - 0.168736f, 1e-5f);  // JPEG's rounded coefficients
    EXPECT_NEAR(red.z, 1.0f, 1e-6f);
    glm::vec3 blue = rgbToYCbCr(glm::vec3(0, 0, 1));
    EXPECT_NEAR(blue.y, 1.0f, 1e-6f);
    EXPECT_NEAR(blue.z, 0.5f - 0.081312f, 1e-5f);
    glm::vec3 g = rgbToYCoCg(glm::vec3(0, 1, 0));
    EXPECT_EQ(g, glm::vec3(0.5f, 0.5f, 1.0f));
}

TEST(Color, QuantisedRoundTripsWithinBounds) {
    Rng rng(51);
    double ycbcr = 0.0, ycocg = 0.0, sqrtDark = 0.0, plainDark = 0.0;
    auto q3 = [](glm::vec3 v) {
        return glm::vec3(dequantizeUnorm(quantizeUnorm(v.x, 8), 8), dequantizeUnorm(quantizeUnorm(v.y, 8), 8),
                         dequantizeUnorm(quantizeUnorm(v.z, 8), 8));
    };
    for (int i = 0; i < 1000000; ++i) {
        glm::vec3 c(float(rng.u01()), float(rng.u01()), float(rng.u01()));
        auto maxAbs = [&](glm::vec3 d) { return double(std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)})); };
        ycbcr = std::max(ycbcr, maxAbs(yCbCrToRgb(q3(rgbToYCbCr(c))) - c));
        ycocg = std::max(ycocg, maxAbs(yCoCgToRgb(q3(rgbToYCoCg(c))) - c));
        glm::vec3 dark = c * 0.05f;  // the sqrt pre-transform spends codes on darks
        sqrtDark = std::max(sqrtDark, maxAbs(yCbCrSqrtToRgb(q3(rgbToYCbCrSqrt(dark))) - dark));
        plainDark = std::max(plainDark, maxAbs(yCbCrToRgb(q3(rgbToYCbCr(dark))) - dark));
    }
    std::printf("[measured] 8-bit max abs: ycbcr %.5f, ycocg %.5f; darks (<0.05): ycbcr %.5f, ycbcr_sqrt %.5f\n",
                ycbcr, ycocg, plainDark, sqrtDark);
    EXPECT_LE(ycbcr, 0.0056);
    EXPECT_LE(ycocg, 0.0060);
    EXPECT_LT(sqrtDark * 2.0, plainDark);
}

TEST(Color, SpecularColorUE4) {
    glm::vec3 base(0.2f, 0.4f, 0.8f);
    EXPECT_EQ(specularColorUE4(base, 0.0f, 0.5f), glm::vec3(0.04f));
    EXPECT_EQ(specularColorUE4(base, 1.0f, 0.5f), base);
    glm::vec3 half = specularColorUE4(base, 0.5f, 1.0f);
    EXPECT_NEAR(half.x, 0.5f * 0.08f + 0.5f * 0.2f, 1e-7f);
}

// ---------------------------------------------------------------------------------------------
// Chroma checkerboard
// ---------------------------------------------------------------------------------------------

TEST(Chroma, CheckerboardPattern) {
    EXPECT_FALSE(chromaIsSecond(ivec2(0, 0)));
    EXPECT_TRUE(chromaIsSecond(ivec2(1, 0)));
    EXPECT_TRUE(chromaIsSecond(ivec2(0, 1)));
    EXPECT_FALSE(chromaIsSecond(ivec2(1, 1)));
    EXPECT_TRUE(chromaIsSecond(ivec2(-1, 0)));
    EXPECT_FALSE(chromaIsSecond(ivec2(-1, -1)));
    EXPECT_EQ(chromaForPixel(ivec2(2, 0), glm::vec2(0.25f, 0.75f)), 0.25f);
    EXPECT_EQ(chromaForPixel(ivec2(2, 1), glm::vec2(0.25f, 0.75f)), 0.75f);
}

TEST(Chroma, EdgeDirectedFilter) {
    // All neighbours similar: plain mean of their chroma.
    glm::vec2 r = reconstructChroma(0.5f, 0.3f, glm::vec4(0.5f), glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    EXPECT_FLOAT_EQ(r.x, 0.3f);
    EXPECT_FLOAT_EQ(r.y, 0.25f);
    // Two neighbours across an edge (|dY| >= 30/255) are dropped.
    r = reconstructChroma(0.5f, 0.3f, glm::vec4(0.5f, 0.9f, 0.52f, 0.1f), glm::vec4(0.1f, 0.9f, 0.3f, 0.9f));
    EXPECT_FLOAT_EQ(r.y, 0.2f);
    // Exactly at the threshold: step(t, t) = 1, weight 0.
    r = reconstructChroma(0.0f, 0.3f, glm::vec4(kChromaEdgeThreshold, 0.0f, 1.0f, 1.0f),
                          glm::vec4(0.9f, 0.1f, 0.7f, 0.7f));
    EXPECT_FLOAT_EQ(r.y, 0.1f);
    // No neighbour within the threshold: the first (+x) alone, as in the paper's listing.
    r = reconstructChroma(0.0f, 0.3f, glm::vec4(0.5f, 0.6f, 0.7f, 0.8f), glm::vec4(0.11f, 0.2f, 0.3f, 0.4f));
    EXPECT_FLOAT_EQ(r.y, 0.11f);
    // With the pixel: (first, second) order.
    glm::vec2 even = reconstructChroma(ivec2(0, 0), 0.5f, 0.3f, glm::vec4(0.5f), glm::vec4(0.7f));
    glm::vec2 odd = reconstructChroma(ivec2(1, 0), 0.5f, 0.3f, glm::vec4(0.5f), glm::vec4(0.7f));
    EXPECT_EQ(even, glm::vec2(0.3f, 0.7f));
    EXPECT_EQ(odd, glm::vec2(0.7f, 0.3f));
}

// The edge test decides every pair of 8-bit luma codes as the integers do (|a - b| >= 30: an
// edge, weight 0), also when each luma is a few ulp off k/255 (a driver's UNORM conversion or
// division rounding otherwise). At 30/255 itself, 134 of the 226 pairs exactly 30 apart fell on
// the wrong side in float32.
TEST(Chroma, EdgeThresholdDecidesEveryCodePairAsTheIntegers) {
    size_t wrong = 0, checked = 0;
    for (int a = 0; a <= 255; ++a)
        for (int b = 0; b <= 255; ++b)
            for (int ulps : {0, -4, 4}) {
                float ya = float(a) / 255.0f, yb = float(b) / 255.0f;
                for (int k = 0; k < std::abs(ulps); ++k) {
                    ya = std::nextafter(ya, ulps > 0 ? 2.0f : -1.0f);
                    yb = std::nextafter(yb, ulps > 0 ? -1.0f : 2.0f);  // the other way: the gap widens or shrinks
                }
                // +x: the luma under test, chroma 0.9; -x: the centre's own luma (always weight 1),
                // chroma 0.1. +x within the threshold: their mean 0.5; across an edge: 0.1 alone.
                const glm::vec2 r = reconstructChroma(ya, 0.5f, glm::vec4(yb, ya, 5.0f, 5.0f),
                                                      glm::vec4(0.9f, 0.1f, 0.3f, 0.3f), glm::vec4(1.0f, 1.0f, 0.0f, 0.0f));
                const bool edge = std::abs(a - b) >= 30;
                wrong += r.y != (edge ? 0.1f : 0.5f);
                ++checked;
            }
    EXPECT_EQ(wrong, 0u) << "of " << checked;
}

TEST(Chroma, FlatImageReconstructsExactly) {
    const int w = 9, h = 7;
    std::vector<glm::vec3> img(size_t(w * h), glm::vec3(0.2f, 0.6f, 0.4f));
    for (const char* name : {"ycocg_checkerboard", "ycbcr_checkerboard"}) {
        std::vector<glm::vec3> out = gbl::roundTripChromaCheckerboard(name, 8, img, w, h);
        for (glm::vec3 c : out) ASSERT_LT(glm::length(c - img[0]), 0.01f) << name;
    }
}

// ---------------------------------------------------------------------------------------------
// Roughness, depth
// ---------------------------------------------------------------------------------------------

TEST(Roughness, MapsInvertAndCrySmoothnessBound) {
    Rng rng(60);
    double worst = 0.0, worstLow = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        float r = float(rng.u01());
        ASSERT_EQ(roughnessFromGloss(glossFromRoughness(r)), 1.0f - (1.0f - r));
        ASSERT_NEAR(roughnessFromSmoothnessCry(smoothnessFromRoughnessCry(r)), r, 2e-7f);
        float back = roughnessFromSmoothnessCry(dequantizeUnorm(quantizeUnorm(smoothnessFromRoughnessCry(r), 8), 8));
        double e = std::fabs(double(back) - double(r));
        worst = std::max(worst, e);
        if (r < 0.01f) worstLow = std::max(worstLow, e);
    }
    std::printf("[measured] smoothness_cry 8 bits: max roughness error %.6f, below r = 0.01: %.6f\n", worst, worstLow);
    EXPECT_LE(worst, 1.0 / 255.0 + 1e-6);  // |d(1-s)^2/ds| <= 2, half a step: 1/255
    EXPECT_LE(worstLow, 0.0008);
}

// cry_gloss_power: every table entry is the double-precision mapping rounded as documented, the
// encoder is exact rounding of g = (log2(2/r^4 - 2) - 1)/10, and the round trip's error is stated.
TEST(CryGlossPower, TablesMatchTheMapping) {
    auto roughnessOfGloss = [](double g) { return std::sqrt(std::sqrt(2.0 / (std::exp2(10.0 * g + 1.0) + 2.0))); };
    for (int k = 0; k < 256; ++k) ASSERT_EQ(kCryGlossRoughness[k], float(roughnessOfGloss(k / 255.0))) << k;
    for (int i = 0; i < 255; ++i) {
        const double t = roughnessOfGloss((i + 0.5) / 255.0);
        const float f = kCryGlossEncodeThresholds[i];
        ASSERT_LE(double(f), t) << i;
        ASSERT_GT(double(std::nextafter(f, 1.0f)), t) << i;  // the largest float <= t
    }
    EXPECT_EQ(decodeCryGlossPower(encodeCryGlossPower(1.0f)), 0.84089643f);  // g = 0, n = 2
    EXPECT_EQ(decodeCryGlossPower(encodeCryGlossPower(0.0f)), 0.17673357f);  // g = 1, n = 2048
    Rng rng(61);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        const float r = float(0.17673357 + (0.84089643 - 0.17673357) * rng.u01());
        const double g = (std::log2(2.0 / std::pow(double(r), 4.0) - 2.0) - 1.0) / 10.0;
        const uint code = encodeCryGlossPower(r);
        ASSERT_NEAR(double(code), std::clamp(std::floor(g * 255.0 + 0.5), 0.0, 255.0), 1.0) << r;
        if (std::abs(g * 255.0 - std::floor(g * 255.0) - 0.5) > 1e-4) {  // away from a tie
            ASSERT_EQ(double(code), std::clamp(std::floor(g * 255.0 + 0.5), 0.0, 255.0)) << r;
        }
        worst = std::max(worst, std::fabs(double(decodeCryGlossPower(code)) - double(r)));
    }
    std::printf("[measured] cry_gloss_power: max roughness error inside [0.1767, 0.8409] %.6f\n", worst);
    EXPECT_LE(worst, 0.0019);
}

TEST(Depth24, EveryCodeRoundTripsAndDepthsRoundExactly) {
    for (uint c = 0; c < (1u << 24); ++c)
        if (quantizeDepth24(dequantizeDepth24(c)) != c) FAIL() << "code " << c;
    const double s = 16777215.0;
    // Every float in [2^-8, 1]: the exact rounding of d * (2^24 - 1), ties up.
    for (std::uint32_t b = bitsOf(std::ldexp(1.0f, -8)); b <= bitsOf(1.0f); ++b) {
        float d = std::bit_cast<float>(b);
        if (quantizeDepth24(d) != uint(std::floor(double(d) * s + 0.5))) FAIL() << "depth " << d;
    }
    Rng rng(24);
    double worst = 0.0;
    for (int i = 0; i < 2000000; ++i) {
        float d = float(std::ldexp(rng.u01(), -int(rng.bits32() % 40u)));  // also tiny depths
        uint c = quantizeDepth24(d);
        ASSERT_EQ(c, uint(std::floor(double(d) * s + 0.5))) << d;
        worst = std::max(worst, std::fabs(double(dequantizeDepth24(c)) - double(d)));
    }
    std::printf("[measured] depth24: max |decode - d| %.3g (%.4f steps)\n", worst, worst * s);
    EXPECT_LE(worst, 0.5 / s + 1e-12);
    EXPECT_EQ(quantizeDepth24(1.0f), 0xffffffu);
    EXPECT_EQ(quantizeDepth24(2.0f), 0xffffffu);
    EXPECT_EQ(quantizeDepth24(-1.0f), 0u);
    EXPECT_EQ(quantizeDepth24(std::nextafter(1.0f, 0.0f)), 0xfffffeu);
}

TEST(Depth24, PositionFromDepthInvertsViewProjection) {
    glm::mat4 proj = glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 100.0f);
    glm::mat4 view = glm::lookAt(glm::vec3(3, 2, 5), glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0));
    glm::mat4 viewProj = proj * view;
    glm::mat4 inv = glm::inverse(viewProj);
    Rng rng(70);
    for (int i = 0; i < 10000; ++i) {
        glm::vec3 p(float(rng.u01() * 4 - 2), float(rng.u01() * 4 - 2), float(rng.u01() * 4 - 2));
        glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
        glm::vec3 ndc = glm::vec3(clip) / clip.w;
        glm::vec2 uv = glm::vec2(ndc) * 0.5f + 0.5f;
        glm::vec3 back = positionFromDepth(uv, ndc.z, inv);
        ASSERT_LT(glm::length(back - p), 1e-3f) << i;
        // Through 24-bit depth: error grows with distance, stays small at these ranges.
        glm::vec3 back24 = positionFromDepth(uv, dequantizeDepth24(quantizeDepth24(ndc.z)), inv);
        ASSERT_LT(glm::length(back24 - p), 0.02f) << i;
    }
}

}  // namespace
