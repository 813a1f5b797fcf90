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
#include "file_io.h"
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

std::vector<unsigned char> readWholeFile(const std::string& path) {
    auto bytes = readBinaryFile(path);
    if (bytes.size() > size_t(INT_MAX))
        throwUserError(path + ": file is larger than 2 GiB, which the image reader does not support");
    return bytes;
}

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown reason";
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
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<unsigned char, StbFree> data(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 0));
    if (!data)
        throwUserError(path + ": cannot decode image (stb_image: " + stbReason() + "); use an 8-bit PNG or JPEG");
    Image8 image{width, height, channels, {}};
    image.pixels.assign(data.get(), data.get() + size_t(width) * size_t(height) * size_t(channels));
    return image;
}

void writePng(const std::string& path, const Image8& image) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw std::invalid_argument("writePng " + path + ": inconsistent image (" + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + "x" + std::to_string(image.channels) + ", " +
                                    std::to_string(image.pixels.size()) + " bytes)");
    // Encode in memory, then one atomic write: the file is complete or absent.
    std::vector<unsigned char> png;
    try {
        png = encodePng(image);
    } catch (const std::runtime_error& e) {  // zlib out of memory: say which file it was
        throwUserError(path + ": PNG encoding failed (" + e.what() + "); free memory or write a smaller image");
    }
    writeFileAtomic(path, png.data(), png.size());
}

Image readEnvironmentFile(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".hdr") return readHdr(path);
    if (ext == ".exr") return readExr(path);
    throwUserError(path + ": unsupported environment map type '" + ext +
                   "'; use an equirectangular Radiance .hdr or OpenEXR .exr file");
}

}  // namespace gbl
