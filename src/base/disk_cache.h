#pragma once
// What gbufferlab's on-disk caches share (the IBL maps, src/shading/ibl_cache.h; SPIR-V and the
// driver's pipeline cache, src/gpu/shader_cache.h): where they live, the hash that keys them, and
// one envelope format that makes a truncated, corrupt or foreign file a miss, never a wrong result.
//
// Directory: $GBL_CACHE_DIR, else $XDG_CACHE_HOME/gbufferlab, else ~/.cache/gbufferlab.
// Envelope (little-endian): magic (8 bytes), u32 format version, u32 hash kind (1), u64 key, u64
// payload bytes, u64 Fnv64::words of the payload, then the payload. Kind 0, FNV-1a byte by byte
// with a mistyped offset basis, was written before 2026-11-25; those files are keyed by that hash
// too, so they are never opened again (a kind 0 file would be a miss). Byte steps cost 22 ms per
// 22 MiB of a glTF scene's mips and IBL maps on every warm run, words 2.8 ms. Writes are atomic
// (temporary + rename, src/base/file_io.h), so concurrent writers cannot leave half a file: the
// last rename wins.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace gbl {

std::filesystem::path cacheDirectory();
// cacheDirectory() / "<kind>-<key as 16 hex digits>.bin", the name every cache file has.
std::filesystem::path cacheFileFor(const std::string& kind, uint64_t key);

// FNV-1a 64.
struct Fnv64 {
    uint64_t h = 14695981039346656037ull;  // the published offset basis (0xcbf29ce484222325)
    void bytes(const void* p, size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) {
            h ^= b[i];
            h *= 1099511628211ull;
        }
    }
    // The FNV-1a step over 8-byte words (the tail byte by byte): for large buffers (a texture's
    // texels), where byte steps cost 4 ms a 1024^2 texture. XOR and multiplication by an odd
    // number are bijections, so buffers that differ in one word differ. Not the same hash as bytes().
    void words(const void* p, size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        size_t i = 0;
        for (; i + 8 <= n; i += 8) {
            uint64_t w;
            std::memcpy(&w, b + i, 8);
            h = (h ^ w) * 1099511628211ull;
        }
        for (; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    }
    template <class T> void value(const T& v) { bytes(&v, sizeof(v)); }
    // Length-prefixed, so that ("ab", "c") and ("a", "bc") differ.
    void text(const std::string& s) {
        value(uint64_t(s.size()));
        bytes(s.data(), s.size());
    }
};

inline constexpr size_t kCacheEnvelopeHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8;
inline constexpr uint32_t kCacheHashWords = 1;

// The payload of a valid file; nullopt when it is missing (why empty) or invalid (why says which:
// unreadable, truncated, bad magic, version, key, size, hash).
std::optional<std::vector<unsigned char>> readCacheEnvelope(const std::filesystem::path& file, const char magic[8],
                                                            uint32_t version, uint64_t key, std::string* why);
// Creates the directory; throws (UserError) when the file cannot be written.
void writeCacheEnvelope(const std::filesystem::path& file, const char magic[8], uint32_t version, uint64_t key,
                        const void* payload, size_t payloadBytes);

}  // namespace gbl
