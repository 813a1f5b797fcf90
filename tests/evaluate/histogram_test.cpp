// The GPU evaluation's histogram quantiles (src/evaluate/histogram.h) against exact nearest-rank
// quantiles (measure/metrics.h), with the bins computed here from the documented layout by
// exponent and mantissa (not by float bits as eval_common.glsl does).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "histogram.h"
#include "metrics.h"

namespace gbl::evaluate {
namespace {

// histogram.h: bin 0 zero, bin 1 (0, 2^-32), then 512 bins per power of two up to 2^32, then the rest.
uint32_t binOf(float v) {
    if (!(v > 0.0f)) return 0;
    if (v < std::ldexp(1.0f, -32)) return 1;
    if (v >= std::ldexp(1.0f, 32)) return kHistBins - 1;
    int e = 0;
    std::frexp(v, &e);                  // v = m 2^e, m in [0.5, 1)
    const int power = e - 1;            // v in [2^power, 2^(power + 1))
    const double frac = double(v) / std::ldexp(1.0, power) - 1.0;  // [0, 1)
    return 2u + uint32_t(power + 32) * 512u + uint32_t(std::floor(frac * 512.0));
}

TEST(Histogram, QuantilesAreWithinTheStatedBoundOfTheExactOnes) {
    std::mt19937 rng(7);
    std::lognormal_distribution<float> spread(-3.0f, 2.5f);  // about 1e-5 .. 1e2: many octaves
    for (const size_t n : {size_t(1), size_t(7), size_t(100), size_t(12345)}) {
        std::vector<float> v(n);
        for (float& x : v) x = spread(rng);
        if (n > 10) v[3] = 0.0f;  // exact zeros go to bin 0
        std::vector<uint32_t> bins(kHistBins, 0);
        for (float x : v) ++bins[binOf(x)];
        const double mx = *std::max_element(v.begin(), v.end());
        for (const double p : {0.5, 0.9, 0.99, 1.0}) {
            std::vector<double> exact(v.begin(), v.end());
            const double want = percentileNearestRank(exact, p);
            const double got = histogramQuantile(bins, p, mx);
            EXPECT_NEAR(got, want, want / 1024.0 + 1e-300) << "n " << n << " p " << p;
            EXPECT_LE(got, mx);
        }
    }
}

TEST(Histogram, ZerosAndEmptyGiveZero) {
    std::vector<uint32_t> bins(kHistBins, 0);
    EXPECT_EQ(histogramQuantile(bins, 0.99, 0.0), 0.0);
    bins[0] = 99;
    bins[binOf(3.0f)] = 1;
    EXPECT_EQ(histogramQuantile(bins, 0.99, 3.0), 0.0);   // rank 99 of 100: a zero
    EXPECT_NEAR(histogramQuantile(bins, 1.0, 3.0), 3.0, 3.0 / 1024.0);
}

TEST(Histogram, BinRangesTileThePositiveFloats) {
    double lo, hi, prevHi = 0.0;
    for (uint32_t b = 1; b < kHistBins - 1; ++b) {
        histogramBinRange(b, lo, hi);
        EXPECT_EQ(lo, prevHi) << b;
        EXPECT_LE(hi - lo, std::max(lo, 1e-300) / 512.0 + (b == 1 ? hi : 0.0)) << b;
        if (b >= 2) {  // bin 1 is open at 0
            EXPECT_EQ(binOf(float(lo)), b) << b;
        }
        prevHi = hi;
    }
    EXPECT_EQ(prevHi, std::ldexp(1.0, 32));
}

}  // namespace
}  // namespace gbl::evaluate
