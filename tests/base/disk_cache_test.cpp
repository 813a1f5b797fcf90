// disk_cache.h's envelope: what it writes, byte for byte, against an independent FNV-1a written
// here; a file of the earlier kind (byte-wise, hash kind 0), a flipped payload byte, an unknown
// hash kind, a foreign key or a cut file is a miss that says why.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "disk_cache.h"

namespace {

namespace fs = std::filesystem;

constexpr uint64_t kOffset = 14695981039346656037ull;  // FNV-1a 64 (Fowler, Noll, Vo)
constexpr uint64_t kPrime = 1099511628211ull;
const char kMagic[8] = {'G', 'B', 'L', 'T', 'E', 'S', 'T', '1'};

// FNV-1a over single bytes: the hash kind 0 files carry.
uint64_t fnvBytes(const std::vector<unsigned char>& p) {
    uint64_t h = kOffset;
    for (unsigned char b : p) h = (h ^ b) * kPrime;
    return h;
}

// The same step over little-endian 8-byte words, the tail byte by byte: hash kind 1.
uint64_t fnvWords(const std::vector<unsigned char>& p) {
    uint64_t h = kOffset;
    size_t i = 0;
    for (; i + 8 <= p.size(); i += 8) {
        uint64_t w = 0;
        for (int k = 7; k >= 0; --k) w = (w << 8) | p[i + size_t(k)];
        h = (h ^ w) * kPrime;
    }
    for (; i < p.size(); ++i) h = (h ^ p[i]) * kPrime;
    return h;
}

template <class T> void put(std::vector<unsigned char>& out, T v) {
    for (size_t k = 0; k < sizeof(T); ++k) out.push_back((unsigned char)(uint64_t(v) >> (8 * k)));
}

std::vector<unsigned char> envelope(uint32_t version, uint32_t kind, uint64_t key, uint64_t hash,
                                    const std::vector<unsigned char>& payload) {
    std::vector<unsigned char> out(kMagic, kMagic + 8);
    put(out, version);
    put(out, kind);
    put(out, key);
    put(out, uint64_t(payload.size()));
    put(out, hash);
    out.insert(out.end(), payload.begin(), payload.end());
    return out;
}

std::vector<unsigned char> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::vector<unsigned char>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

class DiskCacheTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("gbl-disk-cache-test-" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        // 1 MiB + 5 bytes: whole words and a tail; bytes that differ from their neighbours.
        payload_.resize((1u << 20) + 5);
        for (size_t i = 0; i < payload_.size(); ++i) payload_[i] = (unsigned char)((i * 2654435761u) >> 13);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
    std::vector<unsigned char> payload_;
};

TEST_F(DiskCacheTest, WritesTheWordHashAndItsKindByteForByte) {
    const fs::path file = dir_ / "a.bin";
    gbl::writeCacheEnvelope(file, kMagic, 7, 0x1234'5678'9abc'def0ull, payload_.data(), payload_.size());
    const std::vector<unsigned char> expected = envelope(7, 1, 0x1234'5678'9abc'def0ull, fnvWords(payload_), payload_);
    EXPECT_EQ(fileBytes(file), expected);
    // The two kinds are different hashes: a file could not pass as the other kind by accident.
    EXPECT_NE(fnvWords(payload_), fnvBytes(payload_));

    std::string why = "stale";
    const auto back = gbl::readCacheEnvelope(file, kMagic, 7, 0x1234'5678'9abc'def0ull, &why);
    ASSERT_TRUE(back.has_value()) << why;
    EXPECT_EQ(*back, payload_);
    EXPECT_EQ(why, "");
}

TEST_F(DiskCacheTest, AFileOfTheEarlierByteWiseKindIsAMiss) {
    const fs::path file = dir_ / "old.bin";
    writeBytes(file, envelope(3, 0, 42, fnvBytes(payload_), payload_));
    std::string why;
    EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 3, 42, &why).has_value());
    EXPECT_EQ(why, "payload hash kind 0");
}

// Fnv64 is FNV-1a 64 as published: the offset basis and prime of Fowler, Noll and Vo's reference
// (its test vectors: "" and "a"), byte-wise for text and keys.
TEST(Fnv64, MatchesThePublishedTestVectors) {
    gbl::Fnv64 empty;
    EXPECT_EQ(empty.h, 0xcbf29ce484222325ull);
    gbl::Fnv64 a;
    a.bytes("a", 1);
    EXPECT_EQ(a.h, 0xaf63dc4c8601ec8cull);
    gbl::Fnv64 foobar;
    foobar.bytes("foobar", 6);
    EXPECT_EQ(foobar.h, 0x85944171f73967e8ull);
}

TEST_F(DiskCacheTest, AWrongHashOrKindIsAMissThatSaysWhy) {
    const fs::path file = dir_ / "bad.bin";
    std::string why;
    // The byte-wise hash under kind 1 does not verify.
    writeBytes(file, envelope(3, 1, 42, fnvBytes(payload_), payload_));
    EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 3, 42, &why).has_value());
    EXPECT_EQ(why, "payload hash mismatch (corrupt)");
    // One payload byte flipped, in the tail and inside a word.
    for (size_t at : {payload_.size() - 1, size_t(4096 + 3)}) {
        std::vector<unsigned char> bytes = envelope(3, 1, 42, fnvWords(payload_), payload_);
        bytes[gbl::kCacheEnvelopeHeaderBytes + at] ^= 0x10;
        writeBytes(file, bytes);
        EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 3, 42, &why).has_value()) << at;
        EXPECT_EQ(why, "payload hash mismatch (corrupt)");
    }
    writeBytes(file, envelope(3, 2, 42, fnvWords(payload_), payload_));
    EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 3, 42, &why).has_value());
    EXPECT_EQ(why, "payload hash kind 2");
    writeBytes(file, envelope(3, 1, 42, fnvWords(payload_), payload_));
    EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 3, 43, &why).has_value());
    EXPECT_EQ(why, "key mismatch");
    EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 4, 42, &why).has_value());
    EXPECT_EQ(why, "format version 3");
    std::vector<unsigned char> cut = envelope(3, 1, 42, fnvWords(payload_), payload_);
    cut.resize(cut.size() - 1);
    writeBytes(file, cut);
    EXPECT_FALSE(gbl::readCacheEnvelope(file, kMagic, 3, 42, &why).has_value());
    EXPECT_EQ(why.rfind("size ", 0), 0u) << why;
    EXPECT_FALSE(gbl::readCacheEnvelope(dir_ / "missing.bin", kMagic, 3, 42, &why).has_value());
    EXPECT_EQ(why, "");
}

}  // namespace
