#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <numbers>
#include <random>

#include "error.h"
#include "metrics.h"
#include "run_metrics.h"

namespace {

using gbl::Image;
using gbl::SurfaceImages;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A synthetic decoded G-buffer: a covered disc-ish block in the middle, varied unit normals,
// colour gradients, left third metal (metallic 1), the rest dielectric.
SurfaceImages makeSurface(int w, int h, unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    SurfaceImages s;
    s.normal = Image(w, h, 3);
    s.baseColor = Image(w, h, 3);
    s.diffuseColor = Image(w, h, 3);
    s.specularColor = Image(w, h, 3);
    s.roughness = Image(w, h, 1);
    s.metallic = Image(w, h, 1);
    s.occlusion = Image(w, h, 1);
    s.emissive = Image(w, h, 3);
    s.depth = Image(w, h, 1);
    s.viewDepth = Image(w, h, 1);
    s.coverage.assign(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const bool covered = x >= w / 8 && x < w - w / 8 && y >= h / 8 && y < h - h / 8;
            s.coverage[i] = covered ? 1 : 0;
            // A normal in the upper hemisphere with a random direction.
            const double theta = 1.2 * u(rng), phi = 2.0 * std::numbers::pi * u(rng);
            s.normal.at(x, y, 0) = float(std::sin(theta) * std::cos(phi));
            s.normal.at(x, y, 1) = float(std::sin(theta) * std::sin(phi));
            s.normal.at(x, y, 2) = float(std::cos(theta));
            const bool metal = x < w / 3;
            for (int c = 0; c < 3; ++c) {
                s.baseColor.at(x, y, c) = 0.05f + 0.9f * u(rng);
                s.diffuseColor.at(x, y, c) = metal ? 0.0f : s.baseColor.at(x, y, c);
                s.specularColor.at(x, y, c) = metal ? s.baseColor.at(x, y, c) : 0.04f;
            }
            s.roughness.at(x, y, 0) = 0.1f + 0.8f * u(rng);
            s.metallic.at(x, y, 0) = metal ? 1.0f : 0.0f;
            s.occlusion.at(x, y, 0) = 0.5f + 0.5f * u(rng);
            s.viewDepth.at(x, y, 0) = covered ? 1.0f + 20.0f * u(rng) : 0.0f;
            s.depth.at(x, y, 0) = covered ? 1.0f / s.viewDepth.at(x, y, 0) : 0.0f;
        }
    return s;
}

Image makeHdr(int w, int h, unsigned seed = 3) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image im(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = 0.02f + 3.0f * u(rng) * float(x + 1) / float(w);
            im.at(x, y, 3) = 1.0f;
        }
    return im;
}

size_t coveredCount(const SurfaceImages& s) {
    size_t n = 0;
    for (uint8_t c : s.coverage) n += c ? 1 : 0;
    return n;
}

void expectZero(const gbl::AttributeMetrics& m, const char* what) {
    for (const gbl::ClassStats* c : {&m.all, &m.metal, &m.dielectric}) {
        EXPECT_EQ(c->error.mean, 0.0) << what;
        EXPECT_EQ(c->error.p99, 0.0) << what;
        EXPECT_EQ(c->error.max, 0.0) << what;
        EXPECT_EQ(c->rmse, 0.0) << what;
    }
    EXPECT_EQ(m.skipped, 0u) << what;
}

const gbl::AttributeMetrics* allAttributes(const gbl::RunMetrics& r, int i) {
    const gbl::AttributeMetrics* list[] = {&r.normal,    &r.baseColor, &r.diffuseColor, &r.specularColor,
                                           &r.roughness, &r.metallic,  &r.occlusion,    &r.depth};
    return list[i];
}
const char* kNames[] = {"normal", "base", "diffuse", "specular", "roughness", "metallic", "occlusion", "depth"};

