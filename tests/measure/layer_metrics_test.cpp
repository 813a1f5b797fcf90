// The material layers' metrics (run_metrics.h "Material layers", layer_classes.h) on a small
// synthetic reference / decoded pair whose errors are known in closed form: each expected value
// is computed here from the definitions, not by the library's functions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "layer_classes.h"
#include "run_metrics.h"

namespace {

using gbl::Image;
using gbl::LayerAttribute;
using gbl::LayerClass;
using gbl::SurfaceImages;

constexpr int kW = 16, kH = 8;
constexpr double kDeg = std::numbers::pi / 180.0;

// Every pixel covered, normal +z, grey dielectric; no layer anywhere.
SurfaceImages plainSurface() {
    SurfaceImages s;
    for (Image* im : {&s.normal, &s.baseColor, &s.diffuseColor, &s.specularColor, &s.emissive}) *im = Image(kW, kH, 3);
    for (Image* im : {&s.roughness, &s.metallic, &s.occlusion, &s.depth, &s.viewDepth}) *im = Image(kW, kH, 1);
    s.coverage.assign(size_t(kW) * kH, 1);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            s.normal.at(x, y, 2) = 1.0f;
            for (int c = 0; c < 3; ++c) s.baseColor.at(x, y, c) = s.diffuseColor.at(x, y, c) = 0.5f;
            s.roughness.at(x, y, 0) = 0.5f;
            s.occlusion.at(x, y, 0) = 1.0f;
            s.viewDepth.at(x, y, 0) = 2.0f;
            s.depth.at(x, y, 0) = 0.5f;
        }
    return s;
}

// Regions: coated x < 8 (64 px), sheen y < 2 (32 px, 16 of them coated too), anisotropic y >= 6
// and x >= 8 (16 px); plain: the rest (x >= 8, 2 <= y < 6: 32 px).
bool coated(int x, int) { return x < 8; }
bool sheen(int, int y) { return y < 2; }
bool aniso(int x, int y) { return y >= 6 && x >= 8; }

const float kGreyRef = 0.2f, kGreyTest = 0.1f;  // sheen colours (grey: CIEDE2000 in closed form)

SurfaceImages layeredReference() {
    SurfaceImages s = plainSurface();
    s.allocateLayers(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (coated(x, y)) {
                s.coat.at(x, y, 0) = 0.75f;
                s.coatRoughness.at(x, y, 0) = 0.3f;
                // The coat normal 30 degrees from the base normal, about x.
                s.coatNormal.at(x, y, 1) = float(std::sin(30.0 * kDeg));
                s.coatNormal.at(x, y, 2) = float(std::cos(30.0 * kDeg));
            }
            if (sheen(x, y)) {
                for (int c = 0; c < 3; ++c) s.sheenColor.at(x, y, c) = kGreyRef;
                s.sheenRoughness.at(x, y, 0) = 0.9f;
            }
            if (aniso(x, y)) {
                s.anisotropyStrength.at(x, y, 0) = 0.8f;
                s.anisotropyDirection.at(x, y, 0) = 1.0f;
            }
        }
    return s;
}

// A layout that drops the coat (decodes 0: its normal is then the base normal), halves the sheen's
// grey, stores sheen roughness 0.5, anisotropy 0.6 with its direction turned: 40 degrees on the
// left half of the anisotropic pixels, 150 (a line 30 degrees off) on the right half.
SurfaceImages layeredTest() {
    SurfaceImages s = layeredReference();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            s.coat.at(x, y, 0) = 0.0f;
            s.coatRoughness.at(x, y, 0) = 0.0f;
            for (int c = 0; c < 3; ++c) s.coatNormal.at(x, y, c) = 0.0f;
            if (sheen(x, y)) {
                for (int c = 0; c < 3; ++c) s.sheenColor.at(x, y, c) = kGreyTest;
                s.sheenRoughness.at(x, y, 0) = 0.5f;
            }
            if (aniso(x, y)) {
                s.anisotropyStrength.at(x, y, 0) = 0.6f;
                const double a = (x < 12 ? 40.0 : 150.0) * kDeg;
                s.anisotropyDirection.at(x, y, 0) = float(std::cos(a));
                s.anisotropyDirection.at(x, y, 1) = float(std::sin(a));
            }
        }
    return s;
}

Image flatHdr(float v) {
    Image im(kW, kH, 4);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = v;
            im.at(x, y, 3) = 1.0f;
        }
    return im;
}

