// zeux/niagara's G-buffer encodings (src/encoding/niagara_encodings.h, twin of
// shaders/niagara_encodings.glsl) against niagara's formulas written out here in double from
// its source (src/shaders/mesh.frag.glsl, final.comp.glsl, math.h @95f289b7):
//   gbuffer0.a = log2(1 + dot(e, w) / (dot(albedo, w) + 1e-3)) / 5, w = (0.3, 0.6, 0.1), UNORM;
//   emissive = albedo * (exp2(a * 5) - 1);
//   gbuffer1.rg = encodeOct(n) * 0.5 + 0.5 + (2 g - 1) * 0.5 / 1023, UNORM (10 bits),
//   g = fract(52.9829189 * fract(dot(p + 0.5, (0.06711056, 0.00583715)))).
#include "encodings_test_support.h"
#include "niagara_encodings.h"

namespace {

using namespace gbl::enc;
using namespace gbl::enc_test;

double lumaD(glm::dvec3 c) { return 0.3 * c.x + 0.6 * c.y + 0.1 * c.z; }

// Niagara's emissive code in double; `tie` is how far the scaled value lies from a rounding point.
unsigned ratioCodeD(glm::dvec3 e, glm::dvec3 a, unsigned bits, double& tie) {
    const double s = std::ldexp(1.0, int(bits)) - 1.0;
    const double x = std::clamp(std::log2(1.0 + lumaD(e) / (lumaD(a) + 1e-3)) / 5.0, 0.0, 1.0) * s;
    tie = std::fabs(x - std::floor(x) - 0.5);
    return unsigned(std::floor(x + 0.5));
}

// fract of the inner dot product: where it is within float's rounding of 0 or 1, float's noise
// may wrap to the other end (a whole step of dither), so the tests skip those pixels.
double innerFract(int x, int y) {
    const double d = (x + 0.5) * 0.06711056 + (y + 0.5) * 0.00583715;
    return d - std::floor(d);
}

double noiseD(int x, int y) {
    const double d = (x + 0.5) * 0.06711056 + (y + 0.5) * 0.00583715;
    const double g = 52.9829189 * (d - std::floor(d));
    return g - std::floor(g);
}

// Cigolle et al. 2014's octahedral projection (as niagara's encodeOct), in double.
glm::dvec2 octD(glm::dvec3 n) {
    const double l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    glm::dvec2 p(n.x / l1, n.y / l1);
    if (n.z <= 0.0) p = glm::dvec2((1.0 - std::fabs(p.y)) * (p.x >= 0.0 ? 1.0 : -1.0),
                                   (1.0 - std::fabs(p.x)) * (p.y >= 0.0 ? 1.0 : -1.0));
    return p;
}

}  // namespace

TEST(NiagaraEncodings, SeriesLog2AndExp2MatchTheLibraryToAFewUlp) {
    for (int i = 0; i <= 31 * 4096; ++i) {
        const float y = 1.0f + float(i) / 4096.0f;
        ASSERT_NEAR(log2Series(y), std::log2(double(y)), 4e-7) << y;
    }
    for (int i = 0; i <= 5 * 4096; ++i) {
        const float x = float(i) / 4096.0f;
        const double want = std::exp2(double(x));
        ASSERT_NEAR(exp2Series(x), want, want * 4e-7) << x;
    }
}

TEST(NiagaraEncodings, EmissiveCodeIsNiagarasFormula) {
    Rng r(15);
    size_t checked = 0;
    for (int i = 0; i < 200000; ++i) {
        const glm::dvec3 a(r.u01(), r.u01(), r.u01());
        const glm::dvec3 e = glm::dvec3(r.u01(), r.u01(), r.u01()) * (r.u01() < 0.5 ? 1.0 : 8.0);
        for (unsigned bits : {8u, 5u, 12u}) {
            double tie = 0.0;
            const unsigned want = ratioCodeD(e, a, bits, tie);
            const unsigned got = encodeEmissiveAlbedoRatio(glm::vec3(e), glm::vec3(a), bits);
            // float's rounding (a few ulp of the ratio, times the code scale) may take either side of a tie
            if (tie < 2e-6 * std::ldexp(1.0, int(bits)) + 1e-4) {
                ASSERT_LE(std::abs(int(got) - int(want)), 1);
                continue;
            }
            ++checked;
            ASSERT_EQ(got, want) << "bits " << bits << " e " << e.x << "," << e.y << "," << e.z;
        }
    }
    EXPECT_GT(checked, 590000u);
    // Beyond the range (ratio >= 31) the code is the top one, as the UNORM target clamps.
    EXPECT_EQ(encodeEmissiveAlbedoRatio(vec3(100.0f), vec3(0.5f), 8u), 255u);
    EXPECT_EQ(encodeEmissiveAlbedoRatio(vec3(0.0f), vec3(0.5f), 8u), 0u);
}

TEST(NiagaraEncodings, EmissiveDecodesFromTheAlbedoItIsGiven) {
    Rng r(16);
    for (unsigned code = 0; code < 256; ++code) {
        const glm::dvec3 a(r.u01(), r.u01(), r.u01());
        const double k = std::exp2(double(code) / 255.0 * 5.0) - 1.0;
        const vec3 got = decodeEmissiveAlbedoRatio(code, 8u, glm::vec3(a));
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], a[c] * k, 1e-6 * (1.0 + a[c] * k)) << code;
    }
}

