#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>

#include "color_difference.h"
#include "error.h"

namespace gbl {
namespace {

void checkPair(const Image& ref, const Image& test, const Mask* mask, const char* what) {
    if (ref.width != test.width || ref.height != test.height)
        throwUserError(std::string(what) + ": reference is " + std::to_string(ref.width) + "x" +
                       std::to_string(ref.height) + " but test is " + std::to_string(test.width) + "x" +
                       std::to_string(test.height) + "; compare images of the same size");
    if (mask && !mask->empty() && mask->size() != ref.pixelCount())
        throwUserError(std::string(what) + ": the mask has " + std::to_string(mask->size()) + " entries for " +
                       std::to_string(ref.pixelCount()) + " pixels; give one byte per pixel");
}

// Channels [first, first + count) must exist in both images.
void checkChannels(const Image& ref, const Image& test, int first, int count, const char* what) {
    if (first < 0 || ref.channels < first + count || test.channels < first + count)
        throwUserError(std::string(what) + ": needs channels " + std::to_string(first) + ".." +
                       std::to_string(first + count - 1) + " but the images have " + std::to_string(ref.channels) +
                       " and " + std::to_string(test.channels) + "; pick channels both images have");
}

int resolveChannels(const Image& ref, const Image& test, int channels, const char* what) {
    const int c = channels > 0 ? channels : std::min(ref.channels, test.channels);
    if (channels <= 0 && ref.channels != test.channels)
        throwUserError(std::string(what) + ": reference has " + std::to_string(ref.channels) + " channels, test " +
                       std::to_string(test.channels) + "; pass the number of channels to compare");
    checkChannels(ref, test, 0, c, what);
    return c;
}

inline bool covered(const Mask* mask, size_t i) { return !mask || mask->empty() || (*mask)[i] != 0; }

// Exact quantiles without nth_element over every sample: count the samples per bucket of the top
// 16 bits of an order-preserving key of their bit patterns (Herf, "Radix Tricks", 2001: flip
// negatives), find the bucket that holds the wanted rank, then select only among its samples.
// The k-th smallest value is one value however it is found.
constexpr size_t kBuckets = ClassStatsPool::kBuckets;
inline size_t bucketOf(double v) { return ClassStatsPool::bucketOf(v); }

}  // namespace

double normalAngleDeg(const float* a, const float* b, bool& ok) {
    const double ax = a[0], ay = a[1], az = a[2], bx = b[0], by = b[1], bz = b[2];
    const double la = ax * ax + ay * ay + az * az, lb = bx * bx + by * by + bz * bz;
    ok = std::isfinite(la) && std::isfinite(lb) && la > 0.0 && lb > 0.0;
    if (!ok) return 0.0;
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double dot = ax * bx + ay * by + az * bz;
    return std::atan2(cross, dot) * (180.0 / std::numbers::pi);
}

double pixelDeltaE(const float* a, const float* b) {
    return deltaE2000(linearSrgbToLab(a[0], a[1], a[2]), linearSrgbToLab(b[0], b[1], b[2]));
}

size_t nearestRankIndex(double p, size_t n) {
    if (n == 0) return 0;
    const double x = std::clamp(p, 0.0, 1.0) * double(n);
    double r = std::ceil(x);
    const double below = r - 1.0;
    if (below >= 0.0 && x - below <= 1e-9 * std::max(1.0, x)) r = below;  // 99.00000000000001 -> 99
    const size_t rank = std::max<size_t>(1, size_t(r));
    return std::min(rank, n) - 1;
}

double percentileNearestRank(std::vector<double>& s, double p) {
    if (s.empty()) return 0.0;
    return percentileNearestRankAt(s, nearestRankIndex(p, s.size()));
}

double percentileNearestRankAt(std::vector<double>& s, size_t k) {
    std::nth_element(s.begin(), s.begin() + std::ptrdiff_t(k), s.end());
    return s[k];
}

ScalarStats summarize(std::vector<double>& s) {
    ScalarStats r;
    r.count = s.size();
    if (s.empty()) return r;
    double sum = 0.0, sum2 = 0.0, mx = s[0];
    for (double v : s) {
        sum += v;
        sum2 += v * v;
        mx = std::max(mx, v);
    }
    r.mean = sum / double(s.size());
    r.rms = std::sqrt(sum2 / double(s.size()));
    r.max = mx;
    r.p99 = percentileNearestRank(s, 0.99);
    return r;
}

std::array<ScalarStats, 3> summarizeByClass(const std::vector<double>& s, const std::vector<uint8_t>& cls) {
    if (cls.size() != s.size()) throw std::invalid_argument("summarizeByClass: one class byte per sample");
    ClassStatsPool pool(s.size());
    for (size_t i = 0; i < s.size(); ++i) pool.add(s[i], cls[i] != 0);
    return pool.finish();
}

ClassStatsPool::ClassStatsPool(size_t expectedSamples) : histogram_(2 * kBuckets, 0) {
    // Address space only: the pages a class's samples do not reach are never touched.
    for (std::vector<double>& v : samples_) v.reserve(expectedSamples);
}

std::array<ScalarStats, 3> ClassStatsPool::finish() {
    std::array<ScalarStats, 3> out{};
    const size_t zeros[3] = {zeros_[0], zeros_[1], zeros_[0] + zeros_[1]};
    const size_t zeroBucket = bucketOf(0.0);
    size_t bucket[3] = {}, below[3] = {}, rank[3] = {};
    for (int k = 0; k < 3; ++k) {
        ScalarStats& r = out[size_t(k)];
        r.count = nonZero_[k] + zeros[k];
        if (r.count == 0) continue;
        r.mean = sum_[k] / double(r.count);
        r.rms = std::sqrt(sum2_[k] / double(r.count));
        r.max = nonZero_[k] == 0 ? 0.0 : zeros[k] ? std::max(max_[k], 0.0) : max_[k];
        rank[k] = nearestRankIndex(0.99, r.count);
        auto at = [&](size_t b) {
            const size_t inClass =
                k == 2 ? size_t(histogram_[b]) + histogram_[kBuckets + b] : size_t(histogram_[size_t(k) * kBuckets + b]);
            return inClass + (b == zeroBucket ? zeros[k] : 0);
        };
        size_t b = 0, n = 0;
        while (n + at(b) <= rank[k]) n += at(b++);
        bucket[k] = b;
        below[k] = n;
    }
    std::vector<double> inBucket[3];
    for (int c = 0; c < 2; ++c)
        for (double v : samples_[c]) {
            const size_t b = bucketOf(v);
            if (b == bucket[c]) inBucket[c].push_back(v);
            if (b == bucket[2]) inBucket[2].push_back(v);
        }
    for (int k = 0; k < 3; ++k) {
        if (out[size_t(k)].count == 0) continue;
        // The zeros are the smallest members of the zero bucket (+0 before any positive value).
        const size_t kth = rank[k] - below[k], leadingZeros = bucket[k] == zeroBucket ? zeros[k] : 0;
        out[size_t(k)].p99 = kth < leadingZeros ? 0.0 : percentileNearestRankAt(inBucket[k], kth - leadingZeros);
    }
    for (std::vector<double>& v : samples_) std::vector<double>().swap(v);
    return out;
}

double psnrFromMse(double mse, double peak) {
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(peak * peak / mse);
}

namespace {

// Calls f(|t - r|) (in double, as every statistic here uses it) for each compared sample, in
// pixel then channel order.
template <class F>
void forEachAbsError(const Image& ref, const Image& test, const Mask* mask, int c, F&& f) {
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        const float* r = ref.pixels.data() + i * size_t(ref.channels);
        const float* t = test.pixels.data() + i * size_t(test.channels);
        for (int k = 0; k < c; ++k) f(double(t[k]) - double(r[k]), r[k]);
    }
}

}  // namespace

