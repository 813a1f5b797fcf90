#pragma once
// Engine-style automatic exposure: the exposure a game engine would pick for an HDR frame, so that
// compare's tone-mapped images (and their PSNR and LDR-FLIP) look at the range an engine shows.
//
// The method is Unreal Engine 4's histogram eye adaptation (EAutoExposureMethod AEM_Histogram,
// the default of r.DefaultFeature.AutoExposure.Method; PostProcessHistogram / PostProcessEyeAdaptation),
// with its FPostProcessSettings defaults (Engine/Source/Runtime/Engine/Private/Scene.cpp, UE 4.2x):
//   - a 64-bucket histogram of log2 luminance over [HistogramLogMin, HistogramLogMax] = [-8, 4];
//   - the average luminance of the pixels between the AutoExposureLowPercent = 80 and
//     AutoExposureHighPercent = 98.3 percentiles of that histogram (UE's
//     ComputeAverageLuminaneWithoutOutlier: whole buckets, the percentiles cutting a bucket's count);
//   - clamped to [AutoExposureMinBrightness, AutoExposureMaxBrightness] = [0.03, 2.0];
//   - exposure = key / that luminance, key = 1 (UE4's eye adaptation maps the clamped average to 1:
//     ExposureScale = 1 / max(0.0001, luminance) with AutoExposureBias 0).
// Two choices of ours, stated: luminance is CIE Y of linear Rec. 709 / sRGB (the unit of
// run_metrics.h's relative luminance error), and a bucket stands for the luminance at its centre
// (UE takes its lower edge, a bias of half a bucket, 2^(12/128) = 6.7%). Every pixel counts, the
// background's included, as an engine meters the whole screen; no temporal adaptation (one frame).
#include "image.h"

namespace gbl {

// report.json's run.exposure_method for it ("fixed": compare --exposure).
inline constexpr const char* kAutoExposureMethod = "ue4-histogram";

struct AutoExposureSettings {
    int buckets = 64;
    double logMin = -8.0, logMax = 4.0;   // log2 luminance range of the histogram
    double lowPercent = 80.0, highPercent = 98.3;
    double minBrightness = 0.03, maxBrightness = 2.0;
    double key = 1.0;
};

struct AutoExposure {
    double averageLuminance = 0.0;  // between the percentiles, before the clamp
    double meteredLuminance = 0.0;  // clamped to [minBrightness, maxBrightness]
    double exposure = 1.0;          // key / meteredLuminance
};

// The histogram's bucket of a luminance: clamp(floor((log2 Y - logMin) / (logMax - logMin) x
// buckets), 0, buckets - 1); Y <= 0 (no light) falls in bucket 0.
int exposureBucket(double luminance, const AutoExposureSettings& settings);
// The luminance a bucket stands for: 2^(logMin + (b + 0.5) / buckets x (logMax - logMin)).
double exposureBucketLuminance(int bucket, const AutoExposureSettings& settings);

// The exposure of `hdr` (RGB or RGBA linear radiance). Throws std::invalid_argument for an empty
// image or settings outside their ranges.
AutoExposure meterExposure(const Image& hdr, const AutoExposureSettings& settings = {});

}  // namespace gbl
