// The multi-core PNG encoder (png_writer.h), checked against independent code: stb_image decodes
// every file; the test parses the chunks itself, checks each CRC with zlib's crc32, inflates the
// IDAT data with zlib and compares it with Sub-filtered rows computed by its own loop; a one-band
// file is compared byte for byte with stb_image_write's (the encoder writePng used before).
#include <gtest/gtest.h>
#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "png_writer.h"

#include "stb_png_encoder.h"  // the old encoder (stb_image_write), the one-band oracle

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_ONLY_PNG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace gbl {
namespace {

using Bytes = std::vector<unsigned char>;

// Smooth gradients plus noise, like the error heat maps compare writes; `noise` 0 is smooth.
Image8 testImage(int width, int height, int channels, unsigned seed, int noise = 24) {
    Image8 image{width, height, channels, {}};
    image.pixels.resize(size_t(width) * size_t(height) * size_t(channels));
    std::mt19937 rng(seed);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                const int smooth = (x * (c + 1) + y * (3 - c % 3)) / 4;
                const int jitter = noise ? int(rng() % unsigned(noise)) : 0;
                image.pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)] =
                    (unsigned char)(smooth + jitter);
            }
    return image;
}

uint32_t bigEndian32(const unsigned char* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

struct Chunk {
    std::string type;
    Bytes data;
};

// Splits a PNG file into its chunks, checking the signature, every length and every CRC (CRC-32
// of type + data, W3C PNG 5.3) on the way.
std::vector<Chunk> parseChunks(const Bytes& png) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<Chunk> chunks;
    EXPECT_GE(png.size(), 8u);
    if (png.size() < 8 || std::memcmp(png.data(), kSignature, 8) != 0) {
        ADD_FAILURE() << "no PNG signature";
        return chunks;
    }
    size_t at = 8;
    while (at < png.size()) {
        if (png.size() - at < 12) {
            ADD_FAILURE() << "truncated chunk at byte " << at;
            break;
        }
        const size_t length = bigEndian32(&png[at]);
        if (png.size() - at - 12 < length) {
            ADD_FAILURE() << "chunk at byte " << at << " runs past the end";
            break;
        }
        Chunk chunk{std::string(reinterpret_cast<const char*>(&png[at + 4]), 4),
                    Bytes(png.begin() + long(at + 8), png.begin() + long(at + 8 + length))};
        const uint32_t stored = bigEndian32(&png[at + 8 + length]);
        EXPECT_EQ(stored, uint32_t(crc32(0, &png[at + 4], uInt(4 + length)))) << chunk.type << " at byte " << at;
        chunks.push_back(std::move(chunk));
        at += 12 + length;
    }
    return chunks;
}

// The test's own Sub filter (W3C PNG 9.2): each row is filter byte 1, then each byte minus the
// byte one pixel to its left (0 left of the row), mod 256.
Bytes subFiltered(const Image8& image) {
    Bytes out;
    const size_t stride = size_t(image.width) * size_t(image.channels);
    for (int y = 0; y < image.height; ++y) {
        out.push_back(1);
        const unsigned char* row = &image.pixels[size_t(y) * stride];
        for (size_t i = 0; i < stride; ++i)
            out.push_back((unsigned char)(row[i] - (i >= size_t(image.channels) ? row[i - size_t(image.channels)] : 0)));
    }
    return out;
}

Image8 decodeWithStb(const Bytes& png) {
    int width = 0, height = 0, channels = 0;
    unsigned char* data = stbi_load_from_memory(png.data(), int(png.size()), &width, &height, &channels, 0);
    EXPECT_NE(data, nullptr) << (stbi_failure_reason() ? stbi_failure_reason() : "");
    Image8 image{width, height, channels, {}};
    if (data) image.pixels.assign(data, data + size_t(width) * size_t(height) * size_t(channels));
    stbi_image_free(data);
    return image;
}

void expectSameImage(const Image8& a, const Image8& b, const std::string& what) {
    EXPECT_EQ(a.width, b.width) << what;
    EXPECT_EQ(a.height, b.height) << what;
    EXPECT_EQ(a.channels, b.channels) << what;
    EXPECT_TRUE(a.pixels == b.pixels) << what << ": pixels differ";
}