// Round trip: an emissive of the albedo's own hue, e = k * albedo, comes back within half a code
// step in the log domain: |log2(1 + k') - log2(1 + k)| <= 5 * 0.5 / 255 (+ float slack), where
// k = L(e) / (L(albedo) + 0.001) is the ratio niagara stores. Another hue comes back as the albedo's.
TEST(NiagaraEncodings, EmissiveRoundTripIsHalfAStepInLog2) {
    Rng r(17);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const glm::vec3 a(float(r.u01()), float(r.u01()), float(r.u01()));
        const float k = float(r.u01() * 30.0);
        const glm::vec3 e = a * k;
        const unsigned code = encodeEmissiveAlbedoRatio(e, a, 8u);
        const glm::vec3 back = decodeEmissiveAlbedoRatio(code, 8u, a);
        const double ratio = lumaD(glm::dvec3(e)) / (lumaD(glm::dvec3(a)) + 1e-3);
        const double kBack = lumaD(glm::dvec3(a)) > 0.0 ? lumaD(glm::dvec3(back)) / lumaD(glm::dvec3(a)) : 0.0;
        worst = std::max(worst, std::fabs(std::log2(1.0 + kBack) - std::log2(1.0 + ratio)));
    }
    EXPECT_LE(worst, 5.0 * 0.5 / 255.0 + 1e-5);
    EXPECT_GT(worst, 5.0 * 0.4 / 255.0);  // the bound is reached: it is the quantisation's
    // A red glow on a white surface reads back white (niagara keeps the albedo's hue).
    const glm::vec3 back = decodeEmissiveAlbedoRatio(encodeEmissiveAlbedoRatio(vec3(1, 0, 0), vec3(1), 8u), 8u, vec3(1));
    EXPECT_NEAR(back.x, back.y, 1e-6);
    EXPECT_NEAR(back.y, back.z, 1e-6);
}

TEST(NiagaraEncodings, GradientNoiseIsJimenezsOfThePixelCentre) {
    double sum = 0.0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float g = gradientNoise(ivec2(x, y));
            ASSERT_GE(g, 0.0f);
            ASSERT_LT(g, 1.0f);
            // float's rounding of d (< 5) times 52.98: a few 1e-5 at most.
            const double want = noiseD(x, y);
            const double diff = std::fabs(double(g) - want);
            ASSERT_LT(std::min(diff, 1.0 - diff), 1e-4) << x << "," << y;
            sum += g;
        }
    EXPECT_NEAR(sum / 4096.0, 0.5, 0.02);
}

// The code is niagara's: UNORM rounding of p * 0.5 + 0.5 plus the pixel's noise (skipping inputs
// within float slack of a rounding point); the noise never moves it more than one code from the
// undithered rounding; over many pixels the dither is unbiased (mean code = u * 1023).
TEST(NiagaraEncodings, DitheredOctahedralIsNiagarasDeband) {
    Rng r(18);
    size_t checked = 0, moved = 0;
    for (int i = 0; i < 200000; ++i) {
        const glm::dvec3 n = randomUnit(r);
        const ivec2 px(int(r.bits32() % 1920), int(r.bits32() % 1080));
        const glm::dvec2 p = octD(n);
        const double g = noiseD(px.x, px.y);
        const double d = (g * 2.0 - 1.0) * 0.5 / 1023.0;
        const uvec2 got = encodeNormalOctahedralDithered(glm::vec3(n), 10u, px);
        for (int c = 0; c < 2; ++c) {
            const double x = std::clamp(p[c] * 0.5 + 0.5 + d, 0.0, 1.0) * 1023.0;
            const unsigned plain = unsigned(std::floor(std::clamp(p[c] * 0.5 + 0.5, 0.0, 1.0) * 1023.0 + 0.5));
            ASSERT_LE(std::abs(int(got[c]) - int(plain)), 1);
            moved += got[c] != plain;
            // float's noise is within 1e-3 of double's, except where fract wraps (g near 0 or 1)
            if (std::fabs(x - std::floor(x) - 0.5) < 2e-3 || g < 1e-3 || g > 1.0 - 1e-3 ||
                std::min(innerFract(px.x, px.y), 1.0 - innerFract(px.x, px.y)) < 1e-4)
                continue;
            ++checked;
            ASSERT_EQ(got[c], unsigned(std::floor(x + 0.5))) << i << " component " << c;
        }
    }
    EXPECT_GT(checked, 390000u);
    EXPECT_GT(moved, 50000u);  // the noise does move codes (about half a step's worth of them)
    for (double u : {0.3, 0.4137, 0.77}) {
        // n with octahedral p.x = 2u - 1 on the upper hemisphere, p.y = 0
        const double px = 2.0 * u - 1.0;
        const glm::vec3 n = glm::normalize(glm::vec3(float(px), 0.0f, float(1.0 - std::fabs(px))));
        const double target = double(octEncode(n).x) * 0.5 + 0.5;
        double mean = 0.0;
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) mean += encodeNormalOctahedralDithered(n, 10u, ivec2(x, y)).x;
        mean /= 128.0 * 128.0;
        EXPECT_NEAR(mean, target * 1023.0, 0.05) << u;
    }
}

TEST(NiagaraEncodings, DitheredOctahedralAngleErrorIsAtMostOneStep) {
    Rng r(19);
    double worst = 0.0, sum = 0.0;
    const int count = 100000;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 n = randomUnit(r);
        const glm::vec3 back = gbl::roundTripNormal("normal_octahedral_dithered", 10, glm::vec3(n),
                                                    glm::ivec2(i % 256, i / 256));
        const double a = angleDeg(n, glm::dvec3(back));
        worst = std::max(worst, a);
        sum += a;
    }
    // One whole step in u and v (2/1023 in p) at worst; the undithered rounding's half step is
    // 0.118 deg at 10 bits (4 x normal_octahedral's 0.059 at 12).
    EXPECT_LE(worst, 0.47);
    EXPECT_GT(worst, 0.118);
    std::printf("[ niagara  ] normal_octahedral_dithered 10 bits: mean %.4f deg, max %.4f deg\n", sum / count, worst);
}
