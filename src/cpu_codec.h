#pragma once
// The CPU mirror of the generated wiring (wiring_codegen.h): encodes whole images of Surfaces into
// G-buffer words and decodes them back, interpreting the same Layout data with the same
// primitives (src/encodings.h) and the same integer-only placement, so its words equal the GPU's
// bit for bit (bit-exact path only: UINT targets, not --native-formats). Decoding works on whole
// images because checkerboard chroma reads the 4 neighbours (mirrored at the borders).
#include <cstdint>
#include <vector>

#include "layout.h"
#include "surface.h"

namespace gbl {

struct CpuGBuffer {
    int width = 0;
    int height = 0;
    // Per target, row-major, wordsPerPixel(target) 32-bit words per pixel (as RenderOutput::targetWords).
    std::vector<std::vector<uint32_t>> targetWords;
    // Material pass (deferred lighting): per material target, 4 words (float32 bits) per pixel.
    std::vector<std::vector<uint32_t>> materialWords;
};

// `surfaces` is row-major, width * height.
CpuGBuffer encodeGBuffer(const Layout& layout, const std::vector<Surface>& surfaces, int width, int height);
// What readGBuffer returns at every pixel (stored attributes decoded, the rest from fallbacks).
std::vector<Surface> decodeGBuffer(const Layout& layout, const CpuGBuffer& gbuffer);

}  // namespace gbl
