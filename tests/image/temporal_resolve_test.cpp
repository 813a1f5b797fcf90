// compare --temporal N against the mathematics: Halton's published points, the resolve as a mean,
// the normalised mean of normals, and what averaging frames does to a quantiser -- a dither that
// moves with time converges like 1/sqrt(N), plain rounding (and a dither fixed in screen space,
// niagara's) keeps its error at every N.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "niagara_encodings.h"
#include "temporal_resolve.h"

namespace gbl {
namespace {

TEST(Halton, PublishedPoints) {
    // Halton (1960): the radical inverse; base 2: 1/2, 1/4, 3/4, 1/8, 5/8; base 3: 1/3, 2/3, 1/9, 4/9, 7/9.
    const double base2[] = {0.5, 0.25, 0.75, 0.125, 0.625};
    const double base3[] = {1.0 / 3, 2.0 / 3, 1.0 / 9, 4.0 / 9, 7.0 / 9};
    for (unsigned i = 0; i < 5; ++i) {
        EXPECT_DOUBLE_EQ(halton(i + 1, 2), base2[i]);
        EXPECT_DOUBLE_EQ(halton(i + 1, 3), base3[i]);
    }
    EXPECT_EQ(halton(0, 2), 0.0);
}

TEST(TemporalJitter, UnrealOffsetsAndOneFrame) {
    // UE's SampleX = Halton(index + 1, 2) - 0.5, SampleY = Halton(index + 1, 3) - 0.5.
    const std::vector<JitterOffset> j = temporalJitter(8);
    ASSERT_EQ(j.size(), 8u);
    EXPECT_FLOAT_EQ(j[0].x, 0.0f);
    EXPECT_FLOAT_EQ(j[0].y, float(1.0 / 3 - 0.5));
    EXPECT_FLOAT_EQ(j[1].x, -0.25f);
    EXPECT_FLOAT_EQ(j[1].y, float(2.0 / 3 - 0.5));
    EXPECT_FLOAT_EQ(j[7].x, float(1.0 / 16 - 0.5));  // 8 = 1000b -> 0.0001b
    double mx = 0, my = 0;
    for (const JitterOffset& o : j) {
        EXPECT_GE(o.x, -0.5f);
        EXPECT_LT(o.x, 0.5f);
        EXPECT_GE(o.y, -0.5f);
        EXPECT_LT(o.y, 0.5f);
        mx += o.x;
        my += o.y;
    }
    // Low discrepancy: the 8 offsets' centroid is within 1/16 pixel of the pixel centre.
    EXPECT_LT(std::abs(mx / 8), 1.0 / 16);
    EXPECT_LT(std::abs(my / 8), 1.0 / 16);
    const std::vector<JitterOffset> one = temporalJitter(1);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].x, 0.0f);
    EXPECT_EQ(one[0].y, 0.0f);
}

Image randomImage(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image img(w, h, 4);
    for (float& v : img.pixels) v = std::exp(u(rng) * 20.0f - 10.0f) * (u(rng) < 0.5f ? 1.0f : 3.7f);
    return img;
}

TEST(HdrResolve, IdenticalFramesResolveToThatFrameBitForBit) {
    const Image frame = randomImage(37, 23, 1);
    for (ResolveMethod method : {ResolveMethod::Mean, ResolveMethod::Exponential})
        for (int n : {1, 2, 3, 7, 8, 64, 256}) {
            HdrResolve r(method);
            for (int k = 0; k < n; ++k) r.add(frame);
            const Image out = r.resolved();
            ASSERT_EQ(out.pixels.size(), frame.pixels.size());
            EXPECT_EQ(std::memcmp(out.pixels.data(), frame.pixels.data(), frame.pixels.size() * sizeof(float)), 0)
                << resolveMethodName(method) << " of " << n << " frames";
        }
}

