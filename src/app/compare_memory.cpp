#include "compare_memory.h"

namespace gbl::compare {

namespace {

// Peak resident memory of `compare` on lavapipe, measured with /usr/bin/time -v (built-in scene
// and sky, 2 cores, commit dff3d2c, --views 1): layouts ue4, ryse, crysis3-thin whole frames 664
// MiB at 1024x1024 and 1604 MiB at 2048x2048 (313 B a pixel over about 350 MiB), in bands of 64
// rows 321 and 627 MiB (102 B a pixel); all 19 layouts, 1024x1024 whole, 997 MiB: about 21 MiB
// more a layout (its pipelines and their compiled code); with --views 3 1082 MiB, about 41 B a
// pixel more a view. The constants are above each of those.
constexpr double kWholeBytesPerPixel = 360.0;
constexpr double kFrameBytesPerPixel = 120.0;  // in bands: the frame-sized images (renders, 8-bit maps)
constexpr double kBandBytesPerPixel = 360.0;   // in bands: per pixel of a band's images
constexpr double kFixedBytes = double(384u << 20);
constexpr double kBytesPerLayout = double(24u << 20);
constexpr double kBytesPerPixelPerExtraView = 48.0;
// --temporal N > 1, counted from the sizes (not measured): a sequence's accumulators (HDR RGBA and
// 20 surface channels in double: 192 B), its first frame and its resolve kept (HDR and surfaces in
// float: 2 x 96 B), for the reference (and its first frame's prepared tone map and FLIP half) and
// the layout being measured. It does not grow with N.
constexpr double kTemporalBytesPerPixel = 2.0 * (192.0 + 2.0 * 96.0) + 64.0;

}  // namespace

double compareMemoryBytes(uint32_t width, uint32_t height, uint32_t bandImageRows, size_t layouts, int views,
                          int temporalFrames) {
    const double frame = double(width) * double(height);
    const double fixed = kFixedBytes + double(layouts) * kBytesPerLayout +
                         frame * kBytesPerPixelPerExtraView * double(views > 1 ? views - 1 : 0) +
                         (temporalFrames > 1 ? frame * kTemporalBytesPerPixel : 0.0);
    if (bandImageRows == 0 || bandImageRows >= height) return frame * kWholeBytesPerPixel + fixed;
    return frame * kFrameBytesPerPixel + double(width) * double(bandImageRows) * kBandBytesPerPixel + fixed;
}

}  // namespace gbl::compare