// The IDAT chunks of `png`, in order; checks IHDR against `image` and the chunk order.
std::vector<Bytes> idatChunks(const Bytes& png, const Image8& image) {
    const std::vector<Chunk> chunks = parseChunks(png);
    std::vector<Bytes> idats;
    EXPECT_GE(chunks.size(), 3u);
    if (chunks.size() < 3) return idats;
    EXPECT_EQ(chunks.front().type, "IHDR");
    EXPECT_EQ(chunks.back().type, "IEND");
    EXPECT_TRUE(chunks.back().data.empty());
    const Bytes& ihdr = chunks.front().data;
    EXPECT_EQ(ihdr.size(), 13u);
    if (ihdr.size() == 13) {
        EXPECT_EQ(bigEndian32(&ihdr[0]), uint32_t(image.width));
        EXPECT_EQ(bigEndian32(&ihdr[4]), uint32_t(image.height));
        EXPECT_EQ(ihdr[8], 8);  // bit depth
        const int colourType[5] = {-1, 0, 4, 2, 6};  // W3C PNG 11.2.2: Y, YA, RGB, RGBA
        EXPECT_EQ(ihdr[9], colourType[image.channels]);
        EXPECT_EQ(ihdr[10] | ihdr[11] | ihdr[12], 0);  // deflate, adaptive filtering, no interlace
    }
    for (size_t i = 1; i + 1 < chunks.size(); ++i) {
        EXPECT_EQ(chunks[i].type, "IDAT") << "chunk " << i;
        idats.push_back(chunks[i].data);
    }
    return idats;
}

// The IDAT data inflated by zlib (uncompress checks the header and the Adler-32 trailer too).
Bytes inflateAll(const std::vector<Bytes>& idats, size_t expectedSize) {
    Bytes stream;
    for (const Bytes& idat : idats) stream.insert(stream.end(), idat.begin(), idat.end());
    Bytes out(expectedSize + 1);  // one spare byte: more data than expected would show
    uLongf size = uLongf(out.size());
    EXPECT_EQ(uncompress(out.data(), &size, stream.data(), uLong(stream.size())), Z_OK);
    out.resize(size);
    return out;
}

TEST(PngWriter, RoundTripsThroughStbEveryChannelCountAndOddSizes) {
    const int sizes[][2] = {{1, 1}, {3, 7}, {4097, 5}, {1, 300}, {640, 600}};
    for (int channels = 1; channels <= 4; ++channels)
        for (const auto& size : sizes) {
            const Image8 image = testImage(size[0], size[1], channels, unsigned(channels * 131 + size[0]));
            const std::string what = std::to_string(size[0]) + "x" + std::to_string(size[1]) + "x" + std::to_string(channels);
            expectSameImage(decodeWithStb(encodePng(image)), image, what);
            // Every row its own band: the most seams a file can have.
            if (size[1] <= 300) expectSameImage(decodeWithStb(encodePng(image, size[1])), image, what + ", a band per row");
        }
}

// Random bytes do not compress: zlib falls back to stored blocks, the largest output a band can
// have (deflateBound's worst case, plus the flush marker every band but the last ends with).
TEST(PngWriter, IncompressibleImagesRoundTrip) {
    for (int channels : {1, 3, 4}) {
        Image8 image{701, 97, channels, {}};
        std::mt19937 rng(static_cast<unsigned>(channels));
        for (size_t i = 0; i < size_t(701 * 97 * channels); ++i) image.pixels.push_back((unsigned char)rng());
        for (int bands : {1, 3, 97}) {
            const Bytes png = encodePng(image, bands);
            const std::string what = std::to_string(channels) + " channels, " + std::to_string(bands) + " bands";
            expectSameImage(decodeWithStb(png), image, what);
            const Bytes expected = subFiltered(image);
            EXPECT_TRUE(inflateAll(idatChunks(png, image), expected.size()) == expected) << what;
        }
    }
}

