#pragma once
// FLIP: Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild, "FLIP: A Difference
// Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020)
// -- LDR-FLIP, implemented from the paper.
// HDR-FLIP: Andersson, Nilsson, Shirley, Akenine-Möller, "Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics 2021 short papers -- exposure range, tone mapper and the
// per-pixel maximum over LDR-FLIP of the exposures, implemented from that paper.
//
// Conventions (where the papers leave a choice, stated here and in flip.cpp):
//  * Images are gbl::Image with 1 (grey, replicated to RGB) or >= 3 channels; channels past the
//    third are ignored. Reference and test must have the same width and height (else UserError).
//  * LDR input is sRGB-encoded; values are clamped to [0,1] (NaN -> 0) before decoding.
//  * HDR input is linear RGB; negative values and NaN are clamped to 0.
//  * All filters read outside the image as the nearest edge pixel (clamp-to-edge).
//  * The map is computed in float; kernels in double, rounded to float.
#include <cstdint>
#include <memory>
#include <vector>

#include "image.h"

namespace gbl {

// Pixels per degree of visual angle, FLIP eq. (1): p = d * (r / w) * pi / 180, with d the
// viewing distance, r the monitor's horizontal resolution in pixels and w its width (metres).
// The defaults (0.7 m, 3840 px, 0.7 m) give 3840 * pi / 180 = 67.0206... pixels per degree.
double flipPixelsPerDegree(double distanceMeters = 0.7, double monitorWidthPixels = 3840.0,
                           double monitorWidthMeters = 0.7);

// The largest pixels per degree FLIP accepts (a UserError beyond). Its filters widen with it: the
// CSF filter's radius is 0.135 p pixels, the feature filter's 0.123 p, and their taps, time and
// scratch rows grow alike (--ppd 1e9 asked for 12 GB of kernels). 1000 is a 3840-pixel screen
// 0.7 m wide seen from 10 m, farther than any viewing FLIP is meant for.
inline constexpr double kMaxFlipPixelsPerDegree = 1000.0;

// LDR-FLIP of two sRGB-encoded images: a 1-channel map, every value in [0,1].
Image flipLdr(const Image& referenceSrgb, const Image& testSrgb, double pixelsPerDegree = flipPixelsPerDegree());

// The reference's half of LDR-FLIP (its filtered colour and feature planes, 20 bytes per pixel),
// prepared once and reused against many test images: `compare` measures every layout against
// the same reference render. compare(test) equals flipLdr(reference, test) bit for bit.
class LdrFlipReference {
public:
    explicit LdrFlipReference(const Image& referenceSrgb, double pixelsPerDegree = flipPixelsPerDegree());
    ~LdrFlipReference();
    LdrFlipReference(const LdrFlipReference&) = delete;
    LdrFlipReference& operator=(const LdrFlipReference&) = delete;
    Image compare(const Image& testSrgb) const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

// The same pipeline on linear RGB in [0,1] (no sRGB decode; values clamped to [0,1]).
Image flipLdrLinear(const Image& referenceLinear, const Image& testLinear,
                    double pixelsPerDegree = flipPixelsPerDegree());

// ---- HDR-FLIP -------------------------------------------------------------------------------

// The HDR-FLIP tone mapper: the ACES filmic fit (Narkowicz 2016) applied to 0.6 x, i.e.
// t(x) = (0.6*0.6*2.51 x^2 + 0.6*0.03 x) / (0.6*0.6*2.43 x^2 + 0.6*0.59 x + 0.14), clamped to [0,1].
float flipToneMap(float x);

struct FlipExposureRange {
    float start = 0.0f;   // c_start = log2(x_max / Y_max)     (exposures are 2^c scale factors)
    float stop = 0.0f;    // c_stop  = log2(x_max / Y_median)
    int count = 2;        // N = max(2, ceil(c_stop - c_start))
    // Exposure i of N: c_start + i * (c_stop - c_start) / (N - 1).
    float exposure(int i) const;
};

// The exposure range HDR-FLIP derives from the reference: x_max solves t(x_max) = 0.85, Y is the
// luminance (CIE Y of linear sRGB) of the reference. The median is the exact lower median.
// If every reference pixel is black, start = stop = 0. If the median is 0 but some pixel is
// not, the median of the positive luminances is used (the paper does not cover that case).
FlipExposureRange flipExposureRange(const Image& referenceLinear);

// The most exposures HDR-FLIP runs (a UserError beyond): each is a whole LDR-FLIP of the pair.
// The reference's own range needs at most about 280 (the span of float luminances); more come
// only from hand-given exposures, e.g. --start-exposure -1e30 --stop-exposure 1e30.
inline constexpr int kMaxFlipExposures = 1000;

struct HdrFlipResult {
    Image flip;            // 1 channel, in [0,1]: per-pixel max over the exposures
    Image exposureMap;     // 1 channel: index in [0, count) of the exposure that gave the max
    FlipExposureRange range;
};

// HDR-FLIP of linear HDR images. A range with count <= 0 means "compute it from the reference".
HdrFlipResult flipHdr(const Image& referenceLinear, const Image& testLinear,
                      double pixelsPerDegree = flipPixelsPerDegree(), FlipExposureRange range = {0.0f, 0.0f, 0});

// ---- Statistics -------------------------------------------------------------------------------

// Pooled values of a FLIP map over the pixels whose mask byte is non-zero (all pixels when the
// mask is null or empty). Quantiles are exact: the nearest-rank value (smallest v with at least
// the fraction p of the samples <= v). The weighted quantiles weight each pixel by its own FLIP
// value, as the FLIP tool's weighted median does: smallest v_k (sorted) with
// sum_{i<=k} v_i >= p * sum_i v_i; 0 when every value is 0.
struct FlipStats {
    size_t count = 0;
    double mean = 0.0;
    double median = 0.0;          // nearest-rank p = 0.5 (the lower median)
    double weightedMedian = 0.0;
    double weightedQ1 = 0.0;      // weighted p = 0.25
    double weightedQ3 = 0.0;      // weighted p = 0.75
    double min = 0.0;
    double max = 0.0;
};

FlipStats flipStats(const Image& flipMap, const std::vector<uint8_t>* mask = nullptr);

}  // namespace gbl
