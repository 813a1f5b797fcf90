// The GPU evaluation (src/evaluate/) against its CPU oracle (measure/run_metrics.h) on real
// renders, and against values worked out by hand on a tiny case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <tuple>

#include "color_map.h"
#include "error.h"
#include "gpu_evaluator.h"
#include "layout_catalog.h"
#include "renderer.h"
#include "run_metrics.h"
#include "tone_map.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

using test::VulkanTest;

// Tolerances stated in gpu_evaluator.h: sums in double agree to rounding; quantiles from the
// histograms within 2^-10 relative; per-pixel maths in float.
constexpr double kFlipTol = 1e-4;                  // FLIP means, absolute (the goal)
constexpr double kQuantileRel = 1.0 / 1024.0 + 1e-6;

void expectRel(double gpu, double cpu, double rel, double abs, const char* what) {
    EXPECT_NEAR(gpu, cpu, std::max(abs, rel * std::abs(cpu))) << what;
}

void expectStats(const ClassStats& g, const ClassStats& c, double meanRel, const std::string& what) {
    ASSERT_EQ(g.error.count, c.error.count) << what;
    if (c.error.count == 0) return;
    expectRel(g.error.mean, c.error.mean, meanRel, 1e-7, (what + " mean").c_str());
    expectRel(g.error.rms, c.error.rms, meanRel, 1e-7, (what + " rms").c_str());
    expectRel(g.error.max, c.error.max, meanRel, 1e-6, (what + " max").c_str());
    // The quantile's bin is right within the per-pixel float error; its midpoint is within 2^-10.
    expectRel(g.error.p99, c.error.p99, kQuantileRel + meanRel, 1e-6, (what + " p99").c_str());
    expectRel(g.rmse, c.rmse, 1e-6, 1e-9, (what + " rmse").c_str());
}

void expectAttribute(const AttributeMetrics& g, const AttributeMetrics& c, double meanRel, const char* what) {
    expectStats(g.all, c.all, meanRel, std::string(what) + " all");
    expectStats(g.metal, c.metal, meanRel, std::string(what) + " metal");
    expectStats(g.dielectric, c.dielectric, meanRel, std::string(what) + " dielectric");
    EXPECT_EQ(g.skipped, c.skipped) << what;
}

struct Renders {
    RenderOutput reference, ue4, crysis;
};

const Renders& renders() {
    static const Renders r = [] {
        std::vector<RenderOutput> o = test::renderDefaultScene(
            test::decodedFrame(256, 144), {makeReferenceWiring(), generateWiring(loadLayout("ue4")),
                                           generateWiring(loadLayout("crysis3-thin"))});
        return Renders{std::move(o[0]), std::move(o[1]), std::move(o[2])};
    }();
    return r;
}

class GpuEvaluatorTest : public VulkanTest {};

