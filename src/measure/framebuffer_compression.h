#pragma once
// What a render target costs under lossless framebuffer compression, computed from the words the
// run wrote. Two containers, each with its exact arithmetic, and one payload coder, a model:
//
// EXACT (container arithmetic; sources read 2026-12, cited where used in the .cpp):
// - AFBC (Arm Frame Buffer Compression, Mali; "mali-afbc"): 16x16-pixel superblocks, each a
//   16-byte header (a 32-bit body offset and sixteen 6-bit subblock sizes in bytes) and a body of
//   16 subblocks of 4x4 pixels. A superblock of one colour is "solid": header only, no body. A
//   subblock whose payload would not fit the 6-bit size (> 63 bytes) or would not be smaller than
//   its pixels is stored uncompressed (size code 1: 16 x texel bytes). Texels of at most 32 bits
//   are compressed (AFBC's modes in Mesa's pan_afbc.h; "only 32bit formats" on a Mali-G57,
//   as-en GPU_Benchmarks.md); wider targets are stored as they are.
// - DCC (AMD Delta Colour Compression; "desktop-dcc", the desktop class): 256-byte uncompressed
//   blocks (8x8 pixels of 4 bytes, 8x4 of 8, 4x4 of 16), each stored in 32-byte units
//   (MIN_COMPRESSED_BLOCK_SIZE on GPUs with their own memory; 64 on APUs), at most 256 bytes.
//   Every colour format is eligible (radv enables DCC on colour attachments that are not storage
//   images, linear, or mipmapped arrays).
// MODEL (the vendors' coders are not public): each block's payload is the length of a lossless
// predictive code of the block's words (payloadBits below): per channel of the format, the
// lossless YCoCg-R transform on 8- and 10-bit RGB (AFBC's YTR, DCC's colour transform), the
// JPEG-LS / LOCO-I median predictor in raster order inside the block, and Golomb-Rice codes
// of the residuals with the block's best Rice parameter: the family of Rasmusson, Hasselgren and
// Akenine-Moeller, Graphics Hardware 2007 (exact colour-buffer compression: reversible transform,
// prediction, Golomb-Rice). Its parameters are this project's, listed in payloadBits. The
// memory system's cost of an AFBC superblock beyond its body (header reads in 64-byte lines) is
// measured from the published Mali-G57 traffic: kAfbcHeaderReadBytes. The uncertainty is the
// calibration's residuals (tests/measure/framebuffer_compression_test.cpp; docs/bandwidth.md).
#include <cstdint>
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

// The bit layout the coder reads: up to 4 channels of <= 32 bits each, within wordsPerPixel words.
struct TexelLayout {
    int channels = 0;
    int bits[4] = {0, 0, 0, 0};
    int offset[4] = {0, 0, 0, 0};  // first bit in the pixel's little-endian bit string
    int bytesPerPixel = 0;         // the format's nominal size (1, 2, 4, 8, 16)
    int wordsPerPixel = 1;         // as the render reads them back (R8 / R16 widened to a word)
    bool ytr = false;              // 3+ colour channels of equal width 8 or 10: YCoCg-R applies
};
TexelLayout texelLayoutOf(const Target& target);
// A visibility buffer's id target (R32_UINT / R32G32_UINT): one or two 32-bit channels.
TexelLayout texelLayoutOfIds(const VisibilityIds& ids);

// The payload coder's variants (payloadBits): a plain Rice code per channel, or one with a 1-bit
// zero flag before every residual (zero residuals cost one bit). The Mali class uses the first,
// the desktop class the second, each the variant that its calibration rows select
// (docs/bandwidth.md lists both variants' residuals for both classes).
enum class ResidualCode : uint8_t { Rice, ZeroFlagRice };

// Coded bits of a block of w x h texels of `layout` given as its words (wordsPerPixel per texel,
// row stride `strideWords`), by the model coder described above.
int payloadBits(const TexelLayout& layout, const uint32_t* words, int strideWords, int w, int h, ResidualCode code);

