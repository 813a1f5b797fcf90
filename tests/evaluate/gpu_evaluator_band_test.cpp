// A banded GPU evaluation (gpu_evaluator.h beginReferenceBands .. finishRun) against the
// whole-frame evaluate() of the same images: the property is that cutting the frame into bands
// changes nothing but the order of the double sums. Real renders of the default scene at an odd
// size (203 x 157: neither dimension a multiple of 8 or of the passes' workgroups), cut into bands
// of 24, 8 and 40 rows and a short last band, each uploaded with its halo as its own images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

#include "gpu_evaluator.h"
#include "layout_catalog.h"
#include "renderer.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

using test::VulkanTest;

constexpr uint32_t kWidth = 203, kHeight = 157;
const std::vector<uint32_t> kBandRows = {24, 8, 40, 24, 8, 40};  // then the last 13 rows

// Sums in double, in another order: this close (the brief's bound; the sums here are of ~3e4
// non-negative terms, so reordering moves them by ~1e-16 relative per term at most).
constexpr double kSumRel = 1e-12;

struct Renders {
    RenderOutput reference, test;
};

const Renders& renders() {
    static const Renders r = [] {
        RenderSettings rs = test::decodedFrame(kWidth, kHeight);
        rs.splitSumShaderSamples = 16;
        std::vector<RenderOutput> o =
            test::renderDefaultScene(rs, {makeReferenceWiring(), generateWiring(loadLayout("crysis3-thin"))});
        return Renders{std::move(o[0]), std::move(o[1])};
    }();
    return r;
}

// Rows [first, first + rows) of an image (empty stays empty).
Image rowsOf(const Image& im, uint32_t first, uint32_t rows) {
    if (im.empty()) return im;
    Image out(im.width, int(rows), im.channels);
    const size_t row = size_t(im.width) * size_t(im.channels);
    std::copy(im.pixels.begin() + std::ptrdiff_t(first * row), im.pixels.begin() + std::ptrdiff_t((first + rows) * row),
              out.pixels.begin());
    return out;
}

SurfaceImages rowsOf(const SurfaceImages& s, uint32_t first, uint32_t rows) {
    SurfaceImages o;
    o.normal = rowsOf(s.normal, first, rows);
    o.baseColor = rowsOf(s.baseColor, first, rows);
    o.diffuseColor = rowsOf(s.diffuseColor, first, rows);
    o.specularColor = rowsOf(s.specularColor, first, rows);
    o.roughness = rowsOf(s.roughness, first, rows);
    o.metallic = rowsOf(s.metallic, first, rows);
    o.occlusion = rowsOf(s.occlusion, first, rows);
    o.viewDepth = rowsOf(s.viewDepth, first, rows);
    o.coverage.assign(s.coverage.begin() + std::ptrdiff_t(size_t(first) * s.normal.width),
                      s.coverage.begin() + std::ptrdiff_t(size_t(first + rows) * s.normal.width));
    return o;
}

// The bands of kBandRows and the rest, each with `halo` rows above and below (clamped).
std::vector<EvalBand> bandsWithHalo(uint32_t halo) {
    std::vector<EvalBand> bands;
    uint32_t row = 0;
    for (size_t k = 0; row < kHeight; ++k) {
        EvalBand b;
        b.firstRow = row;
        b.rows = k < kBandRows.size() ? kBandRows[k] : kHeight - row;
        b.imageFirstRow = row > halo ? row - halo : 0;
        b.imageRows = std::min(kHeight, row + b.rows + halo) - b.imageFirstRow;
        bands.push_back(b);
        row += b.rows;
    }
    return bands;
}

uint32_t maxImageRows(const std::vector<EvalBand>& bands) {
    uint32_t m = 0;
    for (const EvalBand& b : bands) m = std::max(m, b.imageRows);
    return m;
}

// A band's images on the device, as compare will hold them (render/: keepOnDevice bands).
struct BandUpload {
    BandUpload(const VulkanContext& ctx, const RenderOutput& r, const EvalBand& b, bool surfaces)
        : s(rowsOf(r.surfaces, b.imageFirstRow, b.imageRows)),
          up(ctx, rowsOf(r.hdr, b.imageFirstRow, b.imageRows), surfaces ? &s : nullptr) {}
    SurfaceImages s;
    UploadedRender up;
};

struct BandedResult {
    RunMetrics metrics;
    GpuErrorImages images;
};

