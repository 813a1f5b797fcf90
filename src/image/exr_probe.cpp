#include "exr_probe.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstring>

#include <OpenEXR/openexr.h>

#include "error.h"
#include "file_io.h"
#include "memory_budget.h"

namespace gbl {
namespace {

// OpenEXRCore reports through a callback that would print to stderr; keep the first message
// for the one line the caller throws.
void keepMessage(exr_const_context_t ctxt, exr_result_t, const char* msg) {
    void* user = nullptr;
    if (exr_get_user_data(ctxt, &user) != EXR_ERR_SUCCESS || !user) return;
    auto* text = static_cast<std::string*>(user);
    if (text->empty() && msg) {
        *text = msg;
        std::replace(text->begin(), text->end(), '\n', ' ');
    }
}

struct Context {
    exr_context_t ctxt = nullptr;
    ~Context() {
        if (ctxt) exr_finish(&ctxt);
    }
};

std::string size(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

ExrProbe probeExr(const std::string& path) {
    requireRegularFile(path);  // a FIFO would block the reader
    const std::string name = escapeText(path);
    ExrProbe p;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) p.fileBytes = uint64_t(std::max<off_t>(st.st_size, 0));

    std::string message;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keepMessage;
    init.user_data = &message;
    Context c;
    auto fail = [&](exr_result_t rv) {
        throwUserError(name + ": cannot read OpenEXR file (" +
                       escapeText(message.empty() ? exr_get_error_code_as_string(rv) : message) +
                       "); check that it is a complete, valid .exr");
    };
    if (const exr_result_t rv = exr_start_read(&c.ctxt, path.c_str(), &init); rv != EXR_ERR_SUCCESS) fail(rv);
    exr_storage_t storage{};
    exr_attr_box2i_t window{};
    int32_t chunks = 0;
    const exr_attr_chlist_t* channels = nullptr;
    for (const exr_result_t rv : {exr_get_storage(c.ctxt, 0, &storage), exr_get_data_window(c.ctxt, 0, &window),
                                  exr_get_chunk_count(c.ctxt, 0, &chunks), exr_get_channels(c.ctxt, 0, &channels)})
        if (rv != EXR_ERR_SUCCESS) fail(rv);
    if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
        throwUserError(name + ": a deep OpenEXR file (several samples per pixel); flatten it to one image first");
    const int64_t w = int64_t(window.max.x) - window.min.x + 1, h = int64_t(window.max.y) - window.min.y + 1;
    if (w < 1 || h < 1 || w > INT32_MAX || h > INT32_MAX)
        throwUserError(name + ": OpenEXR data window " + std::to_string(w) + "x" + std::to_string(h) +
                       " holds no pixels; re-export the file");
    p.width = int(w);
    p.height = int(h);
    p.minX = window.min.x;
    p.minY = window.min.y;
    p.chunks = uint64_t(std::max(chunks, 0));
    p.tiled = storage == EXR_STORAGE_TILED;
    double storedBytesPerPixel = 0.0;  // subsampled channels (luminance/chroma files) store fewer
    for (int i = 0; channels && i < channels->num_channels; ++i) {
        const exr_attr_chlist_entry_t& e = channels->entries[i];
        p.channels.emplace_back(e.name.str, size_t(e.name.length));
        const int bytes = e.pixel_type == EXR_PIXEL_HALF ? 2 : 4;
        p.bytesPerPixel += bytes;
        storedBytesPerPixel += double(bytes) / double(std::max(e.x_sampling, 1)) / double(std::max(e.y_sampling, 1));
    }
    if (p.tiled) {
        uint32_t tw = 0, th = 0;
        exr_tile_level_mode_t level{};
        exr_tile_round_mode_t round{};
        if (const exr_result_t rv = exr_get_tile_descriptor(c.ctxt, 0, &tw, &th, &level, &round); rv != EXR_ERR_SUCCESS)
            fail(rv);
        p.linesPerChunk = int(std::max<uint32_t>(th, 1));
    } else {
        int32_t lines = 1;
        if (const exr_result_t rv = exr_get_scanlines_per_chunk(c.ctxt, 0, &lines); rv != EXR_ERR_SUCCESS) fail(rv);
        p.linesPerChunk = std::max(lines, 1);
    }
    exr_compression_t compression = EXR_COMPRESSION_NONE;
    if (const exr_result_t rv = exr_get_compression(c.ctxt, 0, &compression); rv != EXR_ERR_SUCCESS) fail(rv);

    // What a complete file holds at least: its offset table (8 bytes a chunk), every chunk's own
    // header (scanline: y and size, 8 bytes; tile: 4 coordinates and size, 20 bytes) and one byte
    // of data; without compression, every pixel's bytes. Computed in double: hostile counts.
    const double chunkHeader = p.tiled ? 20.0 : 8.0;
    double least = double(p.chunks) * (8.0 + chunkHeader + 1.0);
    if (compression == EXR_COMPRESSION_NONE) least = std::max(least, double(w) * double(h) * storedBytesPerPixel);
    if (p.fileBytes > 0 && least > double(p.fileBytes))
        throwUserError(name + ": its header claims " + size(p.width, p.height) + " pixels in " +
                       std::to_string(p.chunks) + " chunks, which take at least " + formatBytes(least) +
                       ", but the file has " + formatBytes(double(p.fileBytes)) +
                       "; it is truncated or its header is wrong: re-export it");
    return p;
}

}  // namespace gbl
