// Bandwidth as GPUs pay it: tile-memory fits per family, the lighting pass's reads, and the
// traffic per GPU class from a frame's compressed sizes, against sums written out by hand.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "effective_bandwidth.h"
#include "error.h"
#include "layout_catalog.h"

namespace gbl {
namespace {

const TileFit& fitOf(const std::vector<TileFit>& fits, const std::string& family) {
    for (const TileFit& f : fits)
        if (f.family == family) return f;
    throw std::logic_error("no family " + family);
}

TEST(TileMemory, FamiliesAndTheirPublishedLimits) {
    // Apple's Table 1: A7 128 bits, A8-A10 256 bits, A11 512 bits; Arm: 128 bits on Mali since T760.
    const std::map<std::string, int> expected = {{"apple-a7", 16}, {"apple-a8-a10", 32}, {"apple-a11", 64}, {"mali-t760+", 16}};
    int seen = 0;
    for (const TileFamily& f : tileFamilies()) {
        const auto e = expected.find(f.id);
        ASSERT_NE(e, expected.end()) << f.id;
        EXPECT_EQ(f.colourBytesPerPixel, e->second) << f.id;
        EXPECT_NE(std::string(f.source), "");
        ++seen;
    }
    EXPECT_EQ(seen, 4);
}

TEST(TileMemory, FitsPerFamilyByHand) {
    // crysis3-thin: two RGBA8 targets = 8 B, + the RGBA16F lit output 8 B = 16 B in 3 targets:
    // fits Mali's 16 B and the A7's 16 B (4 targets), and everything larger.
    const std::vector<TileFit> thin = tileFits(loadLayout("crysis3-thin"), 8);
    EXPECT_EQ(fitOf(thin, "apple-a7").colourBytesPerPixel, 16);
    EXPECT_TRUE(fitOf(thin, "apple-a7").fits);
    EXPECT_TRUE(fitOf(thin, "mali-t760+").fits);
    EXPECT_TRUE(fitOf(thin, "apple-a11").fits);
    // ue4: RGB10A2 + 4 x RGBA8 = 20 B, + 8 = 28 B in 6 targets: over the A7 (and its 4 targets),
    // within the A8-A10's 32 B; on Mali "slower", on the A7 a "spill".
    const std::vector<TileFit> ue4 = tileFits(loadLayout("ue4"), 8);
    EXPECT_EQ(fitOf(ue4, "apple-a8-a10").colourBytesPerPixel, 28);
    EXPECT_EQ(fitOf(ue4, "apple-a8-a10").colourTargets, 6);
    EXPECT_TRUE(fitOf(ue4, "apple-a8-a10").fits);
    EXPECT_FALSE(fitOf(ue4, "apple-a7").fits);
    EXPECT_EQ(fitOf(ue4, "apple-a7").overflow, "spill");
    EXPECT_FALSE(fitOf(ue4, "mali-t760+").fits);
    EXPECT_EQ(fitOf(ue4, "mali-t760+").overflow, "slower");
    // The reference: 5 x RGBA32F = 80 B + 8: no family.
    for (const TileFit& f : tileFits(loadLayout("reference"), 8)) EXPECT_FALSE(f.fits) << f.family;
}

TEST(Lighting, ParsesTheFlag) {
    EXPECT_EQ(parseLightingModel("tiled", "--lighting").kind, LightingModel::Kind::Tiled);
    EXPECT_EQ(parseLightingModel("clustered", "--lighting").readsPerPixel, 1.0);
    const LightingModel v = parseLightingModel("volumes:2.5", "--lighting");
    EXPECT_EQ(v.kind, LightingModel::Kind::Volumes);
    EXPECT_EQ(v.readsPerPixel, 2.5);
    EXPECT_FALSE(v.counted);
    EXPECT_EQ(v.text(), "volumes:2.5");
    EXPECT_TRUE(parseLightingModel("volumes", "--lighting").counted);
    for (const char* bad : {"volume", "volumes:", "volumes:0", "volumes:-1", "volumes:x", "volumes:nan", ""})
        EXPECT_THROW(parseLightingModel(bad, "--lighting"), UserError) << bad;
}

TEST(Lighting, VolumesMultiplyTheLightingReads) {
    // ue4 at 1920x1080, 1 sample: 25 B/px (20 targets + 5 depth-stencil) written once; read once
    // tiled, 3 times with volumes:3.
    const Layout ue4 = loadLayout("ue4");
    const double pixels = 1920.0 * 1080.0;
    const FrameTraffic tiled = computeFrameTraffic(ue4, 1920, 1080, 1, LightingModel{});
    EXPECT_DOUBLE_EQ(tiled.lightingReadBytes, pixels * 25);
    EXPECT_DOUBLE_EQ(tiled.totalBytes, pixels * 50);
    const FrameTraffic volumes = computeFrameTraffic(ue4, 1920, 1080, 1, parseLightingModel("volumes:3", "--lighting"));
    EXPECT_DOUBLE_EQ(volumes.geometryWriteBytes, pixels * 25);
    EXPECT_DOUBLE_EQ(volumes.lightingReadBytes, pixels * 75);
    EXPECT_DOUBLE_EQ(volumes.totalBytes, pixels * 100);
}

// A frame whose every target stores `dcc` / `afbcRead` / `afbcWrite` bytes per pixel.
FrameCompression uniformCompression(const Layout& layout, double dcc, double afbcRead, double afbcWrite) {
    FrameCompression f;
    f.width = 1920;
    f.height = 1080;
    for (const Target& t : layout.targets) {
        TargetCompression c;
        c.name = t.name;
        c.format = t.format;
        c.bytesPerPixel = t.bytes();
        c.pixels = 1920ull * 1080ull;
        c.dcc.bytes = dcc * double(c.pixels);
        c.afbc.compressed = true;
        c.afbc.readBytes = afbcRead * double(c.pixels);
        c.afbc.headerBytes = 0;
        c.afbc.bodyBytes = afbcWrite * double(c.pixels);
        f.targets.push_back(c);
    }
    return f;
}

TEST(EffectiveBandwidth, ClassesByHand) {
    // ue4's 5 targets at 1 B/px DCC, 1.5 B/px AFBC read, 1.25 written; depth 5 B uncompressed.
    const Layout ue4 = loadLayout("ue4");
    const double pixels = 1920.0 * 1080.0;
    const EffectiveBandwidth e = computeEffectiveBandwidth(ue4, uniformCompression(ue4, 1.0, 1.5, 1.25), 1, LightingModel{});
    EXPECT_DOUBLE_EQ(e.nominalBytesPerPixel, 25.0);
    const ClassTraffic* dcc = e.find("desktop-dcc");
    ASSERT_TRUE(dcc);
    EXPECT_DOUBLE_EQ(dcc->bytesPerPixel, 5 * 1.0 + 5);
    // (targets + depth) written and read once, plus the lit output's 8 B.
    EXPECT_DOUBLE_EQ(dcc->trafficBytes, pixels * (10 * 2 + 8));
    const ClassTraffic* afbc = e.find("mali-afbc");
    ASSERT_TRUE(afbc);
    EXPECT_DOUBLE_EQ(afbc->bytesPerPixel, 5 * 1.5 + 5);
    EXPECT_DOUBLE_EQ(afbc->trafficBytes, pixels * ((5 * 1.25 + 5) + (5 * 1.5 + 5) + 8));
    // ue4 with the lit output is 28 B: it fits the A11's 64 B, so only the lit output leaves.
    const ClassTraffic* tile = e.find("tile-subpass");
    ASSERT_TRUE(tile);
    EXPECT_DOUBLE_EQ(tile->bytesPerPixel, 0.0);
    EXPECT_DOUBLE_EQ(tile->trafficBytes, pixels * 8);
    EXPECT_DOUBLE_EQ(e.nominalTrafficBytes, pixels * (25 * 2 + 8));
    // Light volumes, 2 per pixel: the reads double, the writes do not; the tile class is unchanged.
    const EffectiveBandwidth v = computeEffectiveBandwidth(ue4, uniformCompression(ue4, 1.0, 1.5, 1.25), 1,
                                                           parseLightingModel("volumes:2", "--lighting"));
    EXPECT_DOUBLE_EQ(v.find("desktop-dcc")->trafficBytes, pixels * (10 * 3 + 8));
    EXPECT_DOUBLE_EQ(v.find("tile-subpass")->trafficBytes, pixels * 8);
    EXPECT_DOUBLE_EQ(effectiveBytesPerPixel(ue4, uniformCompression(ue4, 1.0, 1.5, 1.25), "desktop-dcc"), 10.0);
}

TEST(EffectiveBandwidth, WhatDoesNotFitSpills) {
    // The reference (80 B of targets + 4 depth) does not fit the A11: its nominal bytes move.
    const Layout reference = loadLayout("reference");
    const EffectiveBandwidth e =
        computeEffectiveBandwidth(reference, uniformCompression(reference, 2.0, 16.0, 16.0), 1, LightingModel{});
    const ClassTraffic* tile = e.find("tile-subpass");
    ASSERT_TRUE(tile);
    EXPECT_DOUBLE_EQ(tile->bytesPerPixel, e.nominalBytesPerPixel);
    EXPECT_DOUBLE_EQ(tile->trafficBytes, e.nominalTrafficBytes);
}

}  // namespace
}  // namespace gbl
