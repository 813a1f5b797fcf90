// Tests for the encoding primitives (src/encoding/encodings.h, mirror of shaders/encodings.glsl).
// Exhaustive over every code up to 16 bits, millions of fixed-seed random inputs, and
// references written independently here in double arithmetic.
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

namespace {

using namespace gbl::enc;

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(std::uint64_t seed) : gen(seed) {}
    double u01() { return double(gen() >> 11) * 0x1.0p-53; }
    std::uint32_t bits32() { return std::uint32_t(gen() >> 32); }
};

glm::dvec3 randomUnit(Rng& r) {
    double u = r.u01();
    return gbl::uniformSphere(u, r.u01());
}

double angleDeg(glm::dvec3 a, glm::dvec3 b) { return gbl::angleDegrees(a, b); }

std::uint32_t bitsOf(float f) { return std::bit_cast<std::uint32_t>(f); }

// ---------------------------------------------------------------------------------------------
// Fixed point
// ---------------------------------------------------------------------------------------------

TEST(Unorm, EveryCodeUpTo16BitsRoundTrips) {
    for (uint bits = 1; bits <= 16; ++bits) {
        uint top = (1u << bits) - 1u;
        for (uint c = 0; c <= top; ++c) {
            float x = dequantizeUnorm(c, bits);
            ASSERT_EQ(x, float(double(c) / double(top))) << "bits " << bits << " code " << c;  // correctly rounded
            ASSERT_EQ(quantizeUnorm(x, bits), c) << "bits " << bits << " code " << c;
        }
    }
}

TEST(Unorm, RandomInputsWithinHalfStep) {
    Rng rng(11);
    for (uint bits = 1; bits <= 24; ++bits) {
        double s = double((1u << bits) - 1u);
        double worst = 0.0;
        for (int i = 0; i < 100000; ++i) {
            float x = float(rng.u01());
            uint c = quantizeUnorm(x, bits);
            double exact = std::floor(double(x) * s + 0.5);  // ties up, as in the shader
            ASSERT_LE(std::fabs(double(c) - exact), 1.0) << "bits " << bits << " x " << x;
            worst = std::max(worst, std::fabs(double(dequantizeUnorm(c, bits)) - double(x)) * s);
        }
        // In steps: half a step, plus float's rounding of x * s (documented bound).
        EXPECT_LE(worst, 0.5 + std::ldexp(1.0, int(bits) - 24)) << "bits " << bits;
    }
}

TEST(Unorm, ClampsAndNeverOverflows) {
    for (uint bits = 1; bits <= 24; ++bits) {
        uint top = (1u << bits) - 1u;
        EXPECT_EQ(quantizeUnorm(1.0f, bits), top) << bits;  // 24 bits: 16777215 + 0.5 rounds to 2^24
        EXPECT_EQ(quantizeUnorm(1e30f, bits), top) << bits;
        float below = std::nextafter(1.0f, 0.0f);  // 24 bits: 16777214.00000006 -> 16777214
        EXPECT_EQ(quantizeUnorm(below, bits), uint(std::floor(double(below) * top + 0.5))) << bits;
        EXPECT_EQ(quantizeUnorm(-3.0f, bits), 0u) << bits;
        EXPECT_EQ(quantizeUnorm(0.0f, bits), 0u) << bits;
    }
    EXPECT_EQ(quantizeUnorm(0.5f, 8), 128u);  // tie rounds up (floor(x + 0.5)), unlike RNE
}

TEST(Snorm, EveryCodeUpTo16BitsRoundTrips) {
    for (uint bits = 2; bits <= 16; ++bits) {
        int top = int((1u << (bits - 1u)) - 1u);
        uint mask = (1u << bits) - 1u;
        for (int v = -top; v <= top; ++v) {
            uint code = uint(v) & mask;
            float x = dequantizeSnorm(code, bits);
            ASSERT_EQ(x, float(double(v) / double(top))) << "bits " << bits << " value " << v;
            ASSERT_EQ(quantizeSnorm(x, bits), code) << "bits " << bits << " value " << v;
        }
        // The one code outside the symmetric range decodes to -1 and re-encodes to -top.
        uint lowest = uint(-top - 1) & mask;
        EXPECT_EQ(dequantizeSnorm(lowest, bits), -1.0f);
        EXPECT_EQ(quantizeSnorm(-1.0f, bits), uint(-top) & mask);
        EXPECT_EQ(quantizeSnorm(1.0f, bits), uint(top));
        EXPECT_EQ(quantizeSnorm(0.0f, bits), 0u);
        EXPECT_EQ(quantizeSnorm(-5.0f, bits), uint(-top) & mask);
    }
    EXPECT_EQ(quantizeSnorm(-1.0f, 8), 0x81u);
    EXPECT_EQ(dequantizeSnorm(0x80u, 8), -1.0f);
    EXPECT_EQ(dequantizeSnorm(0xffu, 8), -1.0f / 127.0f);
}

TEST(Snorm, RandomInputsWithinHalfStep) {
    Rng rng(12);
    for (uint bits = 2; bits <= 24; ++bits) {
        double s = double((1u << (bits - 1u)) - 1u);
        double worst = 0.0;
        for (int i = 0; i < 100000; ++i) {
            float x = float(2.0 * rng.u01() - 1.0);
            worst = std::max(worst, std::fabs(double(dequantizeSnorm(quantizeSnorm(x, bits), bits)) - double(x)) * s);
        }
        EXPECT_LE(worst, 0.5 + std::ldexp(1.0, int(bits) - 24)) << "bits " << bits;
    }
}

// ---------------------------------------------------------------------------------------------
// Small floats, against references written here in double arithmetic
// ---------------------------------------------------------------------------------------------

// Value of a (5-bit exponent, mb-bit mantissa) code, without sign; NaN / Inf for exponent 31.
double refDecodeSmall(std::uint32_t code, int mb) {
    std::uint32_t e = code >> mb, m = code & ((1u << mb) - 1u);
    if (e == 31) return m ? std::nan("") : INFINITY;
    if (e == 0) return std::ldexp(double(m), -14 - mb);
    return std::ldexp(1.0 + std::ldexp(double(m), -mb), int(e) - 15);
}

