// radixSortFloats against std::sort (the order it replaces in flipStats) on values that exercise
// every part of the key map: negatives, both zeros, denormals, infinities, repeats.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "float_sort.h"

namespace {

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

// Sorted by value with std::sort, then -0 placed before +0 inside each run of zeros (the one
// order std::sort leaves open that radixSortFloats fixes).
std::vector<float> oracle(std::vector<float> v) {
    std::sort(v.begin(), v.end());
    auto zeros = std::equal_range(v.begin(), v.end(), 0.0f);
    std::stable_partition(zeros.first, zeros.second, [](float z) { return std::signbit(z); });
    return v;
}

void expectSameBits(const std::vector<float>& a, const std::vector<float>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(bits(a[i]), bits(b[i])) << "at " << i << ": " << a[i] << " vs " << b[i];
}

TEST(RadixSortFloats, MatchesStdSortOnMixedValues) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1000.0f, 1000.0f);
    std::uniform_int_distribution<uint32_t> anyBits(0, 0xFFFFFFFFu);
    const float special[] = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                             std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                             std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(), 1.0f, 0.5f};
    std::vector<float> v;
    for (int i = 0; i < 50000; ++i) {
        v.push_back(u(rng));
        float f;
        const uint32_t b = anyBits(rng);
        std::memcpy(&f, &b, sizeof f);
        if (!std::isnan(f)) v.push_back(f);  // every exponent, denormals included
        v.push_back(special[i % 10]);
    }
    std::vector<float> r = v;
    gbl::radixSortFloats(r);
    expectSameBits(r, oracle(v));
}

TEST(RadixSortFloats, FlipLikeMapsInUnitInterval) {
    // FLIP values share their top exponent bits: the pass over that digit is skipped, the result
    // must not change.
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> v(300000);
    for (float& x : v) x = u(rng) * u(rng) * u(rng);
    for (size_t i = 0; i < v.size(); i += 7) v[i] = 0.0f;
    std::vector<float> r = v;
    gbl::radixSortFloats(r);
    expectSameBits(r, oracle(v));
    // A constant map: every pass is skipped.
    std::vector<float> c(1000, 0.25f);
    gbl::radixSortFloats(c);
    expectSameBits(c, std::vector<float>(1000, 0.25f));
}

TEST(RadixSortFloats, NansGoToTheEndsByTheirSign) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> v = {2.0f, nan, -1.0f, -nan, 0.5f};
    gbl::radixSortFloats(v);
    EXPECT_TRUE(std::isnan(v.front()) && std::signbit(v.front()));
    EXPECT_TRUE(std::isnan(v.back()) && !std::signbit(v.back()));
    EXPECT_EQ(v[1], -1.0f);
    EXPECT_EQ(v[2], 0.5f);
    EXPECT_EQ(v[3], 2.0f);
    std::vector<float> empty;
    gbl::radixSortFloats(empty);
    EXPECT_TRUE(empty.empty());
}

}  // namespace
