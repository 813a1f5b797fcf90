#include "effective_bandwidth.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "error.h"

namespace gbl {

std::string LightingModel::text() const {
    if (kind == Kind::Tiled) return "tiled";
    char buf[64];
    if (counted) std::snprintf(buf, sizeof(buf), "volumes (counted: %.2f)", readsPerPixel);
    else std::snprintf(buf, sizeof(buf), "volumes:%g", readsPerPixel);
    return buf;
}

LightingModel parseLightingModel(const std::string& text, const std::string& flag) {
    LightingModel m;
    if (text == "tiled" || text == "clustered") return m;
    if (text == "volumes") {
        m.kind = LightingModel::Kind::Volumes;
        m.counted = true;
        return m;
    }
    if (text.rfind("volumes:", 0) == 0) {
        const std::string value = text.substr(8);
        char* end = nullptr;
        const double l = std::strtod(value.c_str(), &end);
        if (!value.empty() && end && *end == '\0' && std::isfinite(l) && l > 0.0 && l <= 1024.0) {
            m.kind = LightingModel::Kind::Volumes;
            m.readsPerPixel = l;
            return m;
        }
    }
    throwUserError(flag + " '" + text +
                   "': expected tiled, clustered, volumes (lights counted from the scene) or volumes:L (L the mean "
                   "lights covering a pixel, 0 < L <= 1024)");
}

FrameTraffic computeFrameTraffic(const Layout& layout, uint32_t width, uint32_t height, int samples,
                                 const LightingModel& lighting) {
    FrameTraffic f = computeFrameTraffic(layout, width, height, samples);
    if (lighting.readsPerPixel == 1.0) return f;
    f.lightingReadBytes *= lighting.readsPerPixel;
    f.totalBytes = f.geometryWriteBytes + f.lightingReadBytes + f.lightBufferBytes + f.vertexFetchBytes;
    return f;
}

const ClassTraffic* EffectiveBandwidth::find(const std::string& gpuClass) const {
    for (const ClassTraffic& c : classes)
        if (c.gpuClass == gpuClass) return &c;
    return nullptr;
}

namespace {

struct Sums {
    double nominal = 0, dcc = 0, afbcRead = 0, afbcWrite = 0;
};

Sums targetSums(const FrameCompression& compression) {
    Sums s;
    for (const TargetCompression& t : compression.targets) {
        s.nominal += t.bytesPerPixel;
        s.dcc += t.dccBytesPerPixel();
        s.afbcRead += t.afbcBytesPerPixel();
        s.afbcWrite += t.afbc.compressed && t.pixels ? (t.afbc.headerBytes + t.afbc.bodyBytes) / double(t.pixels)
                                                      : double(t.bytesPerPixel);
    }
    return s;
}

}  // namespace

double effectiveBytesPerPixel(const Layout& layout, const FrameCompression& compression, const std::string& gpuClass) {
    const Sums s = targetSums(compression);
    const double rest = double(depthAttachmentBytes(layout) + lightBufferBytesPerPixel(layout));
    if (gpuClass == "desktop-dcc") return s.dcc + rest;
    if (gpuClass == "mali-afbc") return s.afbcRead + rest;
    return s.nominal + rest;
}

EffectiveBandwidth computeEffectiveBandwidth(const Layout& layout, const FrameCompression& compression, int frames,
                                             const LightingModel& lighting) {
    EffectiveBandwidth e;
    e.width = compression.width;
    e.height = compression.height;
    e.frames = frames;
    e.lighting = lighting;
    for (const TargetCompression& t : compression.targets) {
        TargetEffective te;
        te.name = t.name;
        te.format = t.format;
        te.bytesPerPixel = t.bytesPerPixel;
        te.dccBytesPerPixel = t.dccBytesPerPixel();
        te.afbcBytesPerPixel = t.afbcBytesPerPixel();
        te.afbc = t.afbc.compressed;
        te.afbcWriteBytesPerPixel = t.afbc.compressed && t.pixels ? (t.afbc.headerBytes + t.afbc.bodyBytes) / double(t.pixels)
                                                                  : double(t.bytesPerPixel);
        te.afbcSolidFraction = t.afbc.superblocks ? double(t.afbc.solidSuperblocks) / double(t.afbc.superblocks) : 0.0;
        te.afbcUncompressedFraction = t.afbc.subblocks ? double(t.afbc.uncompressedSubblocks) / double(t.afbc.subblocks) : 0.0;
        te.dccUncompressedFraction = t.dcc.blocks ? double(t.dcc.uncompressedBlocks) / double(t.dcc.blocks) : 0.0;
        e.targets.push_back(te);
    }
    const Sums s = targetSums(compression);
    const double depth = depthAttachmentBytes(layout);
    const double lightBuffers = lightBufferBytesPerPixel(layout);
    const double pixels = 1920.0 * 1080.0;
    const double L = lighting.readsPerPixel;
    const FrameTraffic nominal = computeFrameTraffic(layout, 1920, 1080, 1, lighting);
    // Every class: the light buffers' traffic (deferred lighting) and the resolve's fetches
    // (visibility buffer) as the nominal model has them; the lit output written once.
    const double shared = nominal.lightBufferBytes + nominal.vertexFetchBytes + nominal.litOutputBytes;
    e.nominalBytesPerPixel = s.nominal + depth + lightBuffers;
    e.nominalTrafficBytes = nominal.totalBytes + nominal.litOutputBytes;
    e.nominalGbPerSecond = e.nominalTrafficBytes * 60.0 / 1e9;

    ClassTraffic dcc;
    dcc.gpuClass = "desktop-dcc";
    dcc.bytesPerPixel = s.dcc + depth + lightBuffers;
    dcc.trafficBytes = pixels * (s.dcc + depth) * (1.0 + L) + shared;
    dcc.assumes = "colour targets as the DCC model stores them (256-byte blocks in 32-byte sectors, the model coder: "
                  "an estimate, see docs/bandwidth.md); depth uncompressed; written once, read " +
                  lighting.text() + "; lit output RGBA16F written once";
    ClassTraffic afbc;
    afbc.gpuClass = "mali-afbc";
    afbc.bytesPerPixel = s.afbcRead + depth + lightBuffers;
    afbc.trafficBytes = pixels * ((s.afbcWrite + depth) + (s.afbcRead + depth) * L) + shared;
    afbc.assumes = "geometry and lighting as two render passes; AFBC on targets of <= 32-bit texels (header and body "
                   "written; body and the header's line read), wider targets and depth uncompressed; read " +
                   lighting.text() + "; lit output RGBA16F written once";
    e.tile = tileFits(layout, kLitOutputBytesPerPixel);
    ClassTraffic tile;
    tile.gpuClass = "tile-subpass";
    const TileFit* fit = nullptr;
    for (const TileFit& f : e.tile)
        if (f.family == kTileSubpassFamily) fit = &f;
    if (fit && fit->fits) {
        tile.bytesPerPixel = 0.0;
        tile.trafficBytes = nominal.vertexFetchBytes + nominal.litOutputBytes;
        tile.assumes = "geometry and lighting as subpasses of one render pass on an Apple A11 (64 bytes of colour per "
                       "pixel): the G-buffer (" + std::to_string(fit->colourBytesPerPixel) +
                       " B/px with the lit output) fits and never leaves the chip; only the lit output is written";
    } else {
        tile.bytesPerPixel = e.nominalBytesPerPixel;
        tile.trafficBytes = e.nominalTrafficBytes;
        tile.assumes = "Apple A11 (64 bytes of colour per pixel): the G-buffer (" +
                       std::to_string(fit ? fit->colourBytesPerPixel : 0) +
                       " B/px with the lit output) does not fit; two render passes, its nominal bytes written and read " +
                       lighting.text();
    }
    for (ClassTraffic* c : {&dcc, &afbc, &tile}) {
        c->gbPerSecond = c->trafficBytes * 60.0 / 1e9;
        e.classes.push_back(*c);
    }
    return e;
}

}  // namespace gbl