// Round-to-nearest-even of ax >= 0 onto the (5, mb) grid; beyond the largest finite: clamp.
std::uint32_t refEncodeSmall(double ax, int mb) {
    std::uint32_t maxCode = (30u << mb) | ((1u << mb) - 1u);
    double maxFinite = refDecodeSmall(maxCode, mb);
    if (!(ax < maxFinite + std::ldexp(1.0, 15 - mb - 1))) return maxCode;  // tie at the top goes to Inf
    if (ax == 0.0) return 0;
    int e2;
    std::frexp(ax, &e2);
    int E = e2 - 1;  // ax in [2^E, 2^(E+1))
    if (E < -14) return std::uint32_t(std::nearbyint(std::ldexp(ax, 14 + mb)));  // may reach 1 << mb
    double q = std::nearbyint(std::ldexp(ax, mb - E));  // in [2^mb, 2^(mb+1)]
    int biased = E + 15;
    if (q == std::ldexp(1.0, mb + 1)) {
        q *= 0.5;
        ++biased;
    }
    return (std::uint32_t(biased) << mb) | (std::uint32_t(q) - (1u << mb));
}

std::uint32_t refEncodeHalf(float x) {
    std::uint32_t sign = std::signbit(x) ? 0x8000u : 0u;
    return sign | refEncodeSmall(std::fabs(double(x)), 10);
}

std::uint32_t refEncodeUnsigned(float x, int mb) { return (x > 0.0f) ? refEncodeSmall(double(x), mb) : 0u; }

// Random floats of every magnitude a small float can hold (and a bit beyond), both signs.
float randomWideFloat(Rng& rng) {
    std::uint32_t b = rng.bits32();
    std::uint32_t exponent = 127u - 30u + (b % 48u);  // 2^-30 .. 2^17
    return std::bit_cast<float>((b & 0x80000000u) | (exponent << 23) | (rng.bits32() & 0x7fffffu));
}

TEST(Float16, AllCodesDecodeExactlyAndReencode) {
    for (std::uint32_t h = 0; h < 65536; ++h) {
        double ref = refDecodeSmall(h & 0x7fffu, 10) * ((h & 0x8000u) ? -1.0 : 1.0);
        float f = decodeFloat16(h);
        if (std::isnan(ref)) {
            ASSERT_TRUE(std::isnan(f)) << h;
            continue;
        }
        ASSERT_EQ(bitsOf(f), bitsOf(float(ref))) << "code " << h;  // also -0 and +-Inf
        if (std::isinf(ref)) {
            ASSERT_EQ(encodeFloat16(f), (h & 0x8000u) | 0x7bffu) << "Inf clamps to max finite";
            continue;
        }
        ASSERT_EQ(encodeFloat16(f), h) << "code " << h;
    }
}

TEST(Float16, RandomAndTiesMatchReference) {
    Rng rng(16);
    for (int i = 0; i < 2000000; ++i) {
        float x = randomWideFloat(rng);
        ASSERT_EQ(encodeFloat16(x), refEncodeHalf(x)) << x;
    }
    for (int i = 0; i < 1000000; ++i) {
        float x = float(rng.u01());
        ASSERT_EQ(encodeFloat16(x), refEncodeHalf(x)) << x;
    }
    // Exact midpoints between neighbouring halves (representable in float): ties to even.
    for (std::uint32_t h = 0; h < 0x7bffu; ++h) {
        float mid = float(0.5 * (refDecodeSmall(h, 10) + refDecodeSmall(h + 1, 10)));
        ASSERT_EQ(double(mid), 0.5 * (refDecodeSmall(h, 10) + refDecodeSmall(h + 1, 10)));
        std::uint32_t even = (h & 1u) ? h + 1 : h;
        ASSERT_EQ(encodeFloat16(mid), even) << "tie above code " << h;
        ASSERT_EQ(encodeFloat16(-mid), even | 0x8000u) << "tie above code " << h;
        ASSERT_EQ(encodeFloat16(std::nextafter(mid, 0.0f)), h);
        ASSERT_EQ(encodeFloat16(std::nextafter(mid, INFINITY)), h + 1);
    }
    // Overflow: 65519.99 rounds to 65504, the tie 65520 and above clamp to max finite (not Inf).
    EXPECT_EQ(encodeFloat16(65519.0f), 0x7bffu);
    EXPECT_EQ(encodeFloat16(65520.0f), 0x7bffu);
    EXPECT_EQ(encodeFloat16(1e20f), 0x7bffu);
    EXPECT_EQ(encodeFloat16(-1e20f), 0xfbffu);
    EXPECT_EQ(encodeFloat16(INFINITY), 0x7bffu);
    // Below the smallest subnormal: 2^-25 is a tie to 0, just above goes to 1.
    EXPECT_EQ(encodeFloat16(std::ldexp(1.0f, -25)), 0u);
    EXPECT_EQ(encodeFloat16(std::nextafter(std::ldexp(1.0f, -25), 1.0f)), 1u);
    EXPECT_EQ(encodeFloat16(1e-30f), 0u);
    EXPECT_EQ(encodeFloat16(-0.0f), 0x8000u);
    EXPECT_EQ(encodeFloat16(1.0f), 0x3c00u);
}

void checkUnsignedSmallFloat(int mb, uint (*encode)(float), float (*decode)(uint), std::uint64_t seed) {
    std::uint32_t codes = 1u << (5 + mb);
    std::uint32_t maxCode = (30u << mb) | ((1u << mb) - 1u);
    for (std::uint32_t c = 0; c < codes; ++c) {
        double ref = refDecodeSmall(c, mb);
        float f = decode(c);
        if (std::isnan(ref)) {
            ASSERT_TRUE(std::isnan(f)) << c;
            continue;
        }
        ASSERT_EQ(bitsOf(f), bitsOf(float(ref))) << "code " << c;
        ASSERT_EQ(encode(f), std::isinf(ref) ? maxCode : c) << "code " << c;
    }
    Rng rng(seed);
    for (int i = 0; i < 1000000; ++i) {
        float x = randomWideFloat(rng);  // half of them negative -> 0
        ASSERT_EQ(encode(x), refEncodeUnsigned(x, mb)) << x;
    }
    for (int i = 0; i < 500000; ++i) {
        float x = float(rng.u01());
        ASSERT_EQ(encode(x), refEncodeUnsigned(x, mb)) << x;
    }
    for (std::uint32_t c = 0; c < maxCode; ++c) {
        double mid = 0.5 * (refDecodeSmall(c, mb) + refDecodeSmall(c + 1, mb));
        ASSERT_EQ(double(float(mid)), mid);
        ASSERT_EQ(encode(float(mid)), (c & 1u) ? c + 1 : c) << "tie above code " << c;
    }
    EXPECT_EQ(encode(-1.0f), 0u);
    EXPECT_EQ(encode(-0.0f), 0u);
    EXPECT_EQ(encode(1e20f), maxCode);
    EXPECT_EQ(encode(1.0f), 15u << mb);
    // Relative error bound for normal values: half an ulp, 2^-(mb+1).
    double worst = 0.0;
    for (int i = 0; i < 500000; ++i) {
        float x = float(std::ldexp(1.0 + rng.u01(), int(rng.bits32() % 29u) - 14));  // [2^-14, 2^15)
        if (x > float(refDecodeSmall(maxCode, mb))) continue;
        worst = std::max(worst, std::fabs(double(decode(encode(x))) - double(x)) / double(x));
    }
    EXPECT_LE(worst, std::ldexp(1.0, -(mb + 1)));
}

