#pragma once
// Disk cache of the pre-computed IBL (src/shading/ibl_precompute.h): one file per (environment content,
// resolved settings, IBL shader sources) triple, so a changed map, setting or shader never reuses
// a stale file.
//
// Directory: $GBL_CACHE_DIR, else $XDG_CACHE_HOME/gbufferlab, else ~/.cache/gbufferlab.
// File: ibl-<key as 16 hex digits>.bin, little-endian:
//   header  "GBLIBL01" (8 bytes), u32 format version, u32 0, u64 key, u64 payload bytes,
//           u64 FNV-1a 64 of the payload
//   payload u32 prefiltered face, u32 mips, u32 lut size, u32 0, 27 floats (SH9 rgb),
//           the mips (6 faces RGBA float each), the LUT (size^2 x 2 floats)
// Reading checks the magic, version, key, file size, payload hash and every size against the
// settings; any mismatch is reported (why) and the file is rebuilt, never used.
// Writes are atomic (temporary + rename), so concurrent runs cannot see half a file.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "ibl_precompute.h"

namespace gbl {

std::filesystem::path iblCacheDirectory();
// FNV-1a 64 of the environment's size and texels, the resolved settings and the IBL shaders' text.
uint64_t iblCacheKey(const EnvironmentMap& environment, const IblSettings& resolvedSettings);
std::filesystem::path iblCacheFile(const std::filesystem::path& directory, uint64_t key);

// nullopt when the file is missing or invalid; `why` then says which (empty when missing).
std::optional<IblMaps> readIblCacheFile(const std::filesystem::path& file, uint64_t key,
                                        const IblSettings& resolvedSettings, std::string* why);
void writeIblCacheFile(const std::filesystem::path& file, uint64_t key, const IblMaps& maps);

struct IblCacheStatus {
    bool hit = false;
    bool rebuiltCorrupt = false;   // a file was there but invalid
    std::string note;              // what happened, for the command's output
    std::filesystem::path file;
};

// Reads the cache or computes (GPU) and writes it. A cache directory that cannot be written is a
// warning in `status.note`, not an error.
IblMaps loadOrComputeIbl(const VulkanContext& ctx, const EnvironmentMap& environment, const IblSettings& settings,
                         IblCacheStatus* status = nullptr);

}  // namespace gbl
