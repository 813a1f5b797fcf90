// The display transform: exact sRGB curve, Narkowicz ACES fit, 8-bit quantisation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "tone_map.h"

namespace gbl {
namespace {

TEST(Srgb, KnownPoints) {
    EXPECT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.7353569f, 1e-7);
    EXPECT_NEAR(linearToSrgb(0.18f), 0.4613561f, 1e-7);
    EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-6);  // where the two pieces meet
    EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-7);
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.0031308f, 1e-8);
    EXPECT_FLOAT_EQ(linearToSrgb(0.001f), 0.01292f);  // linear segment, slope 12.92
}

TEST(Srgb, ContinuousAtTheKnee) {
    // A wrong constant (0.04045 vs 0.0031308 mix-ups) shows as a jump here.
    EXPECT_NEAR(linearToSrgb(0.00313079f), linearToSrgb(0.00313081f), 1e-6);
    EXPECT_NEAR(srgbToLinear(0.0404499f), srgbToLinear(0.0404501f), 1e-7);
}

TEST(Srgb, RoundTripsAndIsMonotonic) {
    float previous = -1.0f;
    for (int i = 0; i <= 100000; ++i) {
        const float x = float(i) / 100000.0f;
        const float encoded = linearToSrgb(x);
        ASSERT_GE(encoded, previous) << x;
        previous = encoded;
        ASSERT_NEAR(srgbToLinear(encoded), x, 2e-7f + 1e-6f * x) << x;
    }
    for (int code = 0; code < 256; ++code) {  // every 8-bit code survives decode + encode
        const float e = float(code) / 255.0f;
        ASSERT_EQ(int(std::floor(linearToSrgb(srgbToLinear(e)) * 255.0f + 0.5f)), code);
    }
}