TEST(HdrResolve, MeanAndExponentialHistoryOfDistinctFrames) {
    const int n = 5;
    std::vector<Image> frames;
    for (int k = 0; k < n; ++k) frames.push_back(randomImage(9, 4, 10 + unsigned(k)));
    HdrResolve mean(ResolveMethod::Mean), history(ResolveMethod::Exponential);
    for (const Image& f : frames) {
        mean.add(f);
        history.add(f);
    }
    const Image m = mean.resolved(), h = history.resolved();
    for (size_t i = 0; i < m.pixels.size(); ++i) {
        long double sum = 0;  // independent: long double, summed in reverse order
        for (int k = n - 1; k >= 0; --k) sum += frames[size_t(k)].pixels[i];
        EXPECT_NEAR(m.pixels[i], double(sum / n), 1e-6 * double(sum / n));
        // The history's weights in closed form: frame 0 (1 - w)^(n - 1), frame k w (1 - w)^(n - 1 - k).
        double expected = frames[0].pixels[i] * std::pow(1.0 - kHistoryBlend, n - 1);
        for (int k = 1; k < n; ++k) expected += frames[size_t(k)].pixels[i] * kHistoryBlend * std::pow(1.0 - kHistoryBlend, n - 1 - k);
        EXPECT_NEAR(h.pixels[i], expected, 1e-5 * expected);
    }
    EXPECT_THROW(mean.add(Image(3, 3, 4)), std::invalid_argument);
}

TEST(SurfaceMean, NormalisedMeanOfNormalsAndCoveredInEveryFrame) {
    // Two pixels; normals at +-30 degrees about +z (lengths 1 and 2: each frame weighs the same).
    auto surfaces = [](float angle, float length, uint8_t coveredSecond) {
        SurfaceImages s;
        s.normal = Image(2, 1, 3);
        s.roughness = Image(2, 1, 1);
        for (int p = 0; p < 2; ++p) {
            s.normal.at(p, 0, 0) = std::sin(angle) * length;
            s.normal.at(p, 0, 2) = std::cos(angle) * length;
            s.roughness.at(p, 0, 0) = angle > 0 ? 0.2f : 0.6f;
        }
        s.coverage = {1, coveredSecond};
        return s;
    };
    const float a = float(M_PI / 6);
    SurfaceMean mean;
    mean.add(surfaces(a, 1.0f, 1));
    mean.add(surfaces(-a, 2.0f, 0));
    const SurfaceImages m = mean.mean();
    EXPECT_EQ(m.coverage[0], 1);
    EXPECT_EQ(m.coverage[1], 0);  // not covered in every frame: left out
    EXPECT_NEAR(m.normal.at(0, 0, 0), 0.0f, 1e-7);
    EXPECT_NEAR(m.normal.at(0, 0, 2), 1.0f, 1e-7);  // the normalised mean, a unit vector
    EXPECT_NEAR(m.roughness.at(0, 0, 0), 0.4f, 1e-7);
    EXPECT_TRUE(m.baseColor.empty());
}

// A flat surface whose stored value lies between two 8-bit codes: the normal whose octahedral x
// coordinate, as niagara's encoder stores it (unorm of p.x * 0.5 + 0.5), is code 100 + 0.3.
struct FlatNormal {
    enc::vec3 n;
    double truth;  // the unquantised unorm value of the x code
};
FlatNormal flatNormal() {
    const double u = (100.0 + 0.3) / 255.0, px = 2.0 * u - 1.0, py = 0.1;
    const double pz = 1.0 - std::abs(px) - std::abs(py);
    const double len = std::sqrt(px * px + py * py + pz * pz);
    const enc::vec3 n(float(px / len), float(py / len), float(pz / len));
    const enc::vec2 p = enc::octEncodeNiagara(n);  // the encoder's own view of the value
    return {n, double(p.x) * 0.5 + 0.5};
}

// RMS over a 64 x 64 patch of the error of each pixel's mean decoded value over frames 0..N-1,
// in codes. `encode` gives the x code of a pixel at a frame.
template <class Encode>
double rmsErrorOfTemporalMean(int frames, double truth, Encode encode) {
    double sq = 0.0;
    int pixels = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            double sum = 0.0;
            for (int k = 0; k < frames; ++k) sum += double(encode(enc::ivec2(x, y), uint32_t(k))) / 255.0;
            const double e = (sum / frames - truth) * 255.0;
            sq += e * e;
            ++pixels;
        }
    return std::sqrt(sq / pixels);
}

// Least-squares slope of log(error) against log(N).
double logSlope(const std::vector<int>& ns, const std::vector<double>& errors) {
    double mx = 0, my = 0;
    for (size_t i = 0; i < ns.size(); ++i) {
        mx += std::log(double(ns[i]));
        my += std::log(errors[i]);
    }
    mx /= double(ns.size());
    my /= double(ns.size());
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < ns.size(); ++i) {
        const double dx = std::log(double(ns[i])) - mx;
        sxy += dx * (std::log(errors[i]) - my);
        sxx += dx * dx;
    }
    return sxy / sxx;
}