// CIEDE2000 of two neutral greys of linear value g1, g2, from Sharma, Wu & Dalal (2005): with
// a* = b* = 0 every chroma and hue term vanishes, so dE00 = |L2 - L1| / S_L, S_L = 1 + 0.015
// (Lbar - 50)^2 / sqrt(20 + (Lbar - 50)^2); a grey's XYZ / white is g, so L* = 116 g^(1/3) - 16.
double greyDeltaE2000(double g1, double g2) {
    const double l1 = 116.0 * std::cbrt(g1) - 16.0, l2 = 116.0 * std::cbrt(g2) - 16.0;
    const double lbar = 0.5 * (l1 + l2), d = (lbar - 50.0) * (lbar - 50.0);
    return std::abs(l2 - l1) / (1.0 + 0.015 * d / std::sqrt(20.0 + d));
}

TEST(LayerMetrics, EachLayerAttributeOverThePixelsCarryingIt) {
    const SurfaceImages ref = layeredReference(), test = layeredTest();
    const Image hdr = flatHdr(1.0f);
    gbl::RunMetricsOptions o;
    o.hdrFlip = false;
    const gbl::RunMetrics m = gbl::computeRunMetrics(ref, test, hdr, hdr, 1.0f, o);
    ASSERT_TRUE(m.layers.has_value());
    const gbl::LayerMetrics& L = *m.layers;
    auto all = [&](LayerAttribute a) { return L[a].all.error; };
    EXPECT_EQ(all(LayerAttribute::Coat).count, 64u);
    EXPECT_NEAR(all(LayerAttribute::Coat).mean, 0.75, 1e-7);  // the dropped coat's error = its amount
    EXPECT_NEAR(all(LayerAttribute::Coat).max, 0.75, 1e-7);
    EXPECT_NEAR(all(LayerAttribute::CoatRoughness).mean, 0.3, 1e-7);
    EXPECT_EQ(all(LayerAttribute::CoatNormal).count, 64u);
    EXPECT_NEAR(all(LayerAttribute::CoatNormal).mean, 30.0, 1e-4);  // against the base normal
    EXPECT_EQ(all(LayerAttribute::SheenColor).count, 32u);
    EXPECT_NEAR(all(LayerAttribute::SheenColor).mean, greyDeltaE2000(kGreyRef, kGreyTest), 1e-6);
    EXPECT_NEAR(L[LayerAttribute::SheenColor].all.rmse, kGreyRef - kGreyTest, 1e-7);
    EXPECT_NEAR(all(LayerAttribute::SheenRoughness).mean, 0.4, 1e-7);
    EXPECT_EQ(all(LayerAttribute::AnisotropyStrength).count, 16u);
    EXPECT_NEAR(all(LayerAttribute::AnisotropyStrength).mean, 0.2, 1e-7);
    // Lines: 40 degrees on 8 pixels, 150 = 30 degrees off on the other 8.
    EXPECT_NEAR(all(LayerAttribute::AnisotropyDirection).mean, 35.0, 1e-4);
    EXPECT_NEAR(all(LayerAttribute::AnisotropyDirection).max, 40.0, 1e-4);
    // All dielectric: the metal class is empty, the dielectric one is `all`.
    EXPECT_EQ(L[LayerAttribute::Coat].metal.error.count, 0u);
    EXPECT_EQ(L[LayerAttribute::Coat].dielectric.error.count, 64u);
}

TEST(LayerMetrics, ImageErrorsPerLayerClassOverlapAndPlainIsTheRest) {
    const SurfaceImages ref = layeredReference(), test = layeredTest();
    const Image refHdr = flatHdr(1.0f);
    Image testHdr = flatHdr(1.0f);
    for (int y = 0; y < kH; ++y)  // the lit image off by 0.1 on the coated pixels only
        for (int x = 0; x < kW; ++x)
            if (coated(x, y))
                for (int c = 0; c < 3; ++c) testHdr.at(x, y, c) = 1.1f;
    gbl::RunMetricsOptions o;
    o.hdrFlip = false;
    const gbl::RunMetrics m = gbl::computeRunMetrics(ref, test, refHdr, testHdr, 1.0f, o);
    ASSERT_TRUE(m.image.layerClasses.has_value());
    const auto& k = *m.image.layerClasses;
    const auto& coatedE = k[size_t(LayerClass::Coated)];
    const auto& sheenE = k[size_t(LayerClass::Sheen)];
    const auto& anisoE = k[size_t(LayerClass::Anisotropic)];
    const auto& plainE = k[size_t(LayerClass::Plain)];
    EXPECT_EQ(coatedE.pixels, 64u);
    EXPECT_EQ(sheenE.pixels, 32u);  // 16 of them coated too: a pixel may be in several classes
    EXPECT_EQ(anisoE.pixels, 16u);
    EXPECT_EQ(plainE.pixels, 32u);
    EXPECT_NEAR(coatedE.rmseLinear, double(1.1f) - 1.0, 1e-7);
    EXPECT_NEAR(coatedE.relLuminanceMean, double(1.1f) - 1.0, 1e-6);
    // Sheen: half its pixels coated, so its mean squared error is half the coated one's.
    EXPECT_NEAR(sheenE.rmseLinear, (double(1.1f) - 1.0) / std::sqrt(2.0), 1e-7);
    EXPECT_EQ(anisoE.rmseLinear, 0.0);
    EXPECT_EQ(plainE.rmseLinear, 0.0);
    EXPECT_GT(coatedE.flipMean, 0.0);
    // The tile means over the class's pixels: 16 x 9 tiles of a 16 x 8 image (one column each,
    // an empty row of tiles is left out), 0 where the class has no pixel.
    EXPECT_FALSE(coatedE.flipTiles.empty());
    EXPECT_EQ(coatedE.flipTiles.size(), anisoE.flipTiles.size());
    // metal / dielectric / covered are as before.
    EXPECT_EQ(m.image.covered.pixels, size_t(kW) * kH);
}