TEST(Float11, AllCodesRandomAndTiesMatchReference) { checkUnsignedSmallFloat(6, encodeFloat11, decodeFloat11, 111); }

TEST(Float10, AllCodesRandomAndTiesMatchReference) { checkUnsignedSmallFloat(5, encodeFloat10, decodeFloat10, 110); }

TEST(Float32, BitsRoundTrip) {
    Rng rng(32);
    for (int i = 0; i < 1000000; ++i) {
        std::uint32_t b = rng.bits32();
        ASSERT_EQ(encodeFloat32(decodeFloat32(b)), b);  // also NaN payloads: pure bit moves
    }
    EXPECT_EQ(encodeFloat32(1.0f), 0x3f800000u);
}

// ---------------------------------------------------------------------------------------------
// sRGB
// ---------------------------------------------------------------------------------------------

double refSrgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double refLinearToSrgb(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }
std::uint32_t refEncodeSrgb8(float x) {
    double c = std::clamp(refLinearToSrgb(std::clamp(double(x), 0.0, 1.0)), 0.0, 1.0);
    return std::uint32_t(std::floor(c * 255.0 + 0.5));
}

// The tables as they should be: decode = float(exact), threshold = smallest float >= exact.
std::vector<float> expectedSrgbDecode() {
    std::vector<float> t(256);
    for (int i = 0; i < 256; ++i) t[size_t(i)] = float(refSrgbToLinear(i / 255.0));
    return t;
}
std::vector<float> expectedSrgbThresholds() {
    std::vector<float> t(255);
    for (int i = 0; i < 255; ++i) {
        double exact = refSrgbToLinear((i + 0.5) / 255.0);
        float f = float(exact);
        if (double(f) < exact) f = std::nextafter(f, 2.0f);
        t[size_t(i)] = f;
    }
    return t;
}

TEST(Srgb8, TablesAreTheExactValues) {
    std::vector<float> d = expectedSrgbDecode(), t = expectedSrgbThresholds();
    for (int i = 0; i < 256; ++i) ASSERT_EQ(bitsOf(kSrgbDecode[i]), bitsOf(d[size_t(i)])) << i;
    for (int i = 0; i < 255; ++i) ASSERT_EQ(bitsOf(kSrgbEncodeThresholds[i]), bitsOf(t[size_t(i)])) << i;
}

TEST(Srgb8, EveryCodeRoundTripsAndEveryBoundaryIsExact) {
    for (uint c = 0; c < 256; ++c) {
        ASSERT_EQ(decodeSrgb8(c), float(refSrgbToLinear(c / 255.0))) << c;
        ASSERT_EQ(encodeSrgb8(decodeSrgb8(c)), c) << c;
    }
    // encode is monotonic, so checking both sides of every threshold proves it exact for all floats.
    for (int i = 0; i < 255; ++i) {
        float t = kSrgbEncodeThresholds[i];
        float below = std::nextafter(t, -1.0f);
        ASSERT_EQ(encodeSrgb8(t), uint(i + 1)) << i;
        ASSERT_EQ(refEncodeSrgb8(t), std::uint32_t(i + 1)) << i;
        ASSERT_EQ(encodeSrgb8(below), uint(i)) << i;
        ASSERT_EQ(refEncodeSrgb8(below), std::uint32_t(i)) << i;
    }
}

TEST(Srgb8, RandomInputsMatchExactFormula) {
    Rng rng(8);
    for (int i = 0; i < 2000000; ++i) {
        float x = float(rng.u01() * 1.2 - 0.1);
        ASSERT_EQ(encodeSrgb8(x), refEncodeSrgb8(x)) << x;
    }
    for (int i = 0; i < 500000; ++i) {  // dense near black, where the linear segment lives
        float x = float(rng.u01() * 0.01);
        ASSERT_EQ(encodeSrgb8(x), refEncodeSrgb8(x)) << x;
    }
    EXPECT_EQ(encodeSrgb8(-1.0f), 0u);
    EXPECT_EQ(encodeSrgb8(5.0f), 255u);
    EXPECT_EQ(encodeSrgb8(1.0f), 255u);
}

// Pulls the numbers of `const float <name>[N] = float[N](...)` out of the GLSL text.
std::vector<std::string> glslArrayLiterals(const std::string& text, const std::string& name) {
    size_t at = text.find("const float " + name + "[");
    if (at == std::string::npos) return {};
    size_t open = text.find('(', at), close = text.find(')', open);
    std::string body = text.substr(open + 1, close - open - 1);
    std::vector<std::string> out;
    std::string tok;
    std::istringstream in(body);
    while (std::getline(in, tok, ',')) {
        tok.erase(0, tok.find_first_not_of(" \n\t"));
        tok.erase(tok.find_last_not_of(" \n\t") + 1);
        if (!tok.empty()) out.push_back(tok);
    }
    return out;
}

TEST(Srgb8, GlslTablesEqualCppTables) {
    std::ifstream file(std::string(GBL_SOURCE_SHADER_DIR) + "/encodings.glsl");
    ASSERT_TRUE(file) << "cannot open shaders/encodings.glsl";
    std::stringstream ss;
    ss << file.rdbuf();
    std::string text = ss.str();
    struct Table {
        const char* name;
        const float* values;
        size_t count;
    };
    for (Table t : {Table{"kSrgbDecode", kSrgbDecode, 256}, Table{"kSrgbEncodeThresholds", kSrgbEncodeThresholds, 255}}) {
        std::vector<std::string> lits = glslArrayLiterals(text, t.name);
        ASSERT_EQ(lits.size(), t.count) << t.name;
        for (size_t i = 0; i < t.count; ++i) {
            float direct = 0.0f;
            auto r = std::from_chars(lits[i].data(), lits[i].data() + lits[i].size(), direct);
            ASSERT_EQ(r.ptr, lits[i].data() + lits[i].size()) << t.name << "[" << i << "] = '" << lits[i] << "'";
            ASSERT_EQ(bitsOf(direct), bitsOf(t.values[i])) << t.name << "[" << i << "]";
            // glslang reads literals as double, then narrows: must give the same float.
            ASSERT_EQ(bitsOf(float(std::strtod(lits[i].c_str(), nullptr))), bitsOf(t.values[i])) << t.name << i;
        }
    }
}

