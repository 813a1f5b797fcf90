#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <set>
#include <string>

#include "color_map.h"
#include "error.h"
#include "error_images.h"
#include "image_io.h"
#include "png_writer.h"
#include "run_metrics.h"
#include "worst_regions.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using gbl::Image;
using gbl::Image8;

struct TempDir : gbl::test::TempDir {
    TempDir() : gbl::test::TempDir("gbl_error_images_") {}
};

bool sameRgb(const Image8& im, int x, int y, gbl::Rgb8 c) {
    const size_t i = (size_t(y) * size_t(im.width) + size_t(x)) * size_t(im.channels);
    return im.pixels[i] == c.r && im.pixels[i + 1] == c.g && im.pixels[i + 2] == c.b;
}

gbl::SurfaceImages makeSurface(int w, int h) {
    gbl::SurfaceImages s;
    for (Image* im : {&s.normal, &s.baseColor, &s.diffuseColor, &s.specularColor, &s.emissive})
        *im = Image(w, h, 3, 0.5f);
    for (Image* im : {&s.roughness, &s.metallic, &s.occlusion, &s.depth, &s.viewDepth}) *im = Image(w, h, 1, 0.5f);
    for (size_t i = 0; i < s.normal.pixelCount(); ++i) s.normal.pixels[i * 3] = 0.0f, s.normal.pixels[i * 3 + 1] = 0.0f,
                                                         s.normal.pixels[i * 3 + 2] = 1.0f;
    s.coverage.assign(size_t(w) * size_t(h), 0);
    for (int y = h / 4; y < h - h / 4; ++y)
        for (int x = w / 4; x < w - w / 4; ++x) s.coverage[size_t(y) * size_t(w) + size_t(x)] = 1;
    return s;
}

Image makeHdr(int w, int h) {
    Image im(w, h, 4, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = 0.05f + 2.0f * float(x) / float(w) + 0.1f * float(c);
    return im;
}

// ---- Heat maps ---------------------------------------------------------------------------------

TEST(ErrorImages, HeatMapHasTitleAndLegendColumns) {
    Image e(100, 60, 1);
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 100; ++x) e.at(x, y, 0) = float(x) / 99.0f;
    const Image8 pic = gbl::heatMapImage(e, 0.0f, 1.0f, "TEST");
    const int band = gbl::titleBandHeight(60);
    EXPECT_GT(band, 0);
    EXPECT_GT(pic.width, 100 + 20);  // a legend beside the map
    EXPECT_GE(pic.height, 60 + band);
    // The map sits below the title band: first column = entry 0, last = entry 255.
    EXPECT_TRUE(sameRgb(pic, 0, band + 5, gbl::viridisTable()[0]));
    EXPECT_TRUE(sameRgb(pic, 99, band + 5, gbl::viridisTable()[255]));
    // The legend's columns hold the colour bar: viridis colours somewhere right of the map.
    std::set<int> barColours;
    for (int x = 100; x < pic.width; ++x)
        for (int y = band; y < pic.height; ++y)
            for (int k = 0; k < 256; k += 51)
                if (sameRgb(pic, x, y, gbl::viridisTable()[size_t(k)])) barColours.insert(k);
    EXPECT_GE(barColours.size(), 4u);
    // Title text: some foreground pixels in the band.
    int bright = 0;
    for (int y = 0; y < band; ++y)
        for (int x = 0; x < 40; ++x) bright += pic.pixels[(size_t(y) * size_t(pic.width) + size_t(x)) * 3] > 200;
    EXPECT_GT(bright, 5);
}

TEST(ErrorImages, ZeroErrorHeatMapIsUniform) {
    const Image e(64, 32, 1, 0.0f);
    const Image8 pic = gbl::heatMapImage(e, 0.0f, 0.1f, "ZERO");
    const int band = gbl::titleBandHeight(32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) ASSERT_TRUE(sameRgb(pic, x, band + y, gbl::viridisTable()[0])) << x << "," << y;
}

TEST(ErrorImages, UnmeasuredPixelsAreDimmedGrey) {
    const Image e(8, 4, 1, 1.0f);
    std::vector<uint8_t> measured(32, 1);
    measured[5] = 0;
    measured[6] = 0;
    Image bg(8, 4, 3, 1.0f);  // white reference
    for (int c = 0; c < 3; ++c) bg.at(6, 0, c) = 0.0f;  // black there
    const Image8 pic = gbl::heatMapImage(e, 0.0f, 1.0f, "N", &bg, &measured);
    const int band = gbl::titleBandHeight(4);
    const auto px = [&](int x, int y, int c) { return pic.pixels[(size_t(band + y) * size_t(pic.width) + size_t(x)) * 3 + size_t(c)]; };
    EXPECT_TRUE(sameRgb(pic, 0, band, gbl::viridisTable()[255]));
    for (int x : {5, 6}) {
        EXPECT_EQ(px(x, 0, 0), px(x, 0, 1));
        EXPECT_EQ(px(x, 0, 1), px(x, 0, 2));
        EXPECT_LT(px(x, 0, 0), 128);  // dimmed
    }
    EXPECT_GT(px(5, 0, 0), px(6, 0, 0));  // follows the reference's brightness
}

