#pragma once
// GpuEvaluator's state and the pieces its whole-frame (gpu_evaluator.cpp) and banded
// (gpu_evaluator_bands.cpp) paths share: where each reduction's fields land in the result
// buffer, the passes of one run, and RunMetrics assembled from the reduced fields and the
// histograms. Internal to gbl_evaluate.
#include <array>
#include <initializer_list>
#include <optional>
#include <vector>

#include "eval_device.h"
#include "gpu_evaluator.h"
#include "gpu_flip.h"

namespace gbl::evaluate {

// Result offsets of the reductions (eval_device reduce), one submission per run (or band).
inline constexpr uint32_t kImageFields = 15, kImageAt = 0;
inline constexpr uint32_t kRefLuminanceAt = 16;  // banded reference statistics: its maximum luminance
inline constexpr uint32_t kAttrs = 8, kPerAttr = 11, kAttrFields = kAttrs * kPerAttr + 5, kAttrAt = 96;
inline constexpr uint32_t kFlipFields = 5, kFlipAt = 200, kHdrFlipAt = 210;
// The material layers (eval_layers.comp.glsl): mode 0's attribute and class fields, mode 1's
// LDR-FLIP sums per layer class.
inline constexpr uint32_t kLayerAttrs = 7, kLayerFields = kLayerAttrs * kPerAttr + 16, kLayerAt = 220;
inline constexpr uint32_t kLayerFlipFields = 4, kLayerFlipAt = 320;
inline constexpr uint32_t kResultDoubles = 4 * kMaxFields;
inline constexpr int kTile = 8;

using FieldMask = std::array<uint32_t, 4>;
FieldMask maskOf(std::initializer_list<uint32_t> fields);
FieldMask imageMaxMask();      // the image pass's maxima (|d|, reference value)
FieldMask attributeMaxMask();  // the attribute pass's maxima (per attribute and class)
FieldMask layerMaxMask();      // the layer pass's (mode 0) maxima

// What one run's error passes need (pass 1 of evaluate(); the first half of a band).
struct ErrorPassSettings {
    bool images = false, noise = false, attributes = false, crops = false;
    bool layers = false;  // both sides have layer images (and surfaces): eval_layers.comp.glsl
    float exposure = 1.0f, amplification = 8.0f, heatMax = 0.1f, floorY = 1e-6f;
};
ErrorPassSettings errorPassSettings(const GpuEvalOptions& o, float exposure, float floorY);
// Image errors (with the 8-bit images), attribute errors and the crop tiles, reduced into their
// result fields; the histograms add up (the caller clears them once per run).
void recordErrorPasses(VkCommandBuffer cmd, const EvalDevice& d, const ErrorPassSettings& s);
// LDR-FLIP (and its 8-bit image), then HDR-FLIP over `range` when hdrFlip, reduced into their fields.
// `layers`: LDR-FLIP summed per layer class too (the reference's layers bound).
void recordFlipPasses(VkCommandBuffer cmd, const EvalDevice& d, GpuFlip& flip, float exposure, bool images,
                      bool hdrFlip, const FlipExposureRange& range, bool layers = false);
// The normal-error picture's scale: the run's p99 normal angle (both classes), at least minDeg.
float normalImageScale(const double* result, const EvalDevice& d, float minDeg);
// Every RunMetrics number from the result fields (laid out as above, over the whole frame of
// n pixels) and the device's histograms (over the whole frame).
RunMetrics assembleMetrics(const double* result, const EvalDevice& d, size_t n, bool attributes, bool hdrFlip,
                           bool noise, const FlipExposureRange& range, bool layers = false);
// The worst regions from the mean relative error of the frame's 8 x 8 tiles (tw x th).
std::vector<Crop> worstCrops(const Image& tiles, uint32_t width, uint32_t height, int cropSize, int cropCount);
// A user error unless `r` (and its surfaces, where set) are w x h.
void checkRender(const DeviceRender& r, uint32_t w, uint32_t h, const char* what);
// Packed 8-bit pixels (R | G << 8 | B << 16) `rows` x width from `packed` into rows [row, row + rows) of `out`.
void unpackRows(const uint32_t* packed, uint32_t rows, Image8& out, uint32_t row);

}  // namespace gbl::evaluate

namespace gbl {

struct GpuEvaluator::State {
    State(const VulkanContext& ctx, uint32_t w, uint32_t h, uint32_t rows) : device(ctx, w, h, rows), flip(device) {}
    evaluate::EvalDevice device;
    evaluate::GpuFlip flip;
    // The reference's statistics, from setReference or from the reference bands.
    DeviceRender reference;  // setReference's (whole frames); null after reference bands
    // Which images `reference` was (GpuImage::serial: hdr, then the surfaces; 0 where null), so a
    // new view's reference is told from the last one even where its structs reuse their addresses.
    std::array<uint64_t, 5> referenceSerials{};
    float exposure = 1.0f;
    float floorY = 1e-6f;
    bool noise = false;
    const Image* noiseSource = nullptr;
    FlipExposureRange hdrRange;
    bool statsReady = false;

    // beginReferenceBands .. endReferenceBands. Host memory: the frame's reference luminance,
    // 4 bytes per pixel, for the exact median (freed by endReferenceBands).
    struct ReferenceBands {
        bool active = false;
        uint32_t nextRow = 0;
        double sumY = 0.0, countY = 0.0, maxY = 0.0;
        std::vector<float> luminance;
    } referenceBands;

    // beginRun .. finishRun. Host memory, whole frame, only what the 8-bit images need: with
    // options.images, five RGB images (render, reference, difference, heat, FLIP; 3 B/px each)
    // and, with surfaces, the normal angles as floats (4 B/px) until the last band maps them into
    // the sixth image (3 B/px): 19 B/px during the run, 22 B/px at its end; plus the 8 x 8 tiles'
    // means (4 B per 64 px) with crops. Without images: nothing per pixel.
    struct Run {
        bool active = false;
        GpuEvalOptions options;
        evaluate::ErrorPassSettings pass;
        uint32_t nextRow = 0;
        uint32_t bands = 0;
        std::array<double, evaluate::kResultDoubles> result{};
        GpuErrorImages images;
        std::vector<float> normalAngles;
        Image tiles;
    } run;
};

}  // namespace gbl