ImageErrorStats imageErrorStats(const Image& ref, const Image& test, const Mask* mask, PsnrPeak peakMode,
                                int channels) {
    checkPair(ref, test, mask, "imageErrorStats");
    const int c = resolveChannels(ref, test, channels, "imageErrorStats");
    // The nearest-rank p99 of |d| is found without keeping the 3 samples per pixel (48 MB at
    // 1080p): pass 1 counts them per bucket (bucketOf), pass 2 keeps only the bucket that holds
    // rank k and selects in it.
    std::vector<uint32_t> histogram(kBuckets, 0);
    size_t count = 0;
    double sum = 0.0, sumAbs = 0.0, sum2 = 0.0, refMax = -std::numeric_limits<double>::infinity();
    double maxAbs = 0.0;
    forEachAbsError(ref, test, mask, c, [&](double d, float r) {
        sum += d;
        sumAbs += std::abs(d);
        sum2 += d * d;
        const double a = std::abs(d);
        maxAbs = count == 0 ? a : std::max(maxAbs, a);
        ++histogram[bucketOf(a)];
        ++count;
        refMax = std::max(refMax, double(r));
    });
    ImageErrorStats s;
    s.count = count;
    s.peak = 1.0;
    if (peakMode == PsnrPeak::ReferenceMax && refMax > 0.0) s.peak = refMax;
    if (s.count == 0) return s;
    const double n = double(s.count);
    s.mean = sum / n;
    s.meanAbs = sumAbs / n;
    s.mse = sum2 / n;
    s.rmse = std::sqrt(s.mse);
    s.psnr = psnrFromMse(s.mse, s.peak);
    s.maxAbs = maxAbs;
    const size_t k = nearestRankIndex(0.99, count);
    size_t below = 0, bucket = 0;
    while (below + histogram[bucket] <= k) below += histogram[bucket++];
    std::vector<double> inBucket;
    inBucket.reserve(histogram[bucket]);
    forEachAbsError(ref, test, mask, c, [&](double d, float) {
        const double a = std::abs(d);
        if (bucketOf(a) == bucket) inBucket.push_back(a);
    });
    s.p99Abs = percentileNearestRankAt(inBucket, k - below);
    return s;
}

