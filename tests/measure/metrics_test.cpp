#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "color_difference.h"
#include "error.h"
#include "metrics.h"

namespace {

using gbl::Image;

Image noise(int w, int h, int c, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image im(w, h, c);
    for (float& v : im.pixels) v = u(rng);
    return im;
}

// ---- Quantiles -------------------------------------------------------------------------------

TEST(Metrics, NearestRankQuantiles) {
    EXPECT_EQ(gbl::nearestRankIndex(0.99, 100), 98u);   // rank 99 of 100, not 100
    EXPECT_EQ(gbl::nearestRankIndex(0.99, 1000), 989u);
    EXPECT_EQ(gbl::nearestRankIndex(0.99, 10), 9u);     // ceil(9.9) = 10
    EXPECT_EQ(gbl::nearestRankIndex(0.5, 4), 1u);       // lower median
    EXPECT_EQ(gbl::nearestRankIndex(0.5, 5), 2u);
    EXPECT_EQ(gbl::nearestRankIndex(0.0, 5), 0u);
    EXPECT_EQ(gbl::nearestRankIndex(1.0, 5), 4u);
    std::vector<double> v;
    for (int i = 100; i >= 1; --i) v.push_back(i);  // 1..100, shuffled order
    std::shuffle(v.begin(), v.end(), std::mt19937(3));
    EXPECT_EQ(gbl::percentileNearestRank(v, 0.99), 99.0);
    EXPECT_EQ(gbl::percentileNearestRank(v, 0.5), 50.0);
    std::vector<double> empty;
    EXPECT_EQ(gbl::percentileNearestRank(empty, 0.99), 0.0);
}

// ---- Image errors ----------------------------------------------------------------------------

TEST(Metrics, IdenticalImagesGiveZeroErrorAndInfinitePsnr) {
    const Image a = noise(31, 17, 4, 1);
    for (gbl::PsnrPeak peak : {gbl::PsnrPeak::One, gbl::PsnrPeak::ReferenceMax}) {
        const gbl::ImageErrorStats s = gbl::imageErrorStats(a, a, nullptr, peak);
        EXPECT_EQ(s.count, a.pixels.size());
        EXPECT_EQ(s.mse, 0.0);
        EXPECT_EQ(s.rmse, 0.0);
        EXPECT_EQ(s.mean, 0.0);
        EXPECT_EQ(s.meanAbs, 0.0);
        EXPECT_EQ(s.maxAbs, 0.0);
        EXPECT_EQ(s.p99Abs, 0.0);
        EXPECT_EQ(s.psnr, std::numeric_limits<double>::infinity());
    }
    for (float v : gbl::absErrorImage(a, a).pixels) ASSERT_EQ(v, 0.0f);
    for (float v : gbl::maxAbsErrorImage(a, a).pixels) ASSERT_EQ(v, 0.0f);
    for (float v : gbl::squaredErrorImage(a, a).pixels) ASSERT_EQ(v, 0.0f);
    EXPECT_EQ(gbl::normalAngleStats(a, a).angleDeg.max, 0.0);
    EXPECT_EQ(gbl::scalarAbsErrorStats(a, a, 3).max, 0.0);
    const gbl::ColorErrorStats c = gbl::colorErrorStats(a, a);
    EXPECT_EQ(c.deltaE2000.max, 0.0);
    EXPECT_EQ(c.rmse, 0.0);
}

TEST(Metrics, PsnrMatchesHandComputation) {
    // One channel, reference 0, test 0, .25, .5, .75 (exact in float):
    // MSE = (0 + 1/16 + 1/4 + 9/16) / 4 = 0.21875; PSNR = 10 log10(1 / 0.21875) = 6.6005194 dB.
    Image r(4, 1, 1, 0.0f), t(4, 1, 1);
    t.pixels = {0.0f, 0.25f, 0.5f, 0.75f};
    gbl::ImageErrorStats s = gbl::imageErrorStats(r, t);
    EXPECT_DOUBLE_EQ(s.mse, 0.21875);
    EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(0.21875));
    EXPECT_NEAR(s.psnr, 6.600519383056492, 1e-12);
    EXPECT_EQ(s.peak, 1.0);
    EXPECT_DOUBLE_EQ(s.mean, 0.375);
    EXPECT_DOUBLE_EQ(s.meanAbs, 0.375);
    EXPECT_EQ(s.maxAbs, 0.75);
    EXPECT_EQ(s.p99Abs, 0.75);
    // Peak = the reference's maximum (4): PSNR = 10 log10(16 / 0.21875) = 18.6417192 dB.
    r.pixels = {4.0f, 0.0f, 0.0f, 0.0f};
    t.pixels = {4.0f, 0.25f, 0.5f, 0.75f};
    s = gbl::imageErrorStats(r, t, nullptr, gbl::PsnrPeak::ReferenceMax);
    EXPECT_EQ(s.peak, 4.0);
    EXPECT_NEAR(s.psnr, 18.64171920961574, 1e-12);
    // A reference max <= 0 falls back to peak 1.
    Image z(4, 1, 1, -1.0f);
    EXPECT_EQ(gbl::imageErrorStats(z, t, nullptr, gbl::PsnrPeak::ReferenceMax).peak, 1.0);
    EXPECT_NEAR(gbl::psnrFromMse(0.01, 1.0), 20.0, 1e-12);
}

