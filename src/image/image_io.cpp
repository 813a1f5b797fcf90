// The stb_image based formats: Radiance .hdr in, PNG/JPEG in; PNG out through our own encoder
// (png_writer.h: one image deflated on several cores); plus the choice of environment reader by
// extension. The EXR side is in exr_io.cpp.
#include "image_io.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "error.h"
#include "exr_probe.h"
#include "file_io.h"
#include "memory_budget.h"
#include "pfm_io.h"
#include "png_writer.h"
#include "radiance_check.h"

// tinygltf's prebuilt .so carries its own (global) stb_image symbols; STATIC keeps ours private
// to this file so the two copies cannot clash at link time. Files are read through
// readBinaryFile (clear errors, one code path), so stb's stdio API is left out.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_ONLY_HDR
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"  // STATIC makes every unused stb entry point warn
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace gbl {
namespace {

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown reason";
}

std::vector<unsigned char> readWholeFile(const std::string& path) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > uintmax_t(INT_MAX))  // before reading it: the bytes would be the first allocation
        throwUserError(escapeText(path) + ": file is larger than 2 GiB, which the image reader does not support");
    auto bytes = readBinaryFile(path);
    if (bytes.size() > size_t(INT_MAX))
        throwUserError(escapeText(path) + ": file is larger than 2 GiB, which the image reader does not support");
    return bytes;
}

// A PNG's IHDR read directly: stb_image refuses to describe a PNG whose frame exceeds 2^30
// bytes and then names no reason but "unknown image type"; the size is what the caller needs to
// say what is wrong.
bool pngHeader(const unsigned char* bytes, size_t size, int& width, int& height, int& channels) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 29 || std::memcmp(bytes, signature, 8) != 0 || std::memcmp(bytes + 12, "IHDR", 4) != 0) return false;
    auto be32 = [&](size_t at) {
        return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
    };
    const uint32_t w = be32(16), h = be32(20);
    const int colourType = bytes[25];
    const int perType[7] = {1, 0, 3, 1, 2, 0, 4};
    if (w == 0 || h == 0 || w > uint32_t(INT_MAX) || h > uint32_t(INT_MAX) || colourType > 6 || perType[colourType] == 0)
        return false;
    width = int(w);
    height = int(h);
    channels = colourType == 3 ? 3 : perType[colourType];
    return true;
}

struct StbInfo {
    int width = 0, height = 0, channels = 0;
    bool sixteenBit = false;
};

StbInfo stbInfo(const std::string& path, const std::vector<unsigned char>& bytes, const char* what) {
    StbInfo i;
    if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &i.width, &i.height, &i.channels) &&
        !pngHeader(bytes.data(), bytes.size(), i.width, i.height, i.channels))
        throwUserError(escapeText(path) + ": cannot read the " + what + " header (stb_image: " + stbReason() +
                       "); check that it is a complete, valid file");
    i.sixteenBit = stbi_is_16_bit_from_memory(bytes.data(), int(bytes.size())) != 0;
    return i;
}

// stb_image decodes into a buffer of its own (PNG: after inflating every row, filter bytes
// included; 16-bit: at 16 bits, then converted), which the readers copy: about three copies of
// the decoded size at the peak.
void requireDecodeMemory(const std::string& path, const StbInfo& i, double bytesPerSample) {
    const double decoded = double(i.width) * double(i.height) * double(i.channels) * bytesPerSample;
    requireMemory(3.0 * decoded * (i.sixteenBit ? 2.0 : 1.0),
                  escapeText(path) + ": decoding its " + std::to_string(i.width) + "x" + std::to_string(i.height) +
                      " pixels",
                  "give a smaller image (crop or scale it), or raise GBL_MEMORY_BUDGET on a machine with more memory");
}


std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

Image readHdr(const std::string& path) {
    const auto bytes = readWholeFile(path);
    const int size = int(bytes.size());
    if (!stbi_is_hdr_from_memory(bytes.data(), size))
        throwUserError(path + ": not a Radiance .hdr file (no #?RADIANCE / #?RGBE signature); convert it to .hdr or .exr");
    if (const auto problem = findRadianceStreamProblem(bytes.data(), bytes.size()); !problem.empty())
        throwUserError(path + ": damaged Radiance .hdr: " + problem + "; re-download or re-export the file");
    // A header stb_image cannot read fails its decode below, with its own reason, before it
    // allocates anything; one it can read is held to the budget first.
    StbInfo info;
    if (stbi_info_from_memory(bytes.data(), size, &info.width, &info.height, &info.channels)) {
        info.channels = 3;
        requireDecodeMemory(path, info, sizeof(float));
    }
    int width = 0, height = 0, fileChannels = 0;
    std::unique_ptr<float, StbFree> data(stbi_loadf_from_memory(bytes.data(), size, &width, &height, &fileChannels, 3));
    if (!data)
        throwUserError(path + ": cannot decode Radiance .hdr (stb_image: " + stbReason() + "); re-export the file");
    if (width <= 0 || height <= 0)
        throwUserError(path + ": Radiance .hdr has no pixels (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    Image image(width, height, 3);
    std::memcpy(image.pixels.data(), data.get(), image.pixels.size() * sizeof(float));
    return image;
}

Image8 readImage8(const std::string& path) {
    const auto bytes = readWholeFile(path);
    requireDecodeMemory(path, stbInfo(path, bytes, "image"), 1.0);
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<unsigned char, StbFree> data(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 0));
    if (!data)
        throwUserError(path + ": cannot decode image (stb_image: " + stbReason() + "); use an 8-bit PNG or JPEG");
    Image8 image{width, height, channels, {}};
    image.pixels.assign(data.get(), data.get() + size_t(width) * size_t(height) * size_t(channels));
    return image;
}

