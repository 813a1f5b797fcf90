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
// - Visibility buffer (Burns & Hunt 2013): the geometry pass writes the ids and depth, the
//   lighting pass reads them (every sample), and its resolve fetches, per pixel (shading once per
//   pixel), MODELLED: the triangle's 3 indices and 3 vertices (position, normal, tangent, uv:
//   kVisibilityVertexBytes each) with no reuse between pixels (an upper bound: real caches share
//   a triangle's vertices among its pixels), counted in the total; and its material's texels,
//   kVisibilityTextureBytes (5 glTF textures x a trilinear footprint of 8 texels x 4 bytes, an
//   assumed full material), NOT in the total, because a G-buffer layout's geometry pass fetches
//   the same texels (not counted for it either): the two pipelines differ by when, not how much.
//   The per-draw draw and material records (240 bytes) are assumed cached (one per draw).
#include <string>
#include <vector>

#include "layout.h"

namespace gbl {

constexpr int kLitOutputBytesPerPixel = 8;  // RGBA16F, the usual HDR scene colour
// The visibility buffer's resolve, per pixel (modelled, see above): 3 x (4-byte index + 48-byte
// vertex: 12 position + 12 normal + 16 tangent + 8 uv, GpuScene's Vertex without its second uv set,
// which only a scene whose textures read TEXCOORD_1 fetches: the resolve compiles it out elsewhere).
constexpr int kVisibilityVertexBytes = 3 * (4 + 48);
constexpr int kVisibilityTextureBytes = 5 * 8 * 4;
// ... and with clusters ([ids] cluster_triangles: Nanite, Bevy's meshlets) the cluster table's
// entry, (draw, first triangle) as two 32-bit words.
constexpr int kVisibilityClusterBytes = 8;

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
    double totalBytes = 0;           // the three above (+ vertexFetchBytes)
    double litOutputBytes = 0;       // lit colour written (same for all layouts)
    double onChipExternalBytes = 0;  // tile-based, G-buffer kept on chip: only the lit output
    double vertexFetchBytes = 0;     // visibility buffer: the resolve's index + vertex fetches (modelled, in total)
    double textureFetchBytes = 0;    // visibility buffer: the resolve's texel fetches (modelled, not in total)
    double gigabytesPerSecond(double fps) const { return totalBytes * fps / 1e9; }
};

struct BandwidthReport {
    std::vector<TargetBytes> targets;  // G-buffer render targets
    int targetBytesPerPixel = 0;
    int depthBytesPerPixel = 0;
    int lightBufferBytesPerPixel = 0;
    int gbufferBytesPerPixel = 0;  // targets + depth-stencil (the usual "bytes per pixel")
    bool deferredLighting = false;
    bool visibilityBuffer = false;  // targets: the id target
    std::vector<FrameTraffic> frames;  // one per requested (resolution, samples)
};

FrameTraffic computeFrameTraffic(const Layout& layout, uint32_t width, uint32_t height, int samples);

// The chosen resolution, 1920x1080 and 3840x2160, each at 1x, 2x and 4x MSAA.
BandwidthReport computeBandwidth(const Layout& layout, uint32_t width, uint32_t height);

}  // namespace gbl
