#include "visibility_verdict.h"

#include <cstdio>

namespace gbl {

namespace {

const FrameTraffic* frame1080(const RunReport& r) {
    for (const FrameTraffic& f : r.bandwidth)
        if (f.width == 1920 && f.height == 1080 && f.samples == 1) return &f;
    return nullptr;
}

bool usable(const RunReport& r, const std::string& reference, const std::string& mode) {
    return r.status == RunStatus::Ok && r.image && frame1080(r) && !r.isLightingComparison() && r.layout != reference &&
           r.iblMode == mode;
}

std::optional<double> meanOf(const RunReport& r, ErrorAttribute a) {
    const auto& all = r.attributes[a].all;
    return all ? std::optional<double>(all->error.mean) : std::nullopt;
}

std::string format(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

}  // namespace

std::optional<VisibilityVerdict> gbufferOrVisibility(const ReportModel& model) {
    if (model.run.iblModes.empty()) return std::nullopt;
    const std::string mode = model.run.iblModes.front();
    const RunReport* gbuffer = nullptr;
    const RunReport* visibility = nullptr;
    for (const RunReport& r : model.runs) {
        if (!usable(r, model.reference.layout, mode)) continue;
        if (r.isVisibilityBuffer()) {
            if (!visibility || frame1080(r)->totalBytes < frame1080(*visibility)->totalBytes) visibility = &r;
        } else if (!gbuffer || r.image->flipMean < gbuffer->image->flipMean) {
            gbuffer = &r;
        }
    }
    if (!gbuffer || !visibility) return std::nullopt;
    VisibilityVerdict v;
    v.iblMode = mode;
    v.gbufferLayout = gbuffer->layout;
    v.visibilityLayout = visibility->layout;
    v.gbufferFlip = gbuffer->image->flipMean;
    v.visibilityFlip = visibility->image->flipMean;
    v.gbufferPsnr = gbuffer->image->psnrToneMapped;
    v.visibilityPsnr = visibility->image->psnrToneMapped;
    v.gbufferNormalDegrees = meanOf(*gbuffer, ErrorAttribute::Normal);
    v.visibilityNormalDegrees = meanOf(*visibility, ErrorAttribute::Normal);
    v.gbufferBaseColorDeltaE = meanOf(*gbuffer, ErrorAttribute::BaseColor);
    v.visibilityBaseColorDeltaE = meanOf(*visibility, ErrorAttribute::BaseColor);
    const FrameTraffic& g = *frame1080(*gbuffer);
    const FrameTraffic& s = *frame1080(*visibility);
    const double pixels = 1920.0 * 1080.0;
    v.gbufferBytesPerPixel = (g.totalBytes - g.vertexFetchBytes) / pixels;
    v.visibilityIdBytesPerPixel = (s.totalBytes - s.vertexFetchBytes) / pixels;
    v.visibilityVertexBytesPerPixel = s.vertexFetchBytes / pixels;

    // The answer: error first (what the user sees), then traffic, with the vertex fetches'
    // break-even (the cache hit rate at which the visibility buffer moves as many bytes).
    const bool lessError = v.visibilityFlip <= v.gbufferFlip;
    const double margin = v.gbufferBytesPerPixel - v.visibilityIdBytesPerPixel;
    std::string a = "On this scene, " + v.visibilityLayout + (lessError ? " loses less than " : " loses more than ") +
                    v.gbufferLayout + ", the best G-buffer layout here (FLIP " + format("%.4f", v.visibilityFlip) +
                    " vs " + format("%.4f", v.gbufferFlip) + "), and writes and reads " +
                    format("%.0f", v.visibilityIdBytesPerPixel) + " B/pixel of ids and depth against the G-buffer's " +
                    format("%.0f", v.gbufferBytesPerPixel) + " B/pixel; ";
    if (margin <= 0) {
        a += "so the G-buffer moves fewer bytes even before the visibility buffer's vertex fetches";
    } else if (margin >= v.visibilityVertexBytesPerPixel) {
        a += "even with every vertex fetch of its resolve missing the cache (" +
             format("%.0f", v.visibilityVertexBytesPerPixel) + " B/pixel, modelled) it moves fewer bytes";
    } else {
        a += "its resolve's vertex fetches (up to " + format("%.0f", v.visibilityVertexBytesPerPixel) +
             " B/pixel with no cache reuse, modelled) keep it ahead while caches serve more than " +
             format("%.0f", 100.0 * (1.0 - margin / v.visibilityVertexBytesPerPixel)) + "% of them";
    }
    a += ". Answer: ";
    if (lessError && margin > 0)
        a += "the visibility buffer.";
    else if (!lessError && margin <= 0)
        a += "the G-buffer (" + v.gbufferLayout + ").";
    else if (lessError)
        a += "the visibility buffer for quality, the G-buffer (" + v.gbufferLayout + ") for bandwidth.";
    else
        a += "the G-buffer (" + v.gbufferLayout + ") for quality, the visibility buffer for bandwidth.";
    v.answer = a;
    return v;
}

}  // namespace gbl
