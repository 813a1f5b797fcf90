// Engine-style auto-exposure (auto_exposure.h) against an independent computation written here:
// every pixel's bucket luminance sorted, the pixels ranked between the 80th and 98.3th percentiles
// averaged (a fractional pixel at each cut), clamped and inverted; and against the defaults of
// UE4's FPostProcessSettings the header cites.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "auto_exposure.h"

using namespace gbl;

namespace {

// The percentile-trimmed mean by sorting: pixels of rank in [low n, high n) count, fractionally at
// the cuts. The sort order equals the bucket order, so this is the histogram walk's answer.
double trimmedMeanBySorting(const Image& hdr, const AutoExposureSettings& s) {
    std::vector<double> lum;
    for (size_t i = 0; i < hdr.pixelCount(); ++i) {
        const float* p = &hdr.pixels[i * size_t(hdr.channels)];
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        int b = 0;
        if (y > 0) b = std::clamp(int(std::floor((std::log2(y) - s.logMin) / (s.logMax - s.logMin) * s.buckets)), 0,
                                  s.buckets - 1);
        lum.push_back(std::exp2(s.logMin + (b + 0.5) / s.buckets * (s.logMax - s.logMin)));
    }
    std::sort(lum.begin(), lum.end());
    const double lo = lum.size() * s.lowPercent / 100.0, hi = lum.size() * s.highPercent / 100.0;
    double sum = 0, weight = 0;
    for (size_t k = 0; k < lum.size(); ++k) {
        const double w = std::max(0.0, std::min(double(k + 1), hi) - std::max(double(k), lo));
        sum += w * lum[k];
        weight += w;
    }
    return sum / weight;
}

}  // namespace

TEST(AutoExposure, DefaultsAreUe4s) {
    const AutoExposureSettings s;
    EXPECT_EQ(s.buckets, 64);
    EXPECT_EQ(s.logMin, -8.0);
    EXPECT_EQ(s.logMax, 4.0);
    EXPECT_EQ(s.lowPercent, 80.0);
    EXPECT_EQ(s.highPercent, 98.3);
    EXPECT_EQ(s.minBrightness, 0.03);
    EXPECT_EQ(s.maxBrightness, 2.0);
    EXPECT_EQ(s.key, 1.0);
}

TEST(AutoExposure, MatchesTheTrimmedMeanBySorting) {
    std::mt19937 rng(7);
    std::lognormal_distribution<float> radiance(-1.0f, 1.5f);  // a wide range, sky-like tail included
    Image hdr(97, 61, 4, 1.0f);
    for (size_t i = 0; i < hdr.pixelCount(); ++i) {
        const float l = radiance(rng);
        hdr.pixels[i * 4 + 0] = l * 1.1f;
        hdr.pixels[i * 4 + 1] = l;
        hdr.pixels[i * 4 + 2] = i % 13 == 0 ? 0.0f : l * 0.8f;
    }
    const AutoExposure e = meterExposure(hdr);
    const double expected = trimmedMeanBySorting(hdr, AutoExposureSettings{});
    EXPECT_NEAR(e.averageLuminance, expected, 1e-9 * expected);
    EXPECT_DOUBLE_EQ(e.meteredLuminance, std::clamp(expected, 0.03, 2.0));
    EXPECT_DOUBLE_EQ(e.exposure, 1.0 / e.meteredLuminance);
}

// A uniform frame of luminance Y meters to Y within half a bucket (2^(12/128)), and the clamp
// holds a black frame and a blinding one to UE's brightness range.
TEST(AutoExposure, UniformFramesAndTheClamp) {
    for (const float y : {0.05f, 0.18f, 0.7f, 1.5f}) {
        Image hdr(8, 8, 3, y);
        const AutoExposure e = meterExposure(hdr);
        EXPECT_LE(std::abs(std::log2(e.averageLuminance / y)), 12.0 / 128.0 + 1e-9) << y;
        EXPECT_NEAR(e.exposure, 1.0 / e.averageLuminance, 1e-12);
    }
    EXPECT_DOUBLE_EQ(meterExposure(Image(4, 4, 3, 0.0f)).exposure, 1.0 / 0.03);
    EXPECT_DOUBLE_EQ(meterExposure(Image(4, 4, 3, 500.0f)).exposure, 1.0 / 2.0);
}

// Only the pixels between the percentiles count: 80% black and 2% blinding do not move it.
TEST(AutoExposure, OutliersBelowAndAboveThePercentilesAreIgnored) {
    Image hdr(100, 10, 3, 0.0f);
    for (size_t i = 0; i < hdr.pixelCount(); ++i) {
        const float v = i < 800 ? 0.001f : i < 983 ? 0.5f : 1e4f;
        for (int c = 0; c < 3; ++c) hdr.pixels[i * 3 + c] = v;
    }
    const AutoExposure e = meterExposure(hdr);
    EXPECT_NEAR(e.averageLuminance, exposureBucketLuminance(exposureBucket(0.5, {}), {}), 1e-12);
    EXPECT_THROW(meterExposure(Image()), std::invalid_argument);
}