TEST(RunMetrics, ReferenceAgainstItselfIsExactlyZero) {
    const SurfaceImages s = makeSurface(64, 48);
    const Image hdr = makeHdr(64, 48);
    gbl::RunErrorMaps maps;
    gbl::RunMetricsOptions options;
    options.maps = &maps;
    const gbl::RunMetrics r = gbl::computeRunMetrics(s, s, hdr, hdr, 1.0f, options);
    const size_t covered = coveredCount(s);
    EXPECT_EQ(r.coverage.both, covered);
    EXPECT_EQ(r.coverage.referenceOnly, 0u);
    EXPECT_EQ(r.coverage.testOnly, 0u);
    EXPECT_EQ(r.coverage.metal + r.coverage.dielectric, covered);
    for (int i = 0; i < 8; ++i) {
        expectZero(*allAttributes(r, i), kNames[i]);
        EXPECT_EQ(allAttributes(r, i)->all.error.count, covered) << kNames[i];
    }
    EXPECT_EQ(r.image.rmseLinear, 0.0);
    EXPECT_EQ(r.image.psnrLinear, kInf);
    EXPECT_EQ(r.image.rmseToneMapped, 0.0);
    EXPECT_EQ(r.image.psnrToneMapped, kInf);
    EXPECT_EQ(r.image.maxAbs, 0.0);
    EXPECT_EQ(r.image.p99Abs, 0.0);
    EXPECT_EQ(r.image.flipMean, 0.0);
    EXPECT_EQ(r.image.flipMedian, 0.0);
    EXPECT_TRUE(r.image.hdrFlipComputed);
    EXPECT_EQ(r.image.hdrFlipMean, 0.0);
    for (const Image* m : {&maps.flip, &maps.hdrFlip, &maps.absLinear, &maps.relLuminance, &maps.normalDeg,
                           &maps.baseColorDe, &maps.depthRel})
        for (float v : m->pixels) ASSERT_EQ(v, 0.0f);
}

// Rotates every normal by `deg` about an axis perpendicular to it.
void rotateNormals(Image& n, double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    for (size_t i = 0; i < n.pixelCount(); ++i) {
        float* p = &n.pixels[i * 3];
        const double nx = p[0], ny = p[1], nz = p[2];
        // t = normalize(n x (1,0,0) or n x (0,1,0)): perpendicular to n.
        double tx, ty, tz;
        if (std::abs(nx) < 0.9) {
            tx = 0.0, ty = nz, tz = -ny;
        } else {
            tx = -nz, ty = 0.0, tz = nx;
        }
        const double tl = std::sqrt(tx * tx + ty * ty + tz * tz);
        tx /= tl, ty /= tl, tz /= tl;
        // Rotation in the plane of n and (t x n): n' = n cos a + (t x n) sin a.
        const double bx = ty * nz - tz * ny, by = tz * nx - tx * nz, bz = tx * ny - ty * nx;
        p[0] = float(nx * std::cos(a) + bx * std::sin(a));
        p[1] = float(ny * std::cos(a) + by * std::sin(a));
        p[2] = float(nz * std::cos(a) + bz * std::sin(a));
    }
}

TEST(RunMetrics, NormalsRotatedByTwoDegrees) {
    const SurfaceImages ref = makeSurface(80, 60);
    SurfaceImages test = ref;
    rotateNormals(test.normal, 2.0);
    const Image hdr = makeHdr(80, 60);
    const gbl::RunMetrics r = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f);
    EXPECT_NEAR(r.normal.all.error.mean, 2.0, 1e-3);
    EXPECT_NEAR(r.normal.all.error.p99, 2.0, 1e-3);
    EXPECT_NEAR(r.normal.all.error.max, 2.0, 1e-3);
    EXPECT_NEAR(r.normal.metal.error.mean, 2.0, 1e-3);
    EXPECT_NEAR(r.normal.dielectric.error.mean, 2.0, 1e-3);
    EXPECT_EQ(r.normal.all.error.count, coveredCount(ref));
    expectZero(r.roughness, "roughness");
    expectZero(r.baseColor, "base");
}

TEST(RunMetrics, RoughnessOffsetAndDepthScale) {
    const SurfaceImages ref = makeSurface(50, 40);
    SurfaceImages test = ref;
    for (float& v : test.roughness.pixels) v += 0.01f;
    for (float& v : test.viewDepth.pixels) v *= 1.01f;
    const Image hdr = makeHdr(50, 40);
    const gbl::RunMetrics r = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f);
    EXPECT_NEAR(r.roughness.all.error.mean, 0.01, 1e-6);
    EXPECT_NEAR(r.roughness.all.error.max, 0.01, 1e-6);
    EXPECT_NEAR(r.roughness.metal.error.mean, 0.01, 1e-6);
    EXPECT_NEAR(r.roughness.dielectric.error.p99, 0.01, 1e-6);
    EXPECT_NEAR(r.depth.all.error.mean, 0.01, 1e-6);
    EXPECT_NEAR(r.depth.all.error.max, 0.01, 1e-6);
    expectZero(r.normal, "normal");
    expectZero(r.metallic, "metallic");
}

