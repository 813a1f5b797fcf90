#pragma once
// What a comparison report holds: the data behind report.html, report.json and report.csv.
// Plain structs, filled by the compare command; docs/report-schema.md documents each field as it
// appears in report.json (units and meaning). Image paths are relative to the report directory
// ("" = not written). Error statistics reuse the metrics module's ScalarStats (count, mean, rms,
// nearest-rank p99, max) and the bandwidth module's FrameTraffic.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bandwidth.h"
#include "effective_bandwidth.h"
#include "layout.h"
#include "layout_atlas.h"
#include "metrics.h"

namespace gbl {

struct ReportDevice {
    std::string name;    // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string driver;  // driver name and version
    std::string type;    // "cpu", "discrete-gpu", "integrated-gpu", ...
};

struct ReportRunInfo {
    std::string scene;        // scene file, or the built-in scene's name
    std::string environment;  // environment map file, or "built-in procedural sky"
    int width = 0, height = 0;
    ReportDevice device;
    std::string date;         // when the comparison ran, ISO 8601 (e.g. 2024-05-01T12:00:00Z)
    std::string commandLine;  // the gbufferlab command line, as typed
    std::vector<std::string> iblModes;
    double exposure = 1.0;    // the tone map's exposure (compare --exposure), the first view's when metered
    // "fixed" (compare --exposure) or "ue4-histogram" (each view's metered from its reference,
    // auto_exposure.h); viewExposures: each view's (empty when fixed).
    std::string exposureMethod = "fixed";
    std::vector<double> viewExposures;
    // Per view: the fraction of its pixels the scene's geometry covers (the reference's alpha).
    std::vector<double> viewCoverage;
    // Per view: why it had nothing to measure (measure/view_content.h), "" when it was measured.
    // A view not measured is left out of every mean, rank and verdict. Empty: every view measured.
    std::vector<std::string> viewNotMeasured;
    std::vector<std::string> notes;  // free-form remarks (e.g. "12 ringing texels clamped to 0")
    std::vector<std::string> views;  // compare --views: how each camera was placed ("scene camera", ...)
    // The pixel type of the EXR files written (render.exr, errors.exr, the reference's):
    // "half" (compare's default) or "float32" (compare --float32-exr). The numbers in the report
    // are computed in 32-bit float either way.
    std::string exrPrecision = "float32";
    // compare --temporal N (image/temporal_resolve.h): frames per view, their sub-pixel jitter
    // (pixels, x right / y down) and the resolve ("mean" or "exp"). 1: one frame, no jitter.
    int temporalFrames = 1;
    std::string temporalResolve = "mean";
    std::vector<std::pair<double, double>> temporalJitter;
    // compare --lighting (measure/effective_bandwidth.h LightingModel::text): how the lighting
    // pass reads the G-buffer in every traffic figure ("tiled": once per pixel).
    std::string lighting = "tiled";
};

struct ReferenceImage {
    std::string iblMode;
    std::string render;  // render.png of the reference under this IBL mode
    std::string renderExr;  // render.exr: its linear HDR render (32-bit float RGBA, A = coverage)
    std::string hdrPreview;  // the viewer's log-encoded 8-bit preview (tone_map.h logEncodeForPreview)
};

struct ReportReference {
    std::string layout;                 // the float reference layout's name
    std::vector<ReferenceImage> images;  // one per IBL mode
    const ReferenceImage* find(const std::string& iblMode) const {
        for (const ReferenceImage& image : images)
            if (image.iblMode == iblMode) return &image;
        return nullptr;
    }
};

// NotMeasured: the run rendered, but no view had anything to measure (measure/view_content.h):
// it has no image errors and counts in no mean, rank or verdict; RunReport::notMeasured says why.
enum class RunStatus : uint8_t { Ok, Failed, NotMeasured };
inline const char* runStatusName(RunStatus s) {
    return s == RunStatus::Ok ? "ok" : s == RunStatus::Failed ? "failed" : "not-measured";
}

struct BytesPerPixel {
    int targets = 0;       // G-buffer colour targets
    int depth = 0;         // depth-stencil attachment
    int lightBuffers = 0;  // deferred lighting's light buffers (0 for deferred shading)
    int total = 0;         // targets + depth + lightBuffers: the table's "bytes/pixel"
};
// Fills all four from computeBandwidth's result (total as stated above).
inline BytesPerPixel bytesPerPixelOf(const BandwidthReport& bandwidth) {
    return {bandwidth.targetBytesPerPixel, bandwidth.depthBytesPerPixel, bandwidth.lightBufferBytesPerPixel,
            bandwidth.targetBytesPerPixel + bandwidth.depthBytesPerPixel + bandwidth.lightBufferBytesPerPixel};
}

// The G-buffer attributes whose error is measured, in report order: the eight of every scene,
// then the seven of the material layers (issue 40), measured only in a scene with layers and
// only over the pixels whose reference carries the layer (errorAttributeLayerClass).
enum class ErrorAttribute : uint8_t {
    Normal, BaseColor, DiffuseColor, SpecularColor, Roughness, Metallic, Occlusion, Depth,
    Coat, CoatRoughness, CoatNormal, SheenColor, SheenRoughness, AnisotropyStrength, AnisotropyDirection
};
constexpr size_t kErrorAttributeCount = 8;  // of kErrorAttributes: every scene's
constexpr std::array<ErrorAttribute, kErrorAttributeCount> kErrorAttributes = {
    ErrorAttribute::Normal,        ErrorAttribute::BaseColor, ErrorAttribute::DiffuseColor,
    ErrorAttribute::SpecularColor, ErrorAttribute::Roughness, ErrorAttribute::Metallic,
    ErrorAttribute::Occlusion,     ErrorAttribute::Depth};
constexpr size_t kLayerErrorAttributeCount = 7;
constexpr std::array<ErrorAttribute, kLayerErrorAttributeCount> kLayerErrorAttributes = {
    ErrorAttribute::Coat,           ErrorAttribute::CoatRoughness,      ErrorAttribute::CoatNormal,
    ErrorAttribute::SheenColor,     ErrorAttribute::SheenRoughness,     ErrorAttribute::AnisotropyStrength,
    ErrorAttribute::AnisotropyDirection};
constexpr size_t kAllErrorAttributeCount = kErrorAttributeCount + kLayerErrorAttributeCount;
constexpr std::array<ErrorAttribute, kAllErrorAttributeCount> kAllErrorAttributes = {
    ErrorAttribute::Normal,        ErrorAttribute::BaseColor,          ErrorAttribute::DiffuseColor,
    ErrorAttribute::SpecularColor, ErrorAttribute::Roughness,          ErrorAttribute::Metallic,
    ErrorAttribute::Occlusion,     ErrorAttribute::Depth,              ErrorAttribute::Coat,
    ErrorAttribute::CoatRoughness, ErrorAttribute::CoatNormal,         ErrorAttribute::SheenColor,
    ErrorAttribute::SheenRoughness, ErrorAttribute::AnisotropyStrength, ErrorAttribute::AnisotropyDirection};
inline bool errorAttributeIsLayer(ErrorAttribute a) { return size_t(a) >= kErrorAttributeCount; }
// "normal", "base_color", ... (the JSON / CSV keys)
inline const char* errorAttributeName(ErrorAttribute a) {
    constexpr const char* kNames[] = {"normal",       "base_color",     "diffuse_color",   "specular_color",
                                      "roughness",    "metallic",       "occlusion",       "depth",
                                      "coat",         "coat_roughness", "coat_normal",     "sheen_color",
                                      "sheen_roughness", "anisotropy_strength", "anisotropy_direction"};
    return kNames[size_t(a)];
}
// "degrees" (angle), "delta_e_2000" (CIEDE2000), "absolute" (|test - reference|),
// "relative" (|test - reference| / reference)
inline const char* errorAttributeUnit(ErrorAttribute a) {
    switch (a) {
        case ErrorAttribute::Normal:
        case ErrorAttribute::CoatNormal:
        case ErrorAttribute::AnisotropyDirection: return "degrees";
        case ErrorAttribute::BaseColor:
        case ErrorAttribute::DiffuseColor:
        case ErrorAttribute::SpecularColor:
        case ErrorAttribute::SheenColor: return "delta_e_2000";
        case ErrorAttribute::Depth: return "relative";
        default: return "absolute";
    }
}
// Base / diffuse / specular / sheen colour: measured in CIEDE2000, with an RMSE of linear RGB too.
inline bool errorAttributeIsColor(ErrorAttribute a) {
    return a == ErrorAttribute::BaseColor || a == ErrorAttribute::DiffuseColor || a == ErrorAttribute::SpecularColor ||
           a == ErrorAttribute::SheenColor;
}
// The material class (measure/layer_classes.h) a layer attribute is measured over: "coated",
// "sheen" or "anisotropic"; "" for the eight of every scene (all covered pixels).
inline const char* errorAttributeLayerClass(ErrorAttribute a) {
    switch (a) {
        case ErrorAttribute::Coat:
        case ErrorAttribute::CoatRoughness:
        case ErrorAttribute::CoatNormal: return "coated";
        case ErrorAttribute::SheenColor:
        case ErrorAttribute::SheenRoughness: return "sheen";
        case ErrorAttribute::AnisotropyStrength:
        case ErrorAttribute::AnisotropyDirection: return "anisotropic";
        default: return "";
    }
}

// Errors of one attribute over one set of pixels.
struct AttributeStats {
    ScalarStats error;          // in errorAttributeUnit: angle, CIEDE2000, |difference|, |d|/reference
    std::optional<double> rmse;  // colours only: RMSE of the linear RGB values (pooled over channels)
};

// One attribute, over all covered pixels and per material class; absent when not applicable
// (the attribute is not measured, or no pixel of that class is covered). A layer attribute's
// pixels are those of its layer class only (errorAttributeLayerClass): `all` is all of those.
struct AttributeErrors {
    std::optional<AttributeStats> all;
    std::optional<AttributeStats> metal;       // pixels of metal materials (as the compare command classes them)
    std::optional<AttributeStats> dielectric;  // pixels of dielectric (non-metal) materials
    bool empty() const { return !all && !metal && !dielectric; }
};

struct AttributeErrorTable {
    std::array<AttributeErrors, kAllErrorAttributeCount> byAttribute{};  // the layers' empty without layers
    AttributeErrors& operator[](ErrorAttribute a) { return byAttribute[size_t(a)]; }
    const AttributeErrors& operator[](ErrorAttribute a) const { return byAttribute[size_t(a)]; }
};

// Errors of the lit image over the pixels of one material class (covered in both renders).
struct ImageClassErrors {
    int64_t pixels = 0;
    double relLuminanceMean = 0.0;  // mean |Y_t - Y_r| / max(Y_r, floor) (run_metrics.h relativeLuminanceError)
    double rmseLinear = 0.0;        // linear HDR, pooled over RGB
    double flipMean = 0.0;          // LDR-FLIP
    // The reference's own estimated noise over the same pixels, in the unit of relLuminanceMean
    // (present when the reference is a progressive ground truth).
    std::optional<double> referenceNoise;
    // Layer classes, CPU evaluation only: LDR-FLIP's mean per tile over the class's pixels, the
    // units of the class's significance test (not written to report.json).
    std::vector<float> flipTiles;
};

// How the ground-truth reference converged (render/renderer.h GroundTruthStats).
struct GroundTruthConvergence {
    int batches = 0;
    int samplesPerPixel = 0;
    double noiseTarget = 0.0;        // mean relative noise asked for
    double meanRelativeNoise = 0.0;  // reached, over covered pixels
    bool targetMet = false;
    double gpuMs = 0.0;              // lighting pass, all batches (timestamps)
};

// Errors of the lit image against the reference render.
struct ImageErrors {
    double rmseLinear = 0.0;      // linear HDR radiance, pooled over RGB
    double psnrLinear = std::numeric_limits<double>::infinity();      // dB, peak = reference maximum; +inf = identical
    double rmseToneMapped = 0.0;  // tone-mapped, sRGB-encoded [0,1]
    double psnrToneMapped = std::numeric_limits<double>::infinity();  // dB, peak 1; +inf = identical
    double maxAbs = 0.0;          // largest |test - reference|, linear HDR
    double p99Abs = 0.0;          // nearest-rank 0.99 of |test - reference|, linear HDR
    double flipMean = 0.0;        // LDR-FLIP, 0 (same) .. 1
    double flipMedian = 0.0;
    // LDR-FLIP's mean per tile of measure/significance.h's grid: the units of the significance test
    // (CPU evaluation only; not written to report.json).
    std::vector<float> flipTiles;
    // HDR-FLIP over the linear images (absent with --no-hdr-flip) and the exposures it took.
    std::optional<double> hdrFlipMean;
    int hdrFlipExposures = 0;
    // Per material class (absent in reports written before they existed).
    std::optional<ImageClassErrors> covered, metal, dielectric;
    // Per layer class (measure/layer_classes.h: a pixel may be in several); absent in a scene
    // without layers, and a class without pixels.
    std::optional<ImageClassErrors> coated, sheen, anisotropic, plain;
};
// The layer classes' members of ImageErrors with their names, in kLayerClasses order.
using ImageClassMember = std::optional<ImageClassErrors> ImageErrors::*;
inline const std::array<std::pair<const char*, ImageClassMember>, 4>& layerImageClasses() {
    static const std::array<std::pair<const char*, ImageClassMember>, 4> kClasses = {{
        {"coated", &ImageErrors::coated},
        {"sheen", &ImageErrors::sheen},
        {"anisotropic", &ImageErrors::anisotropic},
        {"plain", &ImageErrors::plain}}};
    return kClasses;
}

struct PassTimes {
    double gbufferMs = 0.0;   // geometry (G-buffer) pass
    double lightingMs = 0.0;  // lighting pass
    std::string device;       // the device they were measured on
};

struct ReportCrop {
    int x = 0, y = 0, w = 0, h = 0;  // pixels in the render
    std::string reference, layout, heat;  // PNG crops: reference render, this layout's render, heat map
};

struct RunImages {
    std::string render;        // render.png (tone-mapped)
    std::string renderExr;     // render.exr (linear HDR, 32-bit float RGBA, A = coverage)
    std::string hdrPreview;    // render_log.png: the viewer's HDR preview (tone_map.h logEncodeForPreview)
    std::string errorHeatmap;  // error_heatmap.png
    std::string flip;          // flip.png
    std::string normalError;   // normal_error.png
    std::string difference;    // difference.png (amplified)
    std::string errorsExr;     // errors.exr (per-pixel errors, float)
    std::vector<ReportCrop> crops;
};

// One layout rendered under one IBL mode.
// One camera of a run (compare --views): the run's metrics measured from that view alone.
struct ViewMetrics {
    AttributeErrorTable attributes;
    std::optional<ImageErrors> image;
};

// compare --temporal N (N > 1): the first frame of the sequence measured alone, against the
// reference's first frame (both jittered by the sequence's first offset), beside the resolved
// images the run's own `attributes` and `image` are measured on. `views`: per view, as
// RunReport::views; after the last view, `attributes` and `image` are their mean.
struct SingleFrameMetrics {
    AttributeErrorTable attributes;
    std::optional<ImageErrors> image;
    std::vector<ViewMetrics> views;
};

struct RunReport {
    std::string layout;    // name
    std::string title;
    std::string source;    // citation text (Source::text())
    std::string pipeline;  // "deferred-shading" / "deferred-lighting"
    std::string iblMode;
    RunStatus status = RunStatus::Ok;
    std::string error;     // why it failed ("" when ok)
    // The views left out of its metrics and why ("view 1: the camera sees no geometry ..."), "" when
    // every view was measured; with no view measured its status is NotMeasured.
    std::string notMeasured;
    BytesPerPixel bytesPerPixel;
    std::vector<FrameTraffic> bandwidth;  // one per (resolution, MSAA samples)
    AttributeErrorTable attributes;
    std::optional<ImageErrors> image;  // absent when the run failed before measuring
    std::optional<PassTimes> times;    // absent when not measured
    // The reference it was measured against is a progressive ground truth: how far it converged.
    std::optional<GroundTruthConvergence> groundTruth;
    RunImages images;     // the first view's (compare writes per-pixel images for view 0 only)
    // compare --views N: each view's metrics, in the order of ReportRunInfo::views. When present,
    // `attributes` and `image` above hold their mean over the views (view_stats.h averageViews),
    // and every writer reports each metric's spread over them. Empty: a single view.
    std::vector<ViewMetrics> views;
    // compare --temporal N (N > 1): `attributes` are then the errors of the temporal mean of each
    // decoded attribute (normals: the normalised mean) against the reference's, and `image` the
    // resolved image's errors; this holds the first frame's (absent at --temporal 1).
    std::optional<SingleFrameMetrics> singleFrame;

