// The bandwidth model against sums written out by hand from each seed layout's formats.
#include <gtest/gtest.h>

#include <utility>

#include "bandwidth.h"
#include "layout_catalog.h"

namespace gbl {
namespace {

// Bytes per pixel of the formats, from the Vulkan spec, independent of the layout code.
constexpr int kRgba8 = 4, kRgb10A2 = 4, kD24S8 = 4, kD32S8 = 5, kRgba16f = 8, kRgba32 = 16, kD32 = 4;

struct Expected {
    const char* layout;
    int targets, depth, lightBuffers;
};

TEST(Bandwidth, SeedLayoutsEqualTheSumsOfTheirFormats) {
    const Expected expected[] = {
        {"crysis2-slim", kRgba8, kD24S8, 2 * kRgba16f},                 // BFN + gloss; diffuse and specular light
        {"crysis3-thin", 2 * kRgba8, kD24S8, 0},                        // two A8B8G8R8
        {"ue4", kRgb10A2 + 4 * kRgba8, kD32S8, 0},                      // GBufferA..E
        {"reference", 8 * kRgba32, kD32, 0},                            // float32 everything, the layers in three more targets
    };
    for (const Expected& e : expected) {
        const Layout layout = loadLayout(e.layout);
        const BandwidthReport r = computeBandwidth(layout, 1920, 1080);
        EXPECT_EQ(r.targetBytesPerPixel, e.targets) << e.layout;
        EXPECT_EQ(r.depthBytesPerPixel, e.depth) << e.layout;
        EXPECT_EQ(r.lightBufferBytesPerPixel, e.lightBuffers) << e.layout;
        EXPECT_EQ(r.gbufferBytesPerPixel, bytesPerPixel(layout)) << e.layout;
        // Per frame at 1080p, 1 sample: written once, read once, plus the light buffers written
        // and read and depth re-tested by the material pass.
        const FrameTraffic& f = r.frames.at(3);
        ASSERT_EQ(f.width, 1920u);
        ASSERT_EQ(f.samples, 1);
        const double pixels = 1920.0 * 1080.0;
        const double expectedTotal = pixels * (2.0 * (e.targets + e.depth) +
                                               (e.lightBuffers ? 2.0 * e.lightBuffers + e.depth : 0.0));
        EXPECT_DOUBLE_EQ(f.totalBytes, expectedTotal) << e.layout;
        // MSAA 4x moves four times the G-buffer bytes; the on-chip case only the lit output.
        EXPECT_DOUBLE_EQ(r.frames.at(5).totalBytes, 4.0 * expectedTotal) << e.layout;
        EXPECT_DOUBLE_EQ(f.onChipExternalBytes, pixels * kLitOutputBytesPerPixel) << e.layout;
        EXPECT_NEAR(f.gigabytesPerSecond(60.0), expectedTotal * 60.0 / 1e9, 1e-9) << e.layout;
    }
}

TEST(Bandwidth, FewerBytesNeverCostMoreBandwidth) {
    const BandwidthReport thin = computeBandwidth(loadLayout("crysis3-thin"), 1920, 1080);
    const BandwidthReport fat = computeBandwidth(loadLayout("fat-naive"), 1920, 1080);
    ASSERT_LT(thin.gbufferBytesPerPixel, fat.gbufferBytesPerPixel);
    for (size_t i = 0; i < thin.frames.size(); ++i) EXPECT_LT(thin.frames[i].totalBytes, fat.frames[i].totalBytes);
}

// The visibility buffer: ids (R32_UINT 4 B, R32G32_UINT 8 B) and D32 depth written and read per
// sample, plus its resolve's vertex fetches once per pixel, modelled with no cache reuse: 3 indices
// (4 B) and 3 vertices (position 12 + normal 12 + tangent 16 + uv 8 = 48 B): 156 B. Its texel
// fetches (5 textures x 8 trilinear texels x 4 B = 160 B) are stated but in no total.
TEST(Bandwidth, VisibilityBufferIdsDepthAndModelledFetches) {
    const double pixels = 1920.0 * 1080.0;
    const double vertexBytes = 3 * 4 + 3 * (12 + 12 + 16 + 8), texelBytes = 5 * 8 * 4;
    for (auto [name, ids] : {std::pair{"visibility-32", 4}, std::pair{"visibility-64", 8}}) {
        const BandwidthReport r = computeBandwidth(loadLayout(name), 1920, 1080);
        EXPECT_TRUE(r.visibilityBuffer);
        EXPECT_EQ(r.targetBytesPerPixel, ids) << name;
        EXPECT_EQ(r.depthBytesPerPixel, kD32) << name;
        ASSERT_EQ(r.targets.size(), 1u);
        EXPECT_EQ(r.targets[0].name, "ids");
        const FrameTraffic& f = r.frames.at(3);
        EXPECT_DOUBLE_EQ(f.geometryWriteBytes, pixels * (ids + kD32)) << name;
        EXPECT_DOUBLE_EQ(f.lightingReadBytes, pixels * (ids + kD32)) << name;
        EXPECT_DOUBLE_EQ(f.vertexFetchBytes, pixels * vertexBytes) << name;
        EXPECT_DOUBLE_EQ(f.textureFetchBytes, pixels * texelBytes) << name;
        EXPECT_DOUBLE_EQ(f.totalBytes, pixels * (2.0 * (ids + kD32) + vertexBytes)) << name;
        // 4x MSAA: ids and depth per sample, the resolve still once per pixel.
        EXPECT_DOUBLE_EQ(r.frames.at(5).totalBytes, pixels * (4.0 * 2.0 * (ids + kD32) + vertexBytes)) << name;
    }
    // Nanite's and Bevy's meshlet ids: 8 B with the depth in them and no depth attachment (neither
    // raster pass has one), and with clusters the resolve also reads the cluster table's 8-byte
    // entry (draw, first triangle).
    for (const char* name : {"nanite-visbuffer", "bevy-meshlet-visbuffer"}) {
        const BandwidthReport r = computeBandwidth(loadLayout(name), 1920, 1080);
        EXPECT_EQ(r.targetBytesPerPixel, 8) << name;
        EXPECT_EQ(r.depthBytesPerPixel, 0) << name;
        EXPECT_EQ(r.gbufferBytesPerPixel, 8) << name;
        const FrameTraffic& f = r.frames.at(3);
        EXPECT_DOUBLE_EQ(f.geometryWriteBytes, pixels * 8) << name;
        EXPECT_DOUBLE_EQ(f.vertexFetchBytes, pixels * (vertexBytes + 8)) << name;
        EXPECT_DOUBLE_EQ(f.totalBytes, pixels * (2.0 * 8 + vertexBytes + 8)) << name;
    }
    // A G-buffer layout has none of the visibility buffer's fetches.
    const FrameTraffic ue4 = computeBandwidth(loadLayout("ue4"), 1920, 1080).frames.at(3);
    EXPECT_EQ(ue4.vertexFetchBytes, 0.0);
    EXPECT_EQ(ue4.textureFetchBytes, 0.0);
}

}  // namespace
}  // namespace gbl
