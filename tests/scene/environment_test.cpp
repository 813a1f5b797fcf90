// The equirect convention, bilinear lookup, map validation, and the procedural sky.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sys/stat.h>
#include <unistd.h>

#include "environment_map.h"
#include "error.h"
#include "file_io.h"
#include "image_io.h"
#include "procedural_sky.h"
#include "test_paths.h"
#include "temp_dir.h"
#include "user_error.h"

namespace gbl {
namespace {
namespace fs = std::filesystem;
constexpr float kPi = 3.14159265358979323846f;

using test::userErrorOf;

float angleBetween(glm::vec3 a, glm::vec3 b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Evenly spread unit directions (Fibonacci sphere).
std::vector<glm::vec3> sphereDirections(int n) {
    std::vector<glm::vec3> dirs;
    for (int i = 0; i < n; ++i) {
        const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
        const float r = std::sqrt(1.0f - y * y), phi = float(i) * 2.39996323f;
        dirs.push_back({r * std::cos(phi), y, r * std::sin(phi)});
    }
    return dirs;
}

TEST(Equirect, KnownDirections) {
    const auto uv = [](glm::vec3 d) { return directionToEquirectUv(d); };
    EXPECT_NEAR(uv({0, 0, -1}).x, 0.5f, 1e-7);   // straight ahead is the middle of the map
    EXPECT_NEAR(uv({0, 0, -1}).y, 0.5f, 1e-7);
    EXPECT_NEAR(uv({1, 0, 0}).x, 0.75f, 1e-7);   // +X to the right of centre
    EXPECT_NEAR(uv({-1, 0, 0}).x, 0.25f, 1e-7);
    EXPECT_NEAR(uv({0, 1, 0}).y, 0.0f, 1e-7);    // up is row 0
    EXPECT_NEAR(uv({0, -1, 0}).y, 1.0f, 1e-7);
    EXPECT_NEAR(std::fmod(uv({0, 0, 1}).x, 1.0f), 0.0f, 1e-7);  // behind: the seam
    EXPECT_NEAR(uv({0, 1.0000001f, 0}).y, 0.0f, 1e-7);          // clamped, no NaN from acos
    const glm::vec3 ahead = equirectUvToDirection({0.5f, 0.5f});
    EXPECT_NEAR(ahead.z, -1.0f, 1e-6);
    EXPECT_NEAR(equirectUvToDirection({0.75f, 0.5f}).x, 1.0f, 1e-6);
    EXPECT_NEAR(equirectUvToDirection({0.3f, 0.0f}).y, 1.0f, 1e-6);
}

TEST(Equirect, DirectionRoundTrip) {
    float worst = 0.0f;
    for (const glm::vec3 d : sphereDirections(20000)) {
        const glm::vec2 uv = directionToEquirectUv(d);
        ASSERT_GE(uv.x, 0.0f);
        ASSERT_LE(uv.x, 1.0f);
        ASSERT_GE(uv.y, 0.0f);
        ASSERT_LE(uv.y, 1.0f);
        const glm::vec3 back = equirectUvToDirection(uv);
        ASSERT_NEAR(glm::length(back), 1.0f, 1e-6f);
        worst = std::max(worst, angleBetween(d, back));
    }
    EXPECT_LT(worst, 1e-5f);  // acos near the poles limits this
}

TEST(Equirect, UvRoundTrip) {
    for (int j = 1; j < 200; ++j)
        for (int i = 1; i < 400; ++i) {
            const glm::vec2 uv{float(i) / 400.0f, float(j) / 200.0f};
            const glm::vec2 back = directionToEquirectUv(equirectUvToDirection(uv));
            ASSERT_NEAR(back.x, uv.x, 2e-6f / std::sin(uv.y * kPi)) << uv.x << "," << uv.y;
            ASSERT_NEAR(back.y, uv.y, 2e-6f) << uv.x << "," << uv.y;
        }
}

TEST(Equirect, GlslHasTheSameFunctions) {
    // The GPU copy must keep names and formulas; a cheap textual guard against drift.
    const std::string glsl = readTextFile(fs::path(GBL_SOURCE_SHADER_DIR) / "environment_map.glsl");
    EXPECT_EQ(glsl.find("\n#version"), std::string::npos);  // an include file: the includer sets it
    EXPECT_NE(glsl.find("#ifndef GBL_ENVIRONMENT_GLSL"), std::string::npos);
    for (const char* expected : {"vec2 directionToEquirectUv(vec3 direction)", "vec3 equirectUvToDirection(vec2 uv)",
                                 "0.5 + atan(direction.x, -direction.z) / (2.0 * kPi)",
                                 "acos(clamp(direction.y, -1.0, 1.0)) / kPi",
                                 "vec3(sinTheta * sin(phi), cos(theta), -sinTheta * cos(phi))"})
        EXPECT_NE(glsl.find(expected), std::string::npos) << expected;
}

Image rampImage(int width, int height) {  // each texel's value is unique: 1000 y + x
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(1000 * y + x + c);
    return image;
}

TEST(SampleEquirect, TexelCentresWrapAndClamp) {
    const Image image = rampImage(16, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const glm::vec3 d = equirectUvToDirection({(x + 0.5f) / 16.0f, (y + 0.5f) / 8.0f});
            const glm::vec3 s = sampleEquirect(image, d);
            ASSERT_NEAR(s.x, image.at(x, y, 0), 0.02f) << x << "," << y;
            ASSERT_NEAR(s.z, image.at(x, y, 2), 0.02f);
        }
    // Behind (+Z, u = 0 or 1) is halfway between the last and first columns: u wraps.
    const glm::vec3 seam = sampleEquirect(image, equirectUvToDirection({1.0f, 4.5f / 8.0f}));
    EXPECT_NEAR(seam.x, (image.at(15, 4, 0) + image.at(0, 4, 0)) / 2.0f, 0.02f);
    // Straight up clamps to row 0 (no bleeding from the bottom row).
    const glm::vec3 up = sampleEquirect(image, {0, 1, 0});
    EXPECT_LT(up.x, 16.0f);
    EXPECT_EQ(sampleEquirect(image, glm::vec3(std::numeric_limits<float>::quiet_NaN())), glm::vec3(0.0f));
}

TEST(SampleEquirect, ConstantMapIsConstant) {
    const Image image(32, 16, 3, 2.5f);
    for (const glm::vec3 d : sphereDirections(1000)) {
        const glm::vec3 s = sampleEquirect(image, d);
        ASSERT_NEAR(s.x, 2.5f, 1e-5f);
        ASSERT_NEAR(s.y, 2.5f, 1e-5f);
    }
}

TEST(Validate, SizeRules) {
    EXPECT_NO_THROW(validateEnvironmentImage(Image(8, 4, 3, 1.0f), "ok.hdr"));
    EXPECT_EQ(userErrorOf([] { validateEnvironmentImage(Image(10, 4, 3, 1.0f), "wide.hdr"); }),
              "wide.hdr: environment map is 10x4; an equirectangular map must be 2:1 (e.g. 1024x512)");
    EXPECT_EQ(userErrorOf([] { validateEnvironmentImage(Image(512, 512, 3, 1.0f), "cube.exr"); }),
              "cube.exr: environment map is 512x512; an equirectangular map must be 2:1 (e.g. 1024x512)");
    EXPECT_NE(userErrorOf([] { validateEnvironmentImage(Image(4, 2, 3, 1.0f), "tiny.hdr"); }).find("at least 8x4"),
              std::string::npos);
    EXPECT_NE(userErrorOf([] { validateEnvironmentImage(Image(), "empty.hdr"); }).find("empty.hdr: environment map is 0x0"),
              std::string::npos);
}

TEST(Validate, BadValuesAreErrorsNotClamps) {
    Image image(16, 8, 3, 1.0f);
    image.at(3, 1, 1) = std::numeric_limits<float>::quiet_NaN();
    image.at(9, 5, 0) = -0.5f;
    image.at(2, 7, 2) = std::numeric_limits<float>::infinity();
    const std::string message = userErrorOf([&] { validateEnvironmentImage(image, "bad.exr"); });
    EXPECT_EQ(message.rfind("bad.exr: ", 0), 0u) << message;
    EXPECT_NE(message.find("3 invalid values"), std::string::npos) << message;
    EXPECT_NE(message.find("x=3, y=1, channel G, value nan"), std::string::npos) << message;
    Image negative(16, 8, 3, 1.0f);
    negative.at(15, 7, 2) = -0.25f;  // the last texel: the scan covers the whole map
    EXPECT_NE(userErrorOf([&] { validateEnvironmentImage(negative, "n.hdr"); }).find("x=15, y=7, channel B, value -0.25;"),
              std::string::npos);
    Image zero(16, 8, 3, 0.0f);  // black is allowed
    EXPECT_NO_THROW(validateEnvironmentImage(zero, "black.exr"));
}

struct TempDir : test::TempDir {
    TempDir() : test::TempDir("gbl_environment_test_") {}
};

std::string writeCleanMap(const fs::path& dir) {
    const auto path = (dir / "clean.exr").string();
    writeExr(path, Image(16, 8, 3, 0.25f));
    return path;
}

TEST(LoadEnvironmentMap, ValidatesFilesAndNamesThem) {
    TempDir dir;
    Image nan(16, 8, 3, 1.0f);
    nan.at(4, 4, 0) = std::numeric_limits<float>::quiet_NaN();
    const auto nanPath = (dir.path / "nan.exr").string();
    writeExr(nanPath, nan);
    EXPECT_EQ(userErrorOf([&] { loadEnvironmentMap(nanPath); }).rfind(nanPath + ": environment map has 1 invalid", 0), 0u);
    const auto squarePath = (dir.path / "square.exr").string();
    writeExr(squarePath, Image(16, 16, 3, 1.0f));
    EXPECT_EQ(userErrorOf([&] { loadEnvironmentMap(squarePath); }),
              squarePath + ": environment map is 16x16; an equirectangular map must be 2:1 (e.g. 1024x512)");
    const auto good = test::sharedAssets() / "envmaps" / "empty_warehouse_01_1k.hdr";
    GBL_REQUIRE_FILE(good);
    const EnvironmentMap map = loadEnvironmentMap(good.string());
    EXPECT_EQ(map.source, good.string());
    EXPECT_EQ(map.image.width, 1024);
}

// Finite but huge texels overflow the IBL integrals to Inf (and the renders to NaN): refused by
// value, in memory and in an RGBE file whose exponent byte is 255 (~8.5e37).
TEST(Validate, HugeFiniteValuesAreRefused) {
    Image image(16, 8, 3, 1.0f);
    image.at(5, 2, 0) = 3.4e38f;
    const std::string message = userErrorOf([&] { validateEnvironmentImage(image, "huge.exr"); });
    EXPECT_NE(message.find("x=5, y=2, channel R, value 3.39999995e+38"), std::string::npos) << message;
    EXPECT_NE(message.find("above 1e9"), std::string::npos) << message;
    Image bright(16, 8, 3, 1.0f);
    bright.at(0, 0, 0) = kEnvironmentMaxValue;  // the limit itself passes (a sun-bright texel)
    EXPECT_NO_THROW(validateEnvironmentImage(bright, "bright.exr"));

    TempDir dir;
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
    for (int i = 0; i < 16 * 8; ++i) hdr += i == 37 ? std::string("\x80\x80\x80\xff") : std::string("\x80\x80\x80\x81");
    const fs::path path = dir.path / "rgbe255.hdr";
    writeFileAtomic(path, hdr);
    const std::string fileMessage = userErrorOf([&] { loadEnvironmentMap(path.string()); });
    EXPECT_EQ(fileMessage.rfind(path.string() + ": environment map has 3 invalid values", 0), 0u) << fileMessage;
    EXPECT_NE(fileMessage.find("x=5, y=2, channel R"), std::string::npos) << fileMessage;
}

// A directory or a FIFO named as the environment: one line, never a read (a FIFO would block).
TEST(LoadEnvironmentMap, DirectoriesAndFifosAreRefusedWithoutReading) {
    TempDir dir;
    fs::create_directories(dir.path / "dir.hdr");
    const std::string asDir = userErrorOf([&] { loadEnvironmentMap((dir.path / "dir.hdr").string()); });
    EXPECT_NE(asDir.find("is a directory, not a file"), std::string::npos) << asDir;
    for (const char* name : {"sky.hdr", "sky.exr"}) {
        const fs::path fifo = dir.path / name;
        ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
        const std::string message = userErrorOf([&] { loadEnvironmentMap(fifo.string()); });
        EXPECT_NE(message.find("is not a regular file"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// Lossy-compression ringing: negatives within 1/64 are clamped to 0 and counted; anything
// below is still refused with the file, the first bad texel and the count.
TEST(Validate, RingingToleranceBoundary) {
    Image image(16, 8, 3, 1.0f);
    image.at(1, 1, 0) = -0.01f;
    image.at(2, 2, 1) = -kEnvironmentRingingTolerance;  // exactly the tolerance: clamped
    image.at(3, 3, 2) = -0.0f;                            // negative zero is zero: untouched, not counted
    EXPECT_NO_THROW(validateEnvironmentImage(image, "ringing.exr"));
    EXPECT_EQ(clampEnvironmentRinging(image), 2u);
    EXPECT_EQ(image.at(1, 1, 0), 0.0f);
    EXPECT_EQ(image.at(2, 2, 1), 0.0f);
    EXPECT_FALSE(std::signbit(image.at(1, 1, 0)));
    EXPECT_EQ(clampEnvironmentRinging(image), 0u);  // idempotent
    Image past(16, 8, 3, 1.0f);
    past.at(5, 6, 1) = std::nextafter(-kEnvironmentRingingTolerance, -1.0f);
    EXPECT_NE(userErrorOf([&] { validateEnvironmentImage(past, "past.exr"); }).find("1 invalid values"),
              std::string::npos);
}

TEST(LoadEnvironmentMap, SmallNegativesClampedLargeRejected) {
    TempDir dir;
    Image ringing(16, 8, 3, 0.5f);
    ringing.at(7, 3, 2) = -0.01f;
    ringing.at(8, 3, 2) = -0.004f;
    const auto ringingPath = (dir.path / "ringing.exr").string();
    writeExr(ringingPath, ringing);
    const EnvironmentMap map = loadEnvironmentMap(ringingPath);
    EXPECT_EQ(map.clampedNegativeTexels, 2u);
    EXPECT_EQ(map.image.at(7, 3, 2), 0.0f);
    EXPECT_EQ(map.image.at(8, 3, 2), 0.0f);
    EXPECT_EQ(map.image.at(6, 3, 2), 0.5f);  // the rest untouched
    for (float v : map.image.pixels) ASSERT_GE(v, 0.0f);

    Image bad = ringing;
    bad.at(2, 5, 1) = -0.5f;  // first bad texel (row-major) ...
    bad.at(9, 6, 0) = -0.25f;  // ... and a second: count 2 (the -0.01 ringing is not counted)
    const auto badPath = (dir.path / "negative.exr").string();
    writeExr(badPath, bad);
    const std::string message = userErrorOf([&] { loadEnvironmentMap(badPath); });
    EXPECT_EQ(message.rfind(badPath + ": environment map has 2 invalid values", 0), 0u) << message;
    EXPECT_NE(message.find("x=2, y=5, channel G, value -0.5;"), std::string::npos) << message;

    const EnvironmentMap clean = loadEnvironmentMap(writeCleanMap(dir.path));
    EXPECT_EQ(clean.clampedNegativeTexels, 0u);
}

// Debian's blender-data world maps are DWAB-compressed and ring slightly below zero: each must
// load, with its ringing clamped (and counted), and nothing negative left.
TEST(LoadEnvironmentMap, BlenderWorldMapsLoadWithClampedRinging) {
    const fs::path worlds = "/usr/share/blender/datafiles/studiolights/world";
    GBL_REQUIRE_FILE(worlds / "forest.exr");  // Debian blender-data (scripts/setup.sh installs it)
    int count = 0;
    for (const auto& entry : fs::directory_iterator(worlds)) {
        if (entry.path().extension() != ".exr") continue;
        const auto path = entry.path().string();
        EnvironmentMap map;
        ASSERT_NO_THROW(map = loadEnvironmentMap(path)) << path;
        EXPECT_EQ(map.image.width, 1024) << path;
        EXPECT_GT(map.clampedNegativeTexels, 0u) << path;
        for (float v : map.image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << path;
        std::printf("[ info ] %s: %zu ringing texels clamped\n", entry.path().filename().c_str(),
                    map.clampedNegativeTexels);
        ++count;
    }
    EXPECT_GE(count, 8);
}

// Direction of the brightest texel (by luminance-ish sum).
glm::vec3 brightestDirection(const Image& image) {
    int bx = 0, by = 0;
    float best = -1.0f;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float v = image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2);
            if (v > best) best = v, bx = x, by = y;
        }
    return equirectUvToDirection({(bx + 0.5f) / float(image.width), (by + 0.5f) / float(image.height)});
}

TEST(ProceduralSky, FinitePositiveDeterministic) {
    const EnvironmentMap a = makeProceduralSky();
    const EnvironmentMap b = makeProceduralSky();
    ASSERT_EQ(a.image.width, 1024);
    ASSERT_EQ(a.image.height, 512);
    ASSERT_EQ(a.image.channels, 3);
    EXPECT_EQ(a.source, "built-in procedural sky");
    EXPECT_NO_THROW(validateEnvironmentImage(a.image, a.source));
    for (float v : a.image.pixels) ASSERT_GT(v, 0.0f);
    EXPECT_EQ(std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(float)), 0);
}

TEST(ProceduralSky, SunIsTheBrightestDirection) {
    const float texel = 2.0f * kPi / 1024.0f;
    for (const glm::vec3 sun : {SkyParameters{}.sunDirection, glm::normalize(glm::vec3(0.3f, 0.2f, -0.9f)),
                                glm::normalize(glm::vec3(0.01f, 1.0f, 0.0f)), glm::vec3(1.0f, 0.05f, 0.0f)}) {
        SkyParameters p;
        p.sunDirection = sun;
        const EnvironmentMap sky = makeProceduralSky(1024, p);
        EXPECT_LT(angleBetween(brightestDirection(sky.image), glm::normalize(sun)), p.sunAngularRadius + texel)
            << sun.x << "," << sun.y << "," << sun.z;
    }
}

TEST(ProceduralSky, GradientAndGround) {
    SkyParameters p;
    p.sunRadiance = glm::vec3(0.0f);
    const Image sky = makeProceduralSky(256, p).image;
    const glm::vec3 zenith = sampleEquirect(sky, {0, 1, 0});
    const glm::vec3 horizon(sky.at(5, 63, 0), sky.at(5, 63, 1), sky.at(5, 63, 2));  // last sky row
    const glm::vec3 ground = sampleEquirect(sky, {0, -1, 0});
    EXPECT_NEAR(zenith.z, p.zenithColor.z, 0.01f);
    EXPECT_NEAR(zenith.x, p.zenithColor.x, 0.01f);
    EXPECT_NEAR(horizon.x, p.horizonColor.x, 0.05f);  // row centre is 0.7 degrees up: nearly horizon
    EXPECT_NEAR(horizon.z, p.horizonColor.z, 0.05f);
    EXPECT_NEAR(ground.x, p.groundColor.x, 1e-5f);
    EXPECT_LT(ground.x + ground.y + ground.z, horizon.x + horizon.y + horizon.z);  // ground darker
    float previous = 0.0f;  // blue-to-white: red rises monotonically from zenith to horizon
    for (int y = 0; y < sky.height / 2; ++y) {
        ASSERT_GE(sky.at(10, y, 0), previous) << y;
        previous = sky.at(10, y, 0);
    }
}

// The sun's power (radiance x solid angle summed over the map) should be pi r^2 x radiance at
// any map size: a point-sampled disc would gain or lose it with resolution.
TEST(ProceduralSky, SunPowerIndependentOfResolution) {
    SkyParameters p;
    SkyParameters noSun = p;
    noSun.sunRadiance = glm::vec3(0.0f);
    const double expected = double(p.sunRadiance.x) * 2.0 * kPi * (1.0 - std::cos(double(p.sunAngularRadius)));
    for (int width : {64, 256, 1024}) {
        const Image with = makeProceduralSky(width, p).image;
        const Image without = makeProceduralSky(width, noSun).image;
        const int height = width / 2;
        double power = 0.0;
        for (int y = 0; y < height; ++y) {
            const double solidAngle = 2.0 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
            for (int x = 0; x < width; ++x) power += double(with.at(x, y, 0) - without.at(x, y, 0)) * solidAngle;
        }
        EXPECT_NEAR(power / expected, 1.0, 0.03) << "width " << width;
        std::printf("[ info ] sun power / (pi r^2 L) at width %d: %.4f\n", width, power / expected);
    }
}

TEST(ProceduralSky, SunBelowTheHorizonIsHidden) {
    SkyParameters p;
    p.sunDirection = glm::normalize(glm::vec3(0.2f, -0.5f, -1.0f));
    const Image sky = makeProceduralSky(256, p).image;
    EXPECT_LT(*std::max_element(sky.pixels.begin(), sky.pixels.end()), 1.5f);
}

TEST(ProceduralSky, BadParametersAreUserErrors) {
    EXPECT_THROW(makeProceduralSky(7), UserError);
    EXPECT_THROW(makeProceduralSky(0), UserError);
    SkyParameters p;
    p.sunDirection = glm::vec3(0.0f);
    EXPECT_THROW(makeProceduralSky(64, p), UserError);
    p = {};
    p.sunAngularRadius = 0.0f;
    EXPECT_THROW(makeProceduralSky(64, p), UserError);
    p = {};
    p.groundColor.x = -1.0f;
    EXPECT_THROW(makeProceduralSky(64, p), UserError);
}

}  // namespace
}  // namespace gbl
