// A frame rendered in bands of rows (RenderSettings::bandFirstRow, ::bandRows; bounded memory at
// 4K) is the whole frame's render, bit for bit, once the bands are stitched: the HDR image, the
// decoded surfaces, depth and the G-buffer's words. The layouts cover what depends on a pixel's
// place in the frame: dithered normals (niagara: interleaved gradient noise of the pixel),
// checkerboard chroma (crysis3-thin: parity and the 4 neighbours, across a band's edge), the
// light pre-pass's buffers and material pass (crysis2-slim), a visibility buffer's camera ray
// (visibility-32), the reference's float targets and ue4; crysis3-thin also through the
// device-kept path. The oracle is the same renderer's whole-frame render: the property is that
// banding changes nothing. (A band-sized G-buffer behind a viewport shifted by the band's first
// row failed this: llvmpipe interpolated depth and attributes a few ulps off.)
#include <gtest/gtest.h>

#include <cstring>

#include "error.h"
#include "layout_catalog.h"
#include "procedural_sky.h"
#include "renderer.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

class RenderBandTest : public test::VulkanTest {};

constexpr uint32_t kWidth = 72, kHeight = 61;
// Heights not multiples of 8 (the passes' workgroups), odd first rows (the G-buffer's origin is
// rounded down to an even row), a one-row band and the frame's last row.
const std::vector<uint32_t> kBandHeights = {13, 1, 8, 22, 17};

RenderSettings settingsFor(uint32_t firstRow, uint32_t rows, bool onDevice) {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.splitSumShaderSamples = 16;
    s.decodeSurfaces = true;
    s.readTargetWords = !onDevice;
    s.keepOnDevice = onDevice;
    s.bandFirstRow = firstRow;
    s.bandRows = rows;
    return s;
}

// Rows [first, first + rows) of a row-major array of `width` x height elements of `channels`.
template <typename T>
std::vector<T> rowsOf(const std::vector<T>& v, size_t rowElements, uint32_t first, uint32_t rows) {
    return std::vector<T>(v.begin() + std::ptrdiff_t(first * rowElements),
                          v.begin() + std::ptrdiff_t((first + rows) * rowElements));
}

// Bitwise equality of float arrays (NaN == NaN, -0 != +0), naming the first differing element.
void expectSameBits(const std::vector<float>& whole, const std::vector<float>& band, const std::string& what) {
    ASSERT_EQ(whole.size(), band.size()) << what;
    size_t differ = 0, firstAt = 0;
    for (size_t i = 0; i < whole.size(); ++i) {
        uint32_t a, b;
        std::memcpy(&a, &whole[i], 4);
        std::memcpy(&b, &band[i], 4);
        if (a != b && differ++ == 0) firstAt = i;
    }
    EXPECT_EQ(differ, 0u) << what << ": " << differ << " of " << whole.size() << " elements differ, first at "
                          << firstAt << ": " << whole[firstAt] << " whole frame vs " << band[firstAt] << " banded";
}

void expectBandOfImage(const Image& whole, const Image& band, uint32_t first, const std::string& what) {
    ASSERT_EQ(band.width, whole.width) << what;
    ASSERT_EQ(band.channels, whole.channels) << what;
    expectSameBits(rowsOf(whole.pixels, size_t(whole.width) * size_t(whole.channels), first, uint32_t(band.height)),
                   band.pixels, what);
}

