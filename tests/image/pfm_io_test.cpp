// The PFM reader and writer (pfm_io.h) against files this test writes byte by byte from the
// format's definition (Netpbm pfm(5): "PF"/"Pf", width, height, scale whose sign is the byte
// order, one white-space character, floats with rows bottom to top), and the refusals: a
// truncated raster, trailing bytes, a header claiming a huge image, a bad magic or scale, each one
// line naming the file and the place. Then diff's kind rule: a PFM is linear float like EXR, so
// `diff reference.exr viewer.pfm` compares (an RGBA reference's colours against the PFM's RGB),
// and a PFM against a PNG is refused.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <string>

#include "image_diff.h"
#include "image_io.h"
#include "pfm_io.h"
#include "temp_dir.h"
#include "user_error.h"

namespace gbl {
namespace {

struct TempDir : test::TempDir {
    TempDir() : test::TempDir("gbl_pfm_io_") {}
};

std::string floatBytes(float v, bool littleEndian) {
    unsigned char b[4];
    std::memcpy(b, &v, 4);
    if (!littleEndian) std::swap(b[0], b[3]), std::swap(b[1], b[2]);  // the test runs on little-endian x86-64
    return std::string(reinterpret_cast<char*>(b), 4);
}

// A 3x2 RGB image whose value encodes (x, y top-down, channel): 100 y + 10 x + c.
float code(int x, int yTopDown, int c) { return float(100 * yTopDown + 10 * x + c) + 0.25f; }

// The file as the format defines it: the raster's first row is the image's bottom row.
std::string specPfm(const std::string& header, int w, int h, int channels, bool littleEndian) {
    std::string out = header;
    for (int fileRow = 0; fileRow < h; ++fileRow)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) out += floatBytes(code(x, h - 1 - fileRow, c), littleEndian);
    return out;
}

TEST(PfmIo, ReadsLittleEndianRgbWithRowsBottomToTop) {
    TempDir dir;
    const auto path = dir / "le.pfm";
    test::writeFile(path, specPfm("PF\n3 2\n-1.0\n", 3, 2, 3, true));
    const Image img = readPfm(path.string());
    ASSERT_EQ(img.width, 3);
    ASSERT_EQ(img.height, 2);
    ASSERT_EQ(img.channels, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), code(x, y, c)) << x << "," << y << "," << c;
}

TEST(PfmIo, ReadsBigEndianGreyWithAnyWhiteSpaceAndScaleMagnitude) {
    TempDir dir;
    const auto path = dir / "be.pfm";
    // Positive scale = big-endian; its magnitude (2.5) is not applied to the values.
    test::writeFile(path, specPfm("Pf  3\t2\r\n2.5\n", 3, 2, 1, false));
    const Image img = readPfm(path.string());
    ASSERT_EQ(img.channels, 1);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) EXPECT_EQ(img.at(x, y, 0), code(x, y, 0));
    const ImageFileInfo info = probeImageFile(path.string());
    EXPECT_EQ(info.width, 3);
    EXPECT_EQ(info.height, 2);
    EXPECT_EQ(info.channels, 1);
    EXPECT_TRUE(info.hdr);
}