TEST(Metrics, MaskSelectsPixels) {
    Image r(4, 1, 3, 0.0f), t(4, 1, 3, 0.0f);
    for (int c = 0; c < 3; ++c) {
        t.at(1, 0, c) = 0.5f;
        t.at(3, 0, c) = -1.0f;  // masked out
    }
    const gbl::Mask mask = {1, 1, 1, 0};
    const gbl::ImageErrorStats s = gbl::imageErrorStats(r, t, &mask);
    EXPECT_EQ(s.count, 9u);
    EXPECT_DOUBLE_EQ(s.mse, 3 * 0.25 / 9);
    EXPECT_DOUBLE_EQ(s.mean, 1.5 / 9);
    EXPECT_EQ(s.maxAbs, 0.5);
    const Image e = gbl::maxAbsErrorImage(r, t, &mask);
    EXPECT_EQ(e.pixels, (std::vector<float>{0, 0.5f, 0, 0}));
    const gbl::ImageErrorStats all = gbl::imageErrorStats(r, t);
    EXPECT_EQ(all.maxAbs, 1.0);
    const gbl::Mask empty;
    EXPECT_EQ(gbl::imageErrorStats(r, t, &empty).count, 12u);
    const gbl::Mask wrong = {1, 1};
    EXPECT_THROW(gbl::imageErrorStats(r, t, &wrong), gbl::UserError);
}

TEST(Metrics, P99AndChannelsArgument) {
    // 100 pixels, 1 channel, errors 0.01 .. 1.00 in random order; an alpha channel differs by 5.
    Image r(100, 1, 2, 0.0f), t(100, 1, 2, 0.0f);
    std::vector<int> order(100);
    for (int i = 0; i < 100; ++i) order[size_t(i)] = i + 1;
    std::shuffle(order.begin(), order.end(), std::mt19937(5));
    for (int i = 0; i < 100; ++i) {
        t.at(i, 0, 0) = order[size_t(i)] / 100.0f;
        t.at(i, 0, 1) = 5.0f;
    }
    const gbl::ImageErrorStats s = gbl::imageErrorStats(r, t, nullptr, gbl::PsnrPeak::One, 1);
    EXPECT_EQ(s.count, 100u);
    EXPECT_FLOAT_EQ(float(s.p99Abs), 0.99f);
    EXPECT_FLOAT_EQ(float(s.maxAbs), 1.0f);
    EXPECT_THROW(gbl::imageErrorStats(r, t, nullptr, gbl::PsnrPeak::One, 3), gbl::UserError);
    EXPECT_THROW(gbl::imageErrorStats(Image(2, 2, 3), Image(2, 3, 3)), gbl::UserError);
}