TEST(RunMetrics, MaterialClassesFollowTheReference) {
    const int w = 60, h = 30;
    const SurfaceImages ref = makeSurface(w, h);
    SurfaceImages test = ref;
    // Turn a dielectric block metal in the TEST only: still dielectric for the split.
    size_t swapped = 0;
    for (int y = 10; y < 20; ++y)
        for (int x = 30; x < 40; ++x) {
            test.metallic.at(x, y, 0) = 1.0f;
            swapped += ref.coverage[size_t(y) * w + size_t(x)] ? 1 : 0;
        }
    ASSERT_GT(swapped, 0u);
    const Image hdr = makeHdr(w, h);
    gbl::RunMetrics r = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f);
    size_t metal = 0, dielectric = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (ref.coverage[size_t(y) * w + size_t(x)]) ++(x < w / 3 ? metal : dielectric);
    EXPECT_EQ(r.coverage.metal, metal);
    EXPECT_EQ(r.coverage.dielectric, dielectric);
    EXPECT_EQ(r.metallic.metal.error.count, metal);
    EXPECT_EQ(r.metallic.dielectric.error.count, dielectric);
    EXPECT_EQ(r.metallic.metal.error.max, 0.0);
    EXPECT_EQ(r.metallic.dielectric.error.max, 1.0);
    EXPECT_DOUBLE_EQ(r.metallic.dielectric.error.mean, double(swapped) / double(dielectric));
    EXPECT_DOUBLE_EQ(r.metallic.all.error.mean, double(swapped) / double(metal + dielectric));

    // Now the reference itself has the block metal: the counts move class.
    r = gbl::computeRunMetrics(test, test, hdr, hdr, 1.0f);
    EXPECT_EQ(r.coverage.metal, metal + swapped);
    EXPECT_EQ(r.coverage.dielectric, dielectric - swapped);
    EXPECT_EQ(r.roughness.metal.error.count, metal + swapped);
}

TEST(RunMetrics, CoverageMismatchesAreCountedNotMeasured) {
    const SurfaceImages ref = makeSurface(40, 40);
    SurfaceImages test = ref;
    const size_t covered = coveredCount(ref);
    // Lose 3 covered pixels, gain 2 background pixels.
    size_t lost = 0;
    for (size_t i = 0; i < test.coverage.size() && lost < 3; ++i)
        if (test.coverage[i]) test.coverage[i] = 0, ++lost;
    test.coverage[0] = 1;
    test.coverage[1] = 1;
    const Image hdr = makeHdr(40, 40);
    const gbl::RunMetrics r = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f);
    EXPECT_EQ(r.coverage.referenceOnly, 3u);
    EXPECT_EQ(r.coverage.testOnly, 2u);
    EXPECT_EQ(r.coverage.both, covered - 3);
    EXPECT_EQ(r.normal.all.error.count, covered - 3);
    EXPECT_EQ(r.coverage.pixels, 1600u);
}

TEST(RunMetrics, ColourErrorsDeltaEAndRmse) {
    const SurfaceImages ref = makeSurface(30, 30);
    SurfaceImages test = ref;
    for (float& v : test.diffuseColor.pixels) v += 0.02f;
    const Image hdr = makeHdr(30, 30);
    const gbl::RunMetrics r = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f);
    EXPECT_NEAR(r.diffuseColor.all.rmse, 0.02, 1e-6);
    EXPECT_NEAR(r.diffuseColor.metal.rmse, 0.02, 1e-6);
    EXPECT_GT(r.diffuseColor.all.error.mean, 0.1);  // a visible-ish change in CIEDE2000
    EXPECT_LT(r.diffuseColor.all.error.mean, 20.0);
    expectZero(r.baseColor, "base");
    expectZero(r.specularColor, "specular");
}

