#include "shader_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <set>

#include <glslang/build_info.h>

#include "disk_cache.h"
#include "file_io.h"
#include "shader_compiler.h"
#include "vk_context.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

constexpr char kSpirvMagic[8] = {'G', 'B', 'L', 'S', 'P', 'V', '0', '1'};
constexpr char kPipelineMagic[8] = {'G', 'B', 'L', 'P', 'C', 'H', '0', '1'};
// Bump when compileGlsl's options change (target environment, SPIR-V version, optimizer).
constexpr uint32_t kSpirvFormatVersion = 1;
constexpr uint32_t kPipelineFormatVersion = 1;

// Every `#include "x"` / `#include <x>` in `text`, conditional or not (hashing a file that the
// preprocessor then skips costs a miss at worst, never a stale hit).
void hashIncludes(const std::string& text, const ShaderSource& src, Fnv64& f, std::set<std::string>& seen) {
    static const std::regex re(R"(^[ \t]*#[ \t]*include[ \t]*["<]([^">\n]+)[">])", std::regex::multiline);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
        const std::string name = (*it)[1];
        if (!seen.insert(name).second) continue;
        f.text(name);
        const std::optional<std::string> included = resolveShaderInclude(name, src.virtualFiles);
        f.value(uint8_t(included ? 1 : 0));
        if (!included) continue;
        f.text(*included);
        hashIncludes(*included, src, f, seen);
    }
}

}  // namespace

bool shaderCacheEnabled() {
    const char* v = std::getenv("GBL_SHADER_CACHE");
    return !(v && (std::strcmp(v, "0") == 0 || std::strcmp(v, "off") == 0));
}

ShaderCacheCounters& shaderCacheCounters() {
    static ShaderCacheCounters counters;
    return counters;
}

uint64_t spirvCacheKey(const ShaderSource& src) {
    Fnv64 f;
    f.value(kSpirvFormatVersion);
    f.value(uint32_t(GLSLANG_VERSION_MAJOR));
    f.value(uint32_t(GLSLANG_VERSION_MINOR));
    f.value(uint32_t(GLSLANG_VERSION_PATCH));
    f.text(GLSLANG_VERSION_FLAVOR);
    f.value(uint32_t(src.stage));
    f.text(src.name);  // glslang names the file in OpSource / OpString
    f.value(uint64_t(src.defines.size()));
    for (const auto& [k, v] : src.defines) {
        f.text(k);
        f.text(v);
    }
    f.text(src.text);
    std::set<std::string> seen;
    hashIncludes(src.text, src, f, seen);
    return f.h;
}

fs::path spirvCacheFile(uint64_t key) { return cacheFileFor("spv", key); }

std::optional<std::vector<uint32_t>> readSpirvCache(const fs::path& file, uint64_t key, std::string* why) {
    auto payload = readCacheEnvelope(file, kSpirvMagic, kSpirvFormatVersion, key, why);
    if (!payload) return std::nullopt;
    if (payload->size() < 20 || payload->size() % 4 != 0) {
        if (why) *why = "not SPIR-V (" + std::to_string(payload->size()) + " bytes)";
        return std::nullopt;
    }
    std::vector<uint32_t> spirv(payload->size() / 4);
    std::memcpy(spirv.data(), payload->data(), payload->size());
    if (spirv[0] != 0x07230203u) {  // SPIR-V spec, section 2.3 "Physical Layout": the magic number
        if (why) *why = "not SPIR-V (magic number)";
        return std::nullopt;
    }
    return spirv;
}

void writeSpirvCache(const fs::path& file, uint64_t key, const std::vector<uint32_t>& spirv) {
    writeCacheEnvelope(file, kSpirvMagic, kSpirvFormatVersion, key, spirv.data(), spirv.size() * 4);
}

