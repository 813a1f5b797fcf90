#pragma once
// Bandwidth as GPUs pay it: a layout's render-target traffic per GPU class, from the
// compressed sizes of the words it wrote (framebuffer_compression.h), the tile-memory fit of its
// formats (tile_memory.h) and the lighting pass's reads (LightingModel).
//
// Classes (each states what it assumes; ClassTraffic::assumes):
// - desktop-dcc: an immediate-mode GPU with DCC-like lossless compression of the colour targets
//   (framebuffer_compression.h's DCC container and model coder); depth uncompressed (its HiZ /
//   HTILE compression is not modelled); the geometry pass writes each target once, the lighting
//   pass reads it LightingModel::readsPerPixel times.
// - mali-afbc: a Mali GPU with AFBC, geometry and lighting as separate render passes (the G-buffer
//   goes through memory): AFBC writes header and body, a read moves the body and each
//   superblock's header line; targets wider than 32 bits uncompressed; depth uncompressed.
// - tile-subpass: a tile-based GPU with geometry and lighting as subpasses of one render pass
//   (Apple A11 and later's 64 bytes of colour per pixel, tileFamilies()): a G-buffer that fits
//   costs no external traffic, only the lit output; one that does not is split into two passes
//   and pays its nominal bytes written and read.
// Every class: the lit output (RGBA16F) written once; a visibility buffer's resolve fetches
// (bandwidth.h) counted as in the nominal model.
#include <optional>
#include <string>
#include <vector>

#include "bandwidth.h"
#include "framebuffer_compression.h"
#include "tile_memory.h"

namespace gbl {

// How the lighting pass reads the G-buffer: tiled or clustered shading reads it once per pixel;
// light volumes read it once per light covering the pixel (readsPerPixel, the mean over the frame:
// given, or counted from the scene's punctual lights' bounds: scene/light_coverage.h).
struct LightingModel {
    enum class Kind : uint8_t { Tiled, Volumes };
    Kind kind = Kind::Tiled;
    double readsPerPixel = 1.0;
    bool counted = false;      // volumes: counted from the scene's lights, not given
    std::string text() const;  // "tiled", "volumes:2.5", "volumes (counted: 2.00)"
};

// Parses --lighting: "tiled", "clustered" (the same reads), "volumes" (counted), "volumes:L" (L > 0).
// Throws UserError naming `flag`.
LightingModel parseLightingModel(const std::string& text, const std::string& flag);

// The nominal model (bandwidth.h) with the lighting pass reading the G-buffer and depth
// `readsPerPixel` times.
FrameTraffic computeFrameTraffic(const Layout& layout, uint32_t width, uint32_t height, int samples,
                                 const LightingModel& lighting);

struct TargetEffective {
    std::string name;
    std::string format;
    int bytesPerPixel = 0;       // nominal
    double dccBytesPerPixel = 0;  // stored under the desktop-dcc model
    double afbcBytesPerPixel = 0; // read under the mali-afbc model (headers' lines included)
    double afbcWriteBytesPerPixel = 0;  // written: header + body
    double afbcSolidFraction = 0;  // superblocks of one colour
    double afbcUncompressedFraction = 0;  // subblocks stored uncompressed (of those not solid)
    double dccUncompressedFraction = 0;   // DCC blocks stored uncompressed
    bool afbc = false;            // AFBC compresses it (<= 32-bit texels)
};

struct ClassTraffic {
    std::string gpuClass;         // "desktop-dcc", "mali-afbc", "tile-subpass"
    double bytesPerPixel = 0;     // effective: targets (or ids) + depth + light buffers, as stored
    double trafficBytes = 0;      // one 1920x1080 frame, 1 sample: written + read (+ fetches) + lit output
    double gbPerSecond = 0;       // at 60 frames per second
    std::string assumes;
};

struct EffectiveBandwidth {
    uint32_t width = 0, height = 0;  // the frames the words came from
    int frames = 0;                  // frames (views) pooled
    double nominalBytesPerPixel = 0; // targets + depth + light buffers (bytes_per_pixel.total)
    double nominalTrafficBytes = 0;  // the nominal model at 1080p, with the same lighting model
    double nominalGbPerSecond = 0;
    std::vector<TargetEffective> targets;
    std::vector<ClassTraffic> classes;
    std::vector<TileFit> tile;
    LightingModel lighting;
    const ClassTraffic* find(const std::string& gpuClass) const;
};

constexpr const char* kGpuClasses[] = {"desktop-dcc", "mali-afbc", "tile-subpass"};
constexpr const char* kTileSubpassFamily = "apple-a11";

EffectiveBandwidth computeEffectiveBandwidth(const Layout& layout, const FrameCompression& compression, int frames,
                                             const LightingModel& lighting);

// Effective bytes per pixel of one class (desktop-dcc, mali-afbc) from a frame's compression:
// the search's --budget-model (targets as stored, depth and light buffers nominal).
double effectiveBytesPerPixel(const Layout& layout, const FrameCompression& compression, const std::string& gpuClass);

}  // namespace gbl
