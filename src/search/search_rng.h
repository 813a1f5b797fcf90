#pragma once
// The search's only source of randomness: SplitMix64 (Steele, Lea, Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014; the constants of Vigna's reference code). Written
// here rather than taken from <random> so that a seed gives the same stream with every compiler
// and standard library: the search must be deterministic for a given --seed.
#include <cstdint>

namespace gbl::search {

class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, n), n >= 1 (Lemire's multiply-shift; the bias is below 2^-32 for our n).
    int below(int n) { return int(((next() >> 32) * uint64_t(n)) >> 32); }
    // Uniform in [lo, hi].
    int range(int lo, int hi) { return lo + below(hi - lo + 1); }
    // True with probability p.
    bool chance(double p) { return double(next() >> 11) * 0x1.0p-53 < p; }

private:
    uint64_t state_;
};

}  // namespace gbl::search
