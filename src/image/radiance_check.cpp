#include "radiance_check.h"

#include <cstdlib>
#include <cstring>

namespace gbl {
namespace {

// Reads one header line the way stb_image does: up to '\n' or the end of the data.
std::string nextLine(const unsigned char* bytes, size_t size, size_t& pos) {
    std::string line;
    while (pos < size && bytes[pos] != '\n') line += char(bytes[pos++]);
    if (pos < size) ++pos;  // the '\n'
    return line;
}

// Walks one new-style RLE scanline (4 channel planes of `width` bytes each).
std::string checkRleScanline(const unsigned char* bytes, size_t size, size_t& pos, long width, long row) {
    const std::string where = " in scanline " + std::to_string(row);
    for (int channel = 0; channel < 4; ++channel) {
        long filled = 0;
        while (filled < width) {
            if (pos >= size) return "the file ends early" + where + " (truncated?)";
            unsigned count = bytes[pos++];
            if (count > 128) {  // a run: one value repeated count-128 times
                count -= 128;
                if (pos >= size) return "the file ends early" + where + " (truncated?)";
                ++pos;
            } else {            // a dump: count literal bytes
                if (count == 0) return "zero-length RLE chunk" + where + " (corrupt data)";
                if (size - pos < count) return "the file ends early" + where + " (truncated?)";
                pos += count;
            }
            if (long(count) > width - filled) return "RLE run overflows" + where + " (corrupt data)";
            filled += long(count);
        }
    }
    return "";
}

}  // namespace

std::string findRadianceStreamProblem(const unsigned char* bytes, size_t size) {
    size_t pos = 0;
    nextLine(bytes, size, pos);  // "#?RADIANCE"
    bool rgbe = false;            // stb decodes only this format and says so itself otherwise
    for (std::string line = nextLine(bytes, size, pos); !line.empty(); line = nextLine(bytes, size, pos))
        rgbe = rgbe || line == "FORMAT=32-bit_rle_rgbe";
    if (!rgbe) return "";
    const std::string resolution = nextLine(bytes, size, pos);
    // Only the "-Y H +X W" layout stb supports; anything else stb rejects with its own reason.
    if (resolution.compare(0, 3, "-Y ") != 0) return "";
    char* end = nullptr;
    const long height = std::strtol(resolution.c_str() + 3, &end, 10);
    while (*end == ' ') ++end;
    if (std::strncmp(end, "+X ", 3) != 0) return "";
    const long width = std::strtol(end + 3, nullptr, 10);
    if (width <= 0 || height <= 0 || width > (1 << 24) || height > (1 << 24)) return "";

    const auto flatBytes = size_t(width) * size_t(height) * 4;
    const bool rleWidth = width >= 8 && width < 32768;  // stb's rule for trying RLE
    for (long row = 0; rleWidth && row < height; ++row) {
        if (size - pos < 4) return "the file ends early in scanline " + std::to_string(row) + " (truncated?)";
        const bool rle = bytes[pos] == 2 && bytes[pos + 1] == 2 && !(bytes[pos + 2] & 0x80);
        if (!rle) {
            // stb restarts the whole image as flat RGBE here; that only makes sense at row 0.
            if (row != 0) return "scanline " + std::to_string(row) + " is flat after RLE scanlines (unsupported mix)";
            break;
        }
        const long length = (long(bytes[pos + 2]) << 8) | bytes[pos + 3];
        if (length != width) return "";  // stb reports "invalid decoded scanline length"
        pos += 4;
        if (auto problem = checkRleScanline(bytes, size, pos, width, row); !problem.empty()) return problem;
        if (row == height - 1) return "";
    }
    if (size - pos < flatBytes) return "the file ends early in its flat pixel data (truncated?)";
    return "";
}

}  // namespace gbl
