#pragma once
// Portable FloatMap (.pfm, Netpbm): the linear float image tools/gltf-viewer/render.mjs writes
// (the Khronos glTF Sample Viewer's frame), so `gbufferlab diff reference.exr viewer.pfm` works.
// Format (Netpbm's pfm(5); P. Debevec's original definition): "PF" (3 channels) or "Pf" (1), white
// space, width, white space, height, white space, a scale whose sign gives the byte order
// (negative = little-endian, positive = big-endian; its magnitude is not applied), one white-space
// character, then width x height x channels 32-bit floats, rows BOTTOM to top.
#include <cstddef>
#include <string>

#include "image.h"

namespace gbl {

struct PfmHeader {
    int width = 0, height = 0;
    int channels = 0;          // 3 (PF) or 1 (Pf)
    bool littleEndian = true;  // scale < 0
    size_t dataOffset = 0;     // bytes of header before the raster
};

// Reads and checks the header of `bytes` (a PFM file's first bytes, or all of them): the magic,
// the dimensions (1..kPfmMaxSide each), a finite non-zero scale, and the raster's size against
// `fileSize`. A malformed header is a UserError naming `path`, the place (the header's field or
// the byte offset) and the fix. Allocates nothing in proportion to the claimed dimensions.
PfmHeader parsePfmHeader(const std::string& path, const unsigned char* bytes, size_t size, size_t fileSize);
inline constexpr int kPfmMaxSide = 1 << 20;

// The header of the file at `path`, checked as parsePfmHeader does (reads only its first bytes).
PfmHeader probePfm(const std::string& path);

// The image, rows top to bottom (Image's order), 1 or 3 channels; the pixels' memory is held to
// the memory budget (memory_budget.h) before it is allocated.
Image readPfm(const std::string& path);

// Writes a 1- or 3-channel float image as little-endian PFM (scale -1.0), atomically.
void writePfm(const std::string& path, const Image& image);

}  // namespace gbl