// The error maps compare writes at 1080p, with every table colour in the map and the legend and
// NaN pixels, fit an indexed PNG (at most 256 colours): png_writer.h's size figures rest on it.
TEST(ErrorImages, HeatMapsAtFullSizeAreIndexed) {
    Image e(1920, 1080, 1);
    for (int y = 0; y < 1080; ++y)
        for (int x = 0; x < 1920; ++x) e.at(x, y, 0) = (x + y) % 97 == 0 ? NAN : float(x) / 1919.0f;
    const Image8 pic = gbl::heatMapImage(e, 0.0f, 1.0f, "FLIP 0.0123 (mean), 1920x1080");
    Image8 indices;
    std::vector<unsigned char> palette;
    ASSERT_TRUE(gbl::indexColours(pic, indices, palette));
    std::set<int> table;
    for (const gbl::Rgb8& c : gbl::viridisTable()) table.insert(c.r << 16 | c.g << 8 | c.b);
    EXPECT_GE(palette.size() / 3, table.size());  // every table colour, plus NaN grey and text
}

TEST(ErrorImages, AmplifiedDifference) {
    Image a(4, 2, 3, 0.5f), b(4, 2, 3, 0.5f);
    b.at(1, 1, 0) = 0.51f;  // x8 -> 0.08 -> 20
    b.at(2, 1, 1) = 0.0f;   // x8 saturates -> 255
    const Image8 pic = gbl::amplifiedDifferenceImage(a, b, 8.0f, "X8");
    const int band = gbl::titleBandHeight(2);
    const auto px = [&](int x, int y, int c) { return pic.pixels[(size_t(band + y) * size_t(pic.width) + size_t(x)) * 3 + size_t(c)]; };
    EXPECT_EQ(px(0, 0, 0), 0);
    EXPECT_EQ(px(1, 1, 0), 20);
    EXPECT_EQ(px(1, 1, 1), 0);
    EXPECT_EQ(px(2, 1, 1), 255);
}

TEST(ErrorImages, SrgbFloatTo8Rounds) {
    Image a(3, 1, 3, 0.0f);
    a.at(1, 0, 0) = 0.5f;  // 128
    a.at(2, 0, 0) = 2.0f;  // clamps to 255
    a.at(2, 0, 1) = -1.0f;
    const Image8 b = gbl::srgbFloatTo8(a);
    EXPECT_EQ(b.pixels[3], 128);
    EXPECT_EQ(b.pixels[6], 255);
    EXPECT_EQ(b.pixels[7], 0);
}

// ---- Files -------------------------------------------------------------------------------------

// The metrics of `test` against `ref` with a w x h HDR image `hdrScale` times the reference's,
// their error maps in `maps`.
gbl::RunMetrics metricsOf(const gbl::SurfaceImages& ref, const gbl::SurfaceImages& test, int w, int h, float hdrScale,
                          gbl::RunErrorMaps& maps) {
    const Image hdr = makeHdr(w, h);
    Image hdrTest = hdr;
    for (float& v : hdrTest.pixels) v *= hdrScale;
    gbl::RunMetricsOptions options;
    options.maps = &maps;
    return gbl::computeRunMetrics(ref, test, hdr, hdrTest, 1.0f, options);
}