BandedResult runInBands(const VulkanContext& ctx, const std::vector<EvalBand>& bands, GpuEvalOptions options,
                        bool surfaces = true, float exposure = 1.0f) {
    const Renders& r = renders();
    GpuEvaluator ev(ctx, kWidth, kHeight, maxImageRows(bands));
    ev.beginReferenceBands(exposure);
    for (const EvalBand& b : bands) {
        BandUpload ref(ctx, r.reference, b, surfaces);
        ev.addReferenceBand(ref.up.view(), b);
    }
    ev.endReferenceBands();
    BandedResult out;
    if (options.images) options.images = &out.images;
    ev.beginRun(options);
    for (const EvalBand& b : bands) {
        BandUpload ref(ctx, r.reference, b, surfaces), test(ctx, r.test, b, surfaces);
        ev.addBand(ref.up.view(), test.up.view(), b);
    }
    out.metrics = ev.finishRun();
    return out;
}

BandedResult runWhole(const VulkanContext& ctx, GpuEvalOptions options, bool surfaces = true, float exposure = 1.0f) {
    const Renders& r = renders();
    UploadedRender ref(ctx, r.reference.hdr, surfaces ? &r.reference.surfaces : nullptr);
    UploadedRender test(ctx, r.test.hdr, surfaces ? &r.test.surfaces : nullptr);
    GpuEvaluator ev(ctx, kWidth, kHeight);
    ev.setReference(ref.view(), exposure);
    BandedResult out;
    if (options.images) options.images = &out.images;
    out.metrics = ev.evaluate(test.view(), options);
    return out;
}

void expectSum(double banded, double whole, const std::string& what) {
    EXPECT_NEAR(banded, whole, kSumRel * std::abs(whole)) << what;
}

void expectStats(const ClassStats& b, const ClassStats& w, const std::string& what) {
    EXPECT_EQ(b.error.count, w.error.count) << what;
    expectSum(b.error.mean, w.error.mean, what + " mean");
    expectSum(b.error.rms, w.error.rms, what + " rms");
    EXPECT_EQ(b.error.max, w.error.max) << what;  // maxima and histogram quantiles: exact
    EXPECT_EQ(b.error.p99, w.error.p99) << what;
    expectSum(b.rmse, w.rmse, what + " rmse");
}

void expectAttribute(const AttributeMetrics& b, const AttributeMetrics& w, const std::string& what) {
    expectStats(b.all, w.all, what + " all");
    expectStats(b.metal, w.metal, what + " metal");
    expectStats(b.dielectric, w.dielectric, what + " dielectric");
    EXPECT_EQ(b.skipped, w.skipped) << what;
}

void expectClass(const ClassImageErrors& b, const ClassImageErrors& w, const std::string& what) {
    EXPECT_EQ(b.pixels, w.pixels) << what;
    expectSum(b.relLuminanceMean, w.relLuminanceMean, what + " relative luminance");
    expectSum(b.rmseLinear, w.rmseLinear, what + " rmse");
    expectSum(b.flipMean, w.flipMean, what + " FLIP");
    EXPECT_EQ(b.referenceNoise, w.referenceNoise) << what;
}

// Every number but the FLIP-derived ones (which the halo decides).
void expectSameNonFlip(const RunMetrics& b, const RunMetrics& w) {
    EXPECT_EQ(b.coverage.pixels, w.coverage.pixels);
    EXPECT_EQ(b.coverage.both, w.coverage.both);
    EXPECT_EQ(b.coverage.referenceOnly, w.coverage.referenceOnly);
    EXPECT_EQ(b.coverage.testOnly, w.coverage.testOnly);
    EXPECT_EQ(b.coverage.metal, w.coverage.metal);
    EXPECT_EQ(b.coverage.dielectric, w.coverage.dielectric);
    expectAttribute(b.normal, w.normal, "normal");
    expectAttribute(b.baseColor, w.baseColor, "base colour");
    expectAttribute(b.diffuseColor, w.diffuseColor, "diffuse colour");
    expectAttribute(b.specularColor, w.specularColor, "specular colour");
    expectAttribute(b.roughness, w.roughness, "roughness");
    expectAttribute(b.metallic, w.metallic, "metallic");
    expectAttribute(b.occlusion, w.occlusion, "occlusion");
    expectAttribute(b.depth, w.depth, "depth");
    const ShadedErrors &x = b.image, &y = w.image;
    expectSum(x.rmseLinear, y.rmseLinear, "rmse linear");
    expectSum(x.psnrLinear, y.psnrLinear, "psnr linear");
    EXPECT_EQ(x.peakLinear, y.peakLinear);
    expectSum(x.rmseToneMapped, y.rmseToneMapped, "rmse tone-mapped");
    expectSum(x.psnrToneMapped, y.psnrToneMapped, "psnr tone-mapped");
    EXPECT_EQ(x.maxAbs, y.maxAbs);
    EXPECT_EQ(x.p99Abs, y.p99Abs);
    expectSum(x.meanAbs, y.meanAbs, "mean abs");
    EXPECT_EQ(x.hdrFlipComputed, y.hdrFlipComputed);
    EXPECT_EQ(x.hdrFlipExposures, y.hdrFlipExposures);
    for (auto [c, d, what] : {std::tuple{&x.covered, &y.covered, "covered"}, std::tuple{&x.metal, &y.metal, "metal"},
                              std::tuple{&x.dielectric, &y.dielectric, "dielectric"}}) {
        EXPECT_EQ(c->pixels, d->pixels) << what;
        expectSum(c->relLuminanceMean, d->relLuminanceMean, std::string(what) + " relative luminance");
        expectSum(c->rmseLinear, d->rmseLinear, std::string(what) + " rmse");
        EXPECT_EQ(c->referenceNoise, d->referenceNoise) << what;
    }
}

