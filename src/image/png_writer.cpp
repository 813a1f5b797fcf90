// A PNG encoder that deflates one image on several cores.
//
// File layout, after the PNG specification (W3C PNG, 2nd edition = ISO/IEC 15948:2004): the
// 8-byte signature, IHDR, the IDAT chunks, IEND (section 5); each chunk is a 4-byte big-endian
// data length, the 4-byte type, the data and the CRC-32 of type + data (5.3; the CRC of ISO 3309
// / ITU-T V.42, which zlib's crc32 computes). The concatenated IDAT data is one zlib stream
// (section 10, RFC 1950) of the filtered rows: each row is its filter-type byte then the row's
// bytes filtered (section 9). Any split of that stream into IDAT chunks is valid (12.11).
//
// Why several pieces make one stream: a zlib stream (RFC 1950) is a 2-byte header, raw deflate
// data (RFC 1951) and the Adler-32 of the uncompressed data. Deflate data is a sequence of
// blocks, the last one marked BFINAL. Each band of rows is compressed by its own raw-deflate
// stream (deflateInit2 with negative window bits: no header, no checksum). Every band but the
// last ends with Z_FULL_FLUSH: zlib closes the block and appends an empty stored block, which
// ends on a byte boundary (RFC 1951 3.2.4), and since the band's compressor never saw the next
// band's data, no back-reference (<= 32 KiB back, 3.2.5) crosses the seam. The last band ends
// with Z_FINISH (BFINAL). Header + pieces + the Adler-32 of all the filtered data (combined from
// the bands' own with adler32_combine) is therefore a valid zlib stream. This is how pigz
// compresses a file on several cores (its independent-block mode).
#include "png_writer.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "parallel_invoke.h"