// The diffuse colour takes the base colour's CIEDE2000 where its pair (reference, test) is the
// base colour's bit for bit, as every dielectric's is (run_metrics.cpp baseAndDiffuseColor); each
// pixel must still get its own pair's value. Here the test's base colour is off everywhere, its
// diffuse colour is that base colour on dielectric pixels but for every third one, which is off
// by another step: per pixel the map must be pixelDeltaE of the diffuse pair itself, and the
// statistics those values'.
TEST(RunMetrics, DiffuseColourEqualToBaseColourTakesItsValueAndNoOtherPixelDoes) {
    const int w = 40, h = 36;
    const SurfaceImages ref = makeSurface(w, h);
    SurfaceImages test = ref;
    size_t own = 0, shared = 0;
    for (size_t i = 0; i < ref.coverage.size(); ++i) {
        for (int c = 0; c < 3; ++c) test.baseColor.pixels[i * 3 + c] += 0.03f * float(c + 1);
        if (ref.metallic.pixels[i] > 0.5f) continue;  // metal: diffuse 0 on both sides
        const bool differs = i % 3 == 0;
        for (int c = 0; c < 3; ++c)
            test.diffuseColor.pixels[i * 3 + c] = test.baseColor.pixels[i * 3 + c] + (differs ? 0.05f : 0.0f);
        if (ref.coverage[i]) ++(differs ? own : shared);
    }
    ASSERT_GT(own, 100u);
    ASSERT_GT(shared, 200u);
    const Image hdr = makeHdr(w, h);
    gbl::RunErrorMaps maps;
    gbl::RunMetricsOptions options;
    options.maps = &maps;
    const gbl::RunMetrics r = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f, options);
    double sum = 0.0, max = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < ref.coverage.size(); ++i) {
        if (!ref.coverage[i]) continue;
        const double e = gbl::pixelDeltaE(&ref.diffuseColor.pixels[i * 3], &test.diffuseColor.pixels[i * 3]);
        ASSERT_EQ(maps.diffuseColorDe.pixels[i], float(e)) << "pixel " << i;
        sum += e;
        max = std::max(max, e);
        ++n;
    }
    EXPECT_EQ(r.diffuseColor.all.error.count, n);
    EXPECT_EQ(r.diffuseColor.all.error.max, max);
    EXPECT_NEAR(r.diffuseColor.all.error.mean, sum / double(n), 1e-12 * sum / double(n));
}

// Independent tone map for the hand computation: Narkowicz ACES fit, then the sRGB OETF.
double handToneMap(double x) {
    if (!(x > 0.0)) return 0.0;
    double y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    y = std::min(std::max(y, 0.0), 1.0);
    return y <= 0.0031308 ? 12.92 * y : 1.055 * std::pow(y, 1.0 / 2.4) - 0.055;
}

TEST(RunMetrics, PsnrOfAKnownHdrOffsetMatchesHandComputation) {
    const int w = 32, h = 16;
    const SurfaceImages s = makeSurface(w, h);
    Image ref = makeHdr(w, h);
    Image test = ref;
    double sq = 0.0, peak = 0.0, sqTone = 0.0;
    for (size_t i = 0; i < ref.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            float& t = test.pixels[i * 4 + size_t(c)];
            t += 0.125f;  // float rounding: |t - r - 0.125| < 2.5e-7
            const double r = ref.pixels[i * 4 + size_t(c)];
            sq += (double(t) - r) * (double(t) - r);
            peak = std::max(peak, r);
            // The tone-mapped metrics are on the 8-bit values the PNGs hold (byte / 255).
            const auto q = [](double v) { return std::floor(v * 255.0 + 0.5) / 255.0; };
            const double dt = q(handToneMap(0.5 * t)) - q(handToneMap(0.5 * r));
            sqTone += dt * dt;
        }
    test.pixels[3] = 0.0f;  // alpha is not compared
    const double n = 3.0 * double(ref.pixelCount());
    const double mse = sq / n;
    const gbl::RunMetrics r = gbl::computeRunMetrics(s, s, ref, test, 0.5f);
    EXPECT_NEAR(r.image.rmseLinear, 0.125, 1e-6);
    EXPECT_DOUBLE_EQ(r.image.peakLinear, peak);
    EXPECT_NEAR(r.image.psnrLinear, 10.0 * std::log10(peak * peak / mse), 1e-9);
    EXPECT_NEAR(r.image.psnrLinear, 20.0 * std::log10(peak / 0.125), 1e-6);
    EXPECT_NEAR(r.image.maxAbs, 0.125, 1e-6);
    EXPECT_NEAR(r.image.p99Abs, 0.125, 1e-6);
    EXPECT_NEAR(r.image.rmseToneMapped, std::sqrt(sqTone / n), 1e-6);
    EXPECT_NEAR(r.image.psnrToneMapped, 10.0 * std::log10(1.0 / (sqTone / n)), 1e-3);
    EXPECT_GT(r.image.flipMean, 0.0);
    EXPECT_GT(r.image.hdrFlipMean, 0.0);
    // The G-buffers are identical: attribute errors stay 0 while the image differs.
    expectZero(r.normal, "normal");
}

