#pragma once
// The CPU codec's loops over image rows (cpu_codec_encode.cpp, cpu_codec_decode.cpp), run by
// CpuCodec on bands of rows in parallel. Internal to the codec; the API is cpu_codec.h.
#include <cstdint>

#include "cpu_codec_plan.h"

namespace gbl::codec {

// A block of up to kBlock pixels of one row: its Surfaces member-major (s[k][j]), and field by
// field the field's input components (src[c]: a row of s, or of in filled with the field's
// constant; pointing at s saves copying every input of every field), its codes
// (code[k][j]), and the target's words being assembled (words[w][j], word-major: contiguous per
// word), then interleaved (pixels) and streamed to the image.
struct EncodeBlock {
    alignas(32) float s[kSurfaceFloats][kBlock];  // the block's Surfaces, member-major
    alignas(32) float in[4][kBlock];
    const float* src[4] = {in[0], in[1], in[2], in[3]};  // the current field's inputs (see above)
    alignas(32) uint32_t code[4][kBlock];
    alignas(32) uint32_t words[4][kBlock];
    alignas(32) uint32_t pixels[4 * kBlock];  // the block's words interleaved, as in the image
    alignas(32) uint32_t model[kBlock];       // each pixel's shading model (a layout with a selector)
};

// Codes of field `f` for the pixels (x0 + j, y), j < n, from b.src into b.code (mirror of the
// generated writeGBuffer: the same primitives, src/encoding/encodings.h). Also used to fold constants.
void encodeCodes(const FieldPlan& f, int n, int x0, int y, EncodeBlock& b);

// Raw views of a CpuGBuffer: per target / material target, the first word of the image.
struct WordViews {
    uint32_t* const* targets = nullptr;
    uint32_t* const* material = nullptr;
};
struct ConstWordViews {
    const uint32_t* const* targets = nullptr;
    const uint32_t* const* material = nullptr;
    const uint8_t* covered = nullptr;  // width * height, 1 = geometry (CpuGBuffer::covered); nullptr: all
};

// Encodes rows [y0, y1) of the width x height image `surfaces` (row-major) into `out`.
void encodeRows(const CodecPlan& plan, const Surface* surfaces, int width, int y0, int y1, const WordViews& out);

// Decodes rows [y0, y1) into out (row-major, the band's Surfaces: out[0] is pixel (0, y0)). Reads
// the rows above and below the band too (checkerboard chroma), so the whole G-buffer must be readable.
void decodeRows(const CodecPlan& plan, const ConstWordViews& in, int width, int height, int y0, int y1,
                Surface* out);

}  // namespace gbl::codec