TEST(Metrics, ImageStatsEqualAPlainSortOfEverySample) {
    // imageErrorStats selects its p99 in one histogram bucket instead of keeping every sample;
    // here every statistic is recomputed from all samples (sorted, summed in order) and must be
    // the same double. Errors span many exponents, many repeat one value (one crowded bucket),
    // and a mask drops some pixels.
    const int w = 157, h = 93, c = 4;
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image r(w, h, c), t(w, h, c);
    for (size_t i = 0; i < r.pixels.size(); ++i) {
        r.pixels[i] = std::pow(10.0f, -3.0f + 6.0f * u(rng));
        const float kind = u(rng);
        t.pixels[i] = kind < 0.3f ? r.pixels[i] + 0.125f : r.pixels[i] * (1.0f + 0.2f * (u(rng) - 0.5f));
    }
    gbl::Mask mask(size_t(w) * h);
    for (auto& m : mask) m = u(rng) < 0.8f ? 1 : 0;
    const gbl::Mask* masks[] = {nullptr, &mask};
    for (const gbl::Mask* mk : masks)
        for (int channels : {3, 4}) {
            std::vector<double> all;
            double sum = 0.0, sum2 = 0.0;
            for (size_t p = 0; p < r.pixelCount(); ++p) {
                if (mk && !(*mk)[p]) continue;
                for (int k = 0; k < channels; ++k) {
                    const double d = double(t.pixels[p * c + k]) - double(r.pixels[p * c + k]);
                    all.push_back(std::abs(d));
                    sum += d;
                    sum2 += d * d;
                }
            }
            std::vector<double> sorted = all;
            std::sort(sorted.begin(), sorted.end());
            const size_t rank = (99 * sorted.size() + 99) / 100;  // nearest rank ceil(0.99 n), 1-based
            const gbl::ImageErrorStats s = gbl::imageErrorStats(r, t, mk, gbl::PsnrPeak::ReferenceMax, channels);
            ASSERT_EQ(s.count, all.size());
            EXPECT_EQ(s.p99Abs, sorted[rank - 1]) << channels;
            EXPECT_EQ(s.maxAbs, sorted.back());
            EXPECT_EQ(s.mean, sum / double(all.size()));
            EXPECT_EQ(s.mse, sum2 / double(all.size()));
            if (!mk) {
                EXPECT_EQ(gbl::meanSquaredError(r, t, channels), s.mse);  // the same double
            }
        }
    EXPECT_EQ(gbl::meanSquaredError(r, r, 3), 0.0);
    EXPECT_THROW(gbl::meanSquaredError(Image(2, 2, 3), Image(2, 3, 3)), gbl::UserError);
}

TEST(Metrics, SummarizeByClassIsSummarizeOfEachClass) {
    // One pool with a class byte per sample against three separate pools through summarize()
    // (nth_element): the same doubles for every statistic. Samples span exponents, repeat (a
    // crowded bucket), include zeros; sizes include a class with one sample and an empty class.
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // The mixes: a fifth zeros; zeros holding the p99's rank; the rank past the zeros but inside
    // their bucket (subnormal errors share the top 16 bits of +0), where the pool's zeros stand
    // first among the bucket's samples.
    struct Mix {
        double zeros, tiny;
    };
    for (const Mix mix : {Mix{0.2, 0.0}, Mix{0.995, 0.0}, Mix{0.985, 0.012}}) {
    for (size_t n : {size_t(1), size_t(2), size_t(137), size_t(20000)}) {
        for (double metalShare : {0.0, 0.3, 1.0}) {
            std::vector<double> pool;
            std::vector<uint8_t> cls;
            std::vector<double> byClass[2], all;
            for (size_t i = 0; i < n; ++i) {
                const double kind = u(rng);
                const double v = kind < mix.zeros                ? 0.0
                                 : kind < mix.zeros + mix.tiny   ? 1e-310 * (1.0 + u(rng))
                                 : kind < mix.zeros + 0.3 * (1.0 - mix.zeros - mix.tiny) + mix.tiny
                                     ? 1.5
                                     : std::pow(10.0, -5.0 + 8.0 * u(rng));
                const uint8_t c = u(rng) < metalShare ? 1 : 0;
                pool.push_back(v);
                cls.push_back(c);
                byClass[c].push_back(v);
                all.push_back(v);
            }
            const std::array<gbl::ScalarStats, 3> got = gbl::summarizeByClass(pool, cls);
            const gbl::ScalarStats want[3] = {gbl::summarize(byClass[0]), gbl::summarize(byClass[1]), gbl::summarize(all)};
            for (int k = 0; k < 3; ++k) {
                SCOPED_TRACE("n " + std::to_string(n) + " share " + std::to_string(metalShare) + " class " + std::to_string(k));
                EXPECT_EQ(got[size_t(k)].count, want[k].count);
                EXPECT_EQ(got[size_t(k)].mean, want[k].mean);
                EXPECT_EQ(got[size_t(k)].rms, want[k].rms);
                EXPECT_EQ(got[size_t(k)].p99, want[k].p99);
                EXPECT_EQ(got[size_t(k)].max, want[k].max);
            }
        }
    }
    }
    EXPECT_THROW(gbl::summarizeByClass({1.0, 2.0}, {0}), std::invalid_argument);
}

// ---- Normals ---------------------------------------------------------------------------------

