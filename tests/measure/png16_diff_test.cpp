// A 16-bit PNG is read at 16 bits: two files whose low bytes differ everywhere gave diff PSNR inf,
// max 0, LDR-FLIP 0 (the 8-bit reader kept the high bytes only). The files are written here by a
// minimal 16-bit PNG encoder (zlib), independent of gbufferlab's writer, which writes 8 bits.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "image_diff.h"
#include "image_io.h"
#include "temp_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

const test::ScratchDir scratch("gbl_png16_test_");

void put32(std::string& s, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) s += char((v >> shift) & 0xff);
}

void chunk(std::string& png, const char* type, const std::string& data) {
    put32(png, uint32_t(data.size()));
    const std::string typed = std::string(type, 4) + data;
    png += typed;
    put32(png, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(typed.data()), uInt(typed.size()))));
}

// RGB, 16 bits per sample, big-endian, filter None on every row.
void writePng16(const fs::path& path, int width, int height, const std::vector<uint16_t>& rgb) {
    std::string raw;
    for (int y = 0; y < height; ++y) {
        raw += char(0);
        for (int x = 0; x < width * 3; ++x) {
            const uint16_t v = rgb[size_t(y) * size_t(width) * 3 + size_t(x)];
            raw += char(v >> 8);
            raw += char(v & 0xff);
        }
    }
    uLongf size = compressBound(uLong(raw.size()));
    std::string deflated(size, '\0');
    ASSERT_EQ(compress2(reinterpret_cast<Bytef*>(deflated.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                        uLong(raw.size()), 6),
              Z_OK);
    deflated.resize(size);
    std::string png = "\x89PNG\r\n\x1a\n";
    std::string ihdr;
    put32(ihdr, uint32_t(width));
    put32(ihdr, uint32_t(height));
    ihdr += char(16);  // bit depth
    ihdr += char(2);   // RGB
    ihdr += std::string(3, '\0');
    chunk(png, "IHDR", ihdr);
    chunk(png, "IDAT", deflated);
    chunk(png, "IEND", "");
    std::ofstream(path, std::ios::binary) << png;
}

TEST(Png16Diff, LowBytesThatDifferEverywhereAreMeasured) {
    const int w = 24, h = 16;
    std::vector<uint16_t> a(size_t(w) * h * 3), b(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = uint16_t(0x4000 + 37 * i);  // the same high byte pattern in both
        b[i] = uint16_t((a[i] & 0xff00) | ((a[i] + 0x80) & 0xff));  // every low byte differs by 128
    }
    writePng16(scratch() / "a.png", w, h, a);
    writePng16(scratch() / "b.png", w, h, b);
    const DiffInput ref = readDiffInput((scratch() / "a.png").string());
    const DiffInput test = readDiffInput((scratch() / "b.png").string());
    EXPECT_EQ(ref.bitsPerSample, 16);
    EXPECT_EQ(diffPrecision(ref, test), "16-bit");
    EXPECT_FLOAT_EQ(ref.image.pixels[1], float(a[1]) / 65535.0f);
    const DiffResult r = diffImages(ref, test, "a.png", "b.png");
    // Each sample differs by exactly 128 / 65535, one way or the other.
    EXPECT_TRUE(std::isfinite(r.psnrDb)) << r.psnrDb;
    EXPECT_NEAR(r.maxAbs, 128.0 / 65535.0, 1e-7);
    EXPECT_NEAR(r.rmse, 128.0 / 65535.0, 1e-7);
    EXPECT_GT(r.flip.mean, 0.0);
    // Identical 16-bit files: inf and 0, as for 8 bits.
    const DiffResult same = diffImages(ref, ref, "a.png", "a.png");
    EXPECT_TRUE(std::isinf(same.psnrDb));
    EXPECT_EQ(same.flip.mean, 0.0);
    // An 8-bit file beside a 16-bit one: each at its own precision, and said so.
    Image8 eight{w, h, 3, std::vector<unsigned char>(size_t(w) * h * 3, 64)};
    writePng((scratch() / "c8.png").string(), eight);
    const DiffInput c8 = readDiffInput((scratch() / "c8.png").string());
    EXPECT_EQ(c8.bitsPerSample, 8);
    EXPECT_EQ(diffPrecision(c8, ref), "8-bit reference, 16-bit test");
}

}  // namespace
}  // namespace gbl
