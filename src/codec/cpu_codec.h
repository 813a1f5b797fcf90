#pragma once
// The CPU mirror of the generated wiring (wiring_codegen.h): encodes whole images of Surfaces into
// G-buffer words and decodes them back, with the same primitives (src/encoding/encodings.h) and the same
// integer-only placement, so its words equal the GPU's bit for bit (bit-exact path only: UINT
// targets, not --native-formats). Decoding works on whole images because checkerboard chroma
// reads the 4 neighbours (mirrored at the borders).
//
// CpuCodec compiles the layout once (cpu_codec_plan.h: encodings resolved to enums, bit places
// to shifts and masks) and runs it over bands of rows on several threads; the result does not
// depend on the thread count. encodeGBuffer / decodeGBuffer are the one-shot forms.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "layout.h"
#include "surface.h"

namespace gbl {

namespace codec {
struct CodecPlan;
}

struct CpuGBuffer {
    int width = 0;
    int height = 0;
    // Per target, row-major, wordsPerPixel(target) 32-bit words per pixel (as RenderOutput::targetWords).
    std::vector<std::vector<uint32_t>> targetWords;
    // Material pass (deferred lighting): per material target, 4 words (float32 bits) per pixel.
    std::vector<std::vector<uint32_t>> materialWords;
    // Which pixels hold geometry (1) and which only the clear values (0), row-major; empty: every
    // pixel has geometry. Checkerboard chroma never takes a neighbour without geometry (the GPU's
    // gblHasGeometry: depth != clear depth). encode leaves it as it is.
    std::vector<uint8_t> covered;
};

struct CpuCodecOptions {
    int threads = 0;  // bands run in parallel; 0: std::thread::hardware_concurrency()
    // The frame a dither that moves with time encodes (a field's dither_per_frame; compare
    // --temporal's RenderSettings::frameIndex). Fields whose dither is fixed ignore it.
    uint32_t frameIndex = 0;
};

class CpuCodec {
public:
    // Throws std::logic_error for layouts validation rules out (see compilePlan).
    explicit CpuCodec(const Layout& layout, CpuCodecOptions options = {});

    int threads() const { return threads_; }

    // `surfaces` is row-major, width * height.
    CpuGBuffer encode(const std::vector<Surface>& surfaces, int width, int height) const;
    // The same into `out`, reusing its vectors' memory (no allocation when the sizes already fit).
    void encode(const std::vector<Surface>& surfaces, int width, int height, CpuGBuffer& out) const;

    // What readGBuffer returns at every pixel (stored attributes decoded, the rest from fallbacks).
    std::vector<Surface> decode(const CpuGBuffer& gbuffer) const;
    void decode(const CpuGBuffer& gbuffer, std::vector<Surface>& out) const;
    // Rows [y0, y1) of decode(gbuffer) into out[0 .. width * (y1 - y0)), on the calling thread
    // (the same values as decode's: a row's decode does not depend on the band). For a caller
    // that runs bands on its own threads and uses each at once (the renderer's read-back keeps
    // a band of Surfaces per thread, not a frame of them: 88 bytes per pixel).
    void decodeRows(const CpuGBuffer& gbuffer, int y0, int y1, Surface* out) const;
    // False where a stored Surface member has no decoder (an `id` encoding): decode throws.
    bool decodes() const;

private:
    std::shared_ptr<const codec::CodecPlan> plan_;
    int threads_ = 1;
};

// What a pixel without geometry holds: a Surface of zeros with the layout's [clear] values.
Surface clearSurface(const Layout& layout);
// The words each target is cleared with: clearSurface through the layout's own encoders (the
// words of pixel (0, 0); a checkerboard field's chroma there is Cb / Co), 4 per target (unused 0).
std::vector<std::array<uint32_t, 4>> clearWords(const Layout& layout);

// One-shot forms: CpuCodec(layout).encode / .decode with the default thread count.
CpuGBuffer encodeGBuffer(const Layout& layout, const std::vector<Surface>& surfaces, int width, int height);
std::vector<Surface> decodeGBuffer(const Layout& layout, const CpuGBuffer& gbuffer);

}  // namespace gbl
