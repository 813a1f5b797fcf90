// The texture mip cache (render/texture_mip_cache.h): on a CPU device the levels uploaded from the
// cache are byte for byte those the driver's blits make, a whole render from cached mips equals
// one from blits, and a corrupt file is a miss, never a wrong texture.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>
#include <vector>

#include "procedural_sky.h"
#include "renderer.h"
#include "scene.h"
#include "temp_cache_dir.h"
#include "texture_mip_cache.h"
#include "vk_test_support.h"
#include "wiring_codegen.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

// GBL_CACHE_DIR at a fresh folder for the test's lifetime, and the mip files in it.
struct TempCacheDir : test::TempCacheDir {
    TempCacheDir() : test::TempCacheDir("gbl-mip-cache-test") {}
    std::vector<fs::path> mipFiles() const {
        std::vector<fs::path> out;
        if (!fs::exists(dir)) return out;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().filename().string().rfind("mips-", 0) == 0) out.push_back(e.path());
        return out;
    }
};

class TextureMipCacheTest : public test::VulkanTest {
protected:
    void SetUp() override {
        test::VulkanTest::SetUp();
        if (ctx().info.type != VK_PHYSICAL_DEVICE_TYPE_CPU) GTEST_SKIP() << "the cache is for CPU devices only";
    }
};

GpuImage makeTexture(const VulkanContext& ctx, uint32_t w, uint32_t h, VkFormat format) {
    ImageDesc d;
    d.format = format;
    d.width = w;
    d.height = h;
    d.mipLevels = mipCountFor(w, h);
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    return createImage(ctx, d);
}

std::vector<std::vector<uint8_t>> levels(const VulkanContext& ctx, const GpuImage& image) {
    std::vector<std::vector<uint8_t>> out;
    for (uint32_t m = 0; m < image.mipLevels; ++m)
        out.push_back(downloadImage(ctx, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, m));
    return out;
}

// A texture whose sides halve unevenly (60x44 -> 30x22 -> 15x11 -> 7x5 -> 3x2 -> 1x1), in both
// colour spaces (an sRGB blit filters in linear light).
TEST_F(TextureMipCacheTest, CachedLevelsEqualTheBlitsByteForByte) {
    TempCacheDir cache;
    std::mt19937 rng(7);
    std::vector<uint8_t> rgba(60 * 44 * 4);
    for (uint8_t& b : rgba) b = uint8_t(rng());
    for (VkFormat format : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB}) {
        GpuImage blitted = makeTexture(ctx(), 60, 44, format);
        const size_t filesBefore = cache.mipFiles().size();
        uploadTextureWithMips(ctx(), blitted, rgba.data());  // a miss: blits, then stored
        ASSERT_EQ(cache.mipFiles().size(), filesBefore + 1);
        GpuImage cached = makeTexture(ctx(), 60, 44, format);
        uploadTextureWithMips(ctx(), cached, rgba.data());  // a hit
        EXPECT_EQ(cache.mipFiles().size(), filesBefore + 1);
        const auto a = levels(ctx(), blitted), b = levels(ctx(), cached);
        ASSERT_EQ(a.size(), 6u);
        for (size_t m = 0; m < a.size(); ++m) EXPECT_EQ(a[m], b[m]) << "format " << format << " mip " << m;
        // The stored levels are the blits' (a cache that stored something else, e.g. mip 0 again,
        // would still have made the two uploads agree if both read it).
        EXPECT_NE(a[1], std::vector<uint8_t>(a[0].begin(), a[0].begin() + a[1].size()));
        destroyImage(ctx(), blitted);
        destroyImage(ctx(), cached);
    }
}

TEST_F(TextureMipCacheTest, KeyFollowsTexelsFormatAndSize) {
    std::vector<uint8_t> rgba(64 * 64 * 4, 100);
    GpuImage unorm = makeTexture(ctx(), 64, 64, VK_FORMAT_R8G8B8A8_UNORM);
    GpuImage srgb = makeTexture(ctx(), 64, 64, VK_FORMAT_R8G8B8A8_SRGB);
    GpuImage wide = makeTexture(ctx(), 128, 32, VK_FORMAT_R8G8B8A8_UNORM);
    const uint64_t k = textureMipCacheKey(ctx(), unorm, rgba.data());
    EXPECT_EQ(k, textureMipCacheKey(ctx(), unorm, rgba.data()));
    EXPECT_NE(k, textureMipCacheKey(ctx(), srgb, rgba.data()));
    EXPECT_NE(k, textureMipCacheKey(ctx(), wide, rgba.data()));
    for (size_t byte : {size_t(0), size_t(7), rgba.size() / 2 + 3, rgba.size() - 1}) {
        std::vector<uint8_t> changed = rgba;
        changed[byte] ^= 1;
        EXPECT_NE(k, textureMipCacheKey(ctx(), unorm, changed.data())) << "byte " << byte;
    }
    destroyImage(ctx(), unorm);
    destroyImage(ctx(), srgb);
    destroyImage(ctx(), wide);
}

// The built-in scene rendered from blitted mips, from cached ones, and from corrupt cache files.
TEST_F(TextureMipCacheTest, RenderFromCachedOrCorruptCacheEqualsRenderFromBlits) {
    TempCacheDir cache;
    const Scene scene = makeSphereGridScene();
    const EnvironmentMap sky = makeProceduralSky(128);
    RenderSettings s;
    s.width = 160;  // textures seen from afar: their small mips are sampled
    s.height = 90;
    auto render = [&] {
        Renderer renderer(ctx(), scene, sky);
        return renderer.render(makeReferenceWiring(), s).hdr;
    };
    const Image blitted = render();
    const std::vector<fs::path> files = cache.mipFiles();
    ASSERT_FALSE(files.empty());
    const Image cached = render();
    EXPECT_EQ(cached.pixels, blitted.pixels);
    for (const fs::path& f : files) {  // one byte of each payload flipped: its hash no longer holds
        std::fstream io(f, std::ios::in | std::ios::out | std::ios::binary);
        io.seekg(-1, std::ios::end);
        const char last = char(io.get());
        io.seekp(-1, std::ios::end);
        io.put(char(last ^ 0x40));
    }
    const Image rebuilt = render();
    EXPECT_EQ(rebuilt.pixels, blitted.pixels);
    EXPECT_EQ(cache.mipFiles().size(), files.size());
    EXPECT_EQ(render().pixels, blitted.pixels);  // the rewritten files are read again
}

}  // namespace
}  // namespace gbl
