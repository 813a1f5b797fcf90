#pragma once
// The bandwidth a layout costs, computed from its formats alone (no measurement).
//
// Model, stated so the numbers can be checked by hand:
// - Every covered pixel is written once by the geometry pass (no overdraw: a lower bound) and
//   read once by a single full-screen lighting pass (tiled / compute deferred shading).
// - No framebuffer compression (DCC, depth compression): an upper bound on real GPUs.
// - Depth is written by the geometry pass and read by the lighting pass (position from depth).
// - MSAA stores and moves every sample: G-buffer and depth traffic scale with the sample count
//   (the lighting pass is assumed to read all samples, as edge-detecting resolves must).
// - On-chip (tile-based GPUs with subpasses / transient attachments, "framebuffer fetch"): the
//   G-buffer and depth never leave tile memory; only the lit colour is written out.
// - Deferred lighting (light pre-pass): geometry pass 1 writes the slim G-buffer and depth; the
//   light pass reads them and writes the light buffers; geometry pass 2 (the material pass)
//   tests depth and reads the light buffers. The second pass's vertex and texture traffic is not
//   counted (it is scene-dependent), only its render-target traffic.
// - The lit output (RGBA16F, 8 bytes per pixel) is the same for every layout and reported apart.
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

constexpr int kLitOutputBytesPerPixel = 8;  // RGBA16F, the usual HDR scene colour

struct TargetBytes {
    std::string name;
    std::string format;
    int bytesPerPixel = 0;
};

struct FrameTraffic {
    uint32_t width = 0, height = 0;
    int samples = 1;
    double geometryWriteBytes = 0;   // G-buffer targets + depth written by the geometry pass
    double lightingReadBytes = 0;    // G-buffer targets + depth read by the lighting pass
    double lightBufferBytes = 0;     // deferred lighting: light buffers written + read, depth re-tested
    double totalBytes = 0;           // the three above
    double litOutputBytes = 0;       // lit colour written (same for all layouts)
    double onChipExternalBytes = 0;  // tile-based, G-buffer kept on chip: only the lit output
    double gigabytesPerSecond(double fps) const { return totalBytes * fps / 1e9; }
};

struct BandwidthReport {
    std::vector<TargetBytes> targets;  // G-buffer render targets
    int targetBytesPerPixel = 0;
    int depthBytesPerPixel = 0;
    int lightBufferBytesPerPixel = 0;
    int gbufferBytesPerPixel = 0;  // targets + depth-stencil (the usual "bytes per pixel")
    bool deferredLighting = false;
    std::vector<FrameTraffic> frames;  // one per requested (resolution, samples)
};

FrameTraffic computeFrameTraffic(const Layout& layout, uint32_t width, uint32_t height, int samples);

// The chosen resolution, 1920x1080 and 3840x2160, each at 1x, 2x and 4x MSAA.
BandwidthReport computeBandwidth(const Layout& layout, uint32_t width, uint32_t height);

}  // namespace gbl
