#pragma once
// Nothing is compiled twice across runs (issue 14 item 3): two persistent caches in
// cacheDirectory() (src/base/disk_cache.h: $GBL_CACHE_DIR, $XDG_CACHE_HOME/gbufferlab or
// ~/.cache/gbufferlab), both in the checked envelope of disk_cache.h, so a truncated, corrupt or
// foreign file is a miss (recompiled and rewritten), never a wrong result.
//
// - SPIR-V: spv-<key>.bin per shader, key = FNV-1a 64 of everything glslang's output depends on:
//   the source text, every file it #includes (transitively, resolved as the compiler resolves
//   them: virtual files such as the generated gbuffer_wiring.glsl, then built-in generated files,
//   then shaders/), the defines, the stage, the glslang version and the compile options.
//   A hit skips glslang entirely.
// - VkPipelineCache: pipelines-<key>.bin per driver, key = FNV-1a 64 of vendorID, deviceID,
//   driverVersion and pipelineCacheUUID. The driver's data is also checked against its own header
//   (Vulkan 1.3 spec, section "Pipeline Cache", VkPipelineCacheHeaderVersionOne) before it is
//   handed to vkCreatePipelineCache.
//
// GBL_SHADER_CACHE=0 in the environment turns both off (nothing read, nothing written).
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace gbl {

struct ShaderSource;

bool shaderCacheEnabled();

// What this process compiled and what it took from the caches (compare reports them).
struct ShaderCacheCounters {
    std::atomic<int> glslangCompiles{0};    // shaders compiled by glslang
    std::atomic<int> spirvCacheHits{0};     // shaders whose SPIR-V came from the disk cache
    std::atomic<int> spirvCacheInvalid{0};  // cache files found but ignored (corrupt, truncated, ...)
    std::atomic<int> pipelines{0};          // pipelines created
    std::atomic<int> pipelineCacheHits{0};  // ... of which the driver reports found in the VkPipelineCache
    std::atomic<int> pipelinesReused{0};    // pipelines not created: a renderer had built the same before
};
ShaderCacheCounters& shaderCacheCounters();

uint64_t spirvCacheKey(const ShaderSource& source);
std::filesystem::path spirvCacheFile(uint64_t key);
// nullopt when missing or invalid (why then non-empty): also checks the SPIR-V magic number.
std::optional<std::vector<uint32_t>> readSpirvCache(const std::filesystem::path& file, uint64_t key, std::string* why);
void writeSpirvCache(const std::filesystem::path& file, uint64_t key, const std::vector<uint32_t>& spirv);

// The driver's pipeline cache data is usable for this device: Vulkan 1.3 spec, "Pipeline Cache"
// (VkPipelineCacheHeaderVersionOne): headerSize >= 32 and within the data, headerVersion ==
// VK_PIPELINE_CACHE_HEADER_VERSION_ONE, vendorID, deviceID and pipelineCacheUUID equal to the
// device's. `why` names the first field that differs.
bool pipelineCacheHeaderMatches(const std::vector<unsigned char>& data, const VkPhysicalDeviceProperties& properties,
                                std::string* why);
uint64_t pipelineCacheKey(const VkPhysicalDeviceProperties& properties);
std::filesystem::path pipelineCacheFile(const VkPhysicalDeviceProperties& properties);

// The device's VkPipelineCache, seeded from disk when a valid file is there (else empty).
// save() writes it back atomically when the driver's data grew, after merging what another run
// wrote meanwhile. Never throws from save(): a cache that cannot be written is a note.
class PersistentPipelineCache {
public:
    void open(VkDevice device, const VkPhysicalDeviceProperties& properties);
    void save() noexcept;
    void destroy() noexcept;
    VkPipelineCache handle() const { return cache_; }
    const std::string& note() const { return note_; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::vector<unsigned char> loaded_;
    std::string note_;
};

}  // namespace gbl
