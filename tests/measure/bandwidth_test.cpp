// The bandwidth model against sums written out by hand from each seed layout's formats.
#include <gtest/gtest.h>

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
        {"reference", 5 * kRgba32, kD32, 0},                            // float32 everything
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

}  // namespace
}  // namespace gbl