// Regenerates the table literals: encodings_test --gtest_also_run_disabled_tests
//   --gtest_filter='*PrintSrgbTables*' (paste into both shaders/encodings.glsl and
//   src/encoding/encodings.cpp; the C++ copy gets an `f` after each number).
TEST(Srgb8, DISABLED_PrintSrgbTables) {
    auto print = [](const std::vector<float>& v) {
        std::string s;
        for (size_t i = 0; i < v.size(); ++i) {
            char buf[32];
            auto r = std::to_chars(buf, buf + sizeof buf, v[i]);  // shortest round-trip form
            std::string lit(buf, r.ptr);
            if (lit.find_first_of(".e") == std::string::npos) lit += ".0";
            if (i % 8 == 0) s += "    ";
            s += lit;
            if (i + 1 < v.size()) s += (i % 8 == 7) ? ",\n" : ", ";
        }
        std::printf("%s\n\n", s.c_str());
    };
    print(expectedSrgbDecode());
    print(expectedSrgbThresholds());
}

// ---------------------------------------------------------------------------------------------
// Normals
// ---------------------------------------------------------------------------------------------

struct NormalCodec {
    const char* name;
    glm::vec3 (*roundTrip)(glm::vec3, uint);
};

glm::vec3 rtXyz(glm::vec3 n, uint b) { return decodeNormalXyz(encodeNormalXyz(n, b), b); }
glm::vec3 rtBestFit(glm::vec3 n, uint) { return decodeNormalBestFit(encodeNormalBestFit(n)); }
glm::vec3 rtBestFitSearch(glm::vec3 n, uint) { return decodeNormalBestFit(encodeNormalBestFitSearch(n)); }
glm::vec3 rtXyZSign(glm::vec3 n, uint b) { return decodeNormalXyZSign(encodeNormalXyZSign(n, b), b); }
glm::vec3 rtSpheremap(glm::vec3 n, uint b) { return decodeNormalSpheremap(encodeNormalSpheremap(n, b), b); }
glm::vec3 rtStereo(glm::vec3 n, uint b) { return decodeNormalStereographic(encodeNormalStereographic(n, b), b); }
glm::vec3 rtOct(glm::vec3 n, uint b) { return decodeNormalOctahedral(encodeNormalOctahedral(n, b), b); }
glm::vec3 rtOctP(glm::vec3 n, uint b) {
    return decodeNormalOctahedralPrecise(encodeNormalOctahedralPrecise(n, b), b);
}

struct AngleStats {
    double mean = 0.0, max = 0.0;
};

AngleStats measureNormals(glm::vec3 (*rt)(glm::vec3, uint), uint bits, int samples, std::uint64_t seed,
                          double minZ = -2.0) {
    Rng rng(seed);
    AngleStats s;
    int used = 0;
    for (int i = 0; i < samples; ++i) {
        glm::dvec3 n = randomUnit(rng);
        if (n.z < minZ) continue;
        glm::vec3 d = rt(glm::vec3(n), bits);
        EXPECT_NEAR(glm::length(glm::dvec3(d)), 1.0, 1e-6);
        double a = angleDeg(n, glm::dvec3(d));
        s.mean += a;
        s.max = std::max(s.max, a);
        ++used;
    }
    s.mean /= used;
    return s;
}

// Documented bounds (degrees), measured over 1M (here 400k) uniform directions with margin.
TEST(Normals, RandomDirectionsWithinDocumentedBounds) {
    struct Bound {
        const char* name;
        glm::vec3 (*rt)(glm::vec3, uint);
        uint bits;
        double maxDeg, meanDeg, minZ;
    };
    const Bound bounds[] = {
        {"normal_xyz", rtXyz, 8, 0.40, 0.18, -2.0},
        {"normal_xyz", rtXyz, 10, 0.10, 0.045, -2.0},
        {"normal_xyz", rtXyz, 16, 0.0016, 0.0007, -2.0},
        {"normal_bestfit", rtBestFit, 8, 0.32, 0.034, -2.0},
        {"normal_bestfit (search)", rtBestFitSearch, 8, 0.32, 0.029, -2.0},
        {"normal_xy_zsign", rtXyZSign, 8, 6.0, 0.48, -2.0},
        {"normal_xy_zsign", rtXyZSign, 16, 0.36, 0.0031, -2.0},
        {"normal_spheremap", rtSpheremap, 8, 12.0, 0.50, -2.0},
        {"normal_spheremap", rtSpheremap, 16, 0.55, 0.0020, -2.0},
        {"normal_stereographic (z >= 0)", rtStereo, 8, 1.2, 0.48, 0.0},
        {"normal_stereographic (z >= 0)", rtStereo, 16, 0.0046, 0.0019, 0.0},
        {"normal_octahedral", rtOct, 8, 0.95, 0.34, -2.0},
        {"normal_octahedral", rtOct, 10, 0.24, 0.085, -2.0},
        {"normal_octahedral", rtOct, 16, 0.0037, 0.0014, -2.0},
        {"normal_octahedral_precise", rtOctP, 8, 0.64, 0.32, -2.0},
        {"normal_octahedral_precise", rtOctP, 16, 0.0025, 0.00125, -2.0},
    };
    for (const Bound& b : bounds) {
        AngleStats s = measureNormals(b.rt, b.bits, 400000, 21, b.minZ);
        std::printf("[measured] %-30s %2u bits: mean %.5f deg, max %.5f deg\n", b.name, b.bits, s.mean, s.max);
        EXPECT_LE(s.max, b.maxDeg) << b.name << " " << b.bits;
        EXPECT_LE(s.mean, b.meanDeg) << b.name << " " << b.bits;
    }
}

