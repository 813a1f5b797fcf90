#pragma once
// Reading and writing the image files gbufferlab uses. Every writer is atomic
// (temporary name + rename); every reader throws UserError naming the file on bad input.
#include <optional>
#include <string>
#include <vector>

#include "image.h"

namespace gbl {

// What an image file's header says, read without decoding its pixels, by extension: .png,
// .jpg/.jpeg, .hdr, .exr, .pfm (pfm_io.h; others are a UserError). The readers below hold the same numbers
// against the file and the memory budget (memory_budget.h) before they allocate; a caller that
// needs more than the decoded image (diff) checks its own estimate from these first.
struct ImageFileInfo {
    int width = 0, height = 0;
    int channels = 0;   // as stored: PNG/JPEG 1-4, HDR 3, EXR the file's channel count, PFM 1 or 3
    bool hdr = false;   // linear float (EXR, HDR, PFM) rather than 8-bit sRGB (PNG, JPEG)
};
ImageFileInfo probeImageFile(const std::string& path);
// The same from a PNG, JPEG or Radiance .hdr file's bytes (a glTF image); nullopt when stb_image
// cannot read the header (its reason in *whyNot: an unknown format, or a frame over 2^30 bytes,
// which stb_image refuses to decode).
struct ImageMemoryInfo {
    int width = 0, height = 0, channels = 0;
    bool sixteenBit = false;
};
std::optional<ImageMemoryInfo> probeImageMemory(const unsigned char* bytes, size_t size, std::string* whyNot = nullptr);

// Radiance .hdr (RGBE, flat or RLE) -> RGB float image.
Image readHdr(const std::string& path);
// OpenEXR (any compression OpenEXR 3 reads, DWAB included) -> RGB float image (R,G,B; A dropped).
// A Y-only file is replicated to gray; luminance/chroma (Y,RY,BY) goes through OpenEXR's RGBA
// conversion (half precision). The data window is read; the display window is ignored.
Image readExr(const std::string& path);
// Reads the named channels (any pixel type, converted to float) in the order given; a missing
// channel is a UserError listing the channels the file has. For data EXRs (G-buffer dumps).
Image readExrChannels(const std::string& path, const std::vector<std::string>& channelNames);
// The names of the channels an OpenEXR file has (OpenEXR's order: alphabetical).
std::vector<std::string> readExrChannelNames(const std::string& path);
// Picks readHdr or readExr by extension (.hdr / .exr); other extensions are a UserError.
Image readEnvironmentFile(const std::string& path);

// The pixel type an EXR file is written with. Half (OpenEXR's 16-bit float, IEEE 754 binary16):
// 10 stored mantissa bits, so a value is rounded to within 2^-11 of itself (relative) above
// 2^-14 and to within 2^-25 (absolute) below; largest finite value 65504. Finite values beyond
// +-65504 are written as +-65504 (a half file holds no infinity the image did not); NaN and
// infinities stay what they are. Half takes half the bytes and about half the encode time.
enum class ExrPixelType { Float32, Half };
const char* exrPixelTypeName(ExrPixelType type);  // "float32" / "half"
inline constexpr float kHalfMax = 65504.0f;

// Writes a float image (1..4 channels) as EXR, PIZ compression (lossless), every channel `type`.
// channelNames optional: defaults R,G,B,A / Y for 1 channel.
void writeExr(const std::string& path, const Image& image, const std::vector<std::string>& channelNames = {},
              ExrPixelType type = ExrPixelType::Float32);
// The pixel type of an EXR file's channels: Half when every channel is half, else Float32
// (32-bit float or uint channels).
ExrPixelType readExrPixelType(const std::string& path);
// Finite values clamped to +-kHalfMax (NaN, infinities unchanged): what writeExr(Half) converts.
float clampToHalfRange(float v);
// float -> half as writeExr(Half) stores it, back as float.
float roundToHalf(float v);
// Writes an 8-bit PNG (1..4 channels).
void writePng(const std::string& path, const Image8& image);
// Writes a colour-mapped image (the error maps) as encodePngColourMapped does: indexed when it
// has at most 256 colours; the pixels read back are the same as writePng's.
void writeColourMappedPng(const std::string& path, const Image8& image);
// Reads a PNG / JPEG (8-bit) file. A 16-bit PNG keeps only its high bytes here: readers that
// measure (diff) take readImageUnorm.
Image8 readImage8(const std::string& path);
// Reads a PNG or JPEG at the precision it holds: a 16-bit PNG at 16 bits (each value v / 65535),
// anything else at 8 (v / 255); every value in [0, 1], as stored (sRGB-encoded for an sRGB image).
struct UnormImage {
    Image image;           // the file's channels, alpha included
    int bitsPerSample = 8;  // 8 or 16: the precision the values keep
};
UnormImage readImageUnorm(const std::string& path);

}  // namespace gbl
