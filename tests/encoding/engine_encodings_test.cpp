// Tests for the packings of shipped engines (section 8 of src/encoding/encodings.h, mirror of
// shaders/encodings.glsl): RGB9E5, gamma 2.2, the octahedral normals of Bevy, Unity and HDRP,
// Killzone 2's FP16 normal XY and log-range specular power, and the Filament / Bevy reflectance.
// Each is checked against a formula written independently here, in double, from its published
// source.
#include "encodings_test_support.h"

namespace {

using namespace gbl::enc;
using namespace gbl::enc_test;

// Vulkan spec, "Shared Exponent" (E5B9G9R9_UFLOAT_PACK32), written out in double: N = 9 mantissa
// bits, B = 15 exponent bias, Emax = 31.
struct SharedExp {
    unsigned r, g, b, e;
};
SharedExp specRgb9e5(double r, double g, double b) {
    const double N = 9, B = 15, Emax = 31;
    const double sharedexpMax = (std::pow(2.0, N) - 1.0) / std::pow(2.0, N) * std::pow(2.0, Emax - B);
    auto clampC = [&](double c) { return std::min(std::max(c, 0.0), sharedexpMax); };
    const double rc = clampC(r), gc = clampC(g), bc = clampC(b);
    const double maxc = std::max({rc, gc, bc});
    const double lg = maxc > 0.0 ? std::floor(std::log2(maxc)) : -1e9;
    const double expP = std::max(-B - 1.0, lg) + 1.0 + B;
    const double maxs = std::floor(maxc / std::pow(2.0, expP - B - N) + 0.5);
    const double exps = maxs == std::pow(2.0, N) ? expP + 1.0 : expP;
    auto mant = [&](double c) { return unsigned(std::floor(c / std::pow(2.0, exps - B - N) + 0.5)); };
    return {mant(rc), mant(gc), mant(bc), unsigned(exps)};
}

TEST(Rgb9e5, CodesEqualTheSpecFormulaAndDecodeWithinHalfAStep) {
    Rng rng(90);
    std::vector<glm::vec3> inputs = {
        glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(65408.0f), glm::vec3(1e6f, 0.5f, 0.0f),
        glm::vec3(-1.0f, 2.0f, 3.0f), glm::vec3(1e-12f), glm::vec3(511.5f / 512.0f, 0.0f, 0.0f),
        glm::vec3(0.99951172f, 0.25f, 0.125f),  // rounds up to the next exponent
    };
    for (int i = 0; i < 400000; ++i) {
        auto logUniform = [&] { return float(std::exp2(rng.u01() * 50.0 - 33.0)); };  // 2^-33 .. 2^17
        glm::vec3 c(logUniform(), logUniform(), logUniform());
        if (i % 3 == 0) c.y = c.x * float(rng.u01());  // channels of one magnitude, too
        inputs.push_back(c);
    }
    int rounded = 0;
    for (const glm::vec3& c : inputs) {
        const glm::uvec4 code = encodeRgb9e5(c);
        const SharedExp s = specRgb9e5(c.x, c.y, c.z);
        ASSERT_EQ(code.x, s.r) << c.x << " " << c.y << " " << c.z;
        ASSERT_EQ(code.y, s.g) << c.x << " " << c.y << " " << c.z;
        ASSERT_EQ(code.z, s.b) << c.x << " " << c.y << " " << c.z;
        ASSERT_EQ(code.w, s.e) << c.x << " " << c.y << " " << c.z;
        ASSERT_LE(std::max({code.x, code.y, code.z}), 511u);
        ASSERT_LE(code.w, 31u);
        // Decoded: each channel within half a step 2^(e - B - N) of its clamped input.
        const glm::vec3 d = decodeRgb9e5(code);
        const double halfStep = std::ldexp(0.5, int(s.e) - 24);
        for (int k = 0; k < 3; ++k) {
            const double want = std::clamp(double(c[k]), 0.0, 65408.0);
            ASSERT_LE(std::abs(double(d[k]) - want), halfStep * (1.0 + 1e-9)) << k;
            // and the decode is exactly mantissa * 2^(e - 24)
            ASSERT_EQ(double(d[k]), std::ldexp(double(code[k]), int(code.w) - 24));
        }
        rounded += std::max({code.x, code.y, code.z}) < 256u && s.e > 0 ? 1 : 0;
    }
    EXPECT_EQ(rounded, 0) << "the brightest channel always uses the top half of the mantissa range";
    EXPECT_EQ(encodeRgb9e5(glm::vec3(65408.0f)), glm::uvec4(511u, 511u, 511u, 31u));
    EXPECT_EQ(encodeRgb9e5(glm::vec3(1.0f, 0.0f, 0.0f)), glm::uvec4(256u, 0u, 0u, 16u));
}

// Gamma 2.2: the tables hold the formula (computed here in double), and the encoder is the exact
// round(255 x^(1/2.2)) that Bevy's pack4x8unorm(pow(c, 1/2.2)) computes in real arithmetic.
TEST(Gamma22, TablesAndCodesEqualTheFormula) {
    for (int k = 0; k < 256; ++k)
        ASSERT_EQ(kGamma22Decode[k], float(std::pow(k / 255.0, 2.2))) << k;
    for (int k = 0; k < 255; ++k) {
        const double v = std::pow((k + 0.5) / 255.0, 2.2);
        ASSERT_GE(double(kGamma22EncodeThresholds[k]), v) << k;
        ASSERT_LT(double(std::nextafter(kGamma22EncodeThresholds[k], 0.0f)), v) << k;
    }
    Rng rng(91);
    int checked = 0;
    for (int i = 0; i < 1000000; ++i) {
        const float x = i < 1000 ? float(i) / 999.0f : float(rng.u01());
        const double g = 255.0 * std::pow(double(x), 1.0 / 2.2);
        if (std::abs(g - std::floor(g) - 0.5) < 1e-9) continue;  // a tie: either code is right
        ASSERT_EQ(encodeGamma22(x), unsigned(std::floor(g + 0.5))) << x;
        ++checked;
    }
    EXPECT_GT(checked, 999000);
    EXPECT_EQ(encodeGamma22(-1.0f), 0u);
    EXPECT_EQ(encodeGamma22(2.0f), 255u);
    EXPECT_EQ(decodeGamma22(encodeGamma22(1.0f)), 1.0f);
    // Round trip: half a code in the gamma domain, times the slope of x^2.2 (<= 2.2 on [0, 1]).
    for (int i = 0; i <= 100000; ++i) {
        const float x = float(i) / 100000.0f;
        ASSERT_LE(std::abs(decodeGamma22(encodeGamma22(x)) - x), 2.2 * 0.5 / 255.0) << x;
    }
}

// HDRP's fast sRGB: the thresholds hold the formula (in long double here: ((k + 0.5)/255 + 0.055)
// / 1.055)^2.4), so the code is round(255 FastLinearToSRGB(x)) exactly; the decode is HDRP's
// cubic, evaluated in float.
TEST(Srgb8FastHdrp, ThresholdsEqualTheFormulaAndDecodeIsTheCubic) {
    for (int k = 0; k < 255; ++k) {
        const long double v = std::pow(((k + 0.5L) / 255.0L + 0.055L) / 1.055L, 2.4L);
        ASSERT_GE((long double)kSrgbFastHdrpEncodeThresholds[k], v) << k;
        ASSERT_LT((long double)std::nextafter(kSrgbFastHdrpEncodeThresholds[k], 0.0f), v) << k;
    }
    Rng rng(94);
    int checked = 0;
    for (int i = 0; i < 1000000; ++i) {
        const float x = i < 1000 ? float(i) / 999.0f * 0.004f : float(rng.u01());
        const double g = 255.0 * std::clamp(1.055 * std::pow(double(x), 1.0 / 2.4) - 0.055, 0.0, 1.0);
        if (std::abs(g - std::floor(g) - 0.5) < 1e-9) continue;  // a tie: either code is right
        ASSERT_EQ(encodeSrgb8FastHdrp(x), unsigned(std::floor(g + 0.5))) << x;
        ++checked;
    }
    EXPECT_GT(checked, 999000);
    EXPECT_EQ(encodeSrgb8FastHdrp(-0.001f), 1u);  // PositivePow: pow(|x|, 1/2.4)
    EXPECT_EQ(encodeSrgb8FastHdrp(-0.0f), 0u);
    EXPECT_EQ(encodeSrgb8FastHdrp(0.0f), 0u);
    EXPECT_EQ(encodeSrgb8FastHdrp(2.0f), 255u);
    // No linear toe: 0.001 is code 1 (srgb8: 3); above the toe both are sRGB's power segment.
    EXPECT_EQ(encodeSrgb8FastHdrp(0.001f), 1u);
    EXPECT_EQ(encodeSrgb8(0.001f), 3u);
    for (int i = 0; i <= 10000; ++i) {
        const float x = 0.0032f + float(i) / 10000.0f * 0.9968f;
        ASSERT_EQ(encodeSrgb8FastHdrp(x), encodeSrgb8(x)) << x;
    }
    for (unsigned k = 0; k < 256; ++k) {
        const float c = float(k) / 255.0f;
        const float a = c * 0.305306011f;
        const float b = a + 0.682171111f;
        const float d = c * b + 0.012522878f;
        ASSERT_EQ(bitsOf(decodeSrgb8FastHdrp(k)), bitsOf(c * d)) << k;
    }
    EXPECT_NEAR(decodeSrgb8FastHdrp(56u), 0.038883f, 1e-6f);  // the dielectric F0 0.04's code
    EXPECT_EQ(decodeSrgb8FastHdrp(255u), 0.305306011f + 0.682171111f + 0.012522878f);
}

// Octahedral encoding as Bevy's octahedral_encode and Unity's PackNormalOctQuadEncode write it, in
// double: p = n / |n|_1, the lower hemisphere wrapped, then u = p * 0.5 + 0.5. (The bit-exact
// float32 reimplementations of each engine are in engine_packings_test.cpp; this one is the
// real-number formula, which the float codes may miss by one where float and double fall on
// either side of a code boundary.)
glm::dvec2 octUnit(glm::dvec3 n) {
    n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    glm::dvec2 p(n.x, n.y);
    if (n.z < 0.0)
        p = glm::dvec2((1.0 - std::abs(n.y)) * (n.x >= 0.0 ? 1.0 : -1.0), (1.0 - std::abs(n.x)) * (n.y >= 0.0 ? 1.0 : -1.0));
    return p * 0.5 + 0.5;
}

TEST(OctahedralUnorm, BevyRoundsUnityTruncates) {
    Rng rng(92);
    int exact = 0, total = 0;
    double worst[3] = {0.0, 0.0, 0.0}, sum[3] = {0.0, 0.0, 0.0};  // Bevy, Unity, HDRP
    for (int i = 0; i < 300000; ++i) {
        const glm::dvec3 n = randomUnit(rng);
        const glm::vec3 nf(n);
        const glm::dvec2 u = octUnit(glm::dvec3(nf));
        const glm::uvec2 codes[3] = {encodeNormalOctahedralBevy(nf, 12u), encodeNormalOctahedralUnity(nf, 12u),
                                     encodeNormalOctahedralHdrp(nf, 12u)};
        for (int k = 0; k < 2; ++k) {
            const double c = std::clamp(u[k], 0.0, 1.0);
            // Bevy: u32(saturate(u) * 4095 + 0.5), rounding. Unity: uint(u * 4095.5), truncation.
            const double want[2] = {std::floor(c * 4095.0 + 0.5), std::floor(c * 4095.5)};
            for (int e = 0; e < 2; ++e) {
                const double diff = std::abs(double(codes[e][k]) - want[e]);
                ASSERT_LE(diff, 1.0) << e << ": " << n.x << " " << n.y << " " << n.z;
                exact += diff == 0.0 ? 1 : 0;
                ++total;
            }
        }
        // HDRP differs from Unity only where |z| < 1/1024 (its seam clamp).
        if (std::abs(nf.z) >= 1.0f / 1024.0f) {
            ASSERT_EQ(codes[2], codes[1]) << n.x << " " << n.y << " " << n.z;
        }
        for (int e = 0; e < 3; ++e) {
            const double a = angleDeg(n, glm::dvec3(decodeNormalOctahedralUnorm(codes[e], 12u)));
            worst[e] = std::max(worst[e], a);
            sum[e] += a;
        }
    }
    EXPECT_GT(double(exact) / total, 0.999);
    // HDRP within its 1/1024 band around the equator, where the clamp moves the normal first.
    double worstBand = 0.0;
    for (int i = 0; i < 100000; ++i) {
        glm::dvec3 n = randomUnit(rng);
        n.z = (rng.u01() * 2.0 - 1.0) / 1024.0;
        n = glm::normalize(n);
        const glm::uvec2 c = encodeNormalOctahedralHdrp(glm::vec3(n), 12u);
        worstBand = std::max(worstBand, angleDeg(n, glm::dvec3(decodeNormalOctahedralUnorm(c, 12u))));
    }
    std::printf("[ octa 12  ] mean / max angle: Bevy %.4f / %.4f deg, Unity %.4f / %.4f, HDRP %.4f / %.4f (max %.4f "
                "within 1/1024 of z = 0)\n",
                sum[0] / 300000, worst[0], sum[1] / 300000, worst[1], sum[2] / 300000, worst[2], worstBand);
    EXPECT_LT(worstBand, 0.12 + 0.056);
    EXPECT_GT(worstBand, 0.07);
    // Rounding: half a step in u and v (a step is 2/4095 of the octahedron), as normal_octahedral
    // at 12 bits (0.059 degrees); truncation: up to a whole step, `gbufferlab encodings` measures
    // max 0.107 (Unity). HDRP adds the clamp's own shift near the equator, at most 1/1024 rad.
    EXPECT_LT(worst[0], 0.062);
    EXPECT_GT(worst[0], 0.045);
    EXPECT_LT(worst[1], 0.12);
    EXPECT_GT(worst[1], 0.062);
    EXPECT_LT(worst[2], 0.12 + 0.056);
    // +z: u = v = 0.5: Bevy round(2047.5) = 2048; Unity floor(2047.75) = 2047, which
    // PackFloat2To888 writes as R = G = 0xFF (low bytes), B = 0x77 (high nibbles 7 | 7 << 4).
    EXPECT_EQ(encodeNormalOctahedralBevy(glm::vec3(0, 0, 1), 12u), glm::uvec2(2048u, 2048u));
    EXPECT_EQ(encodeNormalOctahedralUnity(glm::vec3(0, 0, 1), 12u), glm::uvec2(2047u, 2047u));
    // +x: u = 1: Bevy 4095, Unity floor(4095.5) = 4095; HDRP's clamp moves it to z = 1/1024:
    // u = (1 + 1/1024)^-1 * 0.5 + 0.5, floor(4093.5..) = 4093.
    EXPECT_EQ(encodeNormalOctahedralBevy(glm::vec3(1, 0, 0), 12u), glm::uvec2(4095u, 2048u));
    EXPECT_EQ(encodeNormalOctahedralUnity(glm::vec3(1, 0, 0), 12u), glm::uvec2(4095u, 2047u));
    EXPECT_EQ(encodeNormalOctahedralHdrp(glm::vec3(1, 0, 0), 12u), glm::uvec2(4093u, 2047u));
    // -z: Bevy's wrap takes sign(0) = -1 (codes 0, 0), Unity's +1 (the top codes).
    EXPECT_EQ(encodeNormalOctahedralBevy(glm::vec3(0, 0, -1), 12u), glm::uvec2(0u, 0u));
    EXPECT_EQ(encodeNormalOctahedralUnity(glm::vec3(0, 0, -1), 12u), glm::uvec2(4095u, 4095u));
}

// Killzone 2's RT1: x, y as half floats, z rebuilt facing the camera.
TEST(NormalXyFloat16, HalfFloatsOfXYAndZRebuiltPositive) {
    Rng rng(93);
    double worstFront = 0.0, worstBack = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const glm::dvec3 n = randomUnit(rng);
        const glm::vec3 nf(n);
        const glm::uvec2 code = encodeNormalXyFloat16(nf);
        ASSERT_EQ(code.x, encodeFloat16(nf.x));
        ASSERT_EQ(code.y, encodeFloat16(nf.y));
        const glm::dvec3 d(decodeNormalXyFloat16(code));
        ASSERT_GE(d.z, 0.0);
        // Facing away (z < 0) comes back mirrored through the xy plane.
        const glm::dvec3 front(n.x, n.y, std::abs(n.z));
        const double a = angleDeg(front, d);
        if (n.z >= 0.2) worstFront = std::max(worstFront, a);
        else worstBack = std::max(worstBack, a);
    }
    // x, y carry 11 significant bits (relative error <= 2^-12 each); z = sqrt(1 - x^2 - y^2)
    // amplifies that by (x^2 + y^2) / z: for z >= 0.2 within 0.1 degrees (measured 0.089), near
    // z = 0 below 2 degrees.
    EXPECT_LT(worstFront, 0.1);
    EXPECT_LT(worstBack, 2.0);
}