TEST_F(GpuEvaluatorTest, AgreesWithTheCpuOracleOnRealRenders) {
    const Renders& r = renders();
    const float exposure = 1.0f;
    const uint32_t w = uint32_t(r.reference.hdr.width), h = uint32_t(r.reference.hdr.height);
    UploadedRender ref(ctx(), r.reference.hdr, &r.reference.surfaces);
    GpuEvaluator evaluator(ctx(), w, h);
    evaluator.setReference(ref.view(), exposure);
    for (const RenderOutput* test : {&r.ue4, &r.crysis}) {
        RunMetricsOptions cpuOptions;
        cpuOptions.hdrFlip = true;
        const RunMetrics c = computeRunMetrics(r.reference.surfaces, test->surfaces, r.reference.hdr, test->hdr,
                                               exposure, cpuOptions);
        UploadedRender t(ctx(), test->hdr, &test->surfaces);
        GpuEvalOptions options;
        options.hdrFlip = true;
        const RunMetrics g = evaluator.evaluate(t.view(), options);
        std::printf("FLIP mean gpu %.7f cpu %.7f; HDR-FLIP gpu %.7f cpu %.7f (%d exposures); PSNR %.5f / %.5f dB\n",
                    g.image.flipMean, c.image.flipMean, g.image.hdrFlipMean, c.image.hdrFlipMean,
                    g.image.hdrFlipExposures, g.image.psnrToneMapped, c.image.psnrToneMapped);
        ASSERT_GT(c.image.flipMean, 1e-4);  // the layouts do lose something: the comparison is not vacuous
        EXPECT_NEAR(g.image.flipMean, c.image.flipMean, kFlipTol);
        EXPECT_NEAR(g.image.hdrFlipMean, c.image.hdrFlipMean, kFlipTol);
        EXPECT_EQ(g.image.hdrFlipExposures, c.image.hdrFlipExposures);
        EXPECT_NEAR(g.image.flipMedian, c.image.flipMedian, kFlipTol + kQuantileRel * c.image.flipMedian);
        expectRel(g.image.rmseLinear, c.image.rmseLinear, 1e-9, 0, "rmse linear");
        expectRel(g.image.psnrLinear, c.image.psnrLinear, 1e-9, 0, "psnr linear");
        expectRel(g.image.meanAbs, c.image.meanAbs, 1e-9, 0, "mean abs");
        EXPECT_EQ(g.image.maxAbs, c.image.maxAbs);
        expectRel(g.image.p99Abs, c.image.p99Abs, kQuantileRel, 0, "p99 abs");
        // 8-bit values can differ by one step at a rounding boundary (float vs double sRGB curve).
        expectRel(g.image.rmseToneMapped, c.image.rmseToneMapped, 1e-3, 0, "rmse tone-mapped");
        EXPECT_NEAR(g.image.psnrToneMapped, c.image.psnrToneMapped, 0.01);
        for (auto [gc, cc, name] : {std::tuple{&g.image.covered, &c.image.covered, "covered"},
                                    std::tuple{&g.image.metal, &c.image.metal, "metal"},
                                    std::tuple{&g.image.dielectric, &c.image.dielectric, "dielectric"}}) {
            EXPECT_EQ(gc->pixels, cc->pixels) << name;
            expectRel(gc->relLuminanceMean, cc->relLuminanceMean, 1e-6, 1e-9, name);
            expectRel(gc->rmseLinear, cc->rmseLinear, 1e-9, 0, name);
            EXPECT_NEAR(gc->flipMean, cc->flipMean, kFlipTol) << name;
        }
        EXPECT_EQ(g.coverage.both, c.coverage.both);
        EXPECT_EQ(g.coverage.metal, c.coverage.metal);
        EXPECT_EQ(g.coverage.dielectric, c.coverage.dielectric);
        EXPECT_EQ(g.coverage.referenceOnly, c.coverage.referenceOnly);
        EXPECT_EQ(g.coverage.testOnly, c.coverage.testOnly);
        // Float angles and CIEDE2000 against the CPU's double: 1e-4 relative on means.
        expectAttribute(g.normal, c.normal, 1e-4, "normal");
        expectAttribute(g.baseColor, c.baseColor, 1e-4, "base colour");
        expectAttribute(g.diffuseColor, c.diffuseColor, 1e-4, "diffuse colour");
        expectAttribute(g.specularColor, c.specularColor, 1e-4, "specular colour");
        expectAttribute(g.roughness, c.roughness, 1e-6, "roughness");
        expectAttribute(g.metallic, c.metallic, 1e-6, "metallic");
        expectAttribute(g.occlusion, c.occlusion, 1e-6, "occlusion");
        expectAttribute(g.depth, c.depth, 1e-5, "depth");
    }
}