double meanSquaredError(const Image& ref, const Image& test, int channels) {
    checkPair(ref, test, nullptr, "meanSquaredError");
    const int c = resolveChannels(ref, test, channels, "meanSquaredError");
    double sum2 = 0.0;
    size_t count = 0;
    forEachAbsError(ref, test, nullptr, c, [&](double d, float) {
        sum2 += d * d;
        ++count;
    });
    return count ? sum2 / double(count) : 0.0;
}

Image absErrorImage(const Image& ref, const Image& test, const Mask* mask) {
    checkPair(ref, test, mask, "absErrorImage");
    const int c = resolveChannels(ref, test, 0, "absErrorImage");
    Image out(ref.width, ref.height, c, 0.0f);
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        for (int k = 0; k < c; ++k) {
            const size_t j = i * size_t(c) + size_t(k);
            out.pixels[j] = std::abs(test.pixels[j] - ref.pixels[j]);
        }
    }
    return out;
}

Image maxAbsErrorImage(const Image& ref, const Image& test, const Mask* mask, int channels) {
    checkPair(ref, test, mask, "maxAbsErrorImage");
    const int c = resolveChannels(ref, test, channels, "maxAbsErrorImage");
    Image out(ref.width, ref.height, 1, 0.0f);
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        float m = 0.0f;
        for (int k = 0; k < c; ++k)
            m = std::max(m, std::abs(test.pixels[i * size_t(test.channels) + size_t(k)] -
                                     ref.pixels[i * size_t(ref.channels) + size_t(k)]));
        out.pixels[i] = m;
    }
    return out;
}

Image squaredErrorImage(const Image& ref, const Image& test, const Mask* mask, int channels) {
    checkPair(ref, test, mask, "squaredErrorImage");
    const int c = resolveChannels(ref, test, channels, "squaredErrorImage");
    Image out(ref.width, ref.height, 1, 0.0f);
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        double s = 0.0;
        for (int k = 0; k < c; ++k) {
            const double d = double(test.pixels[i * size_t(test.channels) + size_t(k)]) -
                             double(ref.pixels[i * size_t(ref.channels) + size_t(k)]);
            s += d * d;
        }
        out.pixels[i] = float(s / c);
    }
    return out;
}

