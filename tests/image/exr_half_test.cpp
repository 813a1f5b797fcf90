// EXR files written as half float (compare's default since issue 14): every value is what
// IEEE 754 binary16 round-to-nearest-even makes of it (checked against a rounding written here
// from the format's definition, not against OpenEXR's), finite values beyond 65504 are clamped
// rather than turned into infinity, and the file says it holds half.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include "image_io.h"
#include "temp_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

struct TempDir : test::TempDir {
    TempDir() : test::TempDir("gbl_exr_half_") {}
};

// binary16: 1 sign bit, 5 exponent bits (bias 15), 10 fraction bits. Normal numbers from 2^-14
// have a spacing of 2^(e - 10) within [2^e, 2^(e+1)); below 2^-14 (subnormal) the spacing is
// 2^-24. Round to nearest, ties to even (std::nearbyint under the default rounding mode), in
// double, where v / spacing is exact. Finite values are clamped to +-65504 first (the writer's
// documented choice); NaN and infinities pass.
double referenceHalf(float v) {
    if (!std::isfinite(v)) return v;
    const double x = std::clamp(double(v), -65504.0, 65504.0);
    if (x == 0.0) return x;
    const double a = std::fabs(x);
    const double spacing = a < std::ldexp(1.0, -14) ? std::ldexp(1.0, -24) : std::ldexp(1.0, int(std::floor(std::log2(a))) - 10);
    return std::nearbyint(x / spacing) * spacing;
}

TEST(ExrHalf, ValuesAreRoundedToNearestEvenAndClamped) {
    std::vector<float> values = {0.0f,     -0.0f,    1.0f,     1.0f / 3.0f, 0.1f,     -2.5f,   65504.0f, 65519.0f,
                                 65520.0f, 1.0e6f,   -1.0e9f,  6.1e-5f,     6.0e-8f,  2.9e-8f, 1.0e-9f,  1.0009765625f,
                                 1.00048828125f /* a tie: 1 + 2^-11 rounds to even, 1 */, 3.0e38f,
                                 std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> exponent(-30.0f, 20.0f);
    while (values.size() < 4 * 64 * 3) values.push_back((rng() & 1 ? -1.0f : 1.0f) * std::exp2(exponent(rng)));
    Image image(64, 4, 3);
    image.pixels = values;
    TempDir dir;
    const std::string path = (dir.path / "h.exr").string();
    writeExr(path, image, {}, ExrPixelType::Half);
    EXPECT_EQ(readExrPixelType(path), ExrPixelType::Half);
    {
        Imf::InputFile file(path.c_str());
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
            EXPECT_EQ(it.channel().type, Imf::HALF) << it.name();
    }
    const Image back = readExrChannels(path, {"R", "G", "B"});
    ASSERT_EQ(back.pixels.size(), values.size());
    for (size_t i = 0; i < values.size(); ++i) {
        const double want = referenceHalf(values[i]);
        EXPECT_EQ(double(back.pixels[i]), want) << "value " << values[i];
        EXPECT_EQ(std::signbit(back.pixels[i]), std::signbit(values[i])) << "value " << values[i];
        EXPECT_EQ(double(roundToHalf(values[i])), want) << "value " << values[i];
        if (std::isfinite(values[i])) {
            EXPECT_TRUE(std::isfinite(back.pixels[i])) << "a finite value became " << back.pixels[i];
            // The documented bound: within 2^-11 relative above 2^-14, 2^-25 absolute below.
            const double a = std::fabs(double(values[i]));
            if (a <= 65504.0) {
                EXPECT_LE(std::fabs(double(back.pixels[i]) - values[i]), std::max(a * std::ldexp(1.0, -11), std::ldexp(1.0, -25)))
                    << values[i];
            }
        }
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Image withNan(1, 1, 1);
    withNan.pixels = {nan};
    writeExr((dir.path / "n.exr").string(), withNan, {}, ExrPixelType::Half);
    EXPECT_TRUE(std::isnan(readExrChannels((dir.path / "n.exr").string(), {"Y"}).pixels[0]));
}

TEST(ExrHalf, Float32StaysTheDefaultAndHalvesTheBytes) {
    Image image(256, 128, 4);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> radiance(0.0f, 8.0f);
    for (float& v : image.pixels) v = radiance(rng);
    TempDir dir;
    const std::string f = (dir.path / "f.exr").string(), h = (dir.path / "h.exr").string();
    writeExr(f, image);
    writeExr(h, image, {}, ExrPixelType::Half);
    EXPECT_EQ(readExrPixelType(f), ExrPixelType::Float32);
    EXPECT_EQ(readExrPixelType(h), ExrPixelType::Half);
    // Noise does not compress: the payload is 4 vs 2 bytes per value.
    EXPECT_LT(double(fs::file_size(h)), 0.6 * double(fs::file_size(f)));
    EXPECT_STREQ(exrPixelTypeName(ExrPixelType::Half), "half");
    EXPECT_STREQ(exrPixelTypeName(ExrPixelType::Float32), "float32");
}

}  // namespace
}  // namespace gbl