// The 8-bit images equal what report/error_images.cpp makes from the CPU maps, but for the
// tone-mapped values' rare one-step differences.
TEST_F(GpuEvaluatorTest, ErrorImagesMatchTheCpuMaps) {
    const Renders& r = renders();
    UploadedRender ref(ctx(), r.reference.hdr, &r.reference.surfaces);
    UploadedRender t(ctx(), r.ue4.hdr, &r.ue4.surfaces);
    GpuEvaluator evaluator(ctx(), uint32_t(r.reference.hdr.width), uint32_t(r.reference.hdr.height));
    evaluator.setReference(ref.view(), 1.0f);
    GpuErrorImages images;
    GpuEvalOptions options;
    options.hdrFlip = false;
    options.images = &images;
    options.cropSize = 32;
    evaluator.evaluate(t.view(), options);
    RunErrorMaps maps;
    RunMetricsOptions cpuOptions;
    cpuOptions.hdrFlip = false;
    cpuOptions.maps = &maps;
    computeRunMetrics(r.reference.surfaces, r.ue4.surfaces, r.reference.hdr, r.ue4.hdr, 1.0f, cpuOptions);
    const Image8 cpuRender = toneMapToSrgb8(r.ue4.hdr, 1.0f);
    ASSERT_EQ(images.render.pixels.size(), cpuRender.pixels.size());
    size_t off = 0, offByMore = 0;
    for (size_t i = 0; i < cpuRender.pixels.size(); ++i) {
        const int d = std::abs(int(images.render.pixels[i]) - int(cpuRender.pixels[i]));
        off += d != 0;
        offByMore += d > 1;
    }
    EXPECT_EQ(offByMore, 0u);
    EXPECT_LT(double(off), 1e-3 * double(cpuRender.pixels.size()));
    const Image8 cpuFlip = applyColorMap(maps.flip, 0.0f, 1.0f);
    size_t flipOff = 0;
    for (size_t i = 0; i < cpuFlip.pixels.size(); ++i) flipOff += cpuFlip.pixels[i] != images.flip.pixels[i];
    EXPECT_LT(double(flipOff), 1e-2 * double(cpuFlip.pixels.size()));  // a colour step where FLIP rounds apart
    ASSERT_FALSE(images.worst.empty());
    const std::vector<Crop> cpuWorst = findWorstRegions(maps.relLuminance, 32, 3);
    ASSERT_FALSE(cpuWorst.empty());
    // The device searches windows aligned to its 8-pixel tiles: its worst window is the best of
    // those on the CPU's map too (within float rounding), and no better than the exact worst. (Where
    // two regions of the scene are about as bad, the two searches may pick different ones.)
    const Image& m = maps.relLuminance;
    auto windowMean = [&](int x0, int y0) {
        double sum = 0.0;
        for (int y = y0; y < y0 + 32; ++y)
            for (int x = x0; x < x0 + 32; ++x) sum += m.pixels[(size_t(y) * m.width + x) * m.channels];
        return sum / (32.0 * 32.0);
    };
    double bestAligned = 0.0;
    for (int y = 0; y + 32 <= m.height; y += 8)
        for (int x = 0; x + 32 <= m.width; x += 8) bestAligned = std::max(bestAligned, windowMean(x, y));
    const double chosen = windowMean(images.worst[0].x, images.worst[0].y);
    EXPECT_EQ(images.worst[0].x % 8, 0);
    EXPECT_EQ(images.worst[0].y % 8, 0);
    EXPECT_GE(chosen, 0.99 * bestAligned) << images.worst[0].x << "," << images.worst[0].y;
    EXPECT_LE(chosen, cpuWorst[0].meanError * 1.0001 + 1e-9);
    EXPECT_GT(chosen, 0.0);
}

// Every pixel covered by the same flat dielectric: normal +z, base and diffuse colour 0.5,
// specular 0.04, roughness 0.5, occlusion 1, view depth 2 (cases change the pixels they test).
SurfaceImages flatSurfaces(int w, int h) {
    SurfaceImages s;
    s.normal = Image(w, h, 3, 0.0f);
    for (int i = 0; i < w * h; ++i) s.normal.pixels[size_t(i) * 3 + 2] = 1.0f;
    s.baseColor = Image(w, h, 3, 0.5f);
    s.diffuseColor = Image(w, h, 3, 0.5f);
    s.specularColor = Image(w, h, 3, 0.04f);
    s.roughness = Image(w, h, 1, 0.5f);
    s.metallic = Image(w, h, 1, 0.0f);
    s.occlusion = Image(w, h, 1, 1.0f);
    s.viewDepth = Image(w, h, 1, 2.0f);
    s.coverage.assign(size_t(w * h), 1);
    return s;
}

