#pragma once
// The per-run comparison in pictures: heat maps with legends, the amplified difference, the raw
// per-pixel errors as EXR and the layout's render. Built from RunErrorMaps (run_metrics.h).
//
// Choices (stated here and in the images' titles):
//  * Shaded-error heat map: the RELATIVE LUMINANCE ERROR |Y_t - Y_r| / max(Y_r, floor) of the
//    linear HDR renders (relativeLuminanceError), every pixel, scale 0 .. heatMax (default 10 %,
//    fixed so layouts compare side by side; larger errors saturate at the top colour).
//  * FLIP map: LDR-FLIP of the tone-mapped images, scale 0 .. 1.
//  * Normal-angle map: degrees, scale 0 .. max(1 deg, the run's p99 normal error).
//  * Attribute maps (normal angle) show background / unmeasured pixels as the reference render in
//    dimmed grey, so the eye goes to the geometry; image-space maps colour every pixel.
//  * Amplified difference: |test - reference| of the tone-mapped sRGB images x k (default 8),
//    clamped to 1, per channel; k is written in the title.
//  * Colour map: viridisTable() (perceptually uniform), legend on the right, title on top.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "color_map.h"  // titledPicture / titleBandHeight: the layout of these pictures
#include "image.h"
#include "image_io.h"
#include "run_metrics.h"

namespace gbl {

struct ErrorImageOptions {
    float heatMax = 0.10f;           // top of the relative-luminance heat scale
    float amplification = 8.0f;      // k of the difference image
    float normalMinScaleDeg = 1.0f;  // the normal map's top is max(this, p99)
    std::string label;               // e.g. the layout's name, prefixed to every title ("" = none)
    ExrPixelType exrType = ExrPixelType::Float32;  // of errors.exr (image_io.h: half's precision)
    // errors.exr is a float dump of every map (16 MB a 1080p run in half): written on request only
    // by compare (--error-exr), since every reported number is recomputable from the PNGs and EXRs.
    bool writeErrorExr = true;
};

// Paths relative to `dir` (prefix + file name); "" when not written.
struct ErrorImagePaths {
    std::string render;       // <prefix>render.png: the layout's tone-mapped render
    std::string heatmap;      // <prefix>error_heatmap.png
    std::string flip;         // <prefix>flip.png
    std::string normalError;  // <prefix>normal_error.png
    std::string difference;   // <prefix>difference.png
    std::string errorsExr;    // <prefix>errors.exr
    std::vector<std::string> all() const;  // the non-empty ones, in the order above
};

// Writes every image (atomic writes; parent directories created). `prefix` is a file-name prefix
// that may contain directories ("layoutA/" or "layoutA_"). Throws UserError when a map is
// missing or a write fails.
ErrorImagePaths writeErrorImages(const std::filesystem::path& dir, const std::string& prefix, const RunErrorMaps& maps,
                                 const RunMetrics& metrics, const ErrorImageOptions& options = {});

// The same pictures from maps already colour-mapped to 8 bits elsewhere (the GPU evaluation,
// src/evaluate/gpu_evaluator.h): the bodies get the titles and legends writeErrorImages gives
// them. `normal` may be empty (no normal map). No errors.exr: its float maps are not at hand.
struct ErrorImageBodies {
    Image8 render, heat, flip, normal, difference;
};
ErrorImagePaths writeErrorImageBodies(const std::filesystem::path& dir, const std::string& prefix,
                                      const ErrorImageBodies& bodies, const RunMetrics& metrics,
                                      const ErrorImageOptions& options = {});

// EXR channel names written to errors.exr, in this order; channels whose map is empty are left
// out: flip, hdr_flip, abs_r, abs_g, abs_b, rel_luminance, normal_deg, base_color_de, diffuse_de,
// specular_de, roughness_abs, metallic_abs, occlusion_abs, depth_rel, measured (1 = compared).
std::vector<std::string> errorExrChannels(const RunErrorMaps& maps);
void writeErrorExr(const std::filesystem::path& path, const RunErrorMaps& maps,
                   ExrPixelType type = ExrPixelType::Float32);
// The paths writeErrorImages(dir, prefix, maps, ...) writes, without writing them.
ErrorImagePaths errorImagePaths(const std::string& prefix, const RunErrorMaps& maps, bool errorExr = true);

// ---- Building blocks (in memory) --------------------------------------------------------------

// sRGB-encoded float [0,1] (1 or >= 3 channels) -> RGB 8-bit, floor(255 v + 0.5).
Image8 srgbFloatTo8(const Image& srgb);

// Colour-maps channel 0 of `scalar` over [lo, hi] and adds a title line and a legend.
// When `measured` is non-null and non-empty, pixels whose byte is 0 show `background`
// (sRGB float, dimmed to grey) or mid grey when `background` is null/empty.
Image8 heatMapImage(const Image& scalar, float lo, float hi, std::string_view title, const Image* background = nullptr,
                    const std::vector<uint8_t>* measured = nullptr);

// min(1, k |test - reference|) per channel of two sRGB float images, with a title line.
Image8 amplifiedDifferenceImage(const Image& referenceSrgb, const Image& testSrgb, float k, std::string_view title);

}  // namespace gbl
