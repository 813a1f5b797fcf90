// PairMemo returns what the function it memoises returns, bit for bit, and calls it only for
// pairs it has not kept: checked against the function itself on data with repeats, with a memo
// small enough that slots collide and are overwritten.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "metrics.h"
#include "pair_memo.h"

namespace {

uint64_t bits(double d) {
    uint64_t u;
    std::memcpy(&u, &d, sizeof u);
    return u;
}

TEST(PairMemo, SameValuesAsTheFunctionWithCollisions) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::uniform_int_distribution<int> pick(0, 299);
    std::vector<float> palette(300 * 6);
    for (float& x : palette) x = u(rng);
    gbl::PairMemo<double> memo(4);  // 16 slots for 300 distinct pairs: most lookups evict
    size_t calls = 0;
    auto deltaE = [&](const float* a, const float* b) {
        ++calls;
        return gbl::pixelDeltaE(a, b);
    };
    size_t lookups = 0;
    for (int i = 0; i < 20000; ++i) {
        const int p = (i % 5 == 0) ? pick(rng) : (i / 5) % 300;  // runs of repeats, then jumps
        const float* a = &palette[size_t(p) * 6];
        const float* b = a + 3;
        const double got = memo.get(a, b, deltaE);
        ++lookups;
        ASSERT_EQ(bits(got), bits(gbl::pixelDeltaE(a, b))) << "pair " << p;
    }
    EXPECT_EQ(memo.misses(), calls);
    EXPECT_LT(calls, lookups);  // the repeats were served from the memo
    EXPECT_GT(calls, size_t(300));  // and collisions did evict
}

TEST(PairMemo, KeysAreBitPatterns) {
    // -0 == +0 as floats, but the memo must not serve one for the other: a function may tell
    // them apart (here through signbit).
    gbl::PairMemo<double> memo;
    auto sign = [](const float* a, const float*) { return std::signbit(a[0]) ? -1.0 : 1.0; };
    const float plus[6] = {0.0f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    const float minus[6] = {-0.0f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    EXPECT_EQ(memo.get(plus, plus + 3, sign), 1.0);
    EXPECT_EQ(memo.get(minus, minus + 3, sign), -1.0);
    EXPECT_EQ(memo.get(plus, plus + 3, sign), 1.0);
    // The test side is part of the key too.
    const float other[6] = {0.0f, 0.5f, 0.5f, 0.5f, 0.5f, 0.25f};
    int calls = 0;
    auto count = [&](const float*, const float* b) { ++calls; return double(b[2]); };
    EXPECT_EQ(memo.get(other, other + 3, count), 0.25);
    EXPECT_EQ(memo.get(other, other + 3, count), 0.25);
    EXPECT_EQ(calls, 1);
}

TEST(PairMemo, EveryWordOfTheKeyCounts) {
    // A pair that differs from the previous one in the lowest bit of any one of its six floats is
    // a new pair (the key compare covers all 24 bytes): the memo calls the function again.
    const float base[6] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    for (int k = 0; k < 6; ++k) {
        gbl::PairMemo<double> memo;
        int calls = 0;
        auto count = [&](const float*, const float*) { return double(++calls); };
        float changed[6];
        std::memcpy(changed, base, sizeof changed);
        uint32_t u;
        std::memcpy(&u, &changed[k], 4);
        u ^= 1u;
        std::memcpy(&changed[k], &u, 4);
        EXPECT_EQ(memo.get(base, base + 3, count), 1.0);
        EXPECT_EQ(memo.get(changed, changed + 3, count), 2.0) << "float " << k;
        EXPECT_EQ(memo.get(changed, changed + 3, count), 2.0) << "float " << k;  // and then kept
    }
}

}  // namespace