// 4 x 2 pixels worked out by hand.
TEST_F(GpuEvaluatorTest, TinyCaseByHand) {
    const int w = 4, h = 2;
    Image refHdr(w, h, 4, 0.5f), testHdr(w, h, 4, 0.5f);
    testHdr.pixels[0] = 0.6f;  // pixel 0, red: +0.1
    SurfaceImages rs = flatSurfaces(w, h), ts = flatSurfaces(w, h);
    const double tenDeg = 10.0 * std::numbers::pi / 180.0;
    ts.normal.pixels[3 * 1 + 0] = float(std::sin(tenDeg));  // pixel 1: normal tilted 10 degrees
    ts.normal.pixels[3 * 1 + 2] = float(std::cos(tenDeg));
    ts.roughness.pixels[2] = 0.75f;   // pixel 2: roughness +0.25
    ts.viewDepth.pixels[3] = 2.2f;    // pixel 3: depth +10 %
    rs.metallic.pixels[4] = 1.0f;     // pixel 4: metal in the reference ...
    ts.metallic.pixels[4] = 1.0f;
    ts.coverage[7] = 0;               // pixel 7: lost by the layout
    UploadedRender ref(ctx(), refHdr, &rs), test(ctx(), testHdr, &ts);
    GpuEvaluator evaluator(ctx(), w, h);
    evaluator.setReference(ref.view(), 1.0f);
    GpuEvalOptions o;
    o.hdrFlip = false;
    const RunMetrics m = evaluator.evaluate(test.view(), o);
    // Image: one sample of 24 differs by 0.1.
    EXPECT_NEAR(m.image.rmseLinear, std::sqrt(0.01 / 24.0), 1e-7);
    EXPECT_NEAR(m.image.meanAbs, 0.1 / 24.0, 1e-8);
    EXPECT_NEAR(m.image.maxAbs, 0.1, 1e-7);
    EXPECT_NEAR(m.image.p99Abs, 0.1, 0.1 / 1024.0);  // rank ceil(0.99 * 24) = 24: the largest
    EXPECT_NEAR(m.image.peakLinear, 0.5, 0.0);
    EXPECT_NEAR(m.image.psnrLinear, 10.0 * std::log10(0.25 / (0.01 / 24.0)), 1e-4);
    // Coverage: 7 pixels in both, one metal; pixel 7 only in the reference.
    EXPECT_EQ(m.coverage.both, 7u);
    EXPECT_EQ(m.coverage.metal, 1u);
    EXPECT_EQ(m.coverage.dielectric, 6u);
    EXPECT_EQ(m.coverage.referenceOnly, 1u);
    EXPECT_EQ(m.coverage.testOnly, 0u);
    // Normal: 10 degrees at one of 7 pixels (all dielectric).
    EXPECT_NEAR(m.normal.all.error.max, 10.0, 1e-4);
    EXPECT_NEAR(m.normal.all.error.mean, 10.0 / 7.0, 1e-5);
    EXPECT_NEAR(m.normal.dielectric.error.mean, 10.0 / 6.0, 1e-5);
    EXPECT_EQ(m.normal.metal.error.count, 1u);
    EXPECT_EQ(m.normal.metal.error.mean, 0.0);
    EXPECT_NEAR(m.roughness.all.error.mean, 0.25 / 7.0, 1e-7);
    EXPECT_NEAR(m.roughness.all.error.rms, std::sqrt(0.0625 / 7.0), 1e-7);
    EXPECT_NEAR(m.depth.all.error.max, 0.1, 1e-6);
    EXPECT_EQ(m.baseColor.all.error.max, 0.0);
    EXPECT_EQ(m.baseColor.all.error.p99, 0.0);
    // p99 of {0 x 6, 10}: rank ceil(6.93) = 7: the 10 degrees, within its bin's half width.
    EXPECT_NEAR(m.normal.all.error.p99, 10.0, 10.0 / 1024.0);
    // Identical tone-mapped pixels but one: FLIP is 0 away from it (its filters spread the change).
    EXPECT_GT(m.image.flipMean, 0.0);
}