TEST(ErrorImages, WritesEveryImageAndTheExrRoundTrips) {
    const int w = 48, h = 36;
    const gbl::SurfaceImages ref = makeSurface(w, h);
    gbl::SurfaceImages test = ref;
    for (float& v : test.roughness.pixels) v += 0.01f;
    for (size_t i = 0; i < test.normal.pixelCount(); ++i) test.normal.pixels[i * 3] = 0.05f;
    gbl::RunErrorMaps maps;
    const gbl::RunMetrics metrics = metricsOf(ref, test, w, h, 1.05f, maps);

    TempDir dir;
    gbl::ErrorImageOptions o;
    o.label = "OCT16";
    const gbl::ErrorImagePaths paths = gbl::writeErrorImages(dir.path, "oct16/", maps, metrics, o);
    ASSERT_EQ(paths.all().size(), 6u);
    EXPECT_EQ(paths.render, "oct16/render.png");
    for (const std::string& p : paths.all()) {
        EXPECT_FALSE(fs::path(p).is_absolute()) << p;
        EXPECT_TRUE(fs::exists(dir.path / p)) << p;
    }
    const Image8 render = gbl::readImage8((dir.path / paths.render).string());
    EXPECT_EQ(render.width, w);
    EXPECT_EQ(render.height, h);
    for (const std::string* p : {&paths.heatmap, &paths.flip, &paths.normalError}) {
        const Image8 pic = gbl::readImage8((dir.path / *p).string());
        EXPECT_GT(pic.width, w) << *p;  // legend columns
        EXPECT_GE(pic.height, h + gbl::titleBandHeight(h)) << *p;
    }
    const Image8 diff = gbl::readImage8((dir.path / paths.difference).string());
    EXPECT_GE(diff.width, w);
    EXPECT_EQ(diff.height, h + gbl::titleBandHeight(h));

    // Raw channels, bit exact.
    const std::vector<std::string> names = gbl::errorExrChannels(maps);
    const std::vector<std::string> expected = {"flip",         "hdr_flip",     "abs_r",         "abs_g",
                                               "abs_b",        "rel_luminance", "normal_deg",   "base_color_de",
                                               "diffuse_de",   "specular_de",  "roughness_abs", "metallic_abs",
                                               "occlusion_abs", "depth_rel",   "measured"};
    EXPECT_EQ(names, expected);
    const Image back = gbl::readExrChannels((dir.path / paths.errorsExr).string(), names);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    ASSERT_EQ(back.channels, int(names.size()));
    const size_t nc = names.size();
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
        ASSERT_EQ(back.pixels[i * nc + 0], maps.flip.pixels[i]);
        ASSERT_EQ(back.pixels[i * nc + 2], maps.absLinear.pixels[i * 3]);
        ASSERT_EQ(back.pixels[i * nc + 4], maps.absLinear.pixels[i * 3 + 2]);
        ASSERT_EQ(back.pixels[i * nc + 6], maps.normalDeg.pixels[i]);
        ASSERT_EQ(back.pixels[i * nc + 10], maps.roughnessAbs.pixels[i]);
        ASSERT_EQ(back.pixels[i * nc + 14], maps.measured[i] ? 1.0f : 0.0f);
    }
    // The roughness channel holds the +0.01 offset where measured.
    const size_t centre = size_t(h / 2) * size_t(w) + size_t(w / 2);
    EXPECT_NEAR(back.pixels[centre * nc + 10], 0.01f, 1e-6f);
    EXPECT_EQ(back.pixels[0 * nc + 10], 0.0f);  // background corner
}

// compare lists a run's files in the report before its background writer writes them: the paths
// said beforehand are the ones written. errors.exr in half holds each map value as binary16.
TEST(ErrorImages, PathsAreKnownBeforeWritingAndHalfExrHoldsRoundedValues) {
    const int w = 40, h = 30;
    const gbl::SurfaceImages ref = makeSurface(w, h);
    gbl::SurfaceImages test = ref;
    for (float& v : test.roughness.pixels) v += 0.013f;
    gbl::RunErrorMaps maps;
    const gbl::RunMetrics metrics = metricsOf(ref, test, w, h, 1.07f, maps);
    TempDir dir;
    gbl::ErrorImageOptions o;
    o.exrType = gbl::ExrPixelType::Half;
    const gbl::ErrorImagePaths said = gbl::errorImagePaths("run/a_", maps);
    const gbl::ErrorImagePaths written = gbl::writeErrorImages(dir.path, "run/a_", maps, metrics, o);
    EXPECT_EQ(said.all(), written.all());
    gbl::RunErrorMaps noNormals = maps;
    noNormals.normalDeg = Image();
    EXPECT_TRUE(gbl::errorImagePaths("x/", noNormals).normalError.empty());

    const std::string exr = (dir.path / written.errorsExr).string();
    EXPECT_EQ(gbl::readExrPixelType(exr), gbl::ExrPixelType::Half);
    const Image back = gbl::readExrChannels(exr, {"rel_luminance", "roughness_abs", "abs_g"});
    size_t nonzero = 0;
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
        ASSERT_EQ(back.pixels[i * 3 + 0], gbl::roundToHalf(maps.relLuminance.pixels[i]));
        ASSERT_EQ(back.pixels[i * 3 + 1], gbl::roundToHalf(maps.roughnessAbs.pixels[i]));
        ASSERT_EQ(back.pixels[i * 3 + 2], gbl::roundToHalf(maps.absLinear.pixels[i * 3 + 1]));
        nonzero += maps.roughnessAbs.pixels[i] != 0.0f;
    }
    EXPECT_GT(nonzero, 0u);  // the comparison saw real values
}

TEST(ErrorImages, MissingMapsAreUserErrors) {
    TempDir dir;
    gbl::RunErrorMaps empty;
    EXPECT_THROW(gbl::writeErrorImages(dir.path, "x_", empty, gbl::RunMetrics{}), gbl::UserError);
}