TEST(RunMetrics, BadSizesAreUserErrors) {
    const SurfaceImages s = makeSurface(16, 16);
    const Image hdr = makeHdr(16, 16);
    EXPECT_THROW(gbl::computeRunMetrics(s, s, hdr, makeHdr(16, 8), 1.0f), gbl::UserError);
    SurfaceImages t = s;
    t.coverage.pop_back();
    EXPECT_THROW(gbl::computeRunMetrics(s, t, hdr, hdr, 1.0f), gbl::UserError);
    t = s;
    t.roughness = Image(8, 8, 1);
    EXPECT_THROW(gbl::computeRunMetrics(s, t, hdr, hdr, 1.0f), gbl::UserError);
    // A layout without an attribute image: not measured, not an error.
    t = s;
    t.occlusion = Image();
    const gbl::RunMetrics r = gbl::computeRunMetrics(s, t, hdr, hdr, 1.0f);
    EXPECT_EQ(r.occlusion.all.error.count, 0u);
    EXPECT_EQ(r.roughness.all.error.count, coveredCount(s));
}

TEST(RunMetrics, PreparedReferenceGivesIdenticalResults) {
    const SurfaceImages ref = makeSurface(200, 180, 7), test = makeSurface(200, 180, 8);
    const Image refHdr = makeHdr(200, 180, 3), testHdr = makeHdr(200, 180, 4);
    gbl::RunMetricsOptions plain;
    plain.hdrFlip = false;
    const gbl::RunMetrics a = gbl::computeRunMetrics(ref, test, refHdr, testHdr, 1.5f, plain);
    const gbl::PreparedReference prepared(refHdr, 1.5f);
    gbl::RunMetricsOptions reuse = plain;
    reuse.prepared = &prepared;
    const gbl::RunMetrics b = gbl::computeRunMetrics(ref, test, refHdr, testHdr, 1.5f, reuse);
    EXPECT_GT(a.image.flipMean, 0.0);
    EXPECT_EQ(a.image.flipMean, b.image.flipMean);
    EXPECT_EQ(a.image.flipMedian, b.image.flipMedian);
    EXPECT_EQ(a.image.psnrToneMapped, b.image.psnrToneMapped);
    EXPECT_EQ(a.image.psnrLinear, b.image.psnrLinear);
    for (int i = 0; i < 8; ++i) {
        EXPECT_EQ(allAttributes(a, i)->all.error.mean, allAttributes(b, i)->all.error.mean) << kNames[i];
        EXPECT_EQ(allAttributes(a, i)->all.error.p99, allAttributes(b, i)->all.error.p99) << kNames[i];
    }
    EXPECT_FALSE(b.image.hdrFlipComputed);
    // Prepared from another image or exposure: refused, not silently wrong.
    const Image otherHdr = refHdr;
    const gbl::PreparedReference wrong(otherHdr, 1.5f);
    reuse.prepared = &wrong;
    EXPECT_THROW(gbl::computeRunMetrics(ref, test, refHdr, testHdr, 1.5f, reuse), std::invalid_argument);
    reuse.prepared = &prepared;
    EXPECT_THROW(gbl::computeRunMetrics(ref, test, refHdr, testHdr, 2.0f, reuse), std::invalid_argument);
}

TEST(RunMetrics, RelativeLuminanceError) {
    Image ref(2, 1, 3, 0.0f), test(2, 1, 3, 0.0f);
    for (int c = 0; c < 3; ++c) ref.at(0, 0, c) = 2.0f, test.at(0, 0, c) = 2.2f;
    // Pixel 1: black reference -> divided by the floor 1e-2 * mean(Y) = 1e-2 * 1.0.
    for (int c = 0; c < 3; ++c) test.at(1, 0, c) = 0.001f;
    const Image e = gbl::relativeLuminanceError(ref, test);
    EXPECT_NEAR(e.pixels[0], 0.1, 1e-6);
    EXPECT_NEAR(e.pixels[1], 0.001 / 0.01, 1e-5);
}

// Speed at 1920x1080 is measured by bench/compare_bench.cpp, not asserted here.

}  // namespace