namespace gbl {
namespace {

// Sub (filter type 1) on every row, as stb_image_write did with its filter forced: on the
// error heat maps and tone-mapped renders compare writes it was the best size/speed trade
// (measured when the stb path was tuned, image_io.cpp's history).
constexpr unsigned char kFilterSub = 1;
// None (filter type 0) for indexed images: their bytes are palette indices, whose differences
// mean nothing; the PNG specification recommends None for colour type 3 (12.8).
constexpr unsigned char kFilterNone = 0;
// IHDR colour type by channel count (11.2.2): Y, YA, RGB, RGBA.
constexpr unsigned char kColourTypeByChannels[5] = {0, 0, 4, 2, 6};
// PNG chunk data is at most 2^31 - 1 bytes (5.3).
constexpr size_t kMaxChunkData = size_t(0x7fffffff);
// zlib's counts are uInt: feed and drain at most this much per call.
constexpr size_t kMaxZlibStep = size_t(1) << 30;

void putBigEndian32(unsigned char* out, uint32_t v) {
    out[0] = (unsigned char)(v >> 24);
    out[1] = (unsigned char)(v >> 16);
    out[2] = (unsigned char)(v >> 8);
    out[3] = (unsigned char)v;
}

// Writes one PNG chunk at `out`: length, type, data, CRC-32 of type + data; returns its end.
unsigned char* putChunk(unsigned char* out, const char* type, const unsigned char* data, size_t size) {
    putBigEndian32(out, uint32_t(size));
    std::memcpy(out + 4, type, 4);
    if (size) std::memcpy(out + 8, data, size);
    putBigEndian32(out + 8 + size, uint32_t(crc32_z(0, out + 4, 4 + size)));
    return out + 12 + size;
}

// What encodeRows writes: `height` rows of `width` pixels of `bpp` bytes each, as PNG colour type
// `colourType` (with its PLTE when indexed), filtered by `filter` (Sub or None) and deflated at
// `level`.
struct RowSource {
    const unsigned char* pixels = nullptr;
    int width = 0, height = 0, bpp = 0;
    unsigned char colourType = 0;
    unsigned char filter = kFilterSub;
    int level = 1;
    const std::vector<unsigned char>* palette = nullptr;  // RGB triples, colour type 3 only
};

// Rows [firstRow, endRow) filtered into `out` (filter byte + row bytes per row). Sub(x) =
// Raw(x) - Raw(x - bpp) mod 256, Raw of a byte left of the row's start being 0; None copies (9.2).
void filterRows(const RowSource& src, int64_t firstRow, int64_t endRow, unsigned char* out) {
    const size_t bpp = size_t(src.bpp), rowBytes = size_t(src.width) * bpp;
    for (int64_t y = firstRow; y < endRow; ++y) {
        const unsigned char* __restrict in = src.pixels + size_t(y) * rowBytes;
        unsigned char* __restrict o = out + size_t(y - firstRow) * (rowBytes + 1);
        *o++ = src.filter;
        if (src.filter == kFilterNone) {
            std::memcpy(o, in, rowBytes);
            continue;
        }
        for (size_t i = 0; i < bpp; ++i) o[i] = in[i];
        for (size_t i = bpp; i < rowBytes; ++i) o[i] = (unsigned char)(in[i] - in[i - bpp]);
    }
}

// A band of rows filtered and raw-deflated: its piece of the zlib stream.
struct Band {
    int64_t firstRow = 0, endRow = 0;
    std::vector<unsigned char> deflated;
    uLong adler = 0;       // Adler-32 of the band's filtered bytes alone
    size_t filtered = 0;   // how many filtered bytes
};

[[noreturn]] void zlibFailed(const char* what, int code, const z_stream& stream) {
    throw std::runtime_error(std::string("PNG encoder: zlib ") + what + " failed (" + std::to_string(code) +
                             (stream.msg ? std::string(", ") + stream.msg : std::string()) + ")");
}

// `level` (1 for RGB: the parameters compress2(..., 1) uses, so a one-band image is deflated to
// the very bytes the old stb + compress2 path wrote), 32 KiB window, memLevel 8, default strategy.
void deflateBand(Band& band, const unsigned char* data, size_t size, bool last, int level) {
    z_stream stream{};
    int rc = deflateInit2(&stream, level, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
    if (rc != Z_OK) zlibFailed("deflateInit2", rc, stream);
    struct End {
        z_stream* s;
        ~End() { deflateEnd(s); }
    } end{&stream};
    // deflateBound holds a Z_FINISH-only stream; a full flush adds an empty stored block (<= 6
    // bytes); the loop below grows the buffer if that is ever not enough.
    std::vector<unsigned char>& out = band.deflated;
    out.resize(size_t(deflateBound(&stream, uLong(std::min(size, size_t(ULONG_MAX))))) + 64);
    size_t produced = 0, consumed = 0;
    const int finalFlush = last ? Z_FINISH : Z_FULL_FLUSH;
    for (;;) {
        const size_t feed = std::min(size - consumed, kMaxZlibStep);
        stream.next_in = const_cast<Bytef*>(data + consumed);  // zlib's API is not const-correct
        stream.avail_in = uInt(feed);
        if (out.size() - produced < 64) out.resize(out.size() + out.size() / 2 + 64);
        const size_t room = std::min(out.size() - produced, kMaxZlibStep);
        stream.next_out = out.data() + produced;
        stream.avail_out = uInt(room);
        const int flush = consumed + feed == size ? finalFlush : Z_NO_FLUSH;
        rc = deflate(&stream, flush);
        if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR) zlibFailed("deflate", rc, stream);
        consumed += feed - stream.avail_in;
        produced += room - stream.avail_out;
        if (rc == Z_STREAM_END) break;
        // A flush is complete when deflate returns with output room to spare (zlib.h, deflate).
        if (flush == Z_FULL_FLUSH && stream.avail_in == 0 && stream.avail_out != 0) break;
    }
    out.resize(produced);
}

}  // namespace

int pngChunkCount(const Image8& image) {
    const int64_t rowBytes = int64_t(image.width) * image.channels + 1;
    if (image.height <= 0 || rowBytes <= 1) return 1;
    const int64_t rowsPerChunk = std::max<int64_t>(1, kPngChunkBytes / rowBytes);
    return int(std::min<int64_t>(image.height, (image.height + rowsPerChunk - 1) / rowsPerChunk));
}

namespace {

std::vector<unsigned char> encodeRows(const RowSource& src, int chunks, size_t maxIdatBytes) {
    const size_t rowBytes = size_t(src.width) * size_t(src.bpp) + 1;
    const int count = std::clamp(chunks, 1, src.height);

    // Filter and deflate every band, side by side; a band's filtered rows live only while it is
    // deflated (1 MiB per thread at the default chunk size).
    std::vector<Band> bands(static_cast<size_t>(count));
    std::vector<std::function<void()>> tasks;
    tasks.reserve(bands.size());
    for (int b = 0; b < count; ++b) {
        Band& band = bands[size_t(b)];
        band.firstRow = int64_t(src.height) * b / count;
        band.endRow = int64_t(src.height) * (b + 1) / count;
        tasks.emplace_back([&src, &band, rowBytes, last = b == count - 1] {
            band.filtered = size_t(band.endRow - band.firstRow) * rowBytes;
            const std::unique_ptr<unsigned char[]> filtered(new unsigned char[band.filtered]);  // every byte written
            filterRows(src, band.firstRow, band.endRow, filtered.get());
            band.adler = adler32_z(adler32_z(0, nullptr, 0), filtered.get(), band.filtered);
            deflateBand(band, filtered.get(), band.filtered, last, src.level);
        });
    }
    parallelInvoke(tasks);

    // The zlib header (RFC 1950 2.2): CMF 0x78 = deflate with a 32 KiB window; FLG = FLEVEL
    // (what zlib writes: 0 "fastest" for level 1, 2 "default" for 6) and FCHECK making
    // CMF*256 + FLG a multiple of 31: 0x7801 = 31 * 991, 0x789c = 31 * 996. The trailer:
    // Adler-32 of all the filtered data.
    uLong adler = bands[0].adler;
    for (size_t b = 1; b < bands.size(); ++b)
        adler = adler32_combine(adler, bands[b].adler, z_off_t(bands[b].filtered));
    const unsigned char zlibHeader[2] = {0x78, (unsigned char)(src.level < 2 ? 0x01 : src.level < 6 ? 0x5e : src.level == 6 ? 0x9c : 0xda)};
    unsigned char zlibTrailer[4];
    putBigEndian32(zlibTrailer, uint32_t(adler));

    // Where each band's IDAT chunk(s) go: band 0's data starts with the header, the last band's
    // ends with the trailer; a band's data over maxIdatBytes is split into several chunks.
    const auto payload = [&](size_t b) {
        return bands[b].deflated.size() + (b == 0 ? 2 : 0) + (b + 1 == bands.size() ? 4 : 0);
    };
    const auto idatCount = [maxIdatBytes](size_t bytes) {
        return std::max<size_t>(1, (bytes + maxIdatBytes - 1) / maxIdatBytes);
    };

    // Signature and IHDR (33 bytes), PLTE when indexed, the bands' IDAT chunks, IEND (12 bytes):
    // sized once.
    const size_t plteBytes = src.palette ? 12 + src.palette->size() : 0;
    std::vector<size_t> offsets(bands.size());
    size_t size = 33 + plteBytes;
    for (size_t b = 0; b < bands.size(); ++b) {
        offsets[b] = size;
        size += payload(b) + 12 * idatCount(payload(b));
    }
    std::vector<unsigned char> png(size + 12);
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::memcpy(png.data(), kSignature, 8);
    // IHDR (11.2.2): width, height, bit depth 8, colour type, compression 0, filter 0, no interlace.
    unsigned char ihdr[13];
    putBigEndian32(ihdr, uint32_t(src.width));
    putBigEndian32(ihdr + 4, uint32_t(src.height));
    ihdr[8] = 8;
    ihdr[9] = src.colourType;
    ihdr[10] = ihdr[11] = ihdr[12] = 0;
    putChunk(png.data() + 8, "IHDR", ihdr, sizeof ihdr);
    // PLTE (11.2.3) follows IHDR and precedes the first IDAT.
    if (src.palette) putChunk(png.data() + 33, "PLTE", src.palette->data(), src.palette->size());
    putChunk(png.data() + size, "IEND", nullptr, 0);

    // Copy each band into its IDAT chunk(s) and checksum them, side by side.
    tasks.clear();
    for (size_t b = 0; b < bands.size(); ++b) {
        tasks.emplace_back([&, b] {
            // The band's payload is [zlib header] deflated [zlib trailer], as up to three spans.
            struct Span {
                const unsigned char* data;
                size_t size;
            };
            std::vector<Span> spans;
            if (b == 0) spans.push_back({zlibHeader, 2});
            spans.push_back({bands[b].deflated.data(), bands[b].deflated.size()});
            if (b + 1 == bands.size()) spans.push_back({zlibTrailer, 4});
            size_t span = 0, used = 0;  // the next byte to copy: spans[span].data[used]
            unsigned char* out = png.data() + offsets[b];
            for (size_t left = payload(b), i = 0; i < idatCount(payload(b)); ++i) {
                const size_t n = std::min(left, maxIdatBytes);
                putBigEndian32(out, uint32_t(n));
                std::memcpy(out + 4, "IDAT", 4);
                for (size_t copied = 0; copied < n;) {
                    const size_t run = std::min(spans[span].size - used, n - copied);
                    if (run) std::memcpy(out + 8 + copied, spans[span].data + used, run);
                    copied += run;
                    used += run;
                    if (used == spans[span].size) ++span, used = 0;
                }
                putBigEndian32(out + 8 + n, uint32_t(crc32_z(0, out + 4, 4 + n)));
                out += 12 + n;
                left -= n;
            }
        });
    }
    parallelInvoke(tasks);
    return png;
}

}  // namespace

std::vector<unsigned char> encodePng(const Image8& image, int chunks, size_t maxIdatBytes) {
    if (maxIdatBytes == 0 || maxIdatBytes > kMaxChunkData)
        throw std::invalid_argument("encodePng: IDAT chunk limit " + std::to_string(maxIdatBytes) +
                                    " is outside [1, 2^31 - 1]");
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw std::invalid_argument("encodePng: inconsistent image (" + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + "x" + std::to_string(image.channels) + ", " +
                                    std::to_string(image.pixels.size()) + " bytes)");
    RowSource src;
    src.pixels = image.pixels.data();
    src.width = image.width;
    src.height = image.height;
    src.bpp = image.channels;
    src.colourType = kColourTypeByChannels[image.channels];
    return encodeRows(src, chunks > 0 ? chunks : pngChunkCount(image), maxIdatBytes);
}

bool indexColours(const Image8& rgb, Image8& indices, std::vector<unsigned char>& palette) {
    if (rgb.channels != 3 || rgb.width <= 0 || rgb.height <= 0 ||
        rgb.pixels.size() != size_t(rgb.width) * size_t(rgb.height) * 3)
        return false;
    // Open addressing on the 24-bit colour, 1024 slots for at most 256 colours (load <= 1/4).
    constexpr uint32_t kEmpty = 0xffffffffu;
    uint32_t keys[1024];
    unsigned char slotIndex[1024];
    std::fill(std::begin(keys), std::end(keys), kEmpty);
    std::vector<unsigned char> out(size_t(rgb.width) * size_t(rgb.height));
    std::vector<unsigned char> table;
    uint32_t lastKey = kEmpty;
    unsigned char lastIndex = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        const unsigned char* p = &rgb.pixels[i * 3];
        const uint32_t key = uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2];
        if (key != lastKey) {
            uint32_t slot = (key * 2654435761u) >> 22;  // Knuth's multiplicative hash, top 10 bits
            while (keys[slot] != kEmpty && keys[slot] != key) slot = (slot + 1) & 1023u;
            if (keys[slot] == kEmpty) {
                if (table.size() == 256 * 3) return false;
                keys[slot] = key;
                slotIndex[slot] = (unsigned char)(table.size() / 3);
                table.insert(table.end(), p, p + 3);
            }
            lastKey = key;
            lastIndex = slotIndex[slot];
        }
        out[i] = lastIndex;
    }
    indices = Image8{rgb.width, rgb.height, 1, std::move(out)};
    palette = std::move(table);
    return true;
}

