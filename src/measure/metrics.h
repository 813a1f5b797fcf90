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
#include <algorithm>
#include <array>
#include <cstring>
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

// summarizeByClass as a stream: add(v, cls) in pool order, then finish() gives the same doubles
// without the pool. compare measures 8 attributes of about 2 million pixels per run at 1080p,
// and most of an exactly stored attribute's errors are 0: a +0 sample only counts (adding +0 to
// a sum of non-negative errors, or to its square, changes no bit), the others go to their class's
// histogram and list. The p99 is selected among the samples of its bucket only, the zeros of the
// zero bucket standing first. Samples are errors, so never -0 or NaN (as summarizeByClass).
class ClassStatsPool {
public:
    explicit ClassStatsPool(size_t expectedSamples = 0);
    void add(double v, bool cls1) {
        const int c = cls1 ? 1 : 0;
        uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        if (bits == 0) {
            ++zeros_[c];
            return;
        }
        accumulate(c, v);
        accumulate(2, v);
        ++histogram_[size_t(c) * kBuckets + bucketOf(v)];
        samples_[c].push_back(v);
    }
    std::array<ScalarStats, 3> finish();  // {class 0, class 1, all}; once

    // The histogram's key: the top 16 bits of an order-preserving map of the bit pattern (Herf,
    // "Radix Tricks", 2001: flip negatives).
    static constexpr int kBucketShift = 48;
    static constexpr size_t kBuckets = size_t(1) << (64 - kBucketShift);
    static size_t bucketOf(double v) {
        uint64_t u;
        std::memcpy(&u, &v, sizeof u);
        u ^= (u >> 63) ? ~uint64_t(0) : (uint64_t(1) << 63);
        return size_t(u >> kBucketShift);
    }

private:
    void accumulate(int k, double v) {
        max_[k] = nonZero_[k] == 0 ? v : std::max(max_[k], v);  // summarize's: from the first sample
        sum_[k] += v;
        sum2_[k] += v * v;
        ++nonZero_[k];
    }
    double sum_[3] = {}, sum2_[3] = {}, max_[3] = {};
    size_t nonZero_[3] = {}, zeros_[2] = {};
    std::vector<uint32_t> histogram_;  // class 0's buckets, then class 1's; "all" is their sum
    std::vector<double> samples_[2];   // each class's samples that are not +0, in pool order
};

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
