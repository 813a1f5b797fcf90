// The paired sign-flip permutation test and the tiles it runs on (significance.h).
#include "significance.h"

#include <algorithm>
#include <cmath>

namespace gbl {

std::vector<float> tileMeans(const Image& map, int columns, int rows, const std::vector<uint8_t>* included) {
    std::vector<float> out;
    if (map.empty() || columns < 1 || rows < 1) return out;
    for (int r = 0; r < rows; ++r) {
        const int y0 = int(int64_t(r) * map.height / rows), y1 = int(int64_t(r + 1) * map.height / rows);
        for (int c = 0; c < columns; ++c) {
            const int x0 = int(int64_t(c) * map.width / columns), x1 = int(int64_t(c + 1) * map.width / columns);
            if (x1 <= x0 || y1 <= y0) continue;
            double sum = 0.0;
            if (included) {
                size_t count = 0;
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) {
                        const size_t i = size_t(y) * map.width + x;
                        if (!(*included)[i]) continue;
                        sum += map.pixels[i * map.channels];
                        ++count;
                    }
                out.push_back(count ? float(sum / double(count)) : 0.0f);
                continue;
            }
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) sum += map.pixels[(size_t(y) * map.width + x) * map.channels];
            out.push_back(float(sum / (double(x1 - x0) * (y1 - y0))));
        }
    }
    return out;
}

double pairedSignFlipPValue(const std::vector<double>& differences, int resamples, uint64_t seed) {
    std::vector<double> d;
    for (double x : differences)
        if (x != 0.0 && std::isfinite(x)) d.push_back(x);  // a zero difference has no sign to flip
    if (d.empty()) return 1.0;
    double observed = 0.0;
    for (double x : d) observed += x;
    observed = std::abs(observed);
    // Sums that equal the observed one up to rounding count as at least as extreme.
    const double tolerance = 1e-12 * std::max(1.0, observed);
    const size_t n = d.size();
    if (n <= size_t(kExactSignFlipUnits)) {
        uint64_t hits = 0;
        const uint64_t assignments = uint64_t(1) << n;
        for (uint64_t mask = 0; mask < assignments; ++mask) {
            double sum = 0.0;
            for (size_t i = 0; i < n; ++i) sum += (mask >> i & 1u) ? -d[i] : d[i];
            if (std::abs(sum) >= observed - tolerance) ++hits;
        }
        return double(hits) / double(assignments);
    }
    // splitmix64 (Steele, Lea, Flood 2014): a fixed seed, so a report is reproducible. Its j-th
    // output (from 0) is mix(seed + (j + 1) gamma); assignment k reads outputs k W .. k W + W - 1,
    // W = ceil(n / 64), one bit per unit from the lowest. Several assignments are summed side by
    // side, each in the order of the units, as one after the other would: the same sums to the
    // last bit, without waiting on one long chain of additions.
    constexpr uint64_t kGamma = 0x9e3779b97f4a7c15ULL;
    auto output = [seed](uint64_t j) {
        uint64_t z = seed + (j + 1) * kGamma;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    const uint64_t words = (n + 63) / 64;
    constexpr int kLanes = 8;
    uint64_t hits = 0;
    for (int k0 = 0; k0 < resamples; k0 += kLanes) {
        double sum[kLanes] = {};
        uint64_t bits[kLanes] = {};
        for (size_t i = 0; i < n; ++i) {
            if (i % 64 == 0)
                for (int l = 0; l < kLanes; ++l) bits[l] = output(uint64_t(k0 + l) * words + i / 64);
            for (int l = 0; l < kLanes; ++l) {
                sum[l] += (bits[l] & 1u) ? -d[i] : d[i];
                bits[l] >>= 1;
            }
        }
        for (int l = 0; l < kLanes && k0 + l < resamples; ++l)
            if (std::abs(sum[l]) >= observed - tolerance) ++hits;
    }
    return double(1 + hits) / double(1 + resamples);
}

}  // namespace gbl