TEST(Normals, KnownCodes) {
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(0, 0, 1), 8), uvec2(0, 0));
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(0, 0, -1), 8), uvec2(127, 127));
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(1, 0, 0), 8), uvec2(127, 0));
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(-1, 0, 0), 8), uvec2(0x81, 0));
    EXPECT_EQ(encodeNormalBestFit(glm::vec3(0, 0, 1)), uvec3(128, 128, 255));
    EXPECT_EQ(encodeNormalXyz(glm::vec3(0, 0, -1), 8), uvec3(128, 128, 0));
    EXPECT_EQ(encodeNormalXyZSign(glm::vec3(0.6f, 0, -0.8f), 8).z, 1u);
    EXPECT_EQ(encodeNormalXyZSign(glm::vec3(0.6f, 0, 0.8f), 8).z, 0u);
    EXPECT_EQ(encodeNormalSpheremap(glm::vec3(0, 0, 1), 8), uvec2(128, 128));
    EXPECT_EQ(encodeNormalSpheremap(glm::vec3(0, 0, -1), 8), uvec2(255, 128));
    EXPECT_GT(angleDeg(glm::dvec3(0, 0, -1), glm::dvec3(rtSpheremap(glm::vec3(0, 0, -1), 8))), -1.0);
    EXPECT_LT(angleDeg(glm::dvec3(0, 0, -1), glm::dvec3(rtSpheremap(glm::vec3(0, 0, -1), 8))), 1e-3);
    // 2^b - 1 levels have no exact centre: +z decodes 1.13 deg off at 8 bits (its worst case).
    EXPECT_LT(angleDeg(glm::dvec3(0, 0, 1), glm::dvec3(rtStereo(glm::vec3(0, 0, 1), 8))), 1.2);
}

// decode(code) re-encodes to the same code, for every code of the 16-bit (2 x 8) encodings,
// apart from the listed degenerate codes.
TEST(Normals, EveryTwoByEightBitCodeReencodes) {
    int octChanged = 0, octPChanged = 0, sphChanged = 0, sphInside = 0, stereoChanged = 0, zsChanged = 0, zsValid = 0;
    for (uint x = 0; x < 256; ++x)
        for (uint y = 0; y < 256; ++y) {
            uvec2 c(x, y);
            // Octahedral: x or y = 0x80 (-128) are never produced. The square's edges are mirror
            // images ((1, t) and (1, -t) are one direction), so edge codes may re-encode as their
            // twin: allowed there only, and only to the same direction.
            bool octValid = x != 0x80 && y != 0x80;
            bool onEdge = x == 0x7f || x == 0x81 || y == 0x7f || y == 0x81;
            glm::vec3 d = decodeNormalOctahedral(c, 8);
            for (uvec2 again : {encodeNormalOctahedral(d, 8), encodeNormalOctahedralPrecise(d, 8)}) {
                if (!octValid || again == c) continue;
                ASSERT_TRUE(onEdge) << x << " " << y;
                ASSERT_LT(angleDeg(glm::dvec3(d), glm::dvec3(decodeNormalOctahedral(again, 8))), 1e-3) << x << " " << y;
            }
            if (octValid && encodeNormalOctahedral(d, 8) != c) ++octChanged;
            if (octValid && encodeNormalOctahedralPrecise(d, 8) != c) ++octPChanged;
            // Spheremap: codes inside the disc.
            glm::vec2 e = glm::vec2(dequantizeUnorm(x, 8), dequantizeUnorm(y, 8)) * 4.0f - 2.0f;
            if (glm::dot(e, e) < 3.99f) {
                ++sphInside;
                if (encodeNormalSpheremap(decodeNormalSpheremap(c, 8), 8) != c) ++sphChanged;
            }
            if (encodeNormalStereographic(decodeNormalStereographic(c, 8), 8) != c) ++stereoChanged;
            for (uint s = 0; s < 2; ++s) {
                uvec3 cz(x, y, s);
                float fx = dequantizeUnorm(x, 8) * 2.0f - 1.0f, fy = dequantizeUnorm(y, 8) * 2.0f - 1.0f;
                if (fx * fx + fy * fy >= 0.98f) continue;  // off the disc or at the equator: z ~ 0
                ++zsValid;
                if (encodeNormalXyZSign(decodeNormalXyZSign(cz, 8), 8) != cz) ++zsChanged;
            }
        }
    std::printf("[measured] re-encode changes: oct %d, octP %d, spheremap %d/%d, stereo %d/65536, xy_zsign %d/%d\n",
                octChanged, octPChanged, sphChanged, sphInside, stereoChanged, zsChanged, zsValid);
    EXPECT_LE(octChanged, 4 * 127);  // at most one of each mirrored pair on the 4 edges
    EXPECT_LE(octPChanged, 4 * 127);
    EXPECT_EQ(sphChanged, 0);
    EXPECT_EQ(stereoChanged, 0);
    EXPECT_EQ(zsChanged, 0);
}

TEST(Normals, BestFitReencodesToSameDirection) {
    Rng rng(5);
    for (int i = 0; i < 30000; ++i) {
        uvec3 c(rng.bits32() & 255u, rng.bits32() & 255u, rng.bits32() & 255u);
        glm::vec3 d = decodeNormalBestFit(c);
        glm::vec3 again = decodeNormalBestFit(encodeNormalBestFitSearch(d));
        ASSERT_LT(angleDeg(glm::dvec3(d), glm::dvec3(again)), 1e-3) << c.x << " " << c.y << " " << c.z;
    }
}

TEST(Normals, BestFitBeatsPlainXyzByALargeFactor) {
    AngleStats bf = measureNormals(rtBestFit, 8, 300000, 3);
    AngleStats xyz = measureNormals(rtXyz, 8, 300000, 3);
    std::printf("[measured] bestfit mean %.5f max %.5f; xyz8 mean %.5f max %.5f; ratio of means %.2f\n", bf.mean,
                bf.max, xyz.mean, xyz.max, xyz.mean / bf.mean);
    EXPECT_LT(bf.mean * 5.0, xyz.mean);
}

// The table (CryEngine's look-up, best_fit_normals.h) against the search it is generated from:
// the error it adds, stated in shaders/encodings.glsl and layouts/README.md.
TEST(Normals, BestFitTableErrorAgainstSearch) {
    Rng rng(7);
    const int n = 200000;
    std::vector<double> table(n), search(n);
    int same = 0;
    for (int i = 0; i < n; ++i) {
        glm::dvec3 v = randomUnit(rng);
        const uvec3 t = encodeNormalBestFit(glm::vec3(v)), s = encodeNormalBestFitSearch(glm::vec3(v));
        same += t == s;
        table[i] = angleDeg(v, glm::dvec3(decodeNormalBestFit(t)));
        search[i] = angleDeg(v, glm::dvec3(decodeNormalBestFit(s)));
        // The search is optimal (next test): the table can only lose.
        ASSERT_GE(table[i], search[i] - 1e-4) << v.x << " " << v.y << " " << v.z;
    }
    auto stats = [](std::vector<double> e) {
        std::sort(e.begin(), e.end());
        double sum = 0.0;
        for (double x : e) sum += x;
        return glm::dvec3(sum / double(e.size()), e[e.size() * 99 / 100], e.back());
    };
    const glm::dvec3 t = stats(table), s = stats(search);
    std::printf("[measured] bestfit table  mean %.4f p99 %.4f max %.4f deg\n", t.x, t.y, t.z);
    std::printf("[measured] bestfit search mean %.4f p99 %.4f max %.4f deg; same code %.1f %%\n", s.x, s.y, s.z,
                100.0 * same / n);
    EXPECT_LE(t.x, s.x * 1.25);  // 1024^2 texels: 0.032 vs 0.028
    EXPECT_LE(t.y, s.y * 1.10);
    EXPECT_LE(t.z, s.z + 0.01);
    EXPECT_GT(same, n / 2);  // 61 % measured
}

