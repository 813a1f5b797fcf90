#pragma once
// Helpers shared by the encoding tests: a fixed-seed random source and small conversions.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "encoding_stats.h"
#include "encodings.h"


namespace gbl::enc_test {

using namespace gbl::enc;

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(std::uint64_t seed) : gen(seed) {}
    double u01() { return double(gen() >> 11) * 0x1.0p-53; }
    std::uint32_t bits32() { return std::uint32_t(gen() >> 32); }
};

inline glm::dvec3 randomUnit(Rng& r) {
    double u = r.u01();
    return gbl::uniformSphere(u, r.u01());
}

inline double angleDeg(glm::dvec3 a, glm::dvec3 b) { return gbl::angleDegrees(a, b); }

inline std::uint32_t bitsOf(float f) { return std::bit_cast<std::uint32_t>(f); }

}  // namespace gbl::enc_test
