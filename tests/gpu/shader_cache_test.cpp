// The persistent SPIR-V cache and the pipeline-cache header check (src/gpu/shader_cache.h):
// a second compile of the same input skips glslang; any change to the input misses; a corrupt
// or truncated cache file gives the same SPIR-V as no cache and is rewritten.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "file_io.h"
#include "shader_cache.h"
#include "shader_compiler.h"
#include "temp_cache_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

// GBL_CACHE_DIR at a fresh folder for the test's lifetime.
struct TempCacheDir : test::TempCacheDir {
    TempCacheDir() : test::TempCacheDir("gbl-shader-cache-test") {}
};

ShaderSource shader() {
    ShaderSource s;
    s.name = "cache_test.comp.glsl";
    s.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    s.text = "#version 450\n#extension GL_GOOGLE_include_directive : require\n"
             "layout(local_size_x = 1) in;\n#include \"generated.glsl\"\n"
             "layout(std430, binding = 0) buffer B { float v[]; };\nvoid main() { v[0] = helper() * SCALE; }\n";
    s.virtualFiles["generated.glsl"] = "#include \"nested.glsl\"\nfloat helper() { return nested(); }\n";
    s.virtualFiles["nested.glsl"] = "float nested() { return 2.0; }\n";
    s.defines = {{"SCALE", "3.0"}};
    return s;
}

TEST(ShaderCache, SecondCompileSkipsGlslangAndReturnsTheSameSpirv) {
    TempCacheDir cache;
    ShaderCacheCounters& c = shaderCacheCounters();
    const std::vector<uint32_t> uncached = compileGlslUncached(shader());
    const int compiles = c.glslangCompiles, hits = c.spirvCacheHits;
    EXPECT_EQ(compileGlsl(shader()), uncached);  // miss: compiled, written
    EXPECT_EQ(c.glslangCompiles, compiles + 1);
    EXPECT_TRUE(fs::exists(spirvCacheFile(spirvCacheKey(shader()))));
    EXPECT_EQ(compileGlsl(shader()), uncached);  // hit
    EXPECT_EQ(c.glslangCompiles, compiles + 1);
    EXPECT_EQ(c.spirvCacheHits, hits + 1);
}

TEST(ShaderCache, EveryInputChangesTheKey) {
    const uint64_t base = spirvCacheKey(shader());
    ShaderSource s = shader();
    s.text += " ";
    EXPECT_NE(spirvCacheKey(s), base) << "source text";
    s = shader();
    s.virtualFiles["generated.glsl"] += " ";
    EXPECT_NE(spirvCacheKey(s), base) << "virtual file";
    s = shader();
    s.virtualFiles["nested.glsl"] = "float nested() { return 4.0; }\n";
    EXPECT_NE(spirvCacheKey(s), base) << "file included by an included file";
    s = shader();
    s.defines[0].second = "3.5";
    EXPECT_NE(spirvCacheKey(s), base) << "define";
    s = shader();
    s.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    EXPECT_NE(spirvCacheKey(s), base) << "stage";
    s = shader();
    s.virtualFiles["unused.glsl"] = "float x;";  // not included: no effect on the output, nor the key
    EXPECT_EQ(spirvCacheKey(s), base);
}

TEST(ShaderCache, CorruptOrTruncatedFileGivesTheSameSpirvAsNoCache) {
    TempCacheDir cache;
    const std::vector<uint32_t> uncached = compileGlslUncached(shader());
    const fs::path file = spirvCacheFile(spirvCacheKey(shader()));
    ShaderCacheCounters& c = shaderCacheCounters();
    auto damage = [&](const char* what, auto&& change) {
        compileGlsl(shader());  // a valid file
        std::vector<unsigned char> bytes = readBinaryFile(file);
        change(bytes);
        writeFileAtomic(file, bytes.data(), bytes.size());
        const int invalid = c.spirvCacheInvalid, compiles = c.glslangCompiles;
        EXPECT_EQ(compileGlsl(shader()), uncached) << what;
        EXPECT_EQ(c.spirvCacheInvalid, invalid + 1) << what;
        EXPECT_EQ(c.glslangCompiles, compiles + 1) << what;
        std::string why;
        EXPECT_TRUE(readSpirvCache(file, spirvCacheKey(shader()), &why)) << what << ": rewritten valid, " << why;
    };
    damage("one payload bit flipped", [](std::vector<unsigned char>& b) { b[b.size() - 7] ^= 0x10; });
    damage("truncated payload", [](std::vector<unsigned char>& b) { b.resize(b.size() - 9); });
    damage("truncated header", [](std::vector<unsigned char>& b) { b.resize(11); });
    damage("empty", [](std::vector<unsigned char>& b) { b.clear(); });
    damage("bad magic", [](std::vector<unsigned char>& b) { b[0] = 'X'; });
    damage("another key's file", [](std::vector<unsigned char>& b) { b[16] ^= 1; });
}

TEST(ShaderCache, DisabledByEnvironmentReadsAndWritesNothing) {
    TempCacheDir cache;
    ::setenv("GBL_SHADER_CACHE", "0", 1);
    const int compiles = shaderCacheCounters().glslangCompiles;
    compileGlsl(shader());
    compileGlsl(shader());
    ::unsetenv("GBL_SHADER_CACHE");
    EXPECT_EQ(shaderCacheCounters().glslangCompiles, compiles + 2);
    EXPECT_FALSE(fs::exists(cache.dir));
}

// Vulkan 1.3 spec, "Pipeline Cache": VkPipelineCacheHeaderVersionOne.
TEST(PipelineCacheHeader, AcceptsOnlyThisDevicesVersionOneHeader) {
    VkPhysicalDeviceProperties p{};
    p.vendorID = 0x10005;
    p.deviceID = 0x42;
    for (uint32_t i = 0; i < VK_UUID_SIZE; ++i) p.pipelineCacheUUID[i] = uint8_t(i * 7 + 1);
    std::vector<unsigned char> data(32 + 8, 0xAB);
    const uint32_t header[4] = {32, VK_PIPELINE_CACHE_HEADER_VERSION_ONE, p.vendorID, p.deviceID};
    std::memcpy(data.data(), header, 16);
    std::memcpy(data.data() + 16, p.pipelineCacheUUID, VK_UUID_SIZE);
    std::string why;
    EXPECT_TRUE(pipelineCacheHeaderMatches(data, p, &why)) << why;
    auto rejects = [&](const char* what, auto&& change) {
        std::vector<unsigned char> d = data;
        change(d);
        EXPECT_FALSE(pipelineCacheHeaderMatches(d, p, &why)) << what;
        EXPECT_FALSE(why.empty()) << what;
    };
    rejects("short", [](auto& d) { d.resize(31); });
    rejects("headerSize 16", [](auto& d) { d[0] = 16; });
    rejects("headerSize beyond the data", [](auto& d) { d[0] = 200; });
    rejects("headerVersion 2", [](auto& d) { d[4] = 2; });
    rejects("vendorID", [](auto& d) { d[8] ^= 1; });
    rejects("deviceID", [](auto& d) { d[12] ^= 1; });
    rejects("UUID", [](auto& d) { d[31] ^= 1; });
    VkPhysicalDeviceProperties q = p;
    q.driverVersion = 7;
    EXPECT_NE(pipelineCacheFile(p), pipelineCacheFile(q)) << "a driver update gets its own file";
}

}  // namespace
}  // namespace gbl
