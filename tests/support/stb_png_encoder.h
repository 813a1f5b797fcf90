#pragma once
// The PNG encoder gbufferlab used before src/image/png_writer.h: stb_image_write with the Sub filter
// forced on every row and deflate by zlib's compress2 at level 1 (through stb's
// STBIW_ZLIB_COMPRESS hook). Kept as an independent oracle (png_writer_test: one band must be
// this file byte for byte) and as the baseline of bench/png_bench.cpp. Include it in one
// translation unit per executable: it holds stb_image_write's implementation.
#include <zlib.h>

#include <cstdlib>
#include <vector>

#include "image.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#define STBIW_ZLIB_COMPRESS gblStbZlibLevel1
static unsigned char* gblStbZlibLevel1(unsigned char* data, int length, int* outLength, int /*stbLevel*/) {
    uLongf size = compressBound(uLong(length));
    auto* out = static_cast<unsigned char*>(std::malloc(size));  // stb frees it with free()
    if (!out || compress2(out, &size, data, uLong(length), 1) != Z_OK) {
        std::free(out);
        return nullptr;
    }
    *outLength = int(size);
    return out;
}
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"  // STATIC makes every unused stb entry point warn
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace gbl::test {

// The old encoder's file; empty if stb fails.
inline std::vector<unsigned char> stbPngSubLevel1(const Image8& image) {
    stbi_write_force_png_filter = 1;
    std::vector<unsigned char> png;
    const auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(context);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, image.channels, image.pixels.data(),
                                image.width * image.channels))
        png.clear();
    return png;
}

}  // namespace gbl::test
