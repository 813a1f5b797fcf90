#include "histogram.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "metrics.h"

namespace gbl::evaluate {

void histogramBinRange(uint32_t bin, double& lo, double& hi) {
    if (bin == 0) {
        lo = hi = 0.0;
    } else if (bin == 1) {
        lo = 0.0;
        hi = double(std::bit_cast<float>(kHistFirstBits));
    } else if (bin >= kHistBins - 1) {
        lo = double(std::bit_cast<float>(0x4F800000u));
        hi = std::numeric_limits<double>::infinity();
    } else {
        const uint32_t first = kHistFirstBits + ((bin - 2) << kHistBinShift);
        lo = double(std::bit_cast<float>(first));
        hi = double(std::bit_cast<float>(first + (1u << kHistBinShift)));
    }
}

double histogramQuantile(std::span<const uint32_t> bins, double p, double exactMax) {
    uint64_t n = 0;
    for (uint32_t c : bins) n += c;
    if (n == 0) return 0.0;
    const uint64_t rank = uint64_t(nearestRankIndex(p, size_t(n)));  // 0-based
    uint64_t seen = 0;
    for (uint32_t b = 0; b < bins.size(); ++b) {
        seen += bins[b];
        if (seen > rank) {
            double lo, hi;
            histogramBinRange(b, lo, hi);
            if (b == 0) return 0.0;
            const double mid = std::isinf(hi) ? lo : 0.5 * (lo + hi);
            return std::min(mid, exactMax);
        }
    }
    return exactMax;
}

}  // namespace gbl::evaluate
