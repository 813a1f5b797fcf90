#pragma once
// gbufferlab's own PNG encoder: one large image deflated on several cores.
//
// The rows are filtered with Sub (PNG filter type 1) and split into contiguous bands of rows
// ("chunks"), each deflated on its own by zlib at level 1 as an independent piece of one zlib
// stream, the way pigz splits a file: every piece but the last ends on a byte boundary with no
// back-reference into the next, so the pieces can be compressed side by side and concatenated.
// writePng (image_io.h) writes what encodePng returns.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "image.h"

namespace gbl {

// Filtered bytes (filter byte + one row) per chunk that pngChunkCount aims at. 1 MiB: a 4K RGB
// image gets 24 chunks (for up to 24 cores) and its file grows by about 0.1% against one zlib
// stream (each chunk starts with an empty dictionary and ends with a 4-5 byte flush marker;
// measured on 4K heat maps, bench/RESULTS.md: 12 chunks +0.05%, 48 chunks +0.19%).
inline constexpr int64_t kPngChunkBytes = int64_t(1) << 20;

// How many chunks encodePng splits `image` into when asked for 0: from the image's size alone
// (never the machine's thread count), so a file's bytes are the same on every machine. An image
// of at most kPngChunkBytes of filtered data is one chunk.
int pngChunkCount(const Image8& image);

// The PNG file for `image` (1-4 channels, 8 bits each: gray, gray+alpha, RGB, RGBA), its rows
// split into `chunks` bands (clamped to [1, height]; 0: pngChunkCount(image)), deflated on up to
// hardwareThreads() threads. One IDAT chunk per band, split into several when a band's data is
// over maxIdatBytes (PNG chunks hold at most 2^31 - 1 bytes; tests pass small values to split
// small bands). With one band the file is byte for byte what stb_image_write writes with the Sub
// filter forced and zlib's compress2 at level 1.
// Throws std::invalid_argument for an inconsistent image or a maxIdatBytes of 0 or over 2^31 - 1
// (bugs of the caller, not user input) and std::runtime_error if zlib fails (out of memory).
inline constexpr size_t kPngMaxIdatBytes = size_t(1) << 30;
std::vector<unsigned char> encodePng(const Image8& image, int chunks = 0, size_t maxIdatBytes = kPngMaxIdatBytes);

// The indexed form of an RGB image: true, with `indices` (1 channel) and `palette` (RGB triples,
// in order of first appearance) when it has at most 256 distinct colours; false, both untouched,
// when it has more (it stops at the 257th) or is not a consistent 3-channel image. The colour-
// mapped error images are such images: 256 table colours, a grey for NaN, and their legend text.
bool indexColours(const Image8& rgb, Image8& indices, std::vector<unsigned char>& palette);

// The deflate level of indexed images and of colour-mapped RGB ones: 1080p error maps are about
// 60% smaller indexed at level 6 than as RGB at level 1 with the Sub filter, and a colour-mapped
// map of more than 256 colours (the normal map over its dimmed backdrop) about 40% smaller as RGB
// with the None filter at level 6 (bench/RESULTS.md, 2026-11-28).
inline constexpr int kPngIndexedLevel = 6;

// The PNG file (colour type 3, bit depth 8, filter None on every row) for 1-channel `indices`
// into `palette` (1 to 256 RGB triples), split into bands as encodePng does, deflated at
// kPngIndexedLevel. Throws std::invalid_argument for an inconsistent image or palette or an
// index beyond the palette.
std::vector<unsigned char> encodePngIndexed(const Image8& indices, const std::vector<unsigned char>& palette,
                                            int chunks = 0, size_t maxIdatBytes = kPngMaxIdatBytes);

// A colour-mapped RGB image (flat colours from a table, noise between them): indexed when it has
// at most 256 colours, else RGB with the None filter (Sub's differences of unrelated table colours
// compress worse) at kPngIndexedLevel. The pixels read back are `image`'s either way.
std::vector<unsigned char> encodePngColourMapped(const Image8& image, int chunks = 0);

}  // namespace gbl