// Killzone 2's RT2.b, written out from the talk (Valient, Develop 2007: "Specular power - stored as
// log2(original)/10.5"): the byte g = code / 255 holds log2(n) / 10.5, so n = 2^(10.5 g). Read as
// GGX roughness with Walter et al.'s n = 2 / alpha^2 - 2 and UE4's alpha = roughness^2.
TEST(Kz2LogPower, TablesMatchTheMapping) {
    auto powerOfCode = [](double g) { return std::pow(2.0, 10.5 * g); };
    auto roughnessOfPower = [](double n) { return std::sqrt(std::sqrt(2.0 / (n + 2.0))); };
    auto storedOfRoughness = [](double r) { return std::log2(2.0 / (r * r * r * r) - 2.0) / 10.5; };
    for (int k = 0; k < 256; ++k)
        ASSERT_EQ(kKz2PowerRoughness[k], float(roughnessOfPower(powerOfCode(k / 255.0)))) << k;
    for (int i = 0; i < 255; ++i) {
        const double t = roughnessOfPower(powerOfCode((i + 0.5) / 255.0));
        const float f = kKz2PowerEncodeThresholds[i];
        ASSERT_LE(double(f), t) << i;
        ASSERT_GT(double(std::nextafter(f, 1.0f)), t) << i;  // the largest float <= t
    }
    // The ends: power 1 (code 0) and 2^10.5 = 1448.15 (code 255); roughness beyond them clamps.
    EXPECT_NEAR(roughnessOfPower(1.0), 0.9036020, 1e-7);
    EXPECT_NEAR(roughnessOfPower(std::pow(2.0, 10.5)), 0.1927098, 1e-7);
    EXPECT_EQ(encodeKz2LogPower(1.0f), 0u);
    EXPECT_EQ(encodeKz2LogPower(0.95f), 0u);
    EXPECT_EQ(encodeKz2LogPower(0.0f), 255u);
    EXPECT_EQ(encodeKz2LogPower(0.1f), 255u);
    EXPECT_EQ(decodeKz2LogPower(0u), 0.903602f);
    EXPECT_EQ(decodeKz2LogPower(255u), 0.19270985f);
    // A decoded code is the power the talk's formula gives for it.
    for (uint k = 0; k < 256; ++k) {
        const double r = decodeKz2LogPower(k);
        const double n = 2.0 / (r * r * r * r) - 2.0;
        ASSERT_NEAR(n / powerOfCode(k / 255.0), 1.0, 2e-5) << k;
    }
    // The encoder rounds the stored value to the nearest code.
    Rng rng(94);
    double worst = 0.0;
    int checked = 0;
    for (int i = 0; i < 1000000; ++i) {
        const float r = float(0.19270985 + (0.90360200 - 0.19270985) * rng.u01());
        const double g = 255.0 * storedOfRoughness(double(r));
        const uint code = encodeKz2LogPower(r);
        if (std::abs(g - std::floor(g) - 0.5) > 1e-4) {  // away from a tie
            ASSERT_EQ(double(code), std::clamp(std::floor(g + 0.5), 0.0, 255.0)) << r;
            ++checked;
        }
        worst = std::max(worst, std::fabs(double(decodeKz2LogPower(code)) - double(r)));
    }
    EXPECT_GT(checked, 999000);
    // Half a code of g, times |d roughness / d g| = roughness / 4 * 10.5 ln 2 * n / (n + 2) <= 1.
    std::printf("[measured] kz2_log_power: max roughness error inside [0.1927, 0.9036] %.6f\n", worst);
    EXPECT_LE(worst, 0.0020);
}