TEST(LayerMetrics, AbsentWithoutLayersAndZeroAgainstItself) {
    const SurfaceImages plain = plainSurface();
    const Image hdr = flatHdr(1.0f);
    gbl::RunMetricsOptions o;
    o.hdrFlip = false;
    const gbl::RunMetrics none = gbl::computeRunMetrics(plain, plain, hdr, hdr, 1.0f, o);
    EXPECT_FALSE(none.layers.has_value());
    EXPECT_FALSE(none.image.layerClasses.has_value());

    const SurfaceImages ref = layeredReference();
    const gbl::RunMetrics self = gbl::computeRunMetrics(ref, ref, hdr, hdr, 1.0f, o);
    ASSERT_TRUE(self.layers.has_value());
    for (const gbl::AttributeMetrics& a : self.layers->byAttribute) {
        EXPECT_GT(a.all.error.count, 0u);
        EXPECT_EQ(a.all.error.max, 0.0);
    }
    // Only one side with layers (a decode that did not fill them): not measured, not zero.
    const gbl::RunMetrics oneSided = gbl::computeRunMetrics(ref, plain, hdr, hdr, 1.0f, o);
    EXPECT_FALSE(oneSided.layers.has_value());
}

TEST(LayerMetrics, AnisotropyDirectionIsAnAngleBetweenLinesInTheTangentPlane) {
    const float n[3] = {0.0f, 0.0f, 1.0f};
    bool ok = false;
    const float x[3] = {1.0f, 0.0f, 0.0f}, minusX[3] = {-1.0f, 0.0f, 0.0f};
    EXPECT_EQ(gbl::anisotropyDirectionErrorDeg(x, n, minusX, n, ok), 0.0);  // t and -t shade alike
    EXPECT_TRUE(ok);
    // A tangent with a normal component is measured after Gram-Schmidt, as the lighting shades it.
    const float tilted[3] = {0.0f, 1.0f, 5.0f};
    EXPECT_NEAR(gbl::anisotropyDirectionErrorDeg(x, n, tilted, n, ok), 90.0, 1e-9);
    const float zero[3] = {0.0f, 0.0f, 0.0f}, alongN[3] = {0.0f, 0.0f, 2.0f};
    gbl::anisotropyDirectionErrorDeg(x, n, zero, n, ok);
    EXPECT_FALSE(ok);  // no direction on one side: skipped
    gbl::anisotropyDirectionErrorDeg(x, n, alongN, n, ok);
    EXPECT_FALSE(ok);
}

TEST(LayerMetrics, ClassesOfAPixel) {
    SurfaceImages s = plainSurface();
    s.allocateLayers(kW, kH);
    s.coat.at(0, 0, 0) = 0.1f;
    s.sheenColor.at(0, 0, 2) = 0.01f;
    s.anisotropyStrength.at(1, 0, 0) = 0.5f;
    const uint8_t both = gbl::layerBitsAt(s, 0), a = gbl::layerBitsAt(s, 1), none = gbl::layerBitsAt(s, 2);
    EXPECT_TRUE(gbl::inLayerClass(both, LayerClass::Coated));
    EXPECT_TRUE(gbl::inLayerClass(both, LayerClass::Sheen));
    EXPECT_FALSE(gbl::inLayerClass(both, LayerClass::Plain));
    EXPECT_TRUE(gbl::inLayerClass(a, LayerClass::Anisotropic));
    EXPECT_TRUE(gbl::inLayerClass(none, LayerClass::Plain));
    EXPECT_FALSE(gbl::inLayerClass(none, LayerClass::Coated));
}

}  // namespace