TEST(PngWriter, ChunkCountFollowsTheImageSize) {
    EXPECT_EQ(pngChunkCount(testImage(1, 1, 1, 1)), 1);
    EXPECT_EQ(pngChunkCount(testImage(4097, 5, 4, 1)), 1);  // 81,945 filtered bytes
    // 3840x2160 RGB: 11,521 filtered bytes a row, 91 rows in 1 MiB (1,048,411 bytes), 2160 / 91
    // rounded up = 24 bands.
    EXPECT_EQ(pngChunkCount(Image8{3840, 2160, 3, {}}), 24);
    // 640x600 RGBA: 2,561 bytes a row, 409 rows a band: 2 bands.
    EXPECT_EQ(pngChunkCount(Image8{640, 600, 4, {}}), 2);
    // One row over 1 MiB: a band per row.
    EXPECT_EQ(pngChunkCount(Image8{300000, 3, 4, {}}), 3);
}

// The IDAT data, inflated by zlib, is the test's own Sub-filtered rows; each band is one IDAT
// that raw-inflates on its own (no back-reference crosses a seam) to whole rows; every CRC holds.
TEST(PngWriter, StreamIsTheSubFilteredRowsInIndependentBands) {
    for (int channels = 1; channels <= 4; ++channels) {
        const Image8 image = testImage(513, 61, channels, unsigned(channels));
        const Bytes expected = subFiltered(image);
        for (int bands : {1, 2, 5, 61, 1000}) {
            const std::string what = std::to_string(channels) + " channels, " + std::to_string(bands) + " bands";
            const std::vector<Bytes> idats = idatChunks(encodePng(image, bands), image);
            EXPECT_EQ(idats.size(), size_t(std::min(bands, image.height))) << what;
            EXPECT_TRUE(inflateAll(idats, expected.size()) == expected) << what;
            ASSERT_FALSE(idats.empty());
            ASSERT_GE(idats.front().size(), 2u);
            // RFC 1950: CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (FLEVEL 0, the check bits).
            EXPECT_EQ(idats.front()[0], 0x78) << what;
            EXPECT_EQ(idats.front()[1], 0x01) << what;

            // Each band alone: a raw inflater fed only that band's bytes (header and trailer
            // left out) must produce whole rows, and the bands' rows in order must be the image's.
            Bytes joined;
            const size_t rowBytes = size_t(image.width) * size_t(channels) + 1;
            for (size_t b = 0; b < idats.size(); ++b) {
                const size_t begin = b == 0 ? 2 : 0, end = idats[b].size() - (b + 1 == idats.size() ? 4 : 0);
                Bytes rows(expected.size());
                z_stream s{};
                ASSERT_EQ(inflateInit2(&s, -15), Z_OK);
                s.next_in = const_cast<Bytef*>(idats[b].data() + begin);
                s.avail_in = uInt(end - begin);
                s.next_out = rows.data();
                s.avail_out = uInt(rows.size());
                const int rc = inflate(&s, Z_SYNC_FLUSH);
                EXPECT_EQ(rc, b + 1 == idats.size() ? Z_STREAM_END : Z_OK) << what << ", band " << b;
                EXPECT_EQ(s.avail_in, 0u) << what << ", band " << b;
                rows.resize(rows.size() - s.avail_out);
                inflateEnd(&s);
                EXPECT_EQ(rows.size() % rowBytes, 0u) << what << ", band " << b;
                EXPECT_FALSE(rows.empty()) << what << ", band " << b;
                joined.insert(joined.end(), rows.begin(), rows.end());
            }
            EXPECT_TRUE(joined == expected) << what;
        }
    }
}

// One band: the file stb_image_write wrote (Sub forced, compress2 level 1), byte for byte. More
// bands: other bytes, the same pixels, and a size within 1% of the one-band file.
TEST(PngWriter, OneBandIsTheOldEncoderByteForByteAndBandsKeepThePixels) {
    for (int channels = 1; channels <= 4; ++channels) {
        const Image8 image = testImage(700, 410, channels, unsigned(100 + channels));
        const Bytes old = test::stbPngSubLevel1(image);
        ASSERT_FALSE(old.empty());
        const Bytes one = encodePng(image, 1);
        EXPECT_TRUE(one == old) << channels << " channels: " << one.size() << " vs " << old.size() << " bytes";
        const Bytes several = encodePng(image, 7);
        EXPECT_FALSE(several == one);
        expectSameImage(decodeWithStb(several), decodeWithStb(one), std::to_string(channels) + " channels, 7 bands");
        EXPECT_LE(double(several.size()), 1.01 * double(one.size())) << channels << " channels";
    }
}