// Rotates v by `deg` degrees about the unit axis k (Rodrigues).
std::array<double, 3> rotate(const std::array<double, 3>& v, const std::array<double, 3>& k, double deg) {
    const double t = deg * std::numbers::pi / 180.0, c = std::cos(t), s = std::sin(t);
    const double kd = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const std::array<double, 3> kx = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    std::array<double, 3> r;
    for (int i = 0; i < 3; ++i) r[size_t(i)] = v[size_t(i)] * c + kx[size_t(i)] * s + k[size_t(i)] * kd * (1 - c);
    return r;
}

TEST(Metrics, NormalAngleExactOnKnownRotations) {
    // Pixel i: a random unit normal n, and n rotated by angle_i about an axis perpendicular to
    // n, so the angle between them is exactly angle_i. Angles 0.01 .. 179 degrees.
    const int n = 200;
    Image r(n, 1, 3), t(n, 1, 3);
    std::vector<double> angles;
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    for (int i = 0; i < n; ++i) {
        std::array<double, 3> v = {g(rng), g(rng), g(rng)}, a = {g(rng), g(rng), g(rng)};
        const double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (double& x : v) x /= lv;
        // axis = normalize(a - (a.v) v)
        const double av = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
        for (int k = 0; k < 3; ++k) a[size_t(k)] -= av * v[size_t(k)];
        const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (double& x : a) x /= la;
        const double angle = i == 0 ? 0.01 : i * 179.0 / (n - 1);
        angles.push_back(angle);
        const auto w = rotate(v, a, angle);
        for (int k = 0; k < 3; ++k) {
            r.at(i, 0, k) = float(v[size_t(k)]);
            t.at(i, 0, k) = float(w[size_t(k)] * (1.0 + i % 3));  // length need not be 1
        }
    }
    const Image img = gbl::normalAngleImage(r, t);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(img.pixels[size_t(i)], angles[size_t(i)], 2e-4) << i;
    const gbl::NormalErrorStats s = gbl::normalAngleStats(r, t);
    double mean = 0;
    for (double a : angles) mean += a;
    mean /= n;
    EXPECT_EQ(s.skipped, 0u);
    EXPECT_EQ(s.angleDeg.count, size_t(n));
    EXPECT_NEAR(s.angleDeg.mean, mean, 1e-4);
    EXPECT_NEAR(s.angleDeg.max, 179.0, 1e-4);
    EXPECT_NEAR(s.angleDeg.p99, angles[197], 1e-4);  // rank ceil(198) = 198 of 200
    EXPECT_NEAR(img.pixels[0], 0.01, 1e-5);             // small angles stay accurate
}

TEST(Metrics, NormalAngleSimpleCasesAndSkips) {
    Image r(4, 1, 4, 0.0f), t(4, 1, 4, 0.0f);
    // 90 degrees, 180 degrees, 45 degrees, and a zero normal (skipped). Channel 0 is padding.
    const float rn[4][3] = {{0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 0, 0}};
    const float tn[4][3] = {{1, 0, 0}, {0, 0, -1}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            r.at(i, 0, k + 1) = rn[i][k];
            t.at(i, 0, k + 1) = tn[i][k];
        }
    const gbl::NormalErrorStats s = gbl::normalAngleStats(r, t, nullptr, 1);
    EXPECT_EQ(s.skipped, 1u);
    EXPECT_EQ(s.angleDeg.count, 3u);
    EXPECT_NEAR(s.angleDeg.mean, (90.0 + 180.0 + 45.0) / 3, 1e-9);
    EXPECT_NEAR(s.angleDeg.max, 180.0, 1e-9);
    const Image img = gbl::normalAngleImage(r, t, nullptr, 1);
    EXPECT_NEAR(img.pixels[2], 45.0f, 1e-5);
    EXPECT_EQ(img.pixels[3], 0.0f);
    EXPECT_THROW(gbl::normalAngleStats(r, t, nullptr, 2), gbl::UserError);
}

// ---- Scalars ---------------------------------------------------------------------------------

