#include "disk_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "file_io.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {
uint64_t payloadHash(const void* payload, size_t bytes) {
    Fnv64 f;
    f.words(payload, bytes);
    return f.h;
}
}  // namespace

fs::path cacheDirectory() {
    if (const char* d = std::getenv("GBL_CACHE_DIR"); d && *d) return fs::path(d);
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "gbufferlab";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "gbufferlab";
    return fs::temp_directory_path() / "gbufferlab-cache";
}

fs::path cacheFileFor(const std::string& kind, uint64_t key) {
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(key));
    return cacheDirectory() / (kind + "-" + hex + ".bin");
}

std::optional<std::vector<unsigned char>> readCacheEnvelope(const fs::path& file, const char magic[8],
                                                            uint32_t version, uint64_t key, std::string* why) {
    auto fail = [&](const std::string& reason) -> std::optional<std::vector<unsigned char>> {
        if (why) *why = reason;
        return std::nullopt;
    };
    if (why) why->clear();
    std::error_code ec;
    if (!fs::exists(file, ec)) return std::nullopt;
    std::vector<unsigned char> bytes;
    try {
        bytes = readBinaryFile(file);
    } catch (const std::exception& e) {
        return fail(std::string("unreadable: ") + e.what());
    }
    if (bytes.size() < kCacheEnvelopeHeaderBytes)
        return fail("truncated header (" + std::to_string(bytes.size()) + " bytes)");
    if (std::memcmp(bytes.data(), magic, 8) != 0) return fail("bad magic");
    uint32_t fileVersion, hashKind;
    uint64_t fileKey, payloadBytes, fileHash;
    std::memcpy(&fileVersion, bytes.data() + 8, 4);
    std::memcpy(&hashKind, bytes.data() + 12, 4);
    std::memcpy(&fileKey, bytes.data() + 16, 8);
    std::memcpy(&payloadBytes, bytes.data() + 24, 8);
    std::memcpy(&fileHash, bytes.data() + 32, 8);
    if (fileVersion != version) return fail("format version " + std::to_string(fileVersion));
    if (fileKey != key) return fail("key mismatch");
    if (payloadBytes != bytes.size() - kCacheEnvelopeHeaderBytes)
        return fail("size " + std::to_string(bytes.size()) + " bytes, header says " +
                    std::to_string(kCacheEnvelopeHeaderBytes + payloadBytes));
    if (hashKind != kCacheHashWords) return fail("payload hash kind " + std::to_string(hashKind));
    if (payloadHash(bytes.data() + kCacheEnvelopeHeaderBytes, payloadBytes) != fileHash)
        return fail("payload hash mismatch (corrupt)");
    bytes.erase(bytes.begin(), bytes.begin() + kCacheEnvelopeHeaderBytes);
    return bytes;
}

void writeCacheEnvelope(const fs::path& file, const char magic[8], uint32_t version, uint64_t key,
                        const void* payload, size_t payloadBytes) {
    std::vector<unsigned char> out(kCacheEnvelopeHeaderBytes + payloadBytes);
    const uint32_t hashKind = kCacheHashWords;
    const uint64_t pb = payloadBytes, hash = payloadHash(payload, payloadBytes);
    std::memcpy(out.data(), magic, 8);
    std::memcpy(out.data() + 8, &version, 4);
    std::memcpy(out.data() + 12, &hashKind, 4);
    std::memcpy(out.data() + 16, &key, 8);
    std::memcpy(out.data() + 24, &pb, 8);
    std::memcpy(out.data() + 32, &hash, 8);
    if (payloadBytes) std::memcpy(out.data() + kCacheEnvelopeHeaderBytes, payload, payloadBytes);
    fs::create_directories(file.parent_path());
    writeFileAtomic(file, out.data(), out.size());
}

}  // namespace gbl