// A new reference is measured as new even where its images reuse the last one's structs (and
// perhaps their handles): compare renders each view's reference after freeing the last, so
// allocators hand the same addresses back. The evaluator once told references apart by address
// and kept view 0's luminance floor and HDR-FLIP exposures for view 1 (compare_bands_cli_test
// failed under load, when the addresses happened to repeat). Here they repeat by construction:
// one slot, a bright reference and then a dim one, each against a test that differs by 0.002 at
// one pixel; the floor (1e-2 x the mean luminance: 0.04 bright, 0.0001 dim) decides its error.
TEST_F(GpuEvaluatorTest, ANewReferenceInTheLastOnesPlaceIsMeasuredAsNew) {
    const int w = 8, h = 8;
    const Image bright(w, h, 4, 4.0f), dim(w, h, 4, 0.01f);
    Image dimTest = dim;
    for (int c = 0; c < 3; ++c) dimTest.pixels[size_t(c)] = 0.012f;
    const SurfaceImages surfaces = flatSurfaces(w, h);
    GpuEvalOptions o;
    o.hdrFlip = true;

    GpuEvaluator fresh(ctx(), w, h);  // the dim reference alone: what the answer must be
    UploadedRender dimAlone(ctx(), dim, &surfaces), test(ctx(), dimTest, &surfaces);
    fresh.setReference(dimAlone.view(), 1.0f);
    const RunMetrics expected = fresh.evaluate(test.view(), o);
    // |0.012 - 0.01| / max(0.01, floor 1e-4) at one pixel of 64 (luminance weights sum to 1).
    EXPECT_NEAR(expected.image.covered.relLuminanceMean, 0.2 / 64.0, 1e-5);

    GpuEvaluator reused(ctx(), w, h);
    std::optional<UploadedRender> slot(std::in_place, ctx(), bright, &surfaces);
    reused.setReference(slot->view(), 1.0f);
    (void)reused.evaluate(test.view(), o);
    const GpuImage* brightHdr = slot->view().hdr;
    slot.reset();
    slot.emplace(ctx(), dim, &surfaces);
    ASSERT_EQ(slot->view().hdr, brightHdr) << "the slot did not give the same address back";
    reused.setReference(slot->view(), 1.0f);
    const RunMetrics got = reused.evaluate(test.view(), o);
    EXPECT_EQ(got.image.covered.relLuminanceMean, expected.image.covered.relLuminanceMean);
    EXPECT_EQ(got.image.hdrFlipExposures, expected.image.hdrFlipExposures);
    EXPECT_EQ(got.image.hdrFlipMean, expected.image.hdrFlipMean);
    EXPECT_EQ(got.image.flipMean, expected.image.flipMean);
}