NormalErrorStats normalAngleStats(const Image& ref, const Image& test, const Mask* mask, int first) {
    checkPair(ref, test, mask, "normalAngleStats");
    checkChannels(ref, test, first, 3, "normalAngleStats");
    NormalErrorStats s;
    std::vector<double> angles;
    angles.reserve(ref.pixelCount());
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        bool ok = false;
        const double a = normalAngleDeg(ref.pixels.data() + i * size_t(ref.channels) + size_t(first),
                                        test.pixels.data() + i * size_t(test.channels) + size_t(first), ok);
        if (ok) angles.push_back(a);
        else ++s.skipped;
    }
    s.angleDeg = summarize(angles);
    return s;
}

Image normalAngleImage(const Image& ref, const Image& test, const Mask* mask, int first) {
    checkPair(ref, test, mask, "normalAngleImage");
    checkChannels(ref, test, first, 3, "normalAngleImage");
    Image out(ref.width, ref.height, 1, 0.0f);
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        bool ok = false;
        out.pixels[i] = float(normalAngleDeg(ref.pixels.data() + i * size_t(ref.channels) + size_t(first),
                                             test.pixels.data() + i * size_t(test.channels) + size_t(first), ok));
    }
    return out;
}

ScalarStats scalarAbsErrorStats(const Image& ref, const Image& test, int channel, const Mask* mask) {
    checkPair(ref, test, mask, "scalarAbsErrorStats");
    checkChannels(ref, test, channel, 1, "scalarAbsErrorStats");
    std::vector<double> e;
    e.reserve(ref.pixelCount());
    for (size_t i = 0; i < ref.pixelCount(); ++i)
        if (covered(mask, i))
            e.push_back(std::abs(double(test.pixels[i * size_t(test.channels) + size_t(channel)]) -
                                 double(ref.pixels[i * size_t(ref.channels) + size_t(channel)])));
    return summarize(e);
}

Image scalarAbsErrorImage(const Image& ref, const Image& test, int channel, const Mask* mask) {
    checkPair(ref, test, mask, "scalarAbsErrorImage");
    checkChannels(ref, test, channel, 1, "scalarAbsErrorImage");
    Image out(ref.width, ref.height, 1, 0.0f);
    for (size_t i = 0; i < ref.pixelCount(); ++i)
        if (covered(mask, i))
            out.pixels[i] = std::abs(test.pixels[i * size_t(test.channels) + size_t(channel)] -
                                     ref.pixels[i * size_t(ref.channels) + size_t(channel)]);
    return out;
}

ColorErrorStats colorErrorStats(const Image& ref, const Image& test, const Mask* mask, int first) {
    checkPair(ref, test, mask, "colorErrorStats");
    checkChannels(ref, test, first, 3, "colorErrorStats");
    std::vector<double> de;
    de.reserve(ref.pixelCount());
    double sum2 = 0.0;
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        const float* r = ref.pixels.data() + i * size_t(ref.channels) + size_t(first);
        const float* t = test.pixels.data() + i * size_t(test.channels) + size_t(first);
        for (int k = 0; k < 3; ++k) {
            const double d = double(t[k]) - double(r[k]);
            sum2 += d * d;
        }
        de.push_back(pixelDeltaE(r, t));
    }
    ColorErrorStats s;
    if (!de.empty()) s.rmse = std::sqrt(sum2 / (3.0 * double(de.size())));
    s.deltaE2000 = summarize(de);
    return s;
}

Image deltaE2000Image(const Image& ref, const Image& test, const Mask* mask, int first) {
    checkPair(ref, test, mask, "deltaE2000Image");
    checkChannels(ref, test, first, 3, "deltaE2000Image");
    Image out(ref.width, ref.height, 1, 0.0f);
    for (size_t i = 0; i < ref.pixelCount(); ++i)
        if (covered(mask, i))
            out.pixels[i] = float(pixelDeltaE(ref.pixels.data() + i * size_t(ref.channels) + size_t(first),
                                              test.pixels.data() + i * size_t(test.channels) + size_t(first)));
    return out;
}

}  // namespace gbl
