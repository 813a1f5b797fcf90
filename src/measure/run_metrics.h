#pragma once
// The per-run comparison in numbers: one layout's decoded G-buffer and shaded image against the
// float reference's, under the same camera and lighting.
//
// Which pixels count
//  * Attribute errors: pixels covered in BOTH the reference and the test (coverage != 0).
//    Pixels covered in only one of them are counted in CoverageCounts, not measured.
//  * Material class: "metal" when the REFERENCE metallic > 0.5, else "dielectric".
//  * Image errors: every pixel (background/sky included), RGB only (alpha = coverage is
//    not compared): the final image is what users see.
//
// Units and choices
//  * normal:                 angle between the normals, degrees (atan2(|a x b|, a . b)). Pixels
//                            whose reference or test normal is zero / not finite are skipped
//                            (counted in AttributeMetrics::skipped).
//  * base/diffuse/specular:  CIEDE2000 (linear sRGB -> XYZ D65 -> CIELAB) per pixel, plus the
//                            RMSE of the linear RGB values pooled over the three channels.
//  * roughness/metallic/occlusion: |test - reference|.
//  * depth:                  |viewDepth_test - viewDepth_ref| / viewDepth_ref; pixels with a
//                            reference viewDepth <= 0 or not finite are skipped.
//  * Linear HDR PSNR:        peak = the largest reference RGB value over the whole image
//                            (metrics PsnrPeak::ReferenceMax; 1 if the image is black).
//  * Tone-mapped:            toneMapToSrgb8AsFloat(exposure) of both: the 8-bit sRGB values the
//                            written PNGs hold, as byte / 255, peak 1 (re-computable from the PNGs).
//  * maxAbs / p99Abs:        of |test - reference| over RGB samples, linear HDR (no exposure).
//  * LDR-FLIP:               flipLdr on those 8-bit tone-mapped images (default 67 pixels/degree):
//                            `gbufferlab diff reference.png render.png` gives the same number.
//  * HDR-FLIP:               flipHdr on the linear images, as written to render.exr (32-bit float)
//                            (exposure range from the reference;
//                            the exposure factor cancels out).
//
// Material layers (issue 40; only when both sides' surfaces have layers, SurfaceImages::hasLayers:
// a scene some material of which has clear coat, sheen or anisotropy; RunMetrics::layers and
// ShadedErrors::layerClasses are absent otherwise). Classes and per-pixel errors: layer_classes.h.
//  * Each layer attribute is measured over the covered pixels whose REFERENCE carries that layer
//    only (a pixel without a coat has no coat roughness to lose), split metal / dielectric as the
//    others:
//    coat, coat roughness, sheen roughness, anisotropy strength: |test - reference|;
//    coat normal: degrees between the coat normals the lighting shades with (0 = the base normal);
//    sheen colour: CIEDE2000 (+ RMSE of linear RGB), as base colour;
//    anisotropy direction: degrees between the tangent lines (layer_classes.h), [0, 90].
//  * Image errors per layer class (coated, sheen, anisotropic, plain; a pixel may be in several):
//    the class errors above (relative luminance, linear RMSE, LDR-FLIP, reference noise) over the
//    class's covered pixels, and LDR-FLIP's tile means over them (the significance test's units).
// The reference against itself gives exactly 0 everywhere and PSNR = +infinity.
#include <array>
#include <cstddef>
#include <optional>
#include <limits>
#include <vector>
#include <memory>

#include "flip.h"
#include "image.h"
#include "layer_classes.h"
#include "metrics.h"
#include "surface_images.h"