std::vector<unsigned char> encodePngIndexed(const Image8& indices, const std::vector<unsigned char>& palette,
                                            int chunks, size_t maxIdatBytes) {
    if (maxIdatBytes == 0 || maxIdatBytes > kMaxChunkData)
        throw std::invalid_argument("encodePngIndexed: IDAT chunk limit " + std::to_string(maxIdatBytes) +
                                    " is outside [1, 2^31 - 1]");
    if (indices.width <= 0 || indices.height <= 0 || indices.channels != 1 ||
        indices.pixels.size() != size_t(indices.width) * size_t(indices.height))
        throw std::invalid_argument("encodePngIndexed: the indices are not a consistent 1-channel image");
    const size_t entries = palette.size() / 3;
    if (palette.empty() || palette.size() % 3 != 0 || entries > 256)
        throw std::invalid_argument("encodePngIndexed: a palette of " + std::to_string(palette.size()) +
                                    " bytes is not 1 to 256 RGB triples");
    for (unsigned char i : indices.pixels)
        if (i >= entries)
            throw std::invalid_argument("encodePngIndexed: index " + std::to_string(i) + " is beyond the palette's " +
                                        std::to_string(entries) + " entries");
    RowSource src;
    src.pixels = indices.pixels.data();
    src.width = indices.width;
    src.height = indices.height;
    src.bpp = 1;
    src.colourType = 3;
    src.filter = kFilterNone;
    src.level = kPngIndexedLevel;
    src.palette = &palette;
    return encodeRows(src, chunks > 0 ? chunks : pngChunkCount(indices), maxIdatBytes);
}

std::vector<unsigned char> encodePngColourMapped(const Image8& image, int chunks) {
    Image8 indices;
    std::vector<unsigned char> palette;
    if (indexColours(image, indices, palette)) return encodePngIndexed(indices, palette, chunks);
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw std::invalid_argument("encodePngColourMapped: inconsistent image (" + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + "x" + std::to_string(image.channels) + ", " +
                                    std::to_string(image.pixels.size()) + " bytes)");
    RowSource src;
    src.pixels = image.pixels.data();
    src.width = image.width;
    src.height = image.height;
    src.bpp = image.channels;
    src.colourType = kColourTypeByChannels[image.channels];
    src.filter = kFilterNone;
    src.level = kPngIndexedLevel;
    return encodeRows(src, chunks > 0 ? chunks : pngChunkCount(image), kPngMaxIdatBytes);
}

}  // namespace gbl