TEST(PfmIo, WriterWritesTheFormatsBytes) {
    Image img(3, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = code(x, y, c);
    TempDir dir;
    writePfm((dir / "w.pfm").string(), img);
    EXPECT_EQ(test::readFile(dir / "w.pfm"), specPfm("PF\n3 2\n-1.0\n", 3, 2, 3, true));
}

void expectRefused(const std::string& bytes, const std::string& needle) {
    TempDir dir;
    const auto path = dir / "bad.pfm";
    test::writeFile(path, bytes);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string read = test::userErrorOf([&] { readPfm(path.string()); });
    const std::string probed = test::userErrorOf([&] { probeImageFile(path.string()); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const std::string& msg : {read, probed}) {
        EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find(needle), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
        EXPECT_NE(msg.find(';'), std::string::npos) << "a fix after the problem: " << msg;
    }
    EXPECT_LT(seconds, 1.0);
}

TEST(PfmIo, RefusesATruncatedRaster) {
    std::string whole = specPfm("PF\n3 2\n-1.0\n", 3, 2, 3, true);
    expectRefused(whole.substr(0, whole.size() - 5), "truncated PFM: its header's 3x2x3 floats need 72 bytes");
}

TEST(PfmIo, RefusesAHugeHeaderBeforeAllocating) {
    // 2^20 x 2^20 RGB would be 12 TiB: refused from the header and the file size alone.
    expectRefused("PF\n1048576 1048576\n-1.0\n" + std::string(64, '\0'), "truncated PFM");
    expectRefused("PF\n99999999 2\n-1.0\n", "PFM header, width: 99999999 is outside 1..1048576");
    expectRefused("PF\n0 2\n-1.0\n", "PFM header, width: 0 is outside");
}

TEST(PfmIo, RefusesMalformedHeadersAndTrailingBytes) {
    expectRefused("P6\n3 2\n255\n", "not a PFM file (it starts 'P6'");
    expectRefused("PF\n3 x\n-1.0\n", "PFM header, height: 'x' is not a whole number");
    expectRefused("PF\n3 2\nabc\n", "PFM header, scale: 'abc' is not a finite non-zero number");
    expectRefused("PF\n3 2\n0\n", "PFM header, scale: '0'");
    expectRefused("PF\n3 2\n-1.0", "PFM header, scale: the header does not end");
    expectRefused(specPfm("PF\n3 2\n-1.0\n", 3, 2, 3, true) + "xyz", "3 bytes after its 3x2x3 floats");
}

// diff's kind rule: EXR, HDR and PFM are linear float (HDR-FLIP); PNG is sRGB.
TEST(PfmIo, DiffComparesExrWithPfmAndRefusesPfmWithPng) {
    Image img(8, 4, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = 0.01f * float(i % 97);
    TempDir dir;
    const std::string exr = (dir / "ref.exr").string(), pfm = (dir / "test.pfm").string(), png = (dir / "t.png").string();
    writeExr(exr, img);
    writePfm(pfm, img);
    const DiffInput a = readDiffInput(exr), b = readDiffInput(pfm);
    EXPECT_EQ(b.kind, DiffKind::Hdr);
    const DiffResult same = diffImages(a, b, exr, pfm);
    EXPECT_EQ(same.kind, DiffKind::Hdr);
    EXPECT_EQ(same.maxAbs, 0.0);
    Image moved = img;
    moved.at(3, 1, 2) += 0.5f;
    writePfm(pfm, moved);
    EXPECT_FLOAT_EQ(float(diffImages(a, readDiffInput(pfm), exr, pfm).maxAbs), 0.5f);

    // compare's reference EXRs carry alpha (coverage); a PFM cannot: their colours are compared.
    Image rgba(8, 4, 4, 1.0f);
    for (size_t p = 0; p < rgba.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c) rgba.pixels[p * 4 + c] = img.pixels[p * 3 + c];
    const std::string exrA = (dir / "ref_rgba.exr").string();
    writeExr(exrA, rgba);
    writePfm(pfm, img);
    const DiffInput withAlpha = readDiffInput(exrA);
    EXPECT_EQ(withAlpha.fileChannels, 4);
    EXPECT_EQ(diffImages(withAlpha, readDiffInput(pfm), exrA, pfm).maxAbs, 0.0);
    // Between two formats that can hold alpha the rule stays: RGBA against RGB is refused.
    const std::string rgbOnly = test::userErrorOf([&] { diffImages(withAlpha, readDiffInput(exr), exrA, exr); });
    EXPECT_NE(rgbOnly.find("has 3 channels but the reference"), std::string::npos) << rgbOnly;

    Image8 ldr{8, 4, 3, std::vector<unsigned char>(8 * 4 * 3, 128)};
    writePng(png, ldr);
    const std::string msg = test::userErrorOf([&] { diffImages(readDiffInput(png), readDiffInput(pfm), png, pfm); });
    EXPECT_NE(msg.find("is HDR float (EXR/HDR/PFM) but the reference"), std::string::npos) << msg;
}

}  // namespace
}  // namespace gbl
