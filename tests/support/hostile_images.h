#pragma once
// Image files made in the test, never committed: valid files of any size that cost little disk
// (a black PNG deflates 2.4 MB of rows into about 60 bytes a row), and headers that claim more
// than their files hold. For the tests of memory bounds and readers.
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gbl::test {

inline void appendBigEndian(std::string& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out += char((v >> s) & 0xFF);
}

inline void appendPngChunk(std::string& out, const char* type, const std::string& data) {
    appendBigEndian(out, uint32_t(data.size()));
    const std::string typed = std::string(type, 4) + data;
    out += typed;
    appendBigEndian(out, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(typed.data()), uInt(typed.size()))));
}

// A valid 8-bit RGB PNG, every pixel black, of any size. Each row (filter byte and zeros) is
// deflated with a full flush, which resets the compressor: every row's bytes are the same, so
// one row is compressed and repeated; the stream ends with an empty final stored block and the
// Adler-32 of the zeros (a = 1, b = the byte count mod 65521).
inline std::string blackPng(uint32_t width, uint32_t height) {
    const std::vector<unsigned char> row(size_t(width) * 3 + 1, 0);
    z_stream z{};
    if (deflateInit(&z, 9) != Z_OK) throw std::runtime_error("deflateInit");
    std::vector<unsigned char> buf(row.size() + 1024);
    auto compressRow = [&] {
        z.next_in = const_cast<Bytef*>(row.data());
        z.avail_in = uInt(row.size());
        z.next_out = buf.data();
        z.avail_out = uInt(buf.size());
        if (deflate(&z, Z_FULL_FLUSH) != Z_OK || z.avail_in != 0) throw std::runtime_error("deflate");
        return std::string(reinterpret_cast<char*>(buf.data()), buf.size() - z.avail_out);
    };
    const std::string first = compressRow();  // with the 2-byte zlib header
    const std::string again = compressRow();
    deflateEnd(&z);
    if (first.size() != again.size() + 2 || first.compare(2, std::string::npos, again) != 0)
        throw std::runtime_error("blackPng: rows did not deflate alike");
    std::string idat = first.substr(0, 2);
    idat.reserve(2 + size_t(height) * again.size() + 9);
    for (uint32_t y = 0; y < height; ++y) idat += again;
    idat += std::string("\x01\x00\x00\xff\xff", 5);  // final, stored, empty
    const uint64_t bytes = uint64_t(row.size()) * height;
    appendBigEndian(idat, uint32_t((bytes % 65521) << 16 | 1));

    std::string png = "\x89PNG\r\n\x1a\n";
    std::string ihdr;
    appendBigEndian(ihdr, width);
    appendBigEndian(ihdr, height);
    ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter method, no interlace
    appendPngChunk(png, "IHDR", ihdr);
    for (size_t at = 0; at < idat.size(); at += 1 << 20) appendPngChunk(png, "IDAT", idat.substr(at, 1 << 20));
    appendPngChunk(png, "IEND", "");
    return png;
}

// The start of a baseline JPEG whose frame header claims width x height, one channel: enough
// for a reader that trusts the header to allocate the frame.
inline std::string jpegHeaderClaiming(uint16_t width, uint16_t height) {
    std::string j = "\xff\xd8\xff\xc0";
    j += std::string("\x00\x0b\x08", 3);
    j += char(height >> 8);
    j += char(height & 0xff);
    j += char(width >> 8);
    j += char(width & 0xff);
    j += std::string("\x01\x01\x11\x00", 4);
    j += std::string(64, '\0');
    return j;
}

// Rewrites an OpenEXR file's data window to claim `height` rows (its pixel data unchanged).
inline void claimExrHeight(const std::string& path, int height) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string key = std::string("dataWindow\0box2i\0", 17);
    const size_t at = bytes.find(key);
    if (at == std::string::npos) throw std::runtime_error("claimExrHeight: no dataWindow");
    const size_t box = at + key.size() + 4;  // after the attribute's size
    int32_t minY = 0;
    std::memcpy(&minY, bytes.data() + box + 4, 4);
    const int32_t maxY = minY + height - 1;
    std::memcpy(bytes.data() + box + 12, &maxY, 4);  // little-endian, as OpenEXR stores it
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

inline void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace gbl::test
