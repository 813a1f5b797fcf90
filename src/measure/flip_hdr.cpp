// HDR-FLIP (Andersson et al., Eurographics 2021 short, marked [HDR]): the tone mapper, the
// exposure range derived from the reference, and the per-pixel maximum of LDR-FLIP over the
// exposures. The LDR pipeline it runs per exposure is flip.cpp's (flip_pipeline.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "color_difference.h"
#include "error.h"
#include "flip.h"
#include "flip_pipeline.h"
#include "metrics.h"

namespace gbl {
namespace {

using namespace flip_pipeline;

// Tone mapper coefficients [HDR]: t(x) = (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5).
constexpr double kTm[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

inline float hdrClamp(float v) { return v >= 0.0f ? v : 0.0f; }  // negatives and NaN -> 0

}  // namespace

float flipToneMap(float x) {
    // t rises monotonically to 2.51/2.43 > 1, so it is 1 (clamped) long before x^2 could
    // overflow: cap x (this also maps +inf to 1; NaN stays NaN and clamps to 0).
    x = x > 1.0e18f ? 1.0e18f : x;
    const float x2 = x * x;
    const float num = float(kTm[0]) * x2 + float(kTm[1]) * x + float(kTm[2]);
    const float den = float(kTm[3]) * x2 + float(kTm[4]) * x + float(kTm[5]);
    return clamp01(num / den);
}

float FlipExposureRange::exposure(int i) const {
    if (count <= 1) return start;
    return start + float(i) * (stop - start) / float(count - 1);
}

FlipExposureRange flipExposureRange(const Image& ref) {
    if (ref.empty() || (ref.channels != 1 && ref.channels < 3))
        throwUserError("flipExposureRange: the reference is empty or has " + std::to_string(ref.channels) +
                       " channels; give a linear RGB(A) or grey image");
    // x_max [HDR]: the input the tone mapper maps to 0.85, the larger root of
    // (k0 - 0.85 k3) x^2 + (k1 - 0.85 k4) x + (k2 - 0.85 k5) = 0.
    const double t = 0.85;
    const double qa = kTm[0] - t * kTm[3], qb = kTm[1] - t * kTm[4], qc = kTm[2] - t * kTm[5];
    const double xMax = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);

    // Luminance of the reference: CIE Y of linear sRGB.
    const Xyz yr = linearSrgbToXyz(1, 0, 0), yg = linearSrgbToXyz(0, 1, 0), yb = linearSrgbToXyz(0, 0, 1);
    const size_t n = ref.pixelCount();
    std::vector<double> lum(n);
    const int ch = ref.channels;
    for (size_t i = 0; i < n; ++i) {
        const float* p = ref.pixels.data() + i * size_t(ch);
        const double r = hdrClamp(p[0]), g = hdrClamp(p[ch == 1 ? 0 : 1]), b = hdrClamp(p[ch == 1 ? 0 : 2]);
        lum[i] = std::isfinite(r + g + b) ? yr.Y * r + yg.Y * g + yb.Y * b : 0.0;
    }
    const double yMax = *std::max_element(lum.begin(), lum.end());
    FlipExposureRange range;
    if (!(yMax > 0.0)) return range;  // all black: a single (repeated) exposure of 0
    double yMedian = percentileNearestRank(lum, 0.5);
    if (!(yMedian > 0.0)) {
        std::vector<double> positive;
        for (double v : lum)
            if (v > 0.0) positive.push_back(v);
        yMedian = percentileNearestRank(positive, 0.5);
    }
    // [HDR]: c_start = log2(x_max / Y_max), c_stop = log2(x_max / Y_median),
    // N = max(2, ceil(c_stop - c_start)).
    range.start = float(std::log2(xMax / yMax));
    range.stop = float(std::log2(xMax / yMedian));
    range.count = std::max(2, int(std::ceil(double(range.stop) - double(range.start))));
    return range;
}

HdrFlipResult flipHdr(const Image& ref, const Image& test, double ppd, FlipExposureRange range) {
    checkPair(ref, test, "flipHdr");
    checkPixelsPerDegree(ppd, "flipHdr");
    if (range.count <= 0) range = flipExposureRange(ref);
    if (range.count > kMaxFlipExposures || !std::isfinite(range.start) || !std::isfinite(range.stop))
        throwUserError("flipHdr: " + std::to_string(range.count) + " exposures from " + std::to_string(range.start) +
                       " to " + std::to_string(range.stop) + "; give finite exposures and at most " +
                       std::to_string(kMaxFlipExposures));
    const int w = ref.width, h = ref.height;
    const size_t n = ref.pixelCount();
    const Kernels k = makeKernels(ppd);
    const float cMax = float(maxColorDifference());

    HdrFlipResult result;
    result.range = range;
    result.flip = Image(w, h, 1, 0.0f);
    result.exposureMap = Image(w, h, 1, 0.0f);
    std::vector<float> cur(n);
    Workspace ws(n);
    Plane pr[3], pt[3];
    for (int c = 0; c < 3; ++c) {
        pr[c].resize(n);
        pt[c].resize(n);
    }
    for (int e = 0; e < range.count; ++e) {
        // Exposure-compensate (x 2^c), tone map each channel, then LDR-FLIP on the result
        // (display-referred linear RGB in [0,1]; sRGB encode + decode would be the identity).
        const float scale = std::exp2(range.exposure(e));
        for (int which = 0; which < 2; ++which) {
            const Image& im = which == 0 ? ref : test;
            Plane* dst = which == 0 ? pr : pt;
            const int ch = im.channels;
            forPixels(n, [&](size_t b, size_t end) {
                for (size_t i = b; i < end; ++i) {
                    const float* p = im.pixels.data() + i * size_t(ch);
                    for (int c = 0; c < 3; ++c) dst[c][i] = flipToneMap(hdrClamp(p[ch == 1 ? 0 : c]) * scale);
                }
            });
        }
        const Prepared a = prepare(pr, w, h, k, ws);
        const Prepared b = prepare(pt, w, h, k, ws);
        combine(a, b, cMax, cur.data(), n);
        // Per-pixel maximum over exposures [HDR]; ties keep the earliest exposure.
        for (size_t i = 0; i < n; ++i)
            if (cur[i] > result.flip.pixels[i]) {
                result.flip.pixels[i] = cur[i];
                result.exposureMap.pixels[i] = float(e);
            }
    }
    return result;
}

}  // namespace gbl