// A band's data split over several IDAT chunks (at 2^31 - 1 bytes in real files; here small
// limits, so that the header, a band's data and the trailer fall across chunk boundaries).
TEST(PngWriter, BandsSplitOverSeveralIdatChunks) {
    const Image8 image = testImage(301, 40, 3, 5);
    const Bytes expected = subFiltered(image);
    for (size_t limit : {1, 2, 3, 5, 1000}) {
        for (int bands : {1, 4}) {
            const std::string what = "limit " + std::to_string(limit) + ", " + std::to_string(bands) + " bands";
            const Bytes png = encodePng(image, bands, limit);
            const std::vector<Bytes> idats = idatChunks(png, image);
            size_t total = 0;
            for (const Bytes& idat : idats) {
                EXPECT_LE(idat.size(), limit) << what;
                EXPECT_GE(idat.size(), 1u) << what;
                total += idat.size();
            }
            EXPECT_GT(idats.size(), size_t(bands)) << what;
            // Same stream as with unlimited chunks: only the framing differs.
            EXPECT_EQ(total + 12 * idats.size() + 45, png.size()) << what;  // + signature, IHDR, IEND
            EXPECT_EQ(png.size() - 12 * idats.size(), encodePng(image, bands).size() - 12 * size_t(bands)) << what;
            EXPECT_TRUE(inflateAll(idats, expected.size()) == expected) << what;
            expectSameImage(decodeWithStb(png), image, what);
        }
    }
    EXPECT_THROW(encodePng(image, 1, 0), std::invalid_argument);
    EXPECT_THROW(encodePng(image, 1, size_t(1) << 31), std::invalid_argument);
}

// An RGB image of exactly `colours` distinct colours (a 6x6x6 cube and greys, then noise
// positions), in a pattern that has long runs and short ones.
Image8 fewColourImage(int width, int height, int colours, unsigned seed) {
    std::vector<std::array<unsigned char, 3>> table;
    for (int i = 0; i < colours; ++i)
        table.push_back({(unsigned char)(i * 37 % 256), (unsigned char)(i * 101 % 251), (unsigned char)(i % 7 * 40)});
    Image8 image{width, height, 3, Bytes(size_t(width) * size_t(height) * 3)};
    std::mt19937 rng(seed);
    for (size_t i = 0; i < image.pixels.size() / 3; ++i) {
        // Every colour at least once (the first `colours` pixels), then runs of a random colour.
        const size_t c = i < size_t(colours) ? i : (rng() % 4 == 0 ? rng() % unsigned(colours) : (i / 17) % size_t(colours));
        std::memcpy(&image.pixels[i * 3], table[c].data(), 3);
    }
    return image;
}

// Indexed: at most 256 colours become a palette in order of first appearance and 1-byte indices;
// the file is IHDR (colour type 3), PLTE, IDATs whose rows are filter byte 0 then the indices
// (inflated by zlib, compared with the test's own rows) and stb decodes it to the RGB pixels.
TEST(PngWriter, IndexedFilesKeepThePixelsOfImagesWithFewColours) {
    for (int colours : {1, 2, 255, 256}) {
        const Image8 image = fewColourImage(301, 77, colours, unsigned(colours));
        Image8 indices;
        Bytes palette;
        ASSERT_TRUE(indexColours(image, indices, palette)) << colours;
        ASSERT_EQ(palette.size(), size_t(colours) * 3);
        ASSERT_EQ(indices.channels, 1);
        for (size_t i = 0; i < image.pixels.size() / 3; ++i)
            ASSERT_EQ(0, std::memcmp(&palette[size_t(indices.pixels[i]) * 3], &image.pixels[i * 3], 3)) << i;
        for (int bands : {1, 3, 77}) {
            const std::string what = std::to_string(colours) + " colours, " + std::to_string(bands) + " bands";
            const Bytes png = encodePngIndexed(indices, palette, bands);
            const std::vector<Chunk> chunks = parseChunks(png);
            ASSERT_GE(chunks.size(), 4u) << what;
            EXPECT_EQ(chunks[0].type, "IHDR");
            EXPECT_EQ(chunks[0].data[9], 3) << what;  // W3C PNG 11.2.2: indexed-colour
            EXPECT_EQ(chunks[1].type, "PLTE");
            EXPECT_TRUE(chunks[1].data == palette) << what;
            std::vector<Bytes> idats;
            for (size_t i = 2; i + 1 < chunks.size(); ++i) idats.push_back(chunks[i].data);
            EXPECT_EQ(idats.size(), size_t(bands)) << what;
            // RFC 1950: FLG 0x9c is FLEVEL 2 (zlib's default level 6) with its check bits.
            EXPECT_EQ(idats.front()[0], 0x78);
            EXPECT_EQ(idats.front()[1], 0x9c);
            Bytes rows;
            for (int y = 0; y < image.height; ++y) {
                rows.push_back(0);
                rows.insert(rows.end(), indices.pixels.begin() + long(y) * image.width,
                            indices.pixels.begin() + long(y + 1) * image.width);
            }
            EXPECT_TRUE(inflateAll(idats, rows.size()) == rows) << what;
            expectSameImage(decodeWithStb(png), image, what);
        }
    }
}