namespace gbl {

struct ClassStats {
    ScalarStats error;   // in the attribute's unit (see above)
    double rmse = 0.0;   // colours only: RMSE of linear RGB (0 for the other attributes)
};

struct AttributeMetrics {
    ClassStats all;
    ClassStats metal;       // reference metallic > 0.5
    ClassStats dielectric;  // the rest
    size_t skipped = 0;     // covered pixels left out (invalid normal / reference depth)
};

struct CoverageCounts {
    size_t pixels = 0;         // width x height
    size_t both = 0;           // covered in reference and test: the attribute pixels
    size_t referenceOnly = 0;  // mismatches: geometry lost by the layout
    size_t testOnly = 0;       // mismatches: geometry the reference does not have
    size_t metal = 0;          // of `both`
    size_t dielectric = 0;     // of `both`
    size_t excluded = 0;       // left out of every metric (RunMetricsOptions::excluded), of `pixels`
};

// Image errors over the pixels of one material class (covered in both, as the attributes; see
// "Which pixels count"): what the lit image loses on metals vs dielectrics.
struct ClassImageErrors {
    size_t pixels = 0;
    double relLuminanceMean = 0.0;  // mean of relativeLuminanceError over the class
    double rmseLinear = 0.0;        // linear HDR, pooled over RGB
    double flipMean = 0.0;          // LDR-FLIP
    // With RunMetricsOptions::referenceNoise: the reference's own noise over the class, in the
    // same unit as relLuminanceMean (mean of noise / max(Y_ref, floor)); -1 when not given.
    double referenceNoise = -1.0;
    // Layer classes only: LDR-FLIP's mean per tile of significance.h's grid over the class's pixels
    // (0 for a tile without any), the units of its significance test. Empty otherwise.
    std::vector<float> flipTiles;
};

struct ShadedErrors {
    double rmseLinear = 0.0;
    double psnrLinear = std::numeric_limits<double>::infinity();  // dB
    double peakLinear = 1.0;                                      // the PSNR peak used
    double rmseToneMapped = 0.0;
    double psnrToneMapped = std::numeric_limits<double>::infinity();  // dB, peak 1
    double maxAbs = 0.0;   // linear
    double p99Abs = 0.0;   // linear, nearest rank
    double meanAbs = 0.0;  // linear
    double flipMean = 0.0;    // LDR-FLIP
    double flipMedian = 0.0;  // LDR-FLIP, nearest-rank lower median
    std::vector<float> flipTiles;  // LDR-FLIP's mean per tile of significance.h's grid (the test's units)
    double hdrFlipMean = 0.0; // HDR-FLIP (0 when not computed)
    bool hdrFlipComputed = false;
    int hdrFlipExposures = 0;  // how many exposures HDR-FLIP evaluated (its cost is ~ this x LDR-FLIP)
    ClassImageErrors covered, metal, dielectric;  // covered = metal + dielectric pixels
    // Per layer class (kLayerClasses order: coated, sheen, anisotropic, plain); absent in a scene
    // without layers.
    std::optional<std::array<ClassImageErrors, kLayerClassCount>> layerClasses;
};

// The layers' attribute errors (see "Material layers" above): each over the pixels carrying it.
enum class LayerAttribute : uint8_t {
    Coat, CoatRoughness, CoatNormal, SheenColor, SheenRoughness, AnisotropyStrength, AnisotropyDirection
};
constexpr size_t kLayerAttributeCount = 7;
struct LayerMetrics {
    std::array<AttributeMetrics, kLayerAttributeCount> byAttribute{};
    AttributeMetrics& operator[](LayerAttribute a) { return byAttribute[size_t(a)]; }
    const AttributeMetrics& operator[](LayerAttribute a) const { return byAttribute[size_t(a)]; }
};
// The class whose pixels a layer attribute is measured over: coated for the coat's three.
inline LayerClass layerAttributeClass(LayerAttribute a) {
    switch (a) {
        case LayerAttribute::Coat:
        case LayerAttribute::CoatRoughness:
        case LayerAttribute::CoatNormal: return LayerClass::Coated;
        case LayerAttribute::SheenColor:
        case LayerAttribute::SheenRoughness: return LayerClass::Sheen;
        default: return LayerClass::Anisotropic;
    }
}

struct RunMetrics {
    CoverageCounts coverage;
    AttributeMetrics normal;         // degrees
    AttributeMetrics baseColor;      // CIEDE2000 (+ rmse)
    AttributeMetrics diffuseColor;   // CIEDE2000 (+ rmse)
    AttributeMetrics specularColor;  // CIEDE2000 (+ rmse)
    AttributeMetrics roughness;      // absolute
    AttributeMetrics metallic;       // absolute
    AttributeMetrics occlusion;      // absolute
    AttributeMetrics depth;          // relative
    std::optional<LayerMetrics> layers;  // absent in a scene without layers
    ShadedErrors image;
};

// Per-pixel error images behind the numbers (all width x height; 1 channel unless stated).
// Attribute maps are 0 where a pixel is not measured (see `measured`).
struct RunErrorMaps {
    std::shared_ptr<const Image> referenceSrgb;  // 3 ch: tone-mapped reference, sRGB [0,1] (shared, not copied)
    Image testSrgb;       // 3 ch: tone-mapped test
    Image flip;           // LDR-FLIP [0,1]
    Image hdrFlip;        // HDR-FLIP [0,1] (empty when not computed)
    Image absLinear;      // 3 ch: |test - reference|, linear HDR
    Image relLuminance;   // |Y_t - Y_r| / max(Y_r, floor), linear; see relativeLuminanceError
    Image normalDeg, baseColorDe, diffuseColorDe, specularColorDe;
    Image roughnessAbs, metallicAbs, occlusionAbs, depthRel;
    std::vector<uint8_t> measured;  // 1 where attributes were compared (covered in both)
};

// What the metrics derive from the reference render alone (its tone-mapped image, its half of
// LDR-FLIP, the floor of the relative luminance error), computed once and shared by every run
// measured against that reference. Keeps a pointer to `referenceHdr`, which must outlive it.
struct PreparedReference {
    PreparedReference(const Image& referenceHdr, float exposure);
    const Image* hdr;
    float exposure;
    std::shared_ptr<const Image> srgb;  // toneMapToSrgbFloat(*hdr, exposure)
    LdrFlipReference flip;
    double luminanceFloor;  // relativeLuminanceError's floor for this reference
};

struct RunMetricsOptions {
    bool hdrFlip = true;   // HDR-FLIP costs one LDR-FLIP per exposure; off for quick runs
    RunErrorMaps* maps = nullptr;  // when set, filled with the per-pixel images
    // When set, must be prepared from the same referenceHdr object and exposure (else
    // std::invalid_argument); the results are identical to a run without it.
    const PreparedReference* prepared = nullptr;
    // The reference's per-pixel noise: standard error of its luminance (1 channel, absolute), e.g.
    // a progressive ground truth's (render/renderer.h RenderOutput::noise). Reported per class.
    const Image* referenceNoise = nullptr;
    // Pixels left out of every metric, one byte per pixel (non-zero: excluded), e.g. where the
    // visible material is drawn forward by a deferred engine (transmission, volume: the view's
    // forward mask, render/forward_mask.h). Attribute errors skip them (CoverageCounts::excluded
    // counts them); every image error (RMSE, PSNR, max, p99, mean, LDR- and HDR-FLIP, the FLIP
    // tiles, the classes) is over the other pixels; the per-pixel maps hold 0 there. Null or
    // empty: no pixel excluded, the numbers of a run without it, bit for bit.
    const std::vector<uint8_t>* excluded = nullptr;
};

// Throws UserError when sizes disagree or an attribute image has too few channels. An attribute
// image that is empty on either side is not measured (its stats keep count 0).
RunMetrics computeRunMetrics(const SurfaceImages& reference, const SurfaceImages& test, const Image& referenceHdr,
                             const Image& testHdr, float exposure, const RunMetricsOptions& options);
RunMetrics computeRunMetrics(const SurfaceImages& reference, const SurfaceImages& test, const Image& referenceHdr,
                             const Image& testHdr, float exposure);
// The same, taking the test surfaces: they are freed (left empty) as soon as the attribute metrics
// are done, before FLIP's working planes are allocated (peak memory: 80 bytes per pixel).
RunMetrics computeRunMetrics(const SurfaceImages& reference, SurfaceImages&& test, const Image& referenceHdr,
                             const Image& testHdr, float exposure, const RunMetricsOptions& options);

// Per-pixel relative luminance error of linear RGB images (CIE Y of linear sRGB):
// |Y_t - Y_r| / max(Y_r, floor), floor = 1e-2 x the reference's mean luminance (at least 1e-6),
// so black pixels do not divide by zero and near-black noise does not dominate. 1 channel.
Image relativeLuminanceError(const Image& referenceLinear, const Image& testLinear);

}  // namespace gbl
