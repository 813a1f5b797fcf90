#pragma once
// Reading and writing the image files gbufferlab uses. Every writer is atomic
// (temporary name + rename); every reader throws UserError naming the file on bad input.
#include <string>
#include <vector>

#include "image.h"

namespace gbl {

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

// Writes a float image (1..4 channels) as EXR, 32-bit float, ZIP compression.
// channelNames optional: defaults R,G,B,A / Y for 1 channel.
void writeExr(const std::string& path, const Image& image, const std::vector<std::string>& channelNames = {});
// Writes an 8-bit PNG (1..4 channels).
void writePng(const std::string& path, const Image8& image);
// Reads a PNG / JPEG (8-bit) file.
Image8 readImage8(const std::string& path);

}  // namespace gbl