void expectSameFlip(const RunMetrics& b, const RunMetrics& w) {
    expectSum(b.image.flipMean, w.image.flipMean, "FLIP mean");
    EXPECT_EQ(b.image.flipMedian, w.image.flipMedian);
    expectSum(b.image.hdrFlipMean, w.image.hdrFlipMean, "HDR-FLIP mean");
    expectClass(b.image.covered, w.image.covered, "covered");
    expectClass(b.image.metal, w.image.metal, "metal");
    expectClass(b.image.dielectric, w.image.dielectric, "dielectric");
}

void expectSameImage(const Image8& b, const Image8& w, const char* what) {
    ASSERT_EQ(b.width, w.width) << what;
    ASSERT_EQ(b.height, w.height) << what;
    ASSERT_EQ(b.channels, w.channels) << what;
    size_t differ = 0, first = 0;
    for (size_t i = 0; i < w.pixels.size(); ++i)
        if (b.pixels[i] != w.pixels[i] && differ++ == 0) first = i;
    EXPECT_EQ(differ, 0u) << what << ": first differing byte " << first << " (pixel " << first / 3 << ")";
}

class GpuEvaluatorBandTest : public VulkanTest {};

TEST_F(GpuEvaluatorBandTest, HaloRowsCoverTheWidestFlipFilter) {
    // At the default 67.02 pixels per degree: the CSF's radius ceil(3 sqrt(0.04 / (2 pi^2)) ppd)
    // = ceil(9.05) = 10 (Andersson et al. 2020, b_max 0.04 of the blue-yellow channel) is wider
    // than the features' ceil(3 * 0.5 * 0.082 ppd) = ceil(8.24) = 9.
    const double ppd = flipPixelsPerDegree();
    const double csf = 3.0 * std::sqrt(0.04 / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd;
    const double features = 3.0 * 0.5 * 0.082 * ppd;
    EXPECT_EQ(flipHaloRows(), uint32_t(std::ceil(std::max(csf, features))));
    EXPECT_EQ(flipHaloRows(), 10u);
}

// Every number and every 8-bit image of a banded run with a FLIP halo equals the whole frame's.
TEST_F(GpuEvaluatorBandTest, BandsWithHaloEqualTheWholeFrame) {
    GpuEvalOptions options;
    options.hdrFlip = true;
    GpuErrorImages marker;
    options.images = &marker;  // runWhole / runInBands point it at their own
    options.cropSize = 32;
    options.cropCount = 3;
    const BandedResult w = runWhole(ctx(), options);
    const BandedResult b = runInBands(ctx(), bandsWithHalo(flipHaloRows()), options);
    std::printf("FLIP mean whole %.17g bands %.17g; HDR-FLIP %.17g / %.17g (%d exposures)\n", w.metrics.image.flipMean,
                b.metrics.image.flipMean, w.metrics.image.hdrFlipMean, b.metrics.image.hdrFlipMean,
                w.metrics.image.hdrFlipExposures);
    ASSERT_GT(w.metrics.image.flipMean, 1e-4);  // the layout loses something: not vacuous
    ASSERT_GT(w.metrics.normal.all.error.p99, 0.0);
    ASSERT_TRUE(w.metrics.image.hdrFlipComputed);
    expectSameNonFlip(b.metrics, w.metrics);
    expectSameFlip(b.metrics, w.metrics);
    expectSameImage(b.images.render, w.images.render, "render");
    expectSameImage(b.images.reference, w.images.reference, "reference");
    expectSameImage(b.images.difference, w.images.difference, "difference");
    expectSameImage(b.images.heat, w.images.heat, "heat");
    expectSameImage(b.images.flip, w.images.flip, "flip");
    ASSERT_FALSE(w.images.normal.pixels.empty());
    expectSameImage(b.images.normal, w.images.normal, "normal");
    ASSERT_EQ(b.images.worst.size(), w.images.worst.size());
    ASSERT_FALSE(w.images.worst.empty());
    for (size_t i = 0; i < w.images.worst.size(); ++i) {
        EXPECT_EQ(b.images.worst[i].x, w.images.worst[i].x) << i;
        EXPECT_EQ(b.images.worst[i].y, w.images.worst[i].y) << i;
        EXPECT_EQ(b.images.worst[i].size, w.images.worst[i].size) << i;
        EXPECT_EQ(b.images.worst[i].meanError, w.images.worst[i].meanError) << i;
    }
}

// Without a halo FLIP's filters clamp at the bands' edges: its mean moves, the rest does not.
TEST_F(GpuEvaluatorBandTest, WithoutHaloFlipDiffers) {
    GpuEvalOptions options;
    options.hdrFlip = false;
    const BandedResult w = runWhole(ctx(), options);
    const BandedResult b = runInBands(ctx(), bandsWithHalo(0), options);
    expectSameNonFlip(b.metrics, w.metrics);
    EXPECT_GT(std::abs(b.metrics.image.flipMean - w.metrics.image.flipMean), 1e3 * kSumRel * w.metrics.image.flipMean);
    // A halo one row short of the filters' is not enough either.
    const BandedResult s = runInBands(ctx(), bandsWithHalo(flipHaloRows() - 1), options);
    EXPECT_NE(s.metrics.image.flipMean, w.metrics.image.flipMean);
}

// HDR-FLIP in bands: the reference bands give the whole frame's exposure range (exact median
// included), without surfaces and at another exposure.
TEST_F(GpuEvaluatorBandTest, HdrFlipInBandsWithoutSurfaces) {
    GpuEvalOptions options;
    options.hdrFlip = true;
    const BandedResult w = runWhole(ctx(), options, false, 0.5f);
    const BandedResult b = runInBands(ctx(), bandsWithHalo(flipHaloRows()), options, false, 0.5f);
    ASSERT_GT(w.metrics.image.hdrFlipMean, 1e-4);
    EXPECT_EQ(b.metrics.image.hdrFlipExposures, w.metrics.image.hdrFlipExposures);
    EXPECT_GE(w.metrics.image.hdrFlipExposures, 2);
    expectSum(b.metrics.image.hdrFlipMean, w.metrics.image.hdrFlipMean, "HDR-FLIP mean");
    expectSum(b.metrics.image.flipMean, w.metrics.image.flipMean, "FLIP mean");
    EXPECT_EQ(b.metrics.image.flipMedian, w.metrics.image.flipMedian);
    EXPECT_EQ(b.metrics.coverage.both, 0u);  // no surfaces: no attributes, as in the whole frame
    EXPECT_EQ(w.metrics.coverage.both, 0u);
}

TEST_F(GpuEvaluatorBandTest, MisuseIsALogicError) {
    const Renders& r = renders();
    const std::vector<EvalBand> bands = bandsWithHalo(flipHaloRows());
    GpuEvaluator ev(ctx(), kWidth, kHeight, maxImageRows(bands));
    EXPECT_THROW(ev.beginRun(GpuEvalOptions{}), std::logic_error);  // no reference statistics yet
    UploadedRender whole(ctx(), r.reference.hdr, nullptr);
    EXPECT_THROW(ev.setReference(whole.view(), 1.0f), std::logic_error);  // planes hold a band only
    ev.beginReferenceBands(1.0f);
    BandUpload second(ctx(), r.reference, bands[1], false);
    EXPECT_THROW(ev.addReferenceBand(second.up.view(), bands[1]), std::logic_error);  // out of order
    for (const EvalBand& b : bands) {
        BandUpload ref(ctx(), r.reference, b, false);
        ev.addReferenceBand(ref.up.view(), b);
    }
    ev.endReferenceBands();
    // Crops need bands starting on multiples of 8: a band of 12 rows breaks the next one's.
    GpuErrorImages images;
    GpuEvalOptions crops;
    crops.images = &images;
    crops.cropSize = 16;
    ev.beginRun(crops);
    EvalBand a{0, 12 + flipHaloRows(), 0, 12}, next{0, 12 + 12 + flipHaloRows(), 12, 12};
    BandUpload ra(ctx(), r.reference, a, false), rn(ctx(), r.reference, next, false);
    ev.addBand(ra.up.view(), ra.up.view(), a);
    EXPECT_THROW(ev.addBand(rn.up.view(), rn.up.view(), next), std::logic_error);
    EXPECT_THROW(ev.finishRun(), std::logic_error);  // the frame is not covered
}

// Ground-truth noise is whole-frame only (the renderer refuses ground-truth bands).
TEST_F(GpuEvaluatorBandTest, NoiseIsRefusedInBands) {
    const Renders& r = renders();
    UploadedRender ref(ctx(), r.reference.hdr, nullptr);
    GpuEvaluator ev(ctx(), kWidth, kHeight, kHeight);  // room for whole frames and bands
    const Image noise(int(kWidth), int(kHeight), 1, 0.01f);
    ev.setReference(ref.view(), 1.0f, &noise);
    EXPECT_THROW(ev.beginRun(GpuEvalOptions{}), std::logic_error);
}

}  // namespace
}  // namespace gbl