TEST(Metrics, ScalarAbsError) {
    Image r(4, 1, 2, 0.0f), t(4, 1, 2, 0.0f);
    const float rough[4] = {0.1f, 0.5f, 0.9f, 0.3f}, rough2[4] = {0.2f, 0.5f, 0.6f, 0.3f};
    for (int i = 0; i < 4; ++i) {
        r.at(i, 0, 1) = rough[i];
        t.at(i, 0, 1) = rough2[i];
    }
    const gbl::ScalarStats s = gbl::scalarAbsErrorStats(r, t, 1);
    EXPECT_EQ(s.count, 4u);
    EXPECT_NEAR(s.mean, (0.1 + 0.3) / 4, 1e-7);
    EXPECT_NEAR(s.max, 0.3, 1e-7);
    EXPECT_NEAR(s.p99, 0.3, 1e-7);
    EXPECT_NEAR(s.rms, std::sqrt((0.01 + 0.09) / 4), 1e-7);
    EXPECT_EQ(gbl::scalarAbsErrorStats(r, t, 0).max, 0.0);
    EXPECT_NEAR(gbl::scalarAbsErrorImage(r, t, 1).pixels[2], 0.3f, 1e-7);
}

// ---- Colour ----------------------------------------------------------------------------------

// Sharma, Wu & Dalal (2005), Table 1: L*a*b* pairs and their CIEDE2000 differences (4 decimals).
struct SharmaPair {
    double L1, a1, b1, L2, a2, b2, dE;
};
constexpr SharmaPair kSharma[] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

TEST(ColorDifference, SharmaTestData) {
    int i = 1;
    for (const SharmaPair& p : kSharma) {
        const gbl::Lab a{p.L1, p.a1, p.b1}, b{p.L2, p.a2, p.b2};
        EXPECT_NEAR(gbl::deltaE2000(a, b), p.dE, 0.5e-4) << "pair " << i;
        EXPECT_NEAR(gbl::deltaE2000(b, a), p.dE, 0.5e-4) << "pair " << i << " swapped";
        ++i;
    }
    EXPECT_EQ(gbl::deltaE2000({50, 10, -20}, {50, 10, -20}), 0.0);
}

TEST(ColorDifference, LabConversions) {
    const gbl::Lab w = gbl::linearSrgbToLab(1, 1, 1);
    EXPECT_NEAR(w.L, 100.0, 1e-9);
    EXPECT_NEAR(w.a, 0.0, 1e-9);
    EXPECT_NEAR(w.b, 0.0, 1e-9);
    // sRGB red (1,0,0): L*a*b* (D65) = (53.2408, 80.0925, 67.2032), to 4 decimals with this matrix.
    const gbl::Lab red = gbl::linearSrgbToLab(1, 0, 0);
    EXPECT_NEAR(red.L, 53.2408, 2e-3);
    EXPECT_NEAR(red.a, 80.0925, 2e-3);
    EXPECT_NEAR(red.b, 67.2032, 2e-3);
    // Round trip Lab -> XYZ -> RGB.
    double r, g, b;
    gbl::xyzToLinearSrgb(gbl::labToXyz(gbl::linearSrgbToLab(0.2, 0.5, 0.03)), r, g, b);
    EXPECT_NEAR(r, 0.2, 1e-12);
    EXPECT_NEAR(g, 0.5, 1e-12);
    EXPECT_NEAR(b, 0.03, 1e-12);
    EXPECT_NEAR(gbl::srgbDecode(gbl::srgbEncode(0.001)), 0.001, 1e-15);
    EXPECT_NEAR(gbl::srgbEncode(0.5), 0.735356983, 1e-8);
}

TEST(Metrics, ColorErrorStats) {
    // White vs black (linear RGB): L* 100 vs 0 at mean L* 50, so S_L = 1 and dE00 = 100.
    Image r(2, 1, 3, 1.0f), t(2, 1, 3, 0.0f);
    const gbl::ColorErrorStats s = gbl::colorErrorStats(r, t);
    EXPECT_NEAR(s.deltaE2000.mean, 100.0, 1e-9);
    EXPECT_NEAR(s.deltaE2000.max, 100.0, 1e-9);
    EXPECT_DOUBLE_EQ(s.rmse, 1.0);
    // Matches the per-pixel image and the direct formula on a random pair.
    const Image a = noise(9, 7, 3, 21), b = noise(9, 7, 3, 22);
    const Image img = gbl::deltaE2000Image(a, b);
    for (size_t i = 0; i < a.pixelCount(); ++i) {
        const float* p = &a.pixels[i * 3];
        const float* q = &b.pixels[i * 3];
        const double d = gbl::deltaE2000(gbl::linearSrgbToLab(p[0], p[1], p[2]), gbl::linearSrgbToLab(q[0], q[1], q[2]));
        EXPECT_NEAR(img.pixels[i], d, 1e-4 * std::max(1.0, d));
    }
}

}  // namespace
