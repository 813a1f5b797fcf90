#pragma once
// Tile-based GPUs keep a render pass's colour attachments in on-chip tile memory: when the
// geometry and lighting passes are subpasses of one render pass, a G-buffer that fits the tile's
// per-pixel colour storage never leaves the chip; only the lit output is written out. Each family
// below has a published per-pixel limit; the fit is computed on the layout's formats.
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

struct TileFamily {
    const char* id;          // "apple-a7", ...
    const char* name;
    int colourBytesPerPixel;  // the limit: combined size of the colour attachments of a render pass
    int maxColourTargets;     // 0: not stated
    bool hardLimit;           // over it the render pass is refused (Apple) or only slower (Mali)
    const char* source;
};

// Apple: "Understanding Color-Renderable Pixel Format Sizes", developer.apple.com Metal
// documentation, Table 1 "Maximum number and size of color render targets for each iOS and tvOS
// GPU": A7 four per render pass, 128 bits per pixel; A8, A9, A10 eight, 256 bits; A11 eight, 512
// bits (the same limits as Unity's SystemInfo.maxTiledPixelStorageSize: 16 bytes for iOS GPU
// family 1, 32 for families 2 and 3). Arm: "for the more recent GPUs (anything since Mali-T760)
// ... We recommend aiming for a maximum of 128-bits per pixel of storage to get the best tile
// pipelining ... More than 128-bits per pixel will work, but it starts to cause some slow downs"
// (Arm community forum, "Multiple render targets and tilebuffer", answer 28891).
const std::vector<TileFamily>& tileFamilies();

struct TileFit {
    std::string family;          // TileFamily::id
    int colourBytesPerPixel = 0; // the G-buffer's colour targets (or ids), light buffers, lit output
    int colourTargets = 0;
    int limitBytesPerPixel = 0;
    bool fits = false;           // bytes and target count within the limit
    // What the pass costs when it does not fit: "spill" (two render passes, the G-buffer written
    // and read through memory) or "slower" (Mali: stays on chip with fewer tiles in flight).
    std::string overflow;
};

// The lit output the lighting subpass writes (RGBA16F), counted in the tile's colour storage.
std::vector<TileFit> tileFits(const Layout& layout, int litOutputBytesPerPixel);

}  // namespace gbl
