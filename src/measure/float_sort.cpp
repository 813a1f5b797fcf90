#include "float_sort.h"

#include <array>
#include <cstdint>
#include <cstring>

namespace gbl {
namespace {

// The order-preserving map from a float's bits to an unsigned key (Herf, "Radix Tricks", 2001):
// flip every bit of a negative number, only the sign bit of a positive one.
inline uint32_t toKey(uint32_t bits) { return bits ^ ((bits & 0x80000000u) ? 0xFFFFFFFFu : 0x80000000u); }
inline uint32_t fromKey(uint32_t key) { return key ^ ((key & 0x80000000u) ? 0x80000000u : 0xFFFFFFFFu); }

constexpr int kDigitBits = 11;  // 3 passes over 32 bits; 2048 counters stay in L1
constexpr int kPasses = 3;
constexpr uint32_t kDigits = 1u << kDigitBits;

}  // namespace

void radixSortFloats(std::vector<float>& values) {
    const size_t n = values.size();
    if (n < 2) return;
    std::vector<uint32_t> a(n), b(n);
    std::memcpy(a.data(), values.data(), n * sizeof(float));
    // All passes' histograms in one read.
    std::array<std::array<size_t, kDigits>, kPasses> count{};
    for (uint32_t& k : a) {
        k = toKey(k);
        for (int p = 0; p < kPasses; ++p) ++count[size_t(p)][(k >> (p * kDigitBits)) & (kDigits - 1)];
    }
    for (int p = 0; p < kPasses; ++p) {
        std::array<size_t, kDigits>& c = count[size_t(p)];
        // A digit every key shares (the exponent bits of values in [0, 1]) needs no pass.
        if (c[(a[0] >> (p * kDigitBits)) & (kDigits - 1)] == n) continue;
        size_t sum = 0;
        for (size_t& x : c) {
            const size_t v = x;
            x = sum;
            sum += v;
        }
        for (uint32_t k : a) b[c[(k >> (p * kDigitBits)) & (kDigits - 1)]++] = k;  // stable
        a.swap(b);
    }
    for (uint32_t& k : a) k = fromKey(k);
    std::memcpy(values.data(), a.data(), n * sizeof(float));
}

}  // namespace gbl
