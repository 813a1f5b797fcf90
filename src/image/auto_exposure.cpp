// UE4's histogram auto-exposure on one frame (auto_exposure.h).
#include "auto_exposure.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace gbl {

int exposureBucket(double luminance, const AutoExposureSettings& s) {
    if (!(luminance > 0.0)) return 0;
    const double position = (std::log2(luminance) - s.logMin) / (s.logMax - s.logMin);
    const double b = std::floor(position * s.buckets);
    return int(std::clamp(b, 0.0, double(s.buckets - 1)));
}

double exposureBucketLuminance(int bucket, const AutoExposureSettings& s) {
    return std::exp2(s.logMin + (bucket + 0.5) / s.buckets * (s.logMax - s.logMin));
}

AutoExposure meterExposure(const Image& hdr, const AutoExposureSettings& s) {
    if (hdr.empty() || hdr.channels < 3) throw std::invalid_argument("auto exposure: an RGB image is needed");
    if (s.buckets < 1 || !(s.logMax > s.logMin) || !(s.lowPercent >= 0.0 && s.lowPercent < s.highPercent &&
                                                      s.highPercent <= 100.0) ||
        !(s.minBrightness > 0.0 && s.minBrightness <= s.maxBrightness) || !(s.key > 0.0))
        throw std::invalid_argument("auto exposure: settings out of range");
    std::vector<double> histogram(size_t(s.buckets), 0.0);
    const size_t n = hdr.pixelCount();
    const int ch = hdr.channels;
    for (size_t i = 0; i < n; ++i) {
        const float* p = &hdr.pixels[i * size_t(ch)];
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];  // CIE Y, Rec. 709 primaries
        histogram[size_t(exposureBucket(y, s))] += 1.0;
    }
    // UE's ComputeAverageLuminaneWithoutOutlier: walk the buckets upwards, dropping the first
    // low% of the pixels and everything past high%, averaging what is left.
    double below = double(n) * s.lowPercent / 100.0, upTo = double(n) * s.highPercent / 100.0;
    double sum = 0.0, weight = 0.0;
    for (int b = 0; b < s.buckets; ++b) {
        double count = histogram[size_t(b)];
        const double dropped = std::min(count, below);
        count -= dropped;
        below -= dropped;
        upTo -= dropped;
        count = std::min(count, upTo);
        upTo -= count;
        sum += exposureBucketLuminance(b, s) * count;
        weight += count;
    }
    AutoExposure e;
    e.averageLuminance = sum / std::max(1e-4, weight);
    e.meteredLuminance = std::clamp(e.averageLuminance, s.minBrightness, s.maxBrightness);
    e.exposure = s.key / e.meteredLuminance;
    return e;
}

}  // namespace gbl
