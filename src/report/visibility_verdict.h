#pragma once
// "G-buffer or visibility buffer?" on the user's own scene: the report's answer, generated from
// the runs. It sets the best G-buffer layout (lowest mean FLIP among the runs of the first IBL
// mode that are neither the reference nor a visibility buffer) against the visibility-buffer
// layout of least traffic, on image error (FLIP, PSNR), attribute error (normal angle, base
// colour) and the bandwidth model's traffic per pixel at 1920x1080, 1 sample
// (src/measure/bandwidth.h): the G-buffer's targets and depth, written and read; the visibility
// buffer's ids and depth, written and read, and apart from them its resolve's vertex fetches,
// MODELLED as an upper bound (no cache reuse). Written into report.json
// ("gbuffer_or_visibility") and report.html (section #gbuffer-or-visibility).
#include <optional>
#include <string>

#include "report_model.h"

namespace gbl {

struct VisibilityVerdict {
    std::string iblMode;
    std::string gbufferLayout, visibilityLayout;
    double gbufferFlip = 0, visibilityFlip = 0;
    double gbufferPsnr = 0, visibilityPsnr = 0;  // tone-mapped, dB
    std::optional<double> gbufferNormalDegrees, visibilityNormalDegrees;  // mean angle
    std::optional<double> gbufferBaseColorDeltaE, visibilityBaseColorDeltaE;  // mean CIEDE2000
    double gbufferBytesPerPixel = 0;         // targets + depth, written and read
    double visibilityIdBytesPerPixel = 0;    // ids + depth, written and read
    double visibilityVertexBytesPerPixel = 0;  // the resolve's vertex fetches, modelled upper bound
    std::string answer;  // the generated sentence
};

// nullopt unless the report holds at least one successful G-buffer run and one visibility run
// (other than the reference) under the same IBL mode, each with image errors and 1080p traffic.
std::optional<VisibilityVerdict> gbufferOrVisibility(const ReportModel& model);

}  // namespace gbl
