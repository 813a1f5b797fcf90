// Portable FloatMap read and write (pfm_io.h). The header is parsed from a bounded prefix and held
// against the file's size and the memory budget before anything sized by it is allocated: a
// header claiming 1048576 x 1048576 pixels, or a truncated raster, costs one line, not the memory.
#include "pfm_io.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "error.h"
#include "file_io.h"
#include "memory_budget.h"

namespace gbl {
namespace {

// A header is "Pf 1048576 1048576 -1.000000e+00\n" at most, plus some generous white space.
constexpr size_t kHeaderPrefix = 256;

bool isSpace(unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

std::string shown(const unsigned char* b, size_t n) {
    return escapeText(std::string_view(reinterpret_cast<const char*>(b), n));
}

struct Cursor {
    const std::string& path;
    const unsigned char* bytes;
    size_t size;
    size_t pos = 0;

    [[noreturn]] void fail(const std::string& place, const std::string& problem, const std::string& fix) const {
        throwUserError(escapeText(path) + ": PFM header, " + place + ": " + problem + "; " + fix);
    }
    void skipSpace(const char* before) {
        const size_t start = pos;
        while (pos < size && isSpace(bytes[pos])) ++pos;
        if (pos == start)
            fail(before, pos < size ? "no white space before it (byte " + std::to_string(pos) + ")"
                                    : "the file ends before it",
                 "write the header as 'PF', width, height and scale separated by white space");
    }
    std::string token() {
        const size_t start = pos;
        while (pos < size && !isSpace(bytes[pos]) && pos - start < 40) ++pos;
        return std::string(reinterpret_cast<const char*>(bytes + start), pos - start);
    }
    int dimension(const char* name) {
        skipSpace(name);
        const std::string t = token();
        if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos)
            fail(name, "'" + escapeText(t) + "' is not a whole number", "give the image's " + std::string(name) + " in pixels");
        if (t.size() > 7 || std::stoll(t) < 1 || std::stoll(t) > kPfmMaxSide)
            fail(name, escapeText(t) + " is outside 1.." + std::to_string(kPfmMaxSide),
                 "give the image's real " + std::string(name) + " (a damaged header?)");
        return int(std::stoll(t));
    }
};

}  // namespace

PfmHeader parsePfmHeader(const std::string& path, const unsigned char* bytes, size_t size, size_t fileSize) {
    Cursor c{path, bytes, std::min(size, kHeaderPrefix)};
    if (c.size < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f'))
        throwUserError(escapeText(path) + ": not a PFM file (it starts '" + shown(bytes, std::min<size_t>(size, 2)) +
                       "', not 'PF' or 'Pf'); give a Portable FloatMap, or the file's real extension");
    PfmHeader h;
    h.channels = bytes[1] == 'F' ? 3 : 1;
    c.pos = 2;
    h.width = c.dimension("width");
    h.height = c.dimension("height");
    c.skipSpace("scale");
    const std::string t = c.token();
    char* end = nullptr;
    const double scale = t.empty() ? 0.0 : std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(scale) || scale == 0.0)
        c.fail("scale", "'" + escapeText(t) + "' is not a finite non-zero number",
               "give -1.0 (little-endian) or 1.0 (big-endian)");
    h.littleEndian = scale < 0.0;
    if (c.pos >= c.size || !isSpace(bytes[c.pos]))
        c.fail("scale", c.pos >= c.size ? "the header does not end within its first " + std::to_string(kHeaderPrefix) + " bytes"
                                        : "no white-space character after it",
               "end the header with one newline after the scale");
    h.dataOffset = c.pos + 1;
    const uint64_t need = uint64_t(h.width) * uint64_t(h.height) * uint64_t(h.channels) * 4u;
    const uint64_t have = fileSize >= h.dataOffset ? uint64_t(fileSize - h.dataOffset) : 0;
    const std::string dims = std::to_string(h.width) + "x" + std::to_string(h.height) + "x" + std::to_string(h.channels);
    if (have < need)
        throwUserError(escapeText(path) + ": truncated PFM: its header's " + dims + " floats need " + std::to_string(need) +
                       " bytes after the header (byte " + std::to_string(h.dataOffset) + "), the file has " +
                       std::to_string(have) + "; write the file again, whole");
    if (have > need)
        throwUserError(escapeText(path) + ": PFM with " + std::to_string(have - need) + " bytes after its " + dims +
                       " floats (from byte " + std::to_string(h.dataOffset + need) +
                       "); the header's dimensions do not match the data: write the file again");
    return h;
}

PfmHeader probePfm(const std::string& path) {
    requireRegularFile(path);
    const uintmax_t fileSize = std::filesystem::file_size(path);
    std::ifstream in(path, std::ios::binary);
    unsigned char prefix[kHeaderPrefix];
    in.read(reinterpret_cast<char*>(prefix), sizeof prefix);
    if (in.bad()) throwUserError(escapeText(path) + ": cannot be read; check the file");
    return parsePfmHeader(path, prefix, size_t(in.gcount()), size_t(fileSize));
}

Image readPfm(const std::string& path) {
    const PfmHeader h = probePfm(path);
    const double raster = double(h.width) * double(h.height) * double(h.channels) * 4.0;
    // The file's bytes and the image, both the raster's size, live at once.
    requireMemory(2.0 * raster, escapeText(path) + ": reading its " + std::to_string(h.width) + "x" +
                                    std::to_string(h.height) + " PFM",
                  "give a smaller image (crop or scale it), or raise GBL_MEMORY_BUDGET on a machine with more memory");
    const auto bytes = readBinaryFile(path);
    const PfmHeader again = parsePfmHeader(path, bytes.data(), bytes.size(), bytes.size());  // the file may have changed
    Image image(again.width, again.height, again.channels);
    const size_t rowFloats = size_t(image.width) * size_t(image.channels);
    const bool swap = again.littleEndian != (std::endian::native == std::endian::little);
    for (int fileRow = 0; fileRow < image.height; ++fileRow) {
        const unsigned char* src = bytes.data() + again.dataOffset + size_t(fileRow) * rowFloats * 4;
        float* dst = image.pixels.data() + size_t(image.height - 1 - fileRow) * rowFloats;  // bottom-to-top rows
        for (size_t i = 0; i < rowFloats; ++i) {
            uint32_t u;
            std::memcpy(&u, src + i * 4, 4);
            if (swap) u = __builtin_bswap32(u);
            std::memcpy(&dst[i], &u, 4);
        }
    }
    return image;
}

void writePfm(const std::string& path, const Image& image) {
    if (image.channels != 1 && image.channels != 3)
        throwUserError(escapeText(path) + ": a PFM holds 1 or 3 channels, the image has " + std::to_string(image.channels) +
                       "; write it as EXR instead");
    const std::string header = std::string(image.channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(image.width) +
                               " " + std::to_string(image.height) + "\n-1.0\n";
    const size_t rowFloats = size_t(image.width) * size_t(image.channels);
    std::vector<unsigned char> out(header.size() + rowFloats * size_t(image.height) * 4);
    std::memcpy(out.data(), header.data(), header.size());
    for (int fileRow = 0; fileRow < image.height; ++fileRow) {
        const float* src = image.pixels.data() + size_t(image.height - 1 - fileRow) * rowFloats;
        unsigned char* dst = out.data() + header.size() + size_t(fileRow) * rowFloats * 4;
        for (size_t i = 0; i < rowFloats; ++i) {
            uint32_t u;
            std::memcpy(&u, &src[i], 4);
            if constexpr (std::endian::native != std::endian::little) u = __builtin_bswap32(u);
            std::memcpy(dst + i * 4, &u, 4);
        }
    }
    writeFileAtomic(path, out.data(), out.size());
}

}  // namespace gbl
