#include "ibl_cache.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "disk_cache.h"
#include "error.h"
#include "file_io.h"
#include "shader_compiler.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'G', 'B', 'L', 'I', 'B', 'L', '0', '1'};
constexpr uint32_t kFormatVersion = 1;
constexpr size_t kHeaderBytes = kCacheEnvelopeHeaderBytes;  // disk_cache.h's envelope

size_t payloadBytesFor(const IblSettings& s) {
    size_t floats = 27;
    for (uint32_t m = 0; m < s.prefilteredMips; ++m) {
        const size_t face = std::max(s.prefilteredFaceSize >> m, 1u);
        floats += face * face * 24;
    }
    floats += size_t(s.lutSize) * s.lutSize * 2;
    return 16 + floats * 4;
}

}  // namespace

fs::path iblCacheDirectory() { return cacheDirectory(); }

uint64_t iblCacheKey(const EnvironmentMap& environment, const IblSettings& s) {
    Fnv64 f;
    f.value(kFormatVersion);
    const Image& img = environment.image;
    f.value(img.width);
    f.value(img.height);
    f.value(img.channels);
    f.bytes(img.pixels.data(), img.pixels.size() * sizeof(float));
    const uint32_t fields[] = {s.sourceFaceSize, s.prefilteredFaceSize, s.prefilteredMips,
                               s.bruteForce ? s.bruteForceSamples : s.prefilterSamples,
                               s.bruteForce ? 1u : 0u, s.lutSize, s.lutSamples, uint32_t(s.lutEstimator)};
    f.bytes(fields, sizeof(fields));
    // The shaders that produce the data: an edited shader must not reuse old results.
    for (const char* name : {"ibl_equirect_to_cube.comp.glsl", "ibl_downsample.comp.glsl", "ibl_prefilter.comp.glsl",
                             "ibl_brdf_lut.comp.glsl", "ibl_math.glsl", "brdf.glsl", "environment_map.glsl",
                             "cube_face.glsl"}) {
        const std::string text = readTextFile(fs::path(shaderDirectory()) / name);
        f.bytes(text.data(), text.size());
    }
    return f.h;
}

fs::path iblCacheFile(const fs::path& directory, uint64_t key) {
    char name[40];
    std::snprintf(name, sizeof(name), "ibl-%016llx.bin", static_cast<unsigned long long>(key));
    return directory / name;
}

std::optional<IblMaps> readIblCacheFile(const fs::path& file, uint64_t key, const IblSettings& s, std::string* why) {
    const auto payload = readCacheEnvelope(file, kMagic, kFormatVersion, key, why);
    if (!payload) return std::nullopt;
    const size_t expected = payloadBytesFor(s);
    if (payload->size() != expected) {
        if (why)
            *why = "size " + std::to_string(kHeaderBytes + payload->size()) + " bytes, expected " +
                   std::to_string(kHeaderBytes + expected);
        return std::nullopt;
    }
    const unsigned char* p = payload->data();
    auto fail = [&](const std::string& reason) -> std::optional<IblMaps> {
        if (why) *why = reason;
        return std::nullopt;
    };
    uint32_t dims[4];
    std::memcpy(dims, p, 16);
    if (dims[0] != s.prefilteredFaceSize || dims[1] != s.prefilteredMips || dims[2] != s.lutSize)
        return fail("sizes do not match the settings");
    p += 16;
    IblMaps maps;
    maps.settings = s;
    float sh[27];
    std::memcpy(sh, p, sizeof(sh));
    p += sizeof(sh);
    for (int k = 0; k < 9; ++k) maps.irradianceSh[k] = glm::vec3(sh[k * 3], sh[k * 3 + 1], sh[k * 3 + 2]);
    for (uint32_t m = 0; m < s.prefilteredMips; ++m) {
        CubeMip mip;
        mip.size = std::max(s.prefilteredFaceSize >> m, 1u);
        mip.rgba.resize(size_t(mip.size) * mip.size * 24);
        std::memcpy(mip.rgba.data(), p, mip.rgba.size() * 4);
        p += mip.rgba.size() * 4;
        maps.prefiltered.push_back(std::move(mip));
    }
    maps.brdfLut = Image(int(s.lutSize), int(s.lutSize), 2);
    std::memcpy(maps.brdfLut.pixels.data(), p, maps.brdfLut.pixels.size() * 4);
    return maps;
}

void writeIblCacheFile(const fs::path& file, uint64_t key, const IblMaps& maps) {
    const IblSettings& s = maps.settings;
    const size_t payloadBytes = payloadBytesFor(s);
    std::vector<unsigned char> payload(payloadBytes);
    unsigned char* p = payload.data();
    const uint32_t dims[4] = {s.prefilteredFaceSize, s.prefilteredMips, s.lutSize, 0};
    std::memcpy(p, dims, 16);
    p += 16;
    for (int k = 0; k < 9; ++k) {
        std::memcpy(p, &maps.irradianceSh[k].x, 12);
        p += 12;
    }
    for (const CubeMip& m : maps.prefiltered) {
        std::memcpy(p, m.rgba.data(), m.rgba.size() * 4);
        p += m.rgba.size() * 4;
    }
    std::memcpy(p, maps.brdfLut.pixels.data(), maps.brdfLut.pixels.size() * 4);
    p += maps.brdfLut.pixels.size() * 4;
    if (size_t(p - payload.data()) != payload.size()) throw std::logic_error("writeIblCacheFile: size mismatch");
    writeCacheEnvelope(file, kMagic, kFormatVersion, key, payload.data(), payload.size());
}

IblMaps loadOrComputeIbl(const VulkanContext& ctx, const EnvironmentMap& environment, const IblSettings& settings,
                         IblCacheStatus* status) {
    IblCacheStatus local;
    IblCacheStatus& st = status ? *status : local;
    st = IblCacheStatus{};
    const IblSettings s = resolveIblSettings(settings, environment);
    const uint64_t key = iblCacheKey(environment, s);
    st.file = iblCacheFile(iblCacheDirectory(), key);
    std::string why;
    if (auto maps = readIblCacheFile(st.file, key, s, &why)) {
        st.hit = true;
        st.note = "IBL cache hit: " + st.file.string();
        return std::move(*maps);
    }
    st.rebuiltCorrupt = !why.empty();
    IblMaps maps = computeIblMaps(ctx, environment, s);
    try {
        writeIblCacheFile(st.file, key, maps);
        st.note = (st.rebuiltCorrupt ? "IBL cache file was invalid (" + why + "), rebuilt: " : "IBL cache written: ") +
                  st.file.string();
    } catch (const std::exception& e) {
        st.note = std::string("IBL cache not written (") + e.what() + ")";
    }
    return maps;
}

}  // namespace gbl