// Each texel holds the search's choice for its centre direction, whatever the thread count.
TEST(Normals, BestFitTableHoldsTheSearchAtTexelCentres) {
    const std::vector<uint32_t>& table = bestFitNormalTable();
    ASSERT_EQ(table.size(), (kBestFitTableEntries + 3) / 4);
    EXPECT_EQ(generateBestFitNormalTable(1), table);
    Rng rng(8);
    for (int s = 0; s < 20000; ++s) {
        const uint32_t i = rng.bits32() % kBestFitTableSize, j = rng.bits32() % (i + 1);
        const glm::vec3 centre = glm::normalize(glm::vec3((float(i) + 0.5f) / float(kBestFitTableSize),
                                                          (float(j) + 0.5f) / float(kBestFitTableSize), 1.0f));
        ASSERT_EQ(encodeNormalBestFit(centre), encodeNormalBestFitSearch(centre)) << "texel " << i << " " << j;
        // Any sign and order of the components: the table covers the sphere by symmetry. The code
        // may differ where two lengths give the same direction (d = (247, 57, -57) and (169, 39, -39) are 19 x and 13 x (13, 3, -3)),
        // which float's rounding of the error breaks either way; the direction may not.
        const glm::vec3 v = rng.bits32() & 1u ? glm::vec3(-centre.y, centre.z, centre.x)
                                              : glm::vec3(centre.z, centre.x, -centre.y);
        const double t = angleDeg(glm::dvec3(v), glm::dvec3(decodeNormalBestFit(encodeNormalBestFit(v))));
        const double r = angleDeg(glm::dvec3(v), glm::dvec3(decodeNormalBestFit(encodeNormalBestFitSearch(v))));
        ASSERT_NEAR(t, r, 1e-4) << "texel " << i << " " << j;
    }
}

// GLSL and C++ read the table at the same place and size.
TEST(Normals, BestFitTableConstantsMatchTheShader) {
    std::ifstream file(std::string(GBL_SOURCE_SHADER_DIR) + "/encodings.glsl");
    ASSERT_TRUE(file);
    std::stringstream text;
    text << file.rdbuf();
    EXPECT_NE(text.str().find("#define GBL_BEST_FIT_TABLE_SIZE " + std::to_string(kBestFitTableSize) + "u\n"),
              std::string::npos);
    EXPECT_NE(text.str().find("#define GBL_BEST_FIT_TABLE_BINDING " + std::to_string(kBestFitTableBinding) + "\n"),
              std::string::npos);
}

// The in-code search is as good as a wider one: every odd max-component k, and +-2 odd steps on
// every component around the ray, scored in double.
TEST(Normals, BestFitSearchIsOptimalInItsNeighbourhood) {
    Rng rng(6);
    for (int i = 0; i < 1500; ++i) {
        glm::dvec3 n = randomUnit(rng);
        uvec3 c = encodeNormalBestFitSearch(glm::vec3(n));
        double ours = angleDeg(n, glm::dvec3(glm::ivec3(c) * 2 - 255));
        double m = std::max(std::fabs(n.x), std::max(std::fabs(n.y), std::fabs(n.z)));
        double best = 1e9;
        for (int k = 1; k <= 255; k += 2) {
            glm::dvec3 t = n / m * double(k);
            glm::ivec3 base(2 * int(std::floor(t.x * 0.5)) + 1, 2 * int(std::floor(t.y * 0.5)) + 1,
                            2 * int(std::floor(t.z * 0.5)) + 1);
            for (int dx = -2; dx <= 2; dx += 2)
                for (int dy = -2; dy <= 2; dy += 2)
                    for (int dz = -2; dz <= 2; dz += 2) {
                        glm::ivec3 d = base + glm::ivec3(dx, dy, dz);
                        if (std::abs(d.x) > 255 || std::abs(d.y) > 255 || std::abs(d.z) > 255) continue;
                        best = std::min(best, angleDeg(n, glm::dvec3(d)));
                    }
        }
        ASSERT_LE(ours, best + 1e-4) << "direction " << n.x << " " << n.y << " " << n.z;
    }
}

TEST(Normals, OctahedralPreciseNeverWorseAndMoreBitsNeverWorse) {
    double prevMax = 1e9, prevMaxP = 1e9;
    for (uint bits = 8; bits <= 16; ++bits) {
        Rng rng(40);
        double maxPlain = 0.0, maxPrecise = 0.0, sumPlain = 0.0, sumPrecise = 0.0;
        const int n = 100000;
        for (int i = 0; i < n; ++i) {
            glm::dvec3 v = randomUnit(rng);
            double a = angleDeg(v, glm::dvec3(rtOct(glm::vec3(v), bits)));
            double p = angleDeg(v, glm::dvec3(rtOctP(glm::vec3(v), bits)));
            // Both are chosen in float from the float-rounded direction (up to 3.4e-6 deg off the
            // double one), so allow that much, plus float's resolution of the distance.
            ASSERT_LE(p, a * (1.0 + 1e-3) + 1e-5) << "bits " << bits << " sample " << i;
            maxPlain = std::max(maxPlain, a);
            maxPrecise = std::max(maxPrecise, p);
            sumPlain += a;
            sumPrecise += p;
        }
        std::printf("[measured] octahedral %2u bits: plain mean %.5f max %.5f, precise mean %.5f max %.5f deg\n", bits,
                    sumPlain / n, maxPlain, sumPrecise / n, maxPrecise);
        EXPECT_LT(sumPrecise, sumPlain);
        EXPECT_LT(maxPrecise, maxPlain);
        EXPECT_LT(maxPlain, prevMax) << bits;
        EXPECT_LT(maxPrecise, prevMaxP) << bits;
        prevMax = maxPlain;
        prevMaxP = maxPrecise;
    }
}