// The memory system's bytes per AFBC superblock read besides its body: measured, not container
// arithmetic. A Mali-G57 read 14 MB for a 8192x8192 RGBA8 or RG16F target of one colour
// (azhirnov/as-en AE/docs/papers/bench/ARM_Mali_G57.md:271, :286, commit 2182035b), whose
// 262,144 superblocks have empty bodies: 14e6 / 262,144 = 53.4 bytes each (the 16-byte header
// and what the header's cache line drags in). Its per-pixel noise row read 16 MB more than the
// target's bytes (:265: "64B per tile"): the two rows bound the overhead to 53-64 bytes.
constexpr int kAfbcHeaderBytes = 16;
constexpr double kAfbcHeaderReadBytes = 14e6 / (8192.0 * 8192.0 / 256.0);
constexpr int kDccSectorBytes = 32;
constexpr int kDccBlockBytes = 256;

struct AfbcStats {
    bool compressed = false;     // the format is one AFBC compresses (<= 32-bit texels)
    uint64_t superblocks = 0;
    uint64_t solidSuperblocks = 0;
    uint64_t subblocks = 0;      // of superblocks that are not solid
    uint64_t uncompressedSubblocks = 0;
    double headerBytes = 0;      // exact: 16 per superblock
    double bodyBytes = 0;        // exact given the payload model
    double readBytes = 0;        // body + kAfbcHeaderReadBytes per superblock (what a read moves)
};

struct DccStats {
    uint64_t blocks = 0;
    uint64_t uncompressedBlocks = 0;
    uint64_t minimumBlocks = 0;  // stored in one 32-byte sector (8:1)
    double bytes = 0;            // sectors x 32
};

struct TargetCompression {
    std::string name;
    std::string format;
    int bytesPerPixel = 0;
    uint64_t pixels = 0;  // width x height of the frame measured (of every frame, pooled)
    AfbcStats afbc;
    DccStats dcc;
    double nominalBytes() const { return double(pixels) * bytesPerPixel; }
    // Bytes per pixel as each class stores them (mali-afbc: what a read moves, headers included;
    // targets AFBC does not compress: nominal).
    double afbcBytesPerPixel() const;
    double dccBytesPerPixel() const;
};

// Feeds a target's rows, top to bottom, in bands of any height; the frame's last superblock row
// may be partial (padded by repeating the edge texels, as AFBC pads a frame to 16 pixels and DCC
// to its block: what a GPU stores in the padding is not known).
class TargetCompressor {
public:
    TargetCompressor(std::string name, std::string format, const TexelLayout& layout, uint32_t width, uint32_t height);
    void addRows(const uint32_t* words, uint32_t rows);
    TargetCompression finish();

private:
    void processRows(const uint32_t* words, uint32_t rows);  // rows: a multiple of 16, or the frame's last
    TargetCompression result_;
    TexelLayout layout_;
    uint32_t width_ = 0, height_ = 0, rowsSeen_ = 0;
    std::vector<uint32_t> pending_;  // rows not yet a full 16-row superblock row
    uint32_t pendingRows_ = 0;
};

// One frame's targets (a layout's G-buffer targets, or a visibility buffer's ids).
struct FrameCompression {
    uint32_t width = 0, height = 0;
    std::vector<TargetCompression> targets;
    double nominalTargetBytesPerPixel() const;
    double afbcTargetBytesPerPixel() const;
    double dccTargetBytesPerPixel() const;
};

// Every target of a frame from whole-frame words (RenderOutput::targetWords / CpuGBuffer's).
FrameCompression compressFrame(const Layout& layout, const std::vector<std::vector<uint32_t>>& targetWords,
                               uint32_t width, uint32_t height);

// Several frames (a layout's views) pooled, target by target: pixels and bytes summed, so that
// each bytes-per-pixel figure is the frames' total over their pixels.
FrameCompression poolCompression(const std::vector<FrameCompression>& frames);

}  // namespace gbl