void expectBandsStitch(Renderer& renderer, const std::string& layoutName) {
    SCOPED_TRACE(layoutName);
    const GBufferWiring wiring = generateWiring(loadLayout(layoutName));
    const RenderOutput whole = renderer.render(wiring, settingsFor(0, 0, false));
    ASSERT_EQ(whole.hdr.height, int(kHeight));
    // Geometry and sky both in the frame (an all-sky frame would stitch trivially).
    size_t covered = 0;
    for (uint8_t c : whole.surfaces.coverage) covered += c;
    ASSERT_GT(covered, whole.surfaces.coverage.size() / 4);
    ASSERT_LT(covered, whole.surfaces.coverage.size());
    uint32_t first = 0;
    for (size_t k = 0; first < kHeight; ++k) {
        const uint32_t rows = std::min(kBandHeights[k % kBandHeights.size()], kHeight - first);
        const std::string at = layoutName + ", rows " + std::to_string(first) + "+" + std::to_string(rows);
        const RenderOutput band = renderer.render(wiring, settingsFor(first, rows, false));
        ASSERT_EQ(band.hdr.height, int(rows)) << at;
        expectBandOfImage(whole.hdr, band.hdr, first, at + " HDR");
        const SurfaceImages& s = whole.surfaces;
        const SurfaceImages& b = band.surfaces;
        expectBandOfImage(s.normal, b.normal, first, at + " normal");
        expectBandOfImage(s.baseColor, b.baseColor, first, at + " base colour");
        expectBandOfImage(s.diffuseColor, b.diffuseColor, first, at + " diffuse colour");
        expectBandOfImage(s.specularColor, b.specularColor, first, at + " specular colour");
        expectBandOfImage(s.roughness, b.roughness, first, at + " roughness");
        expectBandOfImage(s.metallic, b.metallic, first, at + " metallic");
        expectBandOfImage(s.occlusion, b.occlusion, first, at + " occlusion");
        expectBandOfImage(s.emissive, b.emissive, first, at + " emissive");
        expectBandOfImage(s.viewDepth, b.viewDepth, first, at + " view depth");
        expectSameBits(rowsOf(whole.depth, kWidth, first, rows), band.depth, at + " depth");
        EXPECT_EQ(rowsOf(s.coverage, kWidth, first, rows), b.coverage) << at << " coverage";
        ASSERT_EQ(whole.targetWords.size(), band.targetWords.size()) << at;
        for (size_t t = 0; t < whole.targetWords.size(); ++t) {
            const size_t rowWords = whole.targetWords[t].size() / kHeight;
            EXPECT_EQ(rowsOf(whole.targetWords[t], rowWords, first, rows), band.targetWords[t])
                << at << " target " << t << " words";
        }
        if (!whole.lightBufferWords.empty()) {
            const size_t rowWords = whole.lightBufferWords.size() / kHeight;
            EXPECT_EQ(rowsOf(whole.lightBufferWords, rowWords, first, rows), band.lightBufferWords)
                << at << " light buffer words";
        }
        if (!whole.stencil.empty()) {
            EXPECT_EQ(rowsOf(whole.stencil, kWidth, first, rows), band.stencil) << at << " stencil";
        }
        first += rows;
    }
}

TEST_F(RenderBandTest, BandsStitchToTheWholeFrameBitForBit) {
    const Scene scene = makeDefaultScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    for (const char* layout : {"reference", "ue4", "crysis3-thin", "niagara", "crysis2-slim", "visibility-32"})
        expectBandsStitch(renderer, layout);
}

// The device-kept path (compare --eval gpu): the HDR image and the four decoded-surface images
// hold the band's rows, as the whole frame's.
TEST_F(RenderBandTest, DeviceImagesHoldTheBandsRows) {
    const Scene scene = makeDefaultScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    const GBufferWiring wiring = generateWiring(loadLayout("crysis3-thin"));
    const RenderOutput whole = renderer.render(wiring, settingsFor(0, 0, true));
    const Image wholeHdr = whole.device->downloadHdr();
    const uint32_t first = 27, rows = 19;
    const RenderOutput band = renderer.render(wiring, settingsFor(first, rows, true));
    ASSERT_EQ(band.device->hdr.extent.height, rows);
    expectBandOfImage(wholeHdr, band.device->downloadHdr(), first, "device HDR");
    for (size_t k = 0; k < 4; ++k) {
        ASSERT_EQ(band.device->surfaces[k].extent.height, rows);
        const std::vector<uint8_t> a = downloadImage(test::sharedContext(), whole.device->surfaces[k], VK_IMAGE_LAYOUT_GENERAL);
        const std::vector<uint8_t> b = downloadImage(test::sharedContext(), band.device->surfaces[k], VK_IMAGE_LAYOUT_GENERAL);
        const size_t rowBytes = size_t(kWidth) * 16;
        EXPECT_EQ(rowsOf(a, rowBytes, first, rows), b) << "device surface image " << k;
    }
}

TEST_F(RenderBandTest, BandOutsideTheFrameIsAUserError) {
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(64);
    Renderer renderer(test::sharedContext(), scene, sky);
    const GBufferWiring wiring = generateWiring(loadLayout("ue4"));
    EXPECT_THROW(renderer.render(wiring, settingsFor(50, 12, false)), UserError);  // rows 50..62 of 61
    EXPECT_THROW(renderer.render(wiring, settingsFor(61, 1, false)), UserError);
    RenderSettings groundTruth = settingsFor(0, 8, false);
    groundTruth.specularIbl = IblMode::GroundTruth;
    EXPECT_THROW(renderer.render(wiring, groundTruth), UserError);
}

}  // namespace
}  // namespace gbl