TEST(TemporalQuantiser, DitherThatMovesWithTimeConvergesLikeOneOverSqrtN) {
    const FlatNormal f = flatNormal();
    const double fraction = f.truth * 255.0 - std::floor(f.truth * 255.0);
    ASSERT_NEAR(fraction, 0.3, 1e-3);
    // The encoder a dither_per_frame field runs (niagara_encodings.h, mirrored by the GLSL):
    // gradient noise advanced 5.588238 pixels a frame, at 8 bits.
    auto moving = [&](enc::ivec2 p, uint32_t k) { return enc::encodeNormalOctahedralDitheredAtFrame(f.n, 8, p, k).x; };
    const std::vector<int> ns = {1, 2, 4, 8, 16, 32};
    std::vector<double> errors;
    for (int n : ns) errors.push_back(rmsErrorOfTemporalMean(n, f.truth, moving));
    // One frame: each pixel holds code 100 or 101, the RMS of a Bernoulli(0.3) error about its mean
    // is sqrt(0.3 * 0.7) = 0.458 codes (an exact dither: the value is right on average).
    EXPECT_NEAR(errors[0], std::sqrt(fraction * (1 - fraction)), 0.05);
    // Falls at least like 1/sqrt(N) (an i.i.d. dither would give exactly -0.5) ...
    const double slope = logSlope(ns, errors);
    std::printf("RMS error of the temporal mean (codes) at N = 1..32: %.4f %.4f %.4f %.4f %.4f %.4f; slope %.3f\n",
                errors[0], errors[1], errors[2], errors[3], errors[4], errors[5], slope);
    EXPECT_LT(slope, -0.45) << "errors " << errors[0] << " .. " << errors.back();
    // ... and at 32 frames is below sqrt(0.21 / 32) codes, the i.i.d. uniform dither's RMS, with margin.
    EXPECT_LT(errors.back(), 1.2 * std::sqrt(fraction * (1 - fraction) / 32.0));
    // The patch's mean (every pixel, every frame) is the unquantised value: the dither is unbiased.
    double all = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (uint32_t k = 0; k < 32; ++k) all += moving(enc::ivec2(x, y), k) / 255.0;
    EXPECT_NEAR(all / (64.0 * 64 * 32) * 255.0, f.truth * 255.0, 0.02);
}

TEST(TemporalQuantiser, PlainRoundingAndAFixedDitherKeepTheirErrorAtEveryN) {
    const FlatNormal f = flatNormal();
    // Plain 8-bit rounding of the same value: code 100 in every pixel and frame, a bias of 0.3 codes.
    auto rounding = [&](enc::ivec2, uint32_t) { return enc::quantizeUnorm(float(f.truth), 8); };
    // niagara's dither (mesh.frag.glsl:60: gradientNoise(gl_FragCoord.xy), no frame term): fixed in
    // screen space, so each pixel's code is the same in every frame.
    auto fixedDither = [&](enc::ivec2 p, uint32_t) { return enc::encodeNormalOctahedralDithered(f.n, 8, p).x; };
    const double one = rmsErrorOfTemporalMean(1, f.truth, fixedDither);
    for (int n : {1, 2, 4, 8, 16, 32}) {
        EXPECT_NEAR(rmsErrorOfTemporalMean(n, f.truth, rounding), 0.3, 1e-3) << n << " frames";
        EXPECT_NEAR(rmsErrorOfTemporalMean(n, f.truth, fixedDither), one, 1e-9) << n << " frames";
    }
    EXPECT_GT(one, 0.3);  // per pixel, a fixed dither is worse than rounding: only a spatial filter averages it
}

TEST(TemporalQuantiser, FrameZeroIsTheFixedDitherBitForBit) {
    const FlatNormal f = flatNormal();
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const enc::ivec2 p(x * 37, y * 11);
            EXPECT_EQ(enc::gradientNoiseAtFrame(p, 0), enc::gradientNoise(p));
            EXPECT_EQ(enc::gradientNoiseAtFrame(p, 64), enc::gradientNoise(p));  // a 64-frame cycle
            const enc::uvec2 a = enc::encodeNormalOctahedralDitheredAtFrame(f.n, 10, p, 0);
            const enc::uvec2 b = enc::encodeNormalOctahedralDithered(f.n, 10, p);
            EXPECT_EQ(a.x, b.x);
            EXPECT_EQ(a.y, b.y);
        }
}

}  // namespace
}  // namespace gbl