TEST(PngWriter, MoreThan256ColoursAreNotIndexed) {
    const Image8 image = fewColourImage(64, 64, 257, 5);
    Image8 indices{1, 1, 1, Bytes{7}};
    Bytes palette{1, 2, 3};
    EXPECT_FALSE(indexColours(image, indices, palette));
    EXPECT_EQ(indices.pixels, Bytes{7});  // untouched
    EXPECT_EQ(palette, (Bytes{1, 2, 3}));
    EXPECT_FALSE(indexColours(Image8{2, 2, 4, Bytes(16)}, indices, palette));  // RGBA: not indexed
    // The colour-mapped path falls back to RGB rows with filter byte 0 (None), pixels kept; with
    // 256 colours it is the indexed file.
    const Bytes rgb = encodePngColourMapped(image, 2);
    const std::vector<Chunk> chunks = parseChunks(rgb);
    ASSERT_GE(chunks.size(), 3u);
    EXPECT_EQ(chunks[0].data[9], 2);  // RGB
    std::vector<Bytes> idats;
    for (size_t i = 1; i + 1 < chunks.size(); ++i) idats.push_back(chunks[i].data);
    Bytes rows;
    for (int y = 0; y < image.height; ++y) {
        rows.push_back(0);
        rows.insert(rows.end(), image.pixels.begin() + long(y) * image.width * 3,
                    image.pixels.begin() + long(y + 1) * image.width * 3);
    }
    EXPECT_TRUE(inflateAll(idats, rows.size()) == rows);
    expectSameImage(decodeWithStb(rgb), image, "257 colours");
    const Image8 few = fewColourImage(64, 64, 256, 5);
    ASSERT_TRUE(indexColours(few, indices, palette));
    EXPECT_TRUE(encodePngColourMapped(few, 3) == encodePngIndexed(indices, palette, 3));
    // Bad calls of the encoder: an index past the palette, a palette not of whole triples.
    EXPECT_THROW(encodePngIndexed(Image8{2, 1, 1, Bytes{0, 1}}, Bytes{9, 9, 9}), std::invalid_argument);
    EXPECT_THROW(encodePngIndexed(Image8{2, 1, 1, Bytes{0, 0}}, Bytes{9, 9}), std::invalid_argument);
    EXPECT_THROW(encodePngIndexed(Image8{2, 1, 1, Bytes{0, 0}}, Bytes(257 * 3)), std::invalid_argument);
}

TEST(PngWriter, RejectsAnInconsistentImage) {
    EXPECT_THROW(encodePng(Image8{4, 4, 3, {}}), std::invalid_argument);
    EXPECT_THROW(encodePng(Image8{0, 4, 3, {}}), std::invalid_argument);
    EXPECT_THROW(encodePng(Image8{1, 1, 5, Bytes(5)}), std::invalid_argument);
    EXPECT_THROW(encodePng(Image8{2, 2, 1, Bytes(5)}), std::invalid_argument);
}

}  // namespace
}  // namespace gbl