TEST(Normals, MoreBitsNeverWorseForEveryParameterisedEncoding) {
    for (auto rt : {rtXyz, rtXyZSign, rtSpheremap, rtStereo}) {
        double prev = 1e9;
        for (uint bits = 6; bits <= 16; bits += 2) {
            AngleStats s = measureNormals(rt, bits, 50000, 41, rt == rtStereo ? 0.0 : -2.0);
            EXPECT_LE(s.max, prev) << bits;
            prev = s.max;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Colour
// ---------------------------------------------------------------------------------------------

TEST(Color, TransformsInvertAndHitKnownValues) {
    Rng rng(50);
    double worst = 0.0, worstSqrt = 0.0, worstCoCg = 0.0;
    for (int i = 0; i < 500000; ++i) {
        glm::vec3 c(float(rng.u01()), float(rng.u01()), float(rng.u01()));
        glm::vec3 y = rgbToYCbCr(c);
        ASSERT_GE(y.x, 0.0f);
        ASSERT_LE(y.x, 1.0f);
        ASSERT_GE(std::min(y.y, y.z), -1e-6f);
        ASSERT_LE(std::max(y.y, y.z), 1.0f + 1e-6f);
        ASSERT_EQ(y.x, lumaBt601(c));
        glm::vec3 o = rgbToYCoCg(c);
        ASSERT_GE(std::min({o.x, o.y, o.z}), 0.0f);
        ASSERT_LE(std::max({o.x, o.y, o.z}), 1.0f);
        worst = std::max(worst, double(glm::length(yCbCrToRgb(y) - c)));
        worstSqrt = std::max(worstSqrt, double(glm::length(yCbCrSqrtToRgb(rgbToYCbCrSqrt(c)) - c)));
        worstCoCg = std::max(worstCoCg, double(glm::length(yCoCgToRgb(o) - c)));
    }
    std::printf("[measured] unquantised round trip: ycbcr %.3g, ycbcr_sqrt %.3g, ycocg %.3g\n", worst, worstSqrt,
                worstCoCg);
    EXPECT_LT(worst, 1e-6);
    EXPECT_LT(worstSqrt, 1e-6);
    EXPECT_LT(worstCoCg, 1e-6);
    glm::vec3 white = rgbToYCbCr(glm::vec3(1.0f));
    EXPECT_NEAR(white.x, 1.0f, 1e-6f);
    EXPECT_NEAR(white.y, 0.5f, 1e-6f);
    EXPECT_NEAR(white.z, 0.5f, 1e-6f);
    glm::vec3 red = rgbToYCbCr(glm::vec3(1, 0, 0));
    EXPECT_NEAR(red.x, 0.299f, 1e-6f);
    EXPECT_NEAR(red.y, 0.5f - 0.168736f, 1e-5f);  // JPEG's rounded coefficients
    EXPECT_NEAR(red.z, 1.0f, 1e-6f);
    glm::vec3 blue = rgbToYCbCr(glm::vec3(0, 0, 1));
    EXPECT_NEAR(blue.y, 1.0f, 1e-6f);
    EXPECT_NEAR(blue.z, 0.5f - 0.081312f, 1e-5f);
    glm::vec3 g = rgbToYCoCg(glm::vec3(0, 1, 0));
    EXPECT_EQ(g, glm::vec3(0.5f, 0.5f, 1.0f));
}

TEST(Color, QuantisedRoundTripsWithinBounds) {
    Rng rng(51);
    double ycbcr = 0.0, ycocg = 0.0, sqrtDark = 0.0, plainDark = 0.0;
    auto q3 = [](glm::vec3 v) {
        return glm::vec3(dequantizeUnorm(quantizeUnorm(v.x, 8), 8), dequantizeUnorm(quantizeUnorm(v.y, 8), 8),
                         dequantizeUnorm(quantizeUnorm(v.z, 8), 8));
    };
    for (int i = 0; i < 1000000; ++i) {
        glm::vec3 c(float(rng.u01()), float(rng.u01()), float(rng.u01()));
        auto maxAbs = [&](glm::vec3 d) { return double(std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)})); };
        ycbcr = std::max(ycbcr, maxAbs(yCbCrToRgb(q3(rgbToYCbCr(c))) - c));
        ycocg = std::max(ycocg, maxAbs(yCoCgToRgb(q3(rgbToYCoCg(c))) - c));
        glm::vec3 dark = c * 0.05f;  // the sqrt pre-transform spends codes on darks
        sqrtDark = std::max(sqrtDark, maxAbs(yCbCrSqrtToRgb(q3(rgbToYCbCrSqrt(dark))) - dark));
        plainDark = std::max(plainDark, maxAbs(yCbCrToRgb(q3(rgbToYCbCr(dark))) - dark));
    }
    std::printf("[measured] 8-bit max abs: ycbcr %.5f, ycocg %.5f; darks (<0.05): ycbcr %.5f, ycbcr_sqrt %.5f\n",
                ycbcr, ycocg, plainDark, sqrtDark);
    EXPECT_LE(ycbcr, 0.0056);
    EXPECT_LE(ycocg, 0.0060);
    EXPECT_LT(sqrtDark * 2.0, plainDark);
}

TEST(Color, SpecularColorUE4) {
    glm::vec3 base(0.2f, 0.4f, 0.8f);
    EXPECT_EQ(specularColorUE4(base, 0.0f, 0.5f), glm::vec3(0.04f));
    EXPECT_EQ(specularColorUE4(base, 1.0f, 0.5f), base);
    glm::vec3 half = specularColorUE4(base, 0.5f, 1.0f);
    EXPECT_NEAR(half.x, 0.5f * 0.08f + 0.5f * 0.2f, 1e-7f);
}

// ---------------------------------------------------------------------------------------------
// Chroma checkerboard
// ---------------------------------------------------------------------------------------------

TEST(Chroma, CheckerboardPattern) {
    EXPECT_FALSE(chromaIsSecond(ivec2(0, 0)));
    EXPECT_TRUE(chromaIsSecond(ivec2(1, 0)));
    EXPECT_TRUE(chromaIsSecond(ivec2(0, 1)));
    EXPECT_FALSE(chromaIsSecond(ivec2(1, 1)));
    EXPECT_TRUE(chromaIsSecond(ivec2(-1, 0)));
    EXPECT_FALSE(chromaIsSecond(ivec2(-1, -1)));
    EXPECT_EQ(chromaForPixel(ivec2(2, 0), glm::vec2(0.25f, 0.75f)), 0.25f);
    EXPECT_EQ(chromaForPixel(ivec2(2, 1), glm::vec2(0.25f, 0.75f)), 0.75f);
}

