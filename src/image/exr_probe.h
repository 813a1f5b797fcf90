#pragma once
// An OpenEXR file's header, read and checked before OpenEXR's C++ reader opens it. That reader
// sizes its offset table, and the caller its frame buffer, by the header's data window: a
// 480 KB file whose header claims 40000x40000 pixels would cost 19 GB before the first missing
// scanline is noticed. The header is read with OpenEXRCore, which does not load the offset
// table, and held against the file's size: the offset table (8 bytes per chunk) and every
// chunk's own header must be in the file, and an uncompressed file holds every pixel's bytes.
// Internal to the image library (exr_io.cpp).
#include <cstdint>
#include <string>
#include <vector>

namespace gbl {

struct ExrProbe {
    int width = 0, height = 0;
    int minX = 0, minY = 0;
    std::vector<std::string> channels;  // OpenEXR's order (alphabetical)
    int bytesPerPixel = 0;              // all channels, as stored (half 2, float and uint 4)
    int linesPerChunk = 1;              // scanline files; tiled: the tile height
    bool tiled = false;
    uint64_t chunks = 0;
    uint64_t fileBytes = 0;
};

// Throws UserError naming the file when it is not a regular file, not an OpenEXR file, deep, or
// when its header claims more than the file can hold.
ExrProbe probeExr(const std::string& path);

}  // namespace gbl
