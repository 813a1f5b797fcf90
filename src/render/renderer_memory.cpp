// renderMemoryBytes: the render's peak host memory on a CPU device, from its size and bands.
#include "renderer.h"

namespace gbl {

namespace {

// From `gbufferlab render` on lavapipe (the built-in scene and sky, peak resident memory by
// /usr/bin/time -v, 2 cores, commit dff3d2c): whole frames 290 MiB at 1024x1024, 667 MiB at
// 2048x2048 and 2252 MiB at 4096x4096, 126-132 B a pixel over about 165 MiB; in bands of 64 rows
// 237 MiB at 2048x2048 and 505 MiB at 4096x4096, 22 B a pixel of the frame (its HDR image, 16,
// the PNG's 3 and their staging) plus a band's own cost. The constants are above every one of
// those (4096x4096 whole: 2400 MiB estimated).
constexpr double kWholeBytesPerPixel = 138.0;
constexpr double kFrameBytesPerPixel = 24.0;
constexpr double kBandBytesPerPixel = 138.0;  // per pixel of a band and its halo of one row each side
constexpr double kFixedBytes = double(192u << 20);

}  // namespace

double renderMemoryBytes(uint32_t width, uint32_t height, uint32_t bandRows) {
    const double frame = double(width) * double(height);
    if (bandRows == 0 || bandRows >= height) return frame * kWholeBytesPerPixel + kFixedBytes;
    return frame * kFrameBytesPerPixel + double(width) * double(bandRows + 2) * kBandBytesPerPixel + kFixedBytes;
}

}  // namespace gbl