// FLIP's separable passes compute eight outputs per invocation over 512-column row segments and
// 32-row column strips (flip_filter.comp.glsl): sizes that are multiples of none of these (a
// partial last group of eight, a partial segment and strip, frames lower than the filters) agree
// with the CPU oracle (measure/flip.cpp) as the real renders do.
TEST_F(GpuEvaluatorTest, FlipAtOddSizesAgreesWithTheCpuOracle) {
    for (auto [w, h] : {std::pair{203, 37}, std::pair{1029, 19}, std::pair{13, 5}}) {
        Image refHdr(w, h, 4, 1.0f), testHdr(w, h, 4, 1.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c) {
                    const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 4 + size_t(c);
                    // Smooth gradients with edges; the test adds a pattern of small errors and a bright block.
                    refHdr.pixels[i] = 0.2f + 0.6f * float((x * (c + 3) + y * 7) % 41) / 41.0f;
                    testHdr.pixels[i] = refHdr.pixels[i] * (1.0f + 0.05f * float(((x + 2 * y + c) % 5) - 2));
                    if (x % 17 < 3 && y % 11 < 2) testHdr.pixels[i] = 4.0f;
                }
        SurfaceImages rs = flatSurfaces(w, h), ts = flatSurfaces(w, h);
        UploadedRender ref(ctx(), refHdr, &rs), test(ctx(), testHdr, &ts);
        GpuEvaluator evaluator(ctx(), uint32_t(w), uint32_t(h));
        evaluator.setReference(ref.view(), 1.0f);
        GpuErrorImages images;
        GpuEvalOptions options;
        options.hdrFlip = true;
        options.images = &images;
        const RunMetrics g = evaluator.evaluate(test.view(), options);
        RunErrorMaps maps;
        RunMetricsOptions cpuOptions;
        cpuOptions.hdrFlip = true;
        cpuOptions.maps = &maps;
        const RunMetrics c = computeRunMetrics(rs, ts, refHdr, testHdr, 1.0f, cpuOptions);
        const std::string at = std::to_string(w) + "x" + std::to_string(h);
        ASSERT_GT(c.image.flipMean, 1e-3) << at;  // not vacuous
        EXPECT_NEAR(g.image.flipMean, c.image.flipMean, kFlipTol) << at;
        EXPECT_NEAR(g.image.hdrFlipMean, c.image.hdrFlipMean, kFlipTol) << at;
        EXPECT_EQ(g.image.hdrFlipExposures, c.image.hdrFlipExposures) << at;
        // Pixel by pixel: the colour-mapped FLIP map, a colour step apart where FLIP rounds apart.
        const Image8 cpuFlip = applyColorMap(maps.flip, 0.0f, 1.0f);
        ASSERT_EQ(images.flip.pixels.size(), cpuFlip.pixels.size()) << at;
        size_t off = 0, offByMore = 0;
        for (size_t i = 0; i < cpuFlip.pixels.size(); ++i) {
            const int d = std::abs(int(images.flip.pixels[i]) - int(cpuFlip.pixels[i]));
            off += d != 0;
            offByMore += d > 8;  // neighbouring viridis entries differ by a few levels per channel
        }
        EXPECT_EQ(offByMore, 0u) << at;
        EXPECT_LT(double(off), 1e-2 * double(cpuFlip.pixels.size())) << at;

        // Deferred (compare on a GPU: the writer's job unpacks): packed until unpack(), the same
        // bytes then, and untouched by a later run that writes its own images meanwhile.
        GpuErrorImages deferred, later;
        options.images = &deferred;
        options.deferImages = true;
        evaluator.evaluate(test.view(), options);
        EXPECT_TRUE(deferred.render.pixels.empty() && deferred.packed) << at;
        options.images = &later;
        options.deferImages = false;
        evaluator.evaluate(ref.view(), options);  // the reference against itself: other images
        EXPECT_NE(later.difference.pixels, images.difference.pixels) << at;
        deferred.unpack();
        EXPECT_FALSE(deferred.packed) << at;
        const std::pair<const Image8*, const Image8*> same[] = {
            {&deferred.render, &images.render}, {&deferred.reference, &images.reference},
            {&deferred.difference, &images.difference}, {&deferred.heat, &images.heat},
            {&deferred.flip, &images.flip}, {&deferred.normal, &images.normal}};
        for (const auto& [a, b] : same) EXPECT_EQ(a->pixels, b->pixels) << at;
    }
}

TEST_F(GpuEvaluatorTest, ReferenceAgainstItselfIsZero) {
    const Renders& r = renders();
    UploadedRender ref(ctx(), r.reference.hdr, &r.reference.surfaces);
    GpuEvaluator evaluator(ctx(), uint32_t(r.reference.hdr.width), uint32_t(r.reference.hdr.height));
    evaluator.setReference(ref.view(), 1.0f);
    const RunMetrics m = evaluator.evaluate(ref.view(), GpuEvalOptions{});
    EXPECT_EQ(m.image.rmseLinear, 0.0);
    EXPECT_TRUE(std::isinf(m.image.psnrLinear));
    EXPECT_EQ(m.image.flipMean, 0.0);
    EXPECT_EQ(m.image.hdrFlipMean, 0.0);
    EXPECT_EQ(m.normal.all.error.max, 0.0);
    EXPECT_EQ(m.baseColor.all.error.mean, 0.0);
}

TEST_F(GpuEvaluatorTest, WrongSizeIsAUserError) {
    Image a(4, 4, 4, 0.5f), b(4, 2, 4, 0.5f);
    UploadedRender ra(ctx(), a, nullptr), rb(ctx(), b, nullptr);
    GpuEvaluator evaluator(ctx(), 4, 4);
    evaluator.setReference(ra.view(), 1.0f);
    EXPECT_THROW(evaluator.evaluate(rb.view(), GpuEvalOptions{}), UserError);
}

}  // namespace
}  // namespace gbl
