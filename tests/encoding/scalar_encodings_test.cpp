// Tests for the scalar encoding primitives (src/encoding/encodings.h, mirror of
// shaders/scalar_encodings.glsl): fixed point, small floats and 8-bit sRGB. Exhaustive over every code up
// to 16 bits, millions of fixed-seed random inputs, and references written independently here in
// double arithmetic.
#include "encodings_test_support.h"

namespace {

using namespace gbl::enc;
using namespace gbl::enc_test;

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
    std::ifstream file(std::string(GBL_SOURCE_SHADER_DIR) + "/scalar_encodings.glsl");
    ASSERT_TRUE(file) << "cannot open shaders/scalar_encodings.glsl";
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
//   --gtest_filter='*PrintSrgbTables*' (paste into both shaders/scalar_encodings.glsl and
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

}  // namespace
