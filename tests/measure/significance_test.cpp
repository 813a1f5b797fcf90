// The paired sign-flip permutation test (significance.h) against the textbook: Fisher's test of
// Darwin's Zea mays data (The Design of Experiments, 1935, section 21: 1,726 of the 32,768 sign
// assignments are at least as extreme, p = 0.0527 two-sided), against a brute-force enumeration
// written here for other data, and its Monte Carlo estimate against that enumeration.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "significance.h"

using namespace gbl;

namespace {

// Every sign assignment by recursion, counting |sum| >= |observed|.
double bruteForceP(const std::vector<double>& d) {
    double observed = 0;
    for (double x : d) observed += x;
    long hits = 0, total = 0;
    std::function<void(size_t, double)> walk = [&](size_t i, double sum) {
        if (i == d.size()) {
            ++total;
            hits += std::abs(sum) >= std::abs(observed) - 1e-9;
            return;
        }
        walk(i + 1, sum + d[i]);
        walk(i + 1, sum - d[i]);
    };
    walk(0, 0.0);
    return double(hits) / double(total);
}

// The Monte Carlo estimate as first written: one assignment after the other, splitmix64 drawn in
// sequence, each sum over the units in order. pairedSignFlipPValue sums several side by side.
double oneAfterTheOtherP(const std::vector<double>& d, int resamples, uint64_t seed) {
    double observed = 0.0;
    for (double x : d) observed += x;
    observed = std::abs(observed);
    const double tolerance = 1e-12 * std::max(1.0, observed);
    uint64_t state = seed;
    auto next = [&state] {
        uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    uint64_t hits = 0;
    for (int k = 0; k < resamples; ++k) {
        double sum = 0.0;
        uint64_t bits = 0;
        for (size_t i = 0; i < d.size(); ++i) {
            if (i % 64 == 0) bits = next();
            sum += (bits & 1u) ? -d[i] : d[i];
            bits >>= 1;
        }
        if (std::abs(sum) >= observed - tolerance) ++hits;
    }
    return double(1 + hits) / double(1 + resamples);
}

}  // namespace

// Summed side by side, the assignments give the p-value of summing them one after the other, to
// the last bit: every unit count around a 64-bit word's edge, every resample count around the
// lanes', and the sizes compare runs (144 tiles a view, 3 views, 3 scenes).
TEST(Significance, AssignmentsSummedSideBySideGiveTheSamePValue) {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0005, 0.002);
    for (size_t n : {17u, 63u, 64u, 65u, 129u, 432u, 1296u})
        for (int resamples : {1, 7, 8, 9, 999, 4999}) {
            std::vector<double> d(n);
            for (double& x : d) x = noise(rng);
            EXPECT_EQ(pairedSignFlipPValue(d, resamples, 42), oneAfterTheOtherP(d, resamples, 42))
                << n << " units, " << resamples << " resamples";
        }
    std::vector<double> d(432);
    for (double& x : d) x = noise(rng);
    EXPECT_EQ(pairedSignFlipPValue(d), oneAfterTheOtherP(d, kSignFlipResamples, kSignFlipSeed));
}

TEST(Significance, DarwinsZeaMaysAsFisherCountedIt) {
    // Crossed minus self-fertilised heights, eighths of an inch (Fisher 1935, Table 3).
    const std::vector<double> d = {49, -67, 8, 16, 6, 23, 28, 41, 14, 29, 56, 24, 75, 60, -48};
    EXPECT_DOUBLE_EQ(pairedSignFlipPValue(d), 1726.0 / 32768.0);
    EXPECT_DOUBLE_EQ(bruteForceP(d), 1726.0 / 32768.0);
}

TEST(Significance, ExactAndMonteCarloAgreeWithBruteForce) {
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.3, 1.0);
    for (int n : {5, 12, 16}) {
        std::vector<double> d(static_cast<size_t>(n));
        for (double& x : d) x = noise(rng);
        EXPECT_DOUBLE_EQ(pairedSignFlipPValue(d), bruteForceP(d)) << n;
    }
    // Above 16 units: an estimate from 4999 assignments, within 4 standard errors.
    std::vector<double> d(20);
    for (double& x : d) x = noise(rng) * 0.6;
    const double exact = bruteForceP(d), estimate = pairedSignFlipPValue(d);
    EXPECT_NEAR(estimate, exact, 4.0 * std::sqrt(exact * (1 - exact) / 4999.0) + 1.0 / 5000.0);
    EXPECT_EQ(pairedSignFlipPValue(d), pairedSignFlipPValue(d)) << "seeded: the same every time";
    // Nothing to test: p = 1.
    EXPECT_EQ(pairedSignFlipPValue({}), 1.0);
    EXPECT_EQ(pairedSignFlipPValue({0.0, 0.0}), 1.0);
    // 300 tiles all one way: as small as 4999 assignments can say.
    EXPECT_DOUBLE_EQ(pairedSignFlipPValue(std::vector<double>(300, 0.01)), 1.0 / 5000.0);
}

TEST(Significance, TileMeansCoverTheFrame) {
    Image map(33, 19, 1);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) map.at(x, y, 0) = float(x + 100 * y);
    const std::vector<float> tiles = tileMeans(map, 4, 3);
    ASSERT_EQ(tiles.size(), 12u);
    // Tile (1, 2): x in [8, 16), y in [12, 19): mean x 11.5, mean y 15.
    EXPECT_FLOAT_EQ(tiles[2 * 4 + 1], 11.5f + 100.0f * 15.0f);
    EXPECT_EQ(tileMeans(Image(3, 3, 1), 16, 9).size(), 3u * 3u) << "an image narrower than the grid: empty tiles left out";
}