namespace {

// A test surface and render that differ from the reference everywhere, and more (garbage) in a
// block of `excluded` pixels.
struct ExclusionCase {
    SurfaceImages ref, test, testGarbage;
    Image refHdr, testHdr, testHdrGarbage;
    std::vector<uint8_t> excluded;
};

ExclusionCase exclusionCase(int w, int h) {
    ExclusionCase c{makeSurface(w, h, 7), makeSurface(w, h, 8), makeSurface(w, h, 8), makeHdr(w, h, 3), makeHdr(w, h, 4),
                    makeHdr(w, h, 4), std::vector<uint8_t>(size_t(w) * size_t(h), 0)};
    for (int y = h / 4; y < h / 2; ++y)
        for (int x = w / 4; x < w / 2; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            c.excluded[i] = 1;
            for (int k = 0; k < 3; ++k) {
                c.testHdrGarbage.pixels[i * 4 + size_t(k)] = 1e4f;
                c.testGarbage.baseColor.pixels[i * 3 + size_t(k)] = 0.0f;
                c.testGarbage.normal.pixels[i * 3 + size_t(k)] = k == 0 ? 1.0f : 0.0f;
            }
            c.testGarbage.roughness.pixels[i] = 1.0f;
        }
    return c;
}

}  // namespace

// RunMetricsOptions::excluded: the masked pixels count in no metric. What the test holds there
// (here: garbage, radiance 1e4, a wrong normal and colour) changes none of the attribute errors
// and pointwise image errors, and the masked pixels are counted apart; the FLIP map holds 0 there.
// Without a mask the garbage dominates (the case is not vacuous).
TEST(RunMetrics, ExcludedPixelsCountInNoMetric) {
    const int w = 64, h = 48;
    const ExclusionCase c = exclusionCase(w, h);
    gbl::RunMetricsOptions opt;
    opt.hdrFlip = false;
    opt.excluded = &c.excluded;
    gbl::RunErrorMaps maps;
    gbl::RunMetricsOptions withMaps = opt;
    withMaps.maps = &maps;
    const gbl::RunMetrics clean = gbl::computeRunMetrics(c.ref, c.test, c.refHdr, c.testHdr, 1.0f, opt);
    const gbl::RunMetrics garbage = gbl::computeRunMetrics(c.ref, c.testGarbage, c.refHdr, c.testHdrGarbage, 1.0f, withMaps);
    const size_t excluded = size_t(w / 4) * size_t(h / 4);
    EXPECT_EQ(garbage.coverage.excluded, excluded);
    EXPECT_EQ(garbage.coverage.both, clean.coverage.both);
    EXPECT_EQ(garbage.normal.all.error.mean, clean.normal.all.error.mean);
    EXPECT_EQ(garbage.baseColor.all.error.max, clean.baseColor.all.error.max);
    EXPECT_EQ(garbage.roughness.all.error.p99, clean.roughness.all.error.p99);
    EXPECT_EQ(garbage.image.rmseLinear, clean.image.rmseLinear);
    EXPECT_EQ(garbage.image.maxAbs, clean.image.maxAbs);
    EXPECT_EQ(garbage.image.psnrToneMapped, clean.image.psnrToneMapped);
    EXPECT_EQ(garbage.image.covered.rmseLinear, clean.image.covered.rmseLinear);
    EXPECT_LT(garbage.image.maxAbs, 100.0);
    EXPECT_EQ(garbage.image.flipTiles.size(), clean.image.flipTiles.size());
    for (size_t i = 0; i < c.excluded.size(); ++i)
        if (c.excluded[i]) {
            ASSERT_EQ(maps.flip.pixels[i], 0.0f) << i;
            ASSERT_EQ(maps.measured[i], 0) << i;
        }
    // FLIP's filters reach across the mask's edge, so its mean moves a little, not by the garbage.
    EXPECT_NEAR(garbage.image.flipMean, clean.image.flipMean, 0.1 * clean.image.flipMean);
    gbl::RunMetricsOptions none;
    none.hdrFlip = false;
    const gbl::RunMetrics unmasked = gbl::computeRunMetrics(c.ref, c.testGarbage, c.refHdr, c.testHdrGarbage, 1.0f, none);
    EXPECT_GT(unmasked.image.maxAbs, 1000.0);
    EXPECT_EQ(unmasked.coverage.excluded, 0u);
    EXPECT_EQ(unmasked.coverage.both, garbage.coverage.both + excluded);  // the excluded block is covered
    // An empty mask is no mask: the same numbers, bit for bit.
    const std::vector<uint8_t> empty;
    gbl::RunMetricsOptions emptyMask = none;
    emptyMask.excluded = &empty;
    const gbl::RunMetrics same = gbl::computeRunMetrics(c.ref, c.testGarbage, c.refHdr, c.testHdrGarbage, 1.0f, emptyMask);
    EXPECT_EQ(same.image.flipMean, unmasked.image.flipMean);
    EXPECT_EQ(same.image.rmseLinear, unmasked.image.rmseLinear);
}