TEST(Srgb, ClampsOutOfRangeAndNaN) {
    EXPECT_EQ(linearToSrgb(-1.0f), 0.0f);
    EXPECT_EQ(linearToSrgb(2.0f), 1.0f);
    EXPECT_EQ(linearToSrgb(std::numeric_limits<float>::quiet_NaN()), 0.0f);
    EXPECT_EQ(srgbToLinear(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Aces, KnownValuesAndLimits) {
    EXPECT_EQ(acesFilmNarkowicz(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(acesFilmNarkowicz(1.0f), 2.54f / 3.16f);
    EXPECT_NEAR(acesFilmNarkowicz(0.18f), 0.2668989f, 1e-6);
    EXPECT_EQ(acesFilmNarkowicz(7.9f), 1.0f);  // the fit passes 1 at x ~ 7.24 and is saturated
    EXPECT_EQ(acesFilmNarkowicz(1e30f), 1.0f);  // no x*x overflow into inf/inf = NaN
    EXPECT_EQ(acesFilmNarkowicz(std::numeric_limits<float>::infinity()), 1.0f);
    EXPECT_EQ(acesFilmNarkowicz(-3.0f), 0.0f);
    EXPECT_EQ(acesFilmNarkowicz(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Aces, MonotonicFromZeroToHuge) {
    float previous = 0.0f;
    for (int i = 0; i <= 200000; ++i) {  // dense over [0, 20], across the shortcut at 8
        const float x = float(i) * 1e-4f;
        const float y = acesFilmNarkowicz(x);
        ASSERT_GE(y, previous) << x;
        ASSERT_LE(y, 1.0f);
        previous = y;
    }
    previous = 0.0f;
    for (float x = 1e-8f; x < 1e30f; x *= 1.01f) {
        const float y = acesFilmNarkowicz(x);
        ASSERT_GE(y, previous) << x;
        previous = y;
    }
}

TEST(ToneMap, EightBitIsTheFloatVersionQuantised) {
    Image hdr(4096, 1, 3);
    for (size_t i = 0; i < hdr.pixels.size(); ++i) hdr.pixels[i] = std::pow(10.0f, -4.0f + 7.0f * float(i) / float(hdr.pixels.size()));
    const Image8 bytes = toneMapToSrgb8(hdr, 0.7f);
    const Image floats = toneMapToSrgbFloat(hdr, 0.7f);
    ASSERT_EQ(bytes.channels, 3);
    ASSERT_EQ(bytes.pixels.size(), hdr.pixels.size());
    for (size_t i = 0; i < floats.pixels.size(); ++i) {
        ASSERT_GE(floats.pixels[i], 0.0f);
        ASSERT_LE(floats.pixels[i], 1.0f);
        ASSERT_EQ(bytes.pixels[i], (unsigned char)std::floor(floats.pixels[i] * 255.0f + 0.5f)) << i;
    }
}

TEST(ToneMap, KnownPixelsExposureAndChannels) {
    Image rgba(4, 1, 4);
    const float values[4] = {0.0f, 0.18f, 1.0f, 1e9f};
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 4; ++c) rgba.at(x, 0, c) = c == 3 ? 0.25f : values[x];
    const Image8 out = toneMapToSrgb8(rgba);
    ASSERT_EQ(out.channels, 3);  // alpha dropped
    const unsigned char expected[4] = {0, 141, 232, 255};  // from the formulas in double precision
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(out.pixels[size_t(x) * 3 + c], expected[x]) << x;

    Image doubled = rgba;  // exposure is a plain linear scale
    for (auto& v : doubled.pixels) v *= 2.0f;
    EXPECT_EQ(toneMapToSrgb8(rgba, 2.0f).pixels, toneMapToSrgb8(doubled, 1.0f).pixels);

    Image gray(4, 1, 1);  // one channel is shown as gray
    for (int x = 0; x < 4; ++x) gray.at(x, 0, 0) = values[x];
    EXPECT_EQ(toneMapToSrgb8(gray).pixels, out.pixels);
}

// The 8-bit code written for a display value, straight from its definition (with the pow).
int directCode(float y) { return int(std::floor(linearToSrgb(y) * 255.0f + 0.5f)); }

float fromBits(uint32_t b) {
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
}

TEST(ToneMap, SrgbByteEqualsTheCurveAtEveryStep) {
    // srgbByte finds the code from the curve's steps; here each step is found again by this
    // test's own bisection over the float bit patterns of [0,1], and srgbByte must agree on both
    // sides of it. Between steps the code is constant (the curve is monotone), so with the
    // strided sweep below this pins srgbByte to the definition. (An exhaustive run over all
    // 1,065,353,217 floats in [0,1] agreed too; too slow for the suite.)
    const uint32_t one = 0x3F800000u;
    uint32_t lo = 0;
    for (int k = 1; k <= 255; ++k) {
        uint32_t a = lo, b = one;
        while (a < b) {
            const uint32_t m = a + (b - a) / 2;
            if (directCode(fromBits(m)) >= k) b = m;
            else a = m + 1;
        }
        ASSERT_EQ(int(srgbByte(fromBits(a))), directCode(fromBits(a))) << "step " << k;
        ASSERT_EQ(int(srgbByte(fromBits(a - 1))), directCode(fromBits(a - 1))) << "below step " << k;
        ASSERT_EQ(int(srgbByte(fromBits(a + 1))), directCode(fromBits(a + 1))) << "above step " << k;
        lo = a;
    }
    for (uint32_t b = 0; b <= one; b += 4099) ASSERT_EQ(int(srgbByte(fromBits(b))), directCode(fromBits(b))) << fromBits(b);
    for (int i = 0; i <= 4096; ++i) {  // bucket edges
        const float y = float(i) / 4096.0f;
        ASSERT_EQ(int(srgbByte(y)), directCode(y)) << y;
    }
    EXPECT_EQ(srgbByte(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(srgbByte(-0.5f), 0);
    EXPECT_EQ(srgbByte(3.0f), 255);
}

TEST(ToneMap, EightBitImagesAreTheCodesOfTheCurve) {
    // toneMapToSrgb8 (and the AsFloat copy) against the per-value definition, on an image large
    // enough to be split between threads, with NaN, negatives, infinities and huge values.
    Image hdr(700, 300, 4);
    uint32_t state = 12345u;
    for (size_t i = 0; i < hdr.pixels.size(); ++i) {
        state = state * 1664525u + 1013904223u;
        const float u = float(state >> 8) / float(1u << 24);
        hdr.pixels[i] = std::pow(10.0f, -6.0f + 9.0f * u);
    }
    const float special[] = {std::numeric_limits<float>::quiet_NaN(), -1.0f, std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity(), 0.0f, -0.0f, 1e38f, 7.5f};
    for (size_t i = 0; i < 8; ++i) hdr.pixels[i * 997] = special[i];
    for (float exposure : {1.0f, 0.37f, 6.0f}) {
        const Image8 bytes = toneMapToSrgb8(hdr, exposure);
        const Image asFloat = toneMapToSrgb8AsFloat(hdr, exposure);
        for (size_t p = 0; p < hdr.pixelCount(); ++p)
            for (size_t c = 0; c < 3; ++c) {
                const int code = directCode(acesFilmNarkowicz(hdr.pixels[p * 4 + c] * exposure));
                ASSERT_EQ(int(bytes.pixels[p * 3 + c]), code) << p << " " << c << " exposure " << exposure;
                ASSERT_EQ(asFloat.pixels[p * 3 + c], float(code) / 255.0f) << p;
            }
    }
}

}  // namespace
}  // namespace gbl