UnormImage readImageUnorm(const std::string& path) {
    const auto bytes = readWholeFile(path);
    const StbInfo info = stbInfo(path, bytes, "image");
    requireDecodeMemory(path, info, 1.0);
    UnormImage out;
    int width = 0, height = 0, channels = 0;
    auto toImage = [&](const auto* data, float scale) {
        out.image = Image(width, height, channels);
        for (size_t i = 0; i < out.image.pixels.size(); ++i) out.image.pixels[i] = float(data[i]) / scale;
    };
    if (info.sixteenBit) {
        std::unique_ptr<stbi_us, StbFree> data(
            stbi_load_16_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 0));
        if (!data)
            throwUserError(escapeText(path) + ": cannot decode the 16-bit image (stb_image: " + stbReason() +
                           "); re-save it as a PNG");
        out.bitsPerSample = 16;
        toImage(data.get(), 65535.0f);
        return out;
    }
    std::unique_ptr<unsigned char, StbFree> data(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 0));
    if (!data)
        throwUserError(escapeText(path) + ": cannot decode image (stb_image: " + stbReason() +
                       "); use a PNG (8 or 16 bits) or a JPEG");
    toImage(data.get(), 255.0f);
    return out;
}

namespace {

void writeEncodedPng(const std::string& path, const Image8& image, bool colourMapped) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw std::invalid_argument("writePng " + path + ": inconsistent image (" + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + "x" + std::to_string(image.channels) + ", " +
                                    std::to_string(image.pixels.size()) + " bytes)");
    // Encode in memory, then one atomic write: the file is complete or absent.
    std::vector<unsigned char> png;
    try {
        png = colourMapped ? encodePngColourMapped(image) : encodePng(image);
    } catch (const std::runtime_error& e) {  // zlib out of memory: say which file it was
        throwUserError(path + ": PNG encoding failed (" + e.what() + "); free memory or write a smaller image");
    }
    writeFileAtomic(path, png.data(), png.size());
}

}  // namespace

void writePng(const std::string& path, const Image8& image) { writeEncodedPng(path, image, false); }

void writeColourMappedPng(const std::string& path, const Image8& image) { writeEncodedPng(path, image, true); }

ImageFileInfo probeImageFile(const std::string& path) {
    const std::string ext = lowerExtension(path);
    ImageFileInfo info;
    if (ext == ".exr") {
        const ExrProbe p = probeExr(path);
        info.width = p.width;
        info.height = p.height;
        info.channels = int(p.channels.size());
        info.hdr = true;
        return info;
    }
    if (ext == ".pfm") {
        const PfmHeader p = probePfm(path);
        info.width = p.width;
        info.height = p.height;
        info.channels = p.channels;
        info.hdr = true;
        return info;
    }
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".hdr")
        throwUserError(escapeText(path) + ": unknown image type '" + escapeText(ext) +
                       "'; give a .png, .jpg, .exr, .hdr or .pfm file");
    const auto bytes = readWholeFile(path);
    const bool hdr = ext == ".hdr";
    if (hdr != bool(stbi_is_hdr_from_memory(bytes.data(), int(bytes.size()))))
        throwUserError(escapeText(path) + (hdr ? ": not a Radiance .hdr file (no #?RADIANCE / #?RGBE signature)"
                                               : ": a Radiance .hdr file named " + escapeText(ext)) +
                       "; give the file the extension of what it holds");
    const StbInfo i = stbInfo(path, bytes, hdr ? "Radiance .hdr" : "image");
    info.width = i.width;
    info.height = i.height;
    info.channels = hdr ? 3 : i.channels;
    info.hdr = hdr;
    return info;
}

std::optional<ImageMemoryInfo> probeImageMemory(const unsigned char* bytes, size_t size, std::string* whyNot) {
    if (size > size_t(INT_MAX)) {
        if (whyNot) *whyNot = "larger than 2 GiB";
        return std::nullopt;
    }
    ImageMemoryInfo i;
    if (!stbi_info_from_memory(bytes, int(size), &i.width, &i.height, &i.channels) &&
        !pngHeader(bytes, size, i.width, i.height, i.channels)) {
        if (whyNot) *whyNot = stbReason();
        return std::nullopt;
    }
    i.sixteenBit = stbi_is_16_bit_from_memory(bytes, int(size)) != 0;
    return i;
}

Image readEnvironmentFile(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".hdr") return readHdr(path);
    if (ext == ".exr") return readExr(path);
    throwUserError(path + ": unsupported environment map type '" + ext +
                   "'; use an equirectangular Radiance .hdr or OpenEXR .exr file");
}

}  // namespace gbl