bool pipelineCacheHeaderMatches(const std::vector<unsigned char>& data, const VkPhysicalDeviceProperties& p,
                                std::string* why) {
    auto fail = [&](const char* reason) {
        if (why) *why = reason;
        return false;
    };
    // VkPipelineCacheHeaderVersionOne: u32 headerSize, u32 headerVersion, u32 vendorID,
    // u32 deviceID, u8 pipelineCacheUUID[VK_UUID_SIZE]; 32 bytes, little-endian on every host here.
    constexpr size_t kHeaderOne = 16 + VK_UUID_SIZE;
    if (data.size() < kHeaderOne) return fail("pipeline cache data shorter than its header");
    uint32_t headerSize, headerVersion, vendorId, deviceId;
    std::memcpy(&headerSize, data.data(), 4);
    std::memcpy(&headerVersion, data.data() + 4, 4);
    std::memcpy(&vendorId, data.data() + 8, 4);
    std::memcpy(&deviceId, data.data() + 12, 4);
    if (headerSize < kHeaderOne || headerSize > data.size()) return fail("pipeline cache headerSize out of range");
    if (headerVersion != VK_PIPELINE_CACHE_HEADER_VERSION_ONE) return fail("pipeline cache headerVersion");
    if (vendorId != p.vendorID) return fail("pipeline cache vendorID differs");
    if (deviceId != p.deviceID) return fail("pipeline cache deviceID differs");
    if (std::memcmp(data.data() + 16, p.pipelineCacheUUID, VK_UUID_SIZE) != 0)
        return fail("pipeline cache UUID differs");
    return true;
}

uint64_t pipelineCacheKey(const VkPhysicalDeviceProperties& p) {
    Fnv64 f;
    f.value(kPipelineFormatVersion);
    f.value(p.vendorID);
    f.value(p.deviceID);
    f.value(p.driverVersion);
    f.bytes(p.pipelineCacheUUID, VK_UUID_SIZE);
    return f.h;
}

fs::path pipelineCacheFile(const VkPhysicalDeviceProperties& p) {
    return cacheFileFor("pipelines", pipelineCacheKey(p));
}

void PersistentPipelineCache::open(VkDevice device, const VkPhysicalDeviceProperties& properties) {
    device_ = device;
    properties_ = properties;
    std::string why;
    if (shaderCacheEnabled()) {
        const fs::path file = pipelineCacheFile(properties);
        if (auto data = readCacheEnvelope(file, kPipelineMagic, kPipelineFormatVersion, pipelineCacheKey(properties), &why)) {
            if (pipelineCacheHeaderMatches(*data, properties, &why)) loaded_ = std::move(*data);
        }
        if (!why.empty()) note_ = "pipeline cache " + file.string() + " ignored: " + why;
    }
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = loaded_.size();
    info.pInitialData = loaded_.empty() ? nullptr : loaded_.data();
    if (vkCreatePipelineCache(device, &info, nullptr, &cache_) != VK_SUCCESS) {
        // The driver refused the data (it may): start empty rather than fail.
        loaded_.clear();
        info.initialDataSize = 0;
        info.pInitialData = nullptr;
        VK_CHECK(vkCreatePipelineCache(device, &info, nullptr, &cache_));
    }
}

void PersistentPipelineCache::save() noexcept {
    if (!cache_ || !shaderCacheEnabled()) return;
    try {
        const fs::path file = pipelineCacheFile(properties_);
        // What another run wrote since open(): merged in, so concurrent runs add up.
        std::string why;
        auto onDisk = readCacheEnvelope(file, kPipelineMagic, kPipelineFormatVersion, pipelineCacheKey(properties_), &why);
        if (onDisk && *onDisk != loaded_ && pipelineCacheHeaderMatches(*onDisk, properties_, &why)) {
            VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
            info.initialDataSize = onDisk->size();
            info.pInitialData = onDisk->data();
            VkPipelineCache other = VK_NULL_HANDLE;
            if (vkCreatePipelineCache(device_, &info, nullptr, &other) == VK_SUCCESS) {
                vkMergePipelineCaches(device_, cache_, 1, &other);
                vkDestroyPipelineCache(device_, other, nullptr);
            }
        }
        size_t size = 0;
        if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) != VK_SUCCESS) return;
        std::vector<unsigned char> data(size);
        if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) return;
        data.resize(size);
        if (data == loaded_ || (onDisk && data == *onDisk)) return;  // nothing new
        if (!pipelineCacheHeaderMatches(data, properties_, &why)) return;  // never store what we would refuse
        writeCacheEnvelope(file, kPipelineMagic, kPipelineFormatVersion, pipelineCacheKey(properties_), data.data(),
                           data.size());
        loaded_ = std::move(data);
    } catch (const std::exception& e) {
        note_ = std::string("pipeline cache not written: ") + e.what();
    }
}

void PersistentPipelineCache::destroy() noexcept {
    if (cache_) vkDestroyPipelineCache(device_, cache_, nullptr);
    cache_ = VK_NULL_HANDLE;
}

}  // namespace gbl