// Filament / Bevy reflectance: r = sqrt(specular / 2), F0 = 0.16 r^2 = 0.08 specular.
TEST(Reflectance, CodesAreFilamentsReflectance) {
    int checked = 0;
    for (int i = 0; i <= 100000; ++i) {
        const float s = float(i) / 100000.0f;
        const double r = 255.0 * std::sqrt(double(s) / 2.0);
        const unsigned code = quantizeUnorm(reflectanceFromSpecular(s), 8u);
        // Within float's rounding of sqrt of a tie (s = 0.02: r = 25.4999997), either code is right.
        if (std::abs(r - std::floor(r) - 0.5) < 1e-5) {
            ASSERT_LE(std::abs(double(code) - r), 0.5 + 1e-5) << s;
            continue;
        }
        ASSERT_EQ(code, unsigned(std::floor(r + 0.5))) << s;
        const double back = specularFromReflectance(dequantizeUnorm(code, 8u));
        // F0 agrees: 0.16 r^2 with r the stored code's value, against 0.08 s.
        ASSERT_LE(std::abs(0.08 * back - 0.08 * s), 0.08 * 2.83 * 0.5 / 255.0 + 1e-7) << s;
        ++checked;
    }
    EXPECT_GT(checked, 99900);
    EXPECT_EQ(quantizeUnorm(reflectanceFromSpecular(0.5f), 8u), 128u);  // Bevy's default reflectance 0.5
}

}  // namespace
