#pragma once
// Image and G-buffer attribute error metrics, reference vs test.
//
// Masks: a coverage mask is a std::vector<uint8_t> with one byte per pixel (row-major, like
// Image); a pixel counts when its byte is non-zero. A null pointer or an empty vector means
// "every pixel". Sizes that do not match throw gbl::UserError.
//
// Quantiles are exact, by std::nth_element: the nearest-rank p-quantile of n samples is the
// sample of rank ceil(p n) (1-based) in sorted order, i.e. the smallest sample v with at least a
// fraction p of the samples <= v. p99 below is that with p = 0.99.
//
// Identical images give exactly 0 for every error and PSNR = +infinity.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "image.h"

namespace gbl {

using Mask = std::vector<uint8_t>;

// Per-pixel errors, as every metric here computes them.
// Angle in degrees between two 3-vectors, atan2(|a x b|, a . b) in double (accurate near 0 deg,
// where acos is not); ok = false (and 0) when either is zero or not finite.
double normalAngleDeg(const float* a, const float* b, bool& ok);
// CIEDE2000 of two linear sRGB colours (via XYZ D65 and CIELAB).
double pixelDeltaE(const float* a, const float* b);

// 0-based index of the nearest-rank p-quantile among n samples: max(ceil(p n), 1) - 1, with
// ceil computed so that p n within 1e-9 relative of an integer counts as that integer
// (0.99 * 100 is 99, not 99.00000000000001).
size_t nearestRankIndex(double p, size_t n);
// The nearest-rank p-quantile of the samples (reorders them; 0 for no samples).
double percentileNearestRank(std::vector<double>& samples, double p);
// The sample of 0-based rank k in sorted order (reorders them; k < samples.size()).
double percentileNearestRankAt(std::vector<double>& samples, size_t k);

// Summary of a set of non-negative per-sample errors.
struct ScalarStats {
    size_t count = 0;    // samples pooled
    double mean = 0.0;
    double rms = 0.0;
    double p99 = 0.0;    // nearest-rank 0.99
    double max = 0.0;
};
ScalarStats summarize(std::vector<double>& samples);  // reorders the samples
// summarize() of two classes of samples kept in one pool, and of the whole pool: samples[i] is of
// class cls[i] != 0 (1) or == 0 (0). Returns {class 0, class 1, all}, each the same doubles as
// summarize() of that class's samples listed in pool order (the same sums in the same order, the
// same order statistic: p99 is selected inside the one histogram bucket of the bit patterns that
// holds its rank). One pool instead of three, and two streaming passes instead of nth_element
// over every sample. (For -0 against +0, or NaN, which summarize leaves unspecified, the value
// picked may differ.)
std::array<ScalarStats, 3> summarizeByClass(const std::vector<double>& samples, const std::vector<uint8_t>& cls);

// ---- Image (radiance / colour) errors ----------------------------------------------------------

// What PSNR's peak value is.
enum class PsnrPeak {
    One,           // peak 1.0: display-referred (LDR) images in [0,1]
    ReferenceMax,  // peak = the largest reference value over the masked pixels and compared
                   // channels (linear HDR); 1.0 when that maximum is <= 0
};

struct ImageErrorStats {
    size_t count = 0;       // samples pooled: masked pixels x compared channels
    double mean = 0.0;      // mean signed error, test - reference (bias)
    double meanAbs = 0.0;   // mean absolute error
    double mse = 0.0;
    double rmse = 0.0;
    double psnr = std::numeric_limits<double>::infinity();  // 10 log10(peak^2 / MSE) dB; +inf if MSE = 0
    double peak = 1.0;      // the peak PSNR used
    double maxAbs = 0.0;
    double p99Abs = 0.0;    // nearest-rank 0.99 of |test - reference|
};

// Errors pooled over every channel sample of the masked pixels. channels: how many leading
// channels to compare (0 = all, e.g. 3 to skip alpha); both images need at least that many.
ImageErrorStats imageErrorStats(const Image& reference, const Image& test, const Mask* mask = nullptr,
                                PsnrPeak peak = PsnrPeak::One, int channels = 0);

// imageErrorStats(reference, test, nullptr, peak, channels).mse, the same double (the same
// samples summed in the same order), without the work of the other statistics.
double meanSquaredError(const Image& reference, const Image& test, int channels = 0);

// PSNR in dB for a mean squared error and a peak: 10 log10(peak^2 / mse); +inf when mse == 0.
double psnrFromMse(double mse, double peak);

// Per-pixel error images (same size as the inputs; masked-out pixels are 0).
Image absErrorImage(const Image& reference, const Image& test, const Mask* mask = nullptr);    // |t - r| per channel
Image maxAbsErrorImage(const Image& reference, const Image& test, const Mask* mask = nullptr,  // 1 ch: max over channels
                       int channels = 0);
Image squaredErrorImage(const Image& reference, const Image& test, const Mask* mask = nullptr, // 1 ch: mean over channels
                        int channels = 0);

// ---- Attribute errors --------------------------------------------------------------------------

// Angle in degrees between the normals in channels [first, first+3) of both images, computed
// as atan2(|a x b|, a . b) in double (accurate for small angles, unlike acos). The normals need
// not be unit length. Pixels where either normal has zero length or is not finite are left out
// of the statistics (counted in `skipped`) and are 0 in the angle image.
struct NormalErrorStats {
    ScalarStats angleDeg;
    size_t skipped = 0;
};
NormalErrorStats normalAngleStats(const Image& reference, const Image& test, const Mask* mask = nullptr,
                                  int firstChannel = 0);
Image normalAngleImage(const Image& reference, const Image& test, const Mask* mask = nullptr, int firstChannel = 0);

// Absolute error of one scalar channel (roughness, metallic, ...).
ScalarStats scalarAbsErrorStats(const Image& reference, const Image& test, int channel, const Mask* mask = nullptr);
Image scalarAbsErrorImage(const Image& reference, const Image& test, int channel, const Mask* mask = nullptr);

// Colour (base colour / albedo) errors of linear sRGB triplets in channels [first, first+3):
// CIEDE2000 after linear RGB -> XYZ (D65) -> CIELAB (see color_difference.h), and the RMSE of
// the linear RGB values (pooled over the three channels).
struct ColorErrorStats {
    ScalarStats deltaE2000;
    double rmse = 0.0;
};
ColorErrorStats colorErrorStats(const Image& reference, const Image& test, const Mask* mask = nullptr,
                                int firstChannel = 0);
Image deltaE2000Image(const Image& reference, const Image& test, const Mask* mask = nullptr, int firstChannel = 0);

}  // namespace gbl