    // A lighting comparison of `compare` (the reference layout under one IBL mode against the same
    // layout under ground truth, named "reference (<mode> vs ground-truth)"): its errors are the
    // lighting approximation's, not a layout's against the float reference.
    bool isLightingComparison() const {
        return layout.rfind("reference (", 0) == 0 && layout.find(" vs ") != std::string::npos;
    }

    // A visibility buffer's run (pipeline = "visibility-buffer"): its bytes leave out the vertex
    // fetch of the resolve, which the verdicts and the plot count apart.
    bool isVisibilityBuffer() const { return pipeline == pipelineName(Pipeline::VisibilityBuffer); }

    // Bandwidth as GPUs pay it (report_bandwidth.h): the compressed sizes of the words the run's
    // view 0 wrote, per GPU class; absent when not measured (a failed run, compare --no-compression).
    std::optional<EffectiveBandwidth> effective;

    // The 1920x1080, 1-sample frame's traffic at 60 fps in GB/s; nullopt when not in `bandwidth`.
    std::optional<double> gigabytesPerSecond1080p60() const {
        for (const FrameTraffic& frame : bandwidth)
            if (frame.width == 1920 && frame.height == 1080 && frame.samples == 1) return frame.gigabytesPerSecond(60.0);
        return std::nullopt;
    }
};

// The seed's comparison figure (ibl_figure.h): rows = IBL modes, columns = material balls.
struct IblFigureRow {
    std::string iblMode;
    std::string caption;                   // the text printed under the row in the PNG
    std::optional<double> metalError;      // mean relative luminance error vs ground truth, metal balls
    std::optional<double> dielectricError;
    std::optional<double> metalNoise;      // ground truth row: its own noise, same unit
    std::optional<double> dielectricNoise;
};
struct IblFigure {
    std::string png;                       // relative to the report directory
    std::vector<std::string> columns;      // e.g. "metal r=0.05"
    std::vector<IblFigureRow> rows;
};

// Which layouts' error differences are significant, and the tied ranks that follow
// (rank_significance.h computes it; absent in reports written before it existed).
struct PairSignificance {
    std::string better, worse;  // by mean error
    std::string iblMode;
    double meanDifference = 0.0;  // mean error of `worse` - of `better` (>= 0)
    int units = 0;                // paired tiles (or views) the test ran on
    double pValue = 1.0;
    bool significant = false;     // pValue < kSignificanceAlpha
};

struct RankRange {
    std::string layout, iblMode;
    double meanError = 0.0;
    int rank = 0;       // 1 + the layouts of lower mean error
    int low = 0, high = 0;
    std::string text() const { return low == high ? std::to_string(low) : std::to_string(low) + "-" + std::to_string(high); }
};

struct SignificanceReport {
    std::string method;  // one sentence: the test, its units, alpha, resamples
    std::vector<PairSignificance> pairs;
    std::vector<RankRange> ranks;  // by mode, then rank
    const RankRange* find(const std::string& layout, const std::string& iblMode) const;
};

// A report written after an interruption (SIGINT, SIGTERM) lists only the runs that finished:
// this says so, and which runs were asked for and never ran (report.json `status`,
// `interruption`; report.csv's `report_status`; the verdict names them where they fit).
struct PlannedRun {
    std::string layout, iblMode;
    int bytesPerPixel = 0;      // the table's
    double countedBytes = 0.0;  // what a verdict holds against a budget (budget_verdict.h)
};
struct ReportInterruption {
    std::string signal;  // "SIGINT" / "SIGTERM"
    int runsFinished = 0, runsPlanned = 0;
    std::vector<PlannedRun> notRun;  // every layout and mode without a finished run
};

struct ReportModel {
    ReportRunInfo run;
    std::optional<ReportInterruption> interruption;  // absent: the report is complete
    ReportReference reference;
    std::vector<RunReport> runs;
    std::optional<IblFigure> iblFigure;
    // The atlas (report_atlas.h): one entry per compared layout, from its file; empty in reports
    // written before it existed.
    std::vector<AtlasEntry> atlas;
    std::optional<SignificanceReport> significance;
    // The same test per layer class (rank_significance.h), on LDR-FLIP over the class's pixels:
    // (class name, report) for each layer class some run measured; empty in a scene without layers.
    std::vector<std::pair<std::string, SignificanceReport>> classSignificance;
    // Some run measured the material layers: the layer columns of report.csv are written.
    bool hasLayerMetrics() const {
        for (const RunReport& r : runs) {
            for (ErrorAttribute a : kLayerErrorAttributes)
                if (!r.attributes[a].empty()) return true;
            if (r.image)
                for (const auto& [name, m] : layerImageClasses())
                    if ((*r.image).*m) return true;
        }
        return false;
    }
};

}  // namespace gbl