// ---- Worst regions -----------------------------------------------------------------------------

TEST(WorstRegions, FindsAPlantedSquareExactly) {
    Image e(200, 150, 1, 0.0f);
    for (int y = 47; y < 47 + 16; ++y)
        for (int x = 123; x < 123 + 16; ++x) e.at(x, y, 0) = 1.0f;
    const std::vector<gbl::Crop> crops = gbl::findWorstRegions(e, 16, 3);
    ASSERT_EQ(crops.size(), 1u);  // the rest of the map is error free
    EXPECT_EQ(crops[0].x, 123);
    EXPECT_EQ(crops[0].y, 47);
    EXPECT_EQ(crops[0].size, 16);
    EXPECT_DOUBLE_EQ(crops[0].meanError, 1.0);
}

TEST(WorstRegions, RanksSquaresAndNeverOverlaps) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 0.1f);
    Image e(160, 120, 1);
    for (float& v : e.pixels) v = u(rng);
    auto plant = [&](int x0, int y0, float v) {
        for (int y = y0; y < y0 + 12; ++y)
            for (int x = x0; x < x0 + 12; ++x) e.at(x, y, 0) = v;
    };
    plant(10, 90, 2.0f);
    plant(140, 3, 3.0f);
    plant(70, 50, 1.0f);
    const auto crops = gbl::findWorstRegions(e, 12, 6);
    ASSERT_EQ(crops.size(), 6u);
    EXPECT_EQ(crops[0].x, 140);
    EXPECT_EQ(crops[0].y, 3);
    EXPECT_EQ(crops[1].x, 10);
    EXPECT_EQ(crops[1].y, 90);
    EXPECT_EQ(crops[2].x, 70);
    EXPECT_EQ(crops[2].y, 50);
    for (size_t i = 0; i < crops.size(); ++i) {
        if (i > 0) {
            EXPECT_GE(crops[i - 1].meanError, crops[i].meanError);
        }
        for (size_t j = i + 1; j < crops.size(); ++j)
            EXPECT_TRUE(std::abs(crops[i].x - crops[j].x) >= 12 || std::abs(crops[i].y - crops[j].y) >= 12);
    }
    // The 4th is the best window (brute force) that overlaps none of the first three.
    double best = -1.0;
    for (int y = 0; y + 12 <= 120; ++y)
        for (int x = 0; x + 12 <= 160; ++x) {
            bool overlaps = false;
            for (int k = 0; k < 3; ++k)
                overlaps |= std::abs(x - crops[size_t(k)].x) < 12 && std::abs(y - crops[size_t(k)].y) < 12;
            if (overlaps) continue;
            double s = 0.0;
            for (int yy = y; yy < y + 12; ++yy)
                for (int xx = x; xx < x + 12; ++xx) s += e.at(xx, yy, 0);
            best = std::max(best, s / 144.0);
        }
    EXPECT_NEAR(crops[3].meanError, best, 1e-9);
}

TEST(WorstRegions, EdgeCases) {
    EXPECT_TRUE(gbl::findWorstRegions(Image(10, 10, 1, 0.0f), 4, 3).empty());
    EXPECT_TRUE(gbl::findWorstRegions(Image(10, 10, 1, 1.0f), 4, 0).empty());
    const auto big = gbl::findWorstRegions(Image(10, 6, 1, 1.0f), 64, 2);  // clamped to 6
    ASSERT_EQ(big.size(), 1u);
    EXPECT_EQ(big[0].size, 6);
}

TEST(WorstRegions, WritesUpscaledCrops) {
    Image8 a{20, 10, 3, std::vector<unsigned char>(600)};
    for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = static_cast<unsigned char>(i % 251);
    const gbl::Crop crop{3, 2, 5, 1.0};
    const Image8 up = gbl::cropUpscaled(a, crop, 4);
    ASSERT_EQ(up.width, 20);
    ASSERT_EQ(up.height, 20);
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(up.pixels[(size_t(y) * 20 + size_t(x)) * 3 + size_t(c)],
                          a.pixels[(size_t(2 + y / 4) * 20 + size_t(3 + x / 4)) * 3 + size_t(c)]);
    TempDir dir;
    const auto files = gbl::writeCrops(dir.path, "run/", {crop, gbl::Crop{10, 0, 5, 0.5}}, a, a, a);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[1].heat, "run/crop1_heat.png");
    for (const auto& f : files)
        for (const std::string* p : {&f.reference, &f.test, &f.heat}) {
            const Image8 back = gbl::readImage8((dir.path / *p).string());
            EXPECT_EQ(back.width, 20);
            EXPECT_EQ(back.height, 20);
        }
    EXPECT_THROW(gbl::cropUpscaled(a, gbl::Crop{18, 0, 5, 0.0}, 4), gbl::UserError);
}

}  // namespace