TEST(Chroma, EdgeDirectedFilter) {
    // All neighbours similar: plain mean of their chroma.
    glm::vec2 r = reconstructChroma(0.5f, 0.3f, glm::vec4(0.5f), glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    EXPECT_FLOAT_EQ(r.x, 0.3f);
    EXPECT_FLOAT_EQ(r.y, 0.25f);
    // Two neighbours across an edge (|dY| >= 30/255) are dropped.
    r = reconstructChroma(0.5f, 0.3f, glm::vec4(0.5f, 0.9f, 0.52f, 0.1f), glm::vec4(0.1f, 0.9f, 0.3f, 0.9f));
    EXPECT_FLOAT_EQ(r.y, 0.2f);
    // Exactly at the threshold: step(t, t) = 1, weight 0.
    r = reconstructChroma(0.0f, 0.3f, glm::vec4(kChromaEdgeThreshold, 0.0f, 1.0f, 1.0f),
                          glm::vec4(0.9f, 0.1f, 0.7f, 0.7f));
    EXPECT_FLOAT_EQ(r.y, 0.1f);
    // No neighbour within the threshold: the first (+x) alone, as in the paper's listing.
    r = reconstructChroma(0.0f, 0.3f, glm::vec4(0.5f, 0.6f, 0.7f, 0.8f), glm::vec4(0.11f, 0.2f, 0.3f, 0.4f));
    EXPECT_FLOAT_EQ(r.y, 0.11f);
    // With the pixel: (first, second) order.
    glm::vec2 even = reconstructChroma(ivec2(0, 0), 0.5f, 0.3f, glm::vec4(0.5f), glm::vec4(0.7f));
    glm::vec2 odd = reconstructChroma(ivec2(1, 0), 0.5f, 0.3f, glm::vec4(0.5f), glm::vec4(0.7f));
    EXPECT_EQ(even, glm::vec2(0.3f, 0.7f));
    EXPECT_EQ(odd, glm::vec2(0.7f, 0.3f));
}

TEST(Chroma, FlatImageReconstructsExactly) {
    const int w = 9, h = 7;
    std::vector<glm::vec3> img(size_t(w * h), glm::vec3(0.2f, 0.6f, 0.4f));
    for (const char* name : {"ycocg_checkerboard", "ycbcr_checkerboard"}) {
        std::vector<glm::vec3> out = gbl::roundTripChromaCheckerboard(name, 8, img, w, h);
        for (glm::vec3 c : out) ASSERT_LT(glm::length(c - img[0]), 0.01f) << name;
    }
}

// ---------------------------------------------------------------------------------------------
// Roughness, depth
// ---------------------------------------------------------------------------------------------

TEST(Roughness, MapsInvertAndCrySmoothnessBound) {
    Rng rng(60);
    double worst = 0.0, worstLow = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        float r = float(rng.u01());
        ASSERT_EQ(roughnessFromGloss(glossFromRoughness(r)), 1.0f - (1.0f - r));
        ASSERT_NEAR(roughnessFromSmoothnessCry(smoothnessFromRoughnessCry(r)), r, 2e-7f);
        float back = roughnessFromSmoothnessCry(dequantizeUnorm(quantizeUnorm(smoothnessFromRoughnessCry(r), 8), 8));
        double e = std::fabs(double(back) - double(r));
        worst = std::max(worst, e);
        if (r < 0.01f) worstLow = std::max(worstLow, e);
    }
    std::printf("[measured] smoothness_cry 8 bits: max roughness error %.6f, below r = 0.01: %.6f\n", worst, worstLow);
    EXPECT_LE(worst, 1.0 / 255.0 + 1e-6);  // |d(1-s)^2/ds| <= 2, half a step: 1/255
    EXPECT_LE(worstLow, 0.0008);
}

TEST(Depth24, EveryCodeRoundTripsAndDepthsRoundExactly) {
    for (uint c = 0; c < (1u << 24); ++c)
        if (quantizeDepth24(dequantizeDepth24(c)) != c) FAIL() << "code " << c;
    const double s = 16777215.0;
    // Every float in [2^-8, 1]: the exact rounding of d * (2^24 - 1), ties up.
    for (std::uint32_t b = bitsOf(std::ldexp(1.0f, -8)); b <= bitsOf(1.0f); ++b) {
        float d = std::bit_cast<float>(b);
        if (quantizeDepth24(d) != uint(std::floor(double(d) * s + 0.5))) FAIL() << "depth " << d;
    }
    Rng rng(24);
    double worst = 0.0;
    for (int i = 0; i < 2000000; ++i) {
        float d = float(std::ldexp(rng.u01(), -int(rng.bits32() % 40u)));  // also tiny depths
        uint c = quantizeDepth24(d);
        ASSERT_EQ(c, uint(std::floor(double(d) * s + 0.5))) << d;
        worst = std::max(worst, std::fabs(double(dequantizeDepth24(c)) - double(d)));
    }
    std::printf("[measured] depth24: max |decode - d| %.3g (%.4f steps)\n", worst, worst * s);
    EXPECT_LE(worst, 0.5 / s + 1e-12);
    EXPECT_EQ(quantizeDepth24(1.0f), 0xffffffu);
    EXPECT_EQ(quantizeDepth24(2.0f), 0xffffffu);
    EXPECT_EQ(quantizeDepth24(-1.0f), 0u);
    EXPECT_EQ(quantizeDepth24(std::nextafter(1.0f, 0.0f)), 0xfffffeu);
}

TEST(Depth24, PositionFromDepthInvertsViewProjection) {
    glm::mat4 proj = glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 100.0f);
    glm::mat4 view = glm::lookAt(glm::vec3(3, 2, 5), glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0));
    glm::mat4 viewProj = proj * view;
    glm::mat4 inv = glm::inverse(viewProj);
    Rng rng(70);
    for (int i = 0; i < 10000; ++i) {
        glm::vec3 p(float(rng.u01() * 4 - 2), float(rng.u01() * 4 - 2), float(rng.u01() * 4 - 2));
        glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
        glm::vec3 ndc = glm::vec3(clip) / clip.w;
        glm::vec2 uv = glm::vec2(ndc) * 0.5f + 0.5f;
        glm::vec3 back = positionFromDepth(uv, ndc.z, inv);
        ASSERT_LT(glm::length(back - p), 1e-3f) << i;
        // Through 24-bit depth: error grows with distance, stays small at these ranges.
        glm::vec3 back24 = positionFromDepth(uv, dequantizeDepth24(quantizeDepth24(ndc.z)), inv);
        ASSERT_LT(glm::length(back24 - p), 0.02f) << i;
    }
}

}  // namespace
