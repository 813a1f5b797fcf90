#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
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
    const size_t k = nearestRankIndex(p, s.size());
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

double psnrFromMse(double mse, double peak) {
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(peak * peak / mse);
}

ImageErrorStats imageErrorStats(const Image& ref, const Image& test, const Mask* mask, PsnrPeak peakMode,
                                int channels) {
    checkPair(ref, test, mask, "imageErrorStats");
    const int c = resolveChannels(ref, test, channels, "imageErrorStats");
    std::vector<double> absErr;
    absErr.reserve(ref.pixelCount() * size_t(c));
    double sum = 0.0, sumAbs = 0.0, sum2 = 0.0, refMax = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < ref.pixelCount(); ++i) {
        if (!covered(mask, i)) continue;
        const float* r = ref.pixels.data() + i * size_t(ref.channels);
        const float* t = test.pixels.data() + i * size_t(test.channels);
        for (int k = 0; k < c; ++k) {
            const double d = double(t[k]) - double(r[k]);
            sum += d;
            sumAbs += std::abs(d);
            sum2 += d * d;
            absErr.push_back(std::abs(d));
            refMax = std::max(refMax, double(r[k]));
        }
    }
    ImageErrorStats s;
    s.count = absErr.size();
    s.peak = 1.0;
    if (peakMode == PsnrPeak::ReferenceMax && refMax > 0.0) s.peak = refMax;
    if (s.count == 0) return s;
    const double n = double(s.count);
    s.mean = sum / n;
    s.meanAbs = sumAbs / n;
    s.mse = sum2 / n;
    s.rmse = std::sqrt(s.mse);
    s.psnr = psnrFromMse(s.mse, s.peak);
    s.maxAbs = *std::max_element(absErr.begin(), absErr.end());
    s.p99Abs = percentileNearestRank(absErr, 0.99);
    return s;
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
