// Tests of the IBL maths (src/shading/ibl_math.h, mirror of shaders/ibl_math.glsl) and the CPU BRDF LUT
// (src/shading/ibl_brdf_lut.h). Every tolerance is stated next to its assertion, with why it is that size;
// the measured figures quoted here are the ones documented in src/shading/ibl_math.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "brdf.h"
#include "ibl_brdf_lut.h"
#include "ibl_math.h"
#include "environment_map.h"
#include "environment_sampling.h"
#include "ibl_precompute.h"
#include "image.h"

using namespace gbl::shading;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Independent reference for the split-sum environment BRDF: a dense midpoint quadrature over
// the hemisphere of L (not of H, and no importance sampling), in double, written from the
// formulas: int f cos dL with f = D G F / (4 NoL NoV), F = f0 (1 - Fc) + Fc, so
//   A = int D G (1 - Fc) / (4 NoV) dL,   B = int D G Fc / (4 NoV) dL,
// D = GGX (alpha = r^2), G = Smith-Schlick with k = alpha/2, Fc = (1 - v.h)^5.
// V lies in the xz plane, so the integrand is even in phi: integrate phi in [0, pi], double it.
glm::dvec2 quadratureAB(double roughness, double NoV, int thetaSteps, int phiSteps) {
    double alpha = roughness * roughness, a2 = alpha * alpha, k = alpha / 2.0;
    glm::dvec3 V(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
    double dt = 0.5 * kPiD / thetaSteps, dp = kPiD / phiSteps;
    double A = 0.0, B = 0.0;
    for (int i = 0; i < thetaSteps; ++i) {
        double t = (i + 0.5) * dt;
        double st = std::sin(t), NoL = std::cos(t);
        double gl = NoL / (NoL * (1.0 - k) + k);
        double rowA = 0.0, rowB = 0.0;
        for (int j = 0; j < phiSteps; ++j) {
            double p = (j + 0.5) * dp;
            glm::dvec3 L(st * std::cos(p), st * std::sin(p), NoL);
            glm::dvec3 H = glm::normalize(V + L);
            double NoH = H.z, VoH = glm::dot(V, H);
            double d = NoH * NoH * (a2 - 1.0) + 1.0;
            double D = a2 / (kPiD * d * d);
            double gv = NoV / (NoV * (1.0 - k) + k);
            double m = 1.0 - VoH, Fc = m * m * m * m * m;
            double common = D * gv * gl / (4.0 * NoV);
            rowA += common * (1.0 - Fc);
            rowB += common * Fc;
        }
        A += rowA * st;
        B += rowB * st;
    }
    return 2.0 * glm::dvec2(A, B) * dt * dp;
}

// The reference LUT for the bounds tests: integrateBRDFDouble with 4096 samples on a 64 x 64
// grid of texel centres (NoV = (i+0.5)/64, roughness = (j+0.5)/64). Its own error against the
// quadrature is < 1e-3 (see LutMatchesIndependentQuadrature), far below the bounds it checks.
constexpr int kGrid = 64;
const std::vector<glm::dvec2>& referenceLut() {
    static const std::vector<glm::dvec2> lut = [] {
        std::vector<glm::dvec2> v(kGrid * kGrid);
        for (int j = 0; j < kGrid; ++j)
            for (int i = 0; i < kGrid; ++i)
                v[j * kGrid + i] = integrateBRDFDouble((j + 0.5) / kGrid, (i + 0.5) / kGrid, 4096);
        return v;
    }();
    return lut;
}

struct ErrorStats {
    double maxAbs = 0.0, maxAbsNoV25 = 0.0, rms = 0.0, atR = 0.0, atNoV = 0.0;
};

// Max |approx - (f0 A + B)| over the grid, also restricted to NoV >= 0.25, and the RMS.
template <class Approx>
ErrorStats compareWithLut(double f0, Approx approx) {
    const auto& lut = referenceLut();
    ErrorStats s;
    for (int j = 0; j < kGrid; ++j) {
        for (int i = 0; i < kGrid; ++i) {
            double r = (j + 0.5) / kGrid, nov = (i + 0.5) / kGrid;
            glm::dvec2 ab = lut[j * kGrid + i];
            double e = std::fabs(double(approx(float(r), float(nov))) - (f0 * ab.x + ab.y));
            if (e > s.maxAbs) s.maxAbs = e, s.atR = r, s.atNoV = nov;
            if (nov >= 0.25) s.maxAbsNoV25 = std::max(s.maxAbsNoV25, e);
            s.rms += e * e;
        }
    }
    s.rms = std::sqrt(s.rms / (kGrid * kGrid));
    return s;
}

void printStats(const char* name, const ErrorStats& s) {
    std::printf("%-34s max %.4f (r %.3f, NoV %.3f)  max(NoV>=0.25) %.4f  rms %.4f\n", name, s.maxAbs, s.atR,
                s.atNoV, s.maxAbsNoV25, s.rms);
}

// How far a 1024-sample Hammersley estimate of the environment BRDF may sit from the true
// integral, by NoV (measured against quadratureAB at roughness 0.15..1: max 1.05e-2 at NoV 0.1,
// 4.3e-3 at NoV 0.25, 3.4e-3 at NoV >= 0.5; grazing views are where the GGX lobe is cut by
// the horizon and 1024 points resolve it worst). Two such estimates with different point sets
// (a turned tangent frame) differ by less than this as well (measured 1.1e-2 at NoV 0.1).
double qmc1024Tolerance(double NoV) {
    if (NoV < 0.2) return 1.3e-2;
    if (NoV < 0.45) return 5.5e-3;
    return 4.5e-3;
}

}  // namespace

// ---------------------------------------------------------------- Hammersley

// Bit-by-bit reference: bit k of i contributes 2^-(k+1). For i < 2^24 the float result is exact
// (tolerance 0); for any 32-bit i it is the reference truncated to 24 bits (error < 2^-24);
// the double variant is exact for all i.
TEST(Hammersley, RadicalInverseMatchesBitByBitReference) {
    auto reference = [](uint32_t i) {
        double v = 0.0, w = 0.5;
        for (int k = 0; k < 32; ++k, w *= 0.5)
            if (i & (1u << k)) v += w;
        return v;
    };
    EXPECT_EQ(radicalInverseVdC(0), 0.0f);
    EXPECT_EQ(radicalInverseVdC(1), 0.5f);
    EXPECT_EQ(radicalInverseVdC(2), 0.25f);
    EXPECT_EQ(radicalInverseVdC(3), 0.75f);
    EXPECT_EQ(radicalInverseVdC(6), 0.375f);
    for (uint32_t i = 0; i < 70000; ++i) ASSERT_EQ(double(radicalInverseVdC(i)), reference(i)) << i;
    std::mt19937 rng(3);
    for (int n = 0; n < 100000; ++n) {
        uint32_t i = rng();
        double ref = reference(i);
        if (i < (1u << 24)) {
            ASSERT_EQ(double(radicalInverseVdC(i)), ref) << i;
        }
        ASSERT_LT(std::fabs(double(radicalInverseVdC(i)) - ref), std::ldexp(1.0, -24)) << i;
        ASSERT_EQ(radicalInverseVdCDouble(i), ref) << i;
    }
}

// Points lie in [0,1)^2, x = i/N, including the extreme i = 2^32 - 1 for the y coordinate.
TEST(Hammersley, PointsInUnitSquare) {
    for (uint32_t N : {1u, 2u, 16u, 1000u, 1024u, 4096u, 65536u}) {
        for (uint32_t i = 0; i < N; ++i) {
            glm::vec2 p = hammersley(i, N);
            ASSERT_GE(p.x, 0.0f);
            ASSERT_LT(p.x, 1.0f);
            ASSERT_GE(p.y, 0.0f);
            ASSERT_LT(p.y, 1.0f);
            ASSERT_EQ(p.x, float(i) / float(N));
        }
    }
    EXPECT_LT(radicalInverseVdC(0xFFFFFFFFu), 1.0f);
    EXPECT_LT(radicalInverseVdCDouble(0xFFFFFFFFu), 1.0);
    EXPECT_LT(hammersley((1u << 24) - 1, 1u << 24).x, 1.0f);
}

// ---------------------------------------------------------------- importance sampling

// Directions are unit (tolerance 2e-6: a normalise and a 3-term sum in float) and in the
// hemisphere of N (N.H >= -1e-6), for normals at the poles, next to the 0.999 frame switch,
// and random; Xi.y = 0 gives H = N (tolerance 1e-6).
TEST(ImportanceSampleGGX, UnitAndInHemisphere) {
    std::vector<glm::vec3> normals = {
        {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0},
        glm::normalize(glm::vec3(0.0f, 0.0447f, 0.999f)),   // |N.z| just below 0.999 ...
        glm::normalize(glm::vec3(0.0f, 0.0440f, 0.999f)),   // ... and just above
        glm::normalize(glm::vec3(0.03f, 0.0f, -0.9995f))};
    std::mt19937 rng(11);
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (int k = 0; k < 20; ++k) normals.push_back(glm::normalize(glm::vec3(n(rng), n(rng), n(rng))));
    for (const glm::vec3& N : normals) {
        for (float r : {0.0f, 0.05f, 0.3f, 0.7f, 1.0f}) {
            for (uint32_t i = 0; i < 1024; ++i) {
                glm::vec3 H = importanceSampleGGX(hammersley(i, 1024), r, N);
                ASSERT_NEAR(glm::length(H), 1.0f, 2e-6f) << r << " " << i;
                ASSERT_GE(glm::dot(H, N), -1e-6f) << r << " " << i;
            }
            glm::vec3 H0 = importanceSampleGGX(glm::vec2(0.37f, 0.0f), r, N);
            EXPECT_NEAR(glm::length(H0 - N), 0.0f, 1e-6f);
        }
    }
}

// The samples follow D(h)(n.h): the fraction with N.H >= mu equals
// 2 pi int_mu^1 D(c) c dc (quadrature, independent of the inversion formula). Hammersley's
// y coordinate is stratified, so with 4096 samples the error is <= 1/4096 plus the quadrature's
// ~1e-7: tolerance 3e-4. Azimuth (x = i/N is stratified too): each quadrant holds 1/4 of the
// samples off the quadrant boundaries (tolerance 2/4096).
TEST(ImportanceSampleGGX, FollowsGgxDistribution) {
    const uint32_t n = 4096;
    for (float r : {0.2f, 0.5f, 0.8f, 1.0f}) {
        double alpha = double(r) * r, a2 = alpha * alpha;
        std::vector<glm::vec3> hs(n);
        for (uint32_t i = 0; i < n; ++i) hs[i] = importanceSampleGGX(hammersley(i, n), r, glm::vec3(0, 0, 1));
        for (double mu : {0.999, 0.99, 0.95, 0.9, 0.7, 0.4}) {
            double expected = 0.0;
            const int steps = 200000;
            double t1 = std::acos(mu), dt = t1 / steps;
            for (int s = 0; s < steps; ++s) {
                double t = (s + 0.5) * dt, c = std::cos(t);
                double d = c * c * (a2 - 1.0) + 1.0;
                expected += a2 / (kPiD * d * d) * c * std::sin(t);
            }
            expected *= 2.0 * kPiD * dt;
            double fraction = double(std::count_if(hs.begin(), hs.end(), [&](glm::vec3 h) { return h.z >= mu; })) / n;
            EXPECT_NEAR(fraction, expected, 3e-4) << "roughness " << r << " mu " << mu;
        }
        int quadrant[4] = {0, 0, 0, 0}, counted = 0;
        for (const glm::vec3& h : hs) {
            if (std::fabs(h.x) < 1e-5f || std::fabs(h.y) < 1e-5f) continue;  // on a quadrant boundary
            quadrant[(h.x > 0 ? 0 : 1) + (h.y > 0 ? 0 : 2)]++;
            ++counted;
        }
        for (int q = 0; q < 4; ++q) {
            EXPECT_NEAR(quadrant[q] / double(counted), 0.25, 2.0 / n) << r << " quadrant " << q;
        }
    }
}

// ---------------------------------------------------------------- the split-sum LUT

// integrateBRDF (float, 1024 Hammersley samples: the LUT as the GPU will compute it) against the
// independent quadrature. Quadrature: 800 x 1600 midpoints (step 2e-3 rad); halving the step
// moves it by <= 1.2e-4 (at roughness 0.15, NoV 1), <= 2.3e-6 elsewhere.
// Measured |error| of the 1024-sample float LUT: 1.05e-2 (A, r 0.25, NoV 0.1), 4.3e-3 at NoV 0.25,
// 3.4e-3 at NoV >= 0.5, and a bias of +5e-4 in A at NoV = 1 (Hammersley's y = k/N is a
// left-endpoint rule: O(1/2N)); tolerance qmc1024Tolerance(NoV). The 65536-sample double
// estimator: measured 3.8e-4 (r 0.15, NoV 0.1); tolerance 6e-4 (quadrature error included).
TEST(IntegrateBRDF, LutMatchesIndependentQuadrature) {
    double maxErr1024 = 0.0, maxErrDouble = 0.0;
    for (double r : {0.15, 0.25, 0.4, 0.6, 0.8, 1.0}) {
        for (double nov : {0.1, 0.25, 0.5, 0.75, 1.0}) {
            glm::dvec2 q = quadratureAB(r, nov, 800, 1600);
            glm::vec2 lut = integrateBRDF(float(r), float(nov), 1024);
            glm::dvec2 ref = integrateBRDFDouble(r, nov, 65536);
            double e = std::max(std::fabs(lut.x - q.x), std::fabs(lut.y - q.y));
            double ed = std::max(std::fabs(ref.x - q.x), std::fabs(ref.y - q.y));
            maxErr1024 = std::max(maxErr1024, e);
            maxErrDouble = std::max(maxErrDouble, ed);
            EXPECT_NEAR(lut.x, q.x, qmc1024Tolerance(nov)) << "A at r " << r << " NoV " << nov;
            EXPECT_NEAR(lut.y, q.y, qmc1024Tolerance(nov)) << "B at r " << r << " NoV " << nov;
            EXPECT_NEAR(ref.x, q.x, 6e-4) << "A(double) at r " << r << " NoV " << nov;
            EXPECT_NEAR(ref.y, q.y, 6e-4) << "B(double) at r " << r << " NoV " << nov;
        }
    }
    std::printf("LUT vs quadrature: max |err| float/1024 %.2e, double/65536 %.2e\n", maxErr1024, maxErrDouble);
}

// The float estimator equals the double one with the same samples up to float rounding of a
// 1024-term sum (tolerance 2e-5 absolute).
TEST(IntegrateBRDF, FloatMatchesDoubleSameSamples) {
    double worst = 0.0;
    for (int j = 0; j < 16; ++j) {
        for (int i = 0; i < 16; ++i) {
            float r = (j + 0.5f) / 16.0f, nov = (i + 0.5f) / 16.0f;
            glm::vec2 f = integrateBRDF(r, nov, 1024);
            glm::dvec2 d = integrateBRDFDouble(r, nov, 1024);
            worst = std::max({worst, std::fabs(f.x - d.x), std::fabs(f.y - d.y)});
        }
    }
    std::printf("float vs double, same 1024 samples: max |diff| %.2e\n", worst);
    EXPECT_LE(worst, 2e-5);
}

// Roughness 0 is a mirror: every sample is H = N, so A + B = 1 and B = (1 - NoV)^5 (tolerance
// 1e-5: float rounding of 1024 identical terms).
TEST(IntegrateBRDF, MirrorLimit) {
    for (float nov : {0.05f, 0.3f, 0.7f, 1.0f}) {
        glm::vec2 ab = integrateBRDF(0.0f, nov, 1024);
        EXPECT_NEAR(ab.x + ab.y, 1.0f, 1e-5f) << nov;
        EXPECT_NEAR(ab.y, std::pow(1.0 - nov, 5.0), 1e-5) << nov;
    }
}

// White furnace: with f0 = 1 (F = 1), A + B is the directional albedo of the specular lobe; it
// must never exceed 1, and stays close to 1 for smooth surfaces away from grazing.
// Smith-Schlick (k = alpha/2) loses energy; measured with integrateBRDFDouble, 4096 samples,
// 64 NoV midpoints (E_avg = 2 int E(mu) mu dmu, the cosine-weighted average):
//   roughness        0.0    0.1    0.2    0.3    0.4    0.5    0.6    0.7    0.8    0.9    1.0
//   E_avg            1.000  0.990  0.964  0.923  0.869  0.802  0.723  0.637  0.547  0.459  0.377
//   min, NoV>=0.05   1.000  0.843  0.652  0.647  0.663  0.666  0.650  0.612  0.533  0.412  0.308
//   min, NoV>=0.5    1.000  0.990  0.959  0.905  0.829  0.750  0.679  0.613  0.533  0.412  0.308
//   (E at NoV = 1 is 0.895 at roughness 0.5 and 0.307 at 1; the quadrature agrees.)
// Tolerances: <= 1 + 1e-3 for the float LUT (QMC noise of 1024 samples); E_avg within 0.005 of
// the table (the table is for 4096 samples; a changed k or a lost factor moves it by >> 0.005);
// close to 1 when smooth and not grazing: E >= 0.985 for roughness <= 0.1 and NoV >= 0.5
// (measured min 0.990), E >= 0.955 at roughness 0.2 and NoV >= 0.5 (measured min 0.959).
TEST(IntegrateBRDF, WhiteFurnace) {
    gbl::Image lut = computeBrdfLutCpu(32, 1024);
    for (int y = 0; y < lut.height; ++y)
        for (int x = 0; x < lut.width; ++x)
            ASSERT_LE(lut.at(x, y, 0) + lut.at(x, y, 1), 1.0f + 1e-3f) << "texel " << x << "," << y;

    const double expectedAvg[11] = {1.000, 0.990, 0.964, 0.923, 0.869, 0.802, 0.723, 0.637, 0.547, 0.459, 0.377};
    std::printf("roughness  E_avg   min E (NoV>=0.05)  min E (NoV>=0.5)\n");
    for (int ri = 0; ri <= 10; ++ri) {
        double r = ri / 10.0, avg = 0.0, mn = 2.0, mn05 = 2.0;
        const int n = 64;
        for (int i = 0; i < n; ++i) {
            double nov = (i + 0.5) / n;
            glm::dvec2 ab = integrateBRDFDouble(r, nov, 4096);
            double e = ab.x + ab.y;
            EXPECT_LE(e, 1.0 + 1e-4) << r << " " << nov;
            avg += 2.0 * e * nov / n;
            if (nov >= 0.05) mn = std::min(mn, e);
            if (nov >= 0.5 && ri <= 1) {
                EXPECT_GE(e, 0.985) << r << " " << nov;
            }
            if (nov >= 0.5 && ri == 2) {
                EXPECT_GE(e, 0.955) << r << " " << nov;
            }
            if (nov >= 0.5) mn05 = std::min(mn05, e);
        }
        std::printf("  %.1f      %.4f  %.4f  %.4f\n", r, avg, mn, mn05);
        EXPECT_NEAR(avg, expectedAvg[ri], 5e-3) << "roughness " << r;
    }
}

// ---------------------------------------------------------------- ground truth and pre-filter

// For a constant white environment the split sum is exact, so SpecularIBL with f0 = 1 equals
// A + B. With N = +z and V in the xz plane both estimators use the same samples: tolerance
// 5e-5 relative (float rounding of two differently grouped 1024-term sums, <= N eps / 2 = 3e-5),
// and for any f0 it equals f0 A + B (same tolerance, linearity). For other N the tangent frame
// turns the sample set: a QMC difference, tolerance qmc1024Tolerance(NoV).
TEST(SpecularIBL, ConstantEnvironmentEqualsLut) {
    EnvironmentLodFn white = [](glm::vec3, float) { return glm::vec3(1.0f); };
    for (float r : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f}) {
        for (float nov : {0.1f, 0.4f, 0.8f, 1.0f}) {
            glm::vec3 V(std::sqrt(1.0f - nov * nov), 0.0f, nov);
            glm::vec2 ab = integrateBRDF(r, nov);
            glm::vec3 gt = specularIBLGroundTruth(white, glm::vec3(1.0f), r, glm::vec3(0, 0, 1), V);
            EXPECT_NEAR(gt.x, ab.x + ab.y, 5e-5f * (ab.x + ab.y)) << r << " " << nov;
            glm::vec3 f0(0.04f, 0.5f, 0.9f);
            glm::vec3 gtc = specularIBLGroundTruth(white, f0, r, glm::vec3(0, 0, 1), V);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(gtc[c], f0[c] * ab.x + ab.y, 5e-5f * (ab.x + ab.y)) << r << " " << nov << " ch " << c;
            }
            // Turned frames: build an orthonormal (T, B, N) and express V in it.
            for (glm::vec3 N : {glm::normalize(glm::vec3(1, 2, 3)), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1)}) {
                glm::vec3 t = glm::normalize(glm::cross(std::fabs(N.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0), N));
                glm::vec3 Vn = glm::normalize(t * std::sqrt(1.0f - nov * nov) + N * nov);
                glm::vec3 g = specularIBLGroundTruth(white, glm::vec3(1.0f), r, N, Vn);
                EXPECT_NEAR(g.x, ab.x + ab.y, qmc1024Tolerance(nov)) << r << " " << nov;
                EXPECT_LE(g.x, 1.0f + 1e-3f);
            }
        }
    }
}

// Pre-filtering a constant environment returns it (weights are normalised; the constants are
// powers of two, so exact up to one rounding: tolerance 1e-6 relative). Roughness 0 returns
// env(R) (tolerance 1e-5). A linear environment 0.5 + 0.5 a.d with a orthogonal to R averages to
// 0.5 if the lobe is centred on R (tolerance 3e-3: QMC asymmetry; a lobe centred elsewhere, e.g.
// on +z, is off by >= 0.1 here); with a = R it decreases with roughness.
TEST(PrefilterEnvMap, ConstantLinearAndMirror) {
    EnvironmentLodFn constant = [](glm::vec3, float) { return glm::vec3(0.25f, 0.5f, 2.0f); };
    std::vector<glm::vec3> dirs = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, glm::normalize(glm::vec3(1, -2, 0.5f)),
                                   glm::normalize(glm::vec3(0.02f, 0.0f, 1.0f))};
    for (const glm::vec3& R : dirs) {
        for (float r : {0.0f, 0.2f, 0.5f, 1.0f}) {
            glm::vec3 c = prefilterEnvMap(constant, r, R);
            EXPECT_NEAR(c.x, 0.25f, 0.25e-6f);
            EXPECT_NEAR(c.y, 0.5f, 0.5e-6f);
            EXPECT_NEAR(c.z, 2.0f, 2e-6f);
        }
        glm::vec3 a = glm::normalize(glm::cross(R, std::fabs(R.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
        EnvironmentLodFn linear = [a](glm::vec3 d, float) { return glm::vec3(0.5f + 0.5f * glm::dot(a, d)); };
        EnvironmentLodFn along = [R](glm::vec3 d, float) { return glm::vec3(0.5f + 0.5f * glm::dot(R, d)); };
        EXPECT_NEAR(prefilterEnvMap(along, 0.0f, R).x, 1.0f, 1e-5f);
        float previous = 1.0f + 1e-5f;
        for (float r : {0.1f, 0.3f, 0.5f, 0.7f, 1.0f}) {
            EXPECT_NEAR(prefilterEnvMap(linear, r, R).x, 0.5f, 3e-3f) << "roughness " << r;
            float v = prefilterEnvMap(along, r, R).x;
            EXPECT_LT(v, previous) << "roughness " << r;
            previous = v;
        }
    }
}

// Filtered importance sampling: constant environment -> constant (tolerance 1e-6 relative);
// lods >= 0; the sample with Xi.y = 0 sits at the lobe centre, pdf = D(1)/4 = 1/(4 pi alpha^2),
// whose lod is computed here by hand (tolerance 1e-4); roughness 0 reads env(R) at lod 0.
TEST(PrefilterEnvMap, FilteredLodPerSample) {
    std::vector<float> lods;
    EnvironmentLodFn recording = [&lods](glm::vec3, float lod) {
        lods.push_back(lod);
        return glm::vec3(0.5f);
    };
    const float face = 256.0f, r = 0.5f;
    const uint32_t n = 32;
    glm::vec3 c = prefilterEnvMapFiltered(recording, r, glm::normalize(glm::vec3(1, 1, 1)), n, face);
    EXPECT_NEAR(c.x, 0.5f, 0.5e-6f);
    ASSERT_FALSE(lods.empty());
    for (float l : lods) EXPECT_GE(l, 0.0f);
    double alpha = 0.25, pdf = 1.0 / (4.0 * kPiD * alpha * alpha);
    double omegaS = 1.0 / (n * pdf), omegaP = 4.0 * kPiD / (6.0 * face * face);
    double centreLod = 0.5 * std::log2(omegaS / omegaP);  // = 4.79
    EXPECT_NEAR(lods.front(), centreLod, 1e-4);
    EXPECT_NEAR(*std::min_element(lods.begin(), lods.end()), centreLod, 1e-4);  // lowest lod at the peak
    lods.clear();
    prefilterEnvMapFiltered(recording, 0.0f, glm::vec3(0, 0, 1), n, face);
    ASSERT_EQ(lods.size(), 1u);
    EXPECT_EQ(lods[0], 0.0f);
}

// lod = 0.5 log2(Os/Op) on hand-made cases: Os = Op -> 0; Os = 4 Op -> 1; Os = Op/4 -> clamped
// to 0; four times the samples -> one level finer. Tolerance 1e-5.
TEST(FilteredImportanceSampling, LodFormula) {
    const float w = 128.0f;
    double omegaP = 4.0 * kPiD / (6.0 * w * w);
    EXPECT_NEAR(filteredSampleLod(float(1.0 / omegaP), 1.0f, w), 0.0f, 1e-5f);
    EXPECT_NEAR(filteredSampleLod(float(1.0 / (4.0 * omegaP)), 1.0f, w), 1.0f, 1e-5f);
    EXPECT_EQ(filteredSampleLod(float(4.0 / omegaP), 1.0f, w), 0.0f);
    float a = filteredSampleLod(0.5f, 16.0f, w), b = filteredSampleLod(0.5f, 64.0f, w);
    EXPECT_NEAR(a - b, 1.0f, 1e-5f);
}

// Linear mip <-> roughness, and inverse of each other (tolerance 1e-6).
TEST(FilteredImportanceSampling, MipRoughnessMapping) {
    EXPECT_EQ(mipFromRoughness(0.0f, 8.0f), 0.0f);
    EXPECT_EQ(mipFromRoughness(1.0f, 8.0f), 7.0f);
    EXPECT_EQ(roughnessFromMip(7.0f, 8.0f), 1.0f);
    EXPECT_EQ(roughnessFromMip(3.0f, 1.0f), 0.0f);
    EXPECT_EQ(mipFromRoughness(0.7f, 1.0f), 0.0f);
    for (float r = 0.0f; r <= 1.0f; r += 0.05f) EXPECT_NEAR(roughnessFromMip(mipFromRoughness(r, 9.0f), 9.0f), r, 1e-6f);
}

// ---------------------------------------------------------------- EnvBRDF and its fits

// The 2% rule: B is scaled by saturate(50 f0.g) (exact arithmetic on these values: tolerance 1e-7).
TEST(EnvBRDF, TwoPercentRule) {
    glm::vec2 AB(0.6f, 0.3f);
    glm::vec3 none = envBRDF(glm::vec3(0.5f, 0.0f, 0.5f), AB);
    EXPECT_NEAR(none.x, 0.3f, 1e-7f);
    EXPECT_NEAR(none.y, 0.0f, 1e-7f);
    glm::vec3 half = envBRDF(glm::vec3(0.01f), AB);
    EXPECT_NEAR(half.x, 0.01f * 0.6f + 0.5f * 0.3f, 1e-7f);
    glm::vec3 full = envBRDF(glm::vec3(0.04f), AB);
    EXPECT_NEAR(full.x, 0.04f * 0.6f + 0.3f, 1e-7f);
    glm::vec3 metal = envBRDF(glm::vec3(1.0f, 0.8f, 0.3f), AB);
    EXPECT_NEAR(metal.z, 0.3f * 0.6f + 0.3f, 1e-7f);
}

// UE4 mobile's EnvBRDFApprox against our LUT over the 64 x 64 grid. Measured:
//   f0 = 0.04: max 0.245 (r 0.086, NoV 0.008), max over NoV >= 0.25: 0.042, rms 0.029
//   f0 = 1   : max 0.332 (r 0.086, NoV 0.008), max over NoV >= 0.25: 0.178, rms 0.079
// The worst case is the smooth grazing corner, where our LUT (k = alpha/2) is near 1 and the
// fit much lower. Asserted: each figure <= 1.05x the measurement and >= 0.95x (so the documented
// numbers stay true). EnvBRDFApproxNonmetal is EnvBRDFApprox(0.04) up to
// 0.0016 (1 - a004) - 0.00088 r (algebra of the constants): tolerance 1.6e-3.
// The fully-rough shortcut: EnvBRDFApprox(f0, 1, NoV) = 0.4524 f0 - 0.0024, so 0.45 f0 is within
// 2.5e-3.
TEST(EnvBRDFApprox, BoundsAgainstLut) {
    ErrorStats s004 = compareWithLut(0.04, [](float r, float nov) { return envBRDFApprox(glm::vec3(0.04f), r, nov).x; });
    ErrorStats s1 = compareWithLut(1.0, [](float r, float nov) { return envBRDFApprox(glm::vec3(1.0f), r, nov).x; });
    printStats("envBRDFApprox f0=0.04", s004);
    printStats("envBRDFApprox f0=1", s1);
    auto within = [](double measured, double documented) {
        EXPECT_LE(measured, 1.05 * documented);
        EXPECT_GE(measured, 0.95 * documented);
    };
    within(s004.maxAbs, 0.245);
    within(s004.maxAbsNoV25, 0.042);
    within(s004.rms, 0.029);
    within(s1.maxAbs, 0.332);
    within(s1.maxAbsNoV25, 0.178);
    within(s1.rms, 0.079);

    for (float r = 0.0f; r <= 1.0f; r += 0.05f) {
        for (float nov = 0.0f; nov <= 1.0f; nov += 0.05f) {
            EXPECT_NEAR(envBRDFApproxNonmetal(r, nov), envBRDFApprox(glm::vec3(0.04f), r, nov).x, 1.6e-3f);
        }
    }
    for (float f0 = 0.0f; f0 <= 1.0f; f0 += 0.1f) {
        for (float nov : {0.0f, 0.5f, 1.0f}) {
            EXPECT_NEAR(envBRDFApprox(glm::vec3(f0), 1.0f, nov).x, 0.45f * f0, 2.5e-3f);
        }
    }
    glm::vec3 diffuse(0.2f, 0.3f, 0.4f), specular(0.9f, 0.5f, 0.04f);
    envBRDFApproxFullyRough(diffuse, specular);
    EXPECT_NEAR(diffuse.x, 0.2f + 0.45f * 0.9f, 1e-6f);
    EXPECT_NEAR(diffuse.z, 0.4f + 0.45f * 0.04f, 1e-6f);
    EXPECT_EQ(specular, glm::vec3(0.0f));
}

// Black Ops 2: the folded EnvironmentBRDF equals saturate(a0r + rf0 (a1vf - a0r)) written from the
// separate fits (tolerance 1e-6: the folded constants round differently).
TEST(BlackOps2, FoldedFormEqualsSeparateFits) {
    for (float g = 0.0f; g <= 1.0f; g += 0.05f) {
        for (float nov = 0.0f; nov <= 1.0f; nov += 0.05f) {
            for (float rf0 : {0.0f, 0.04f, 0.5f, 1.0f}) {
                float a0 = bo2A0r(g, nov), a1 = bo2A1vf(g);
                float expected = std::clamp(a0 + rf0 * (a1 - a0), 0.0f, 1.0f);
                ASSERT_NEAR(environmentBRDF(g, nov, glm::vec3(rf0)).x, expected, 1e-6f) << g << " " << nov << " " << rf0;
            }
            // a004 is the rf0 = 0.04 curve by construction.
            ASSERT_NEAR(environmentBRDF(g, nov, glm::vec3(0.04f)).x, std::clamp(bo2A004(g, nov), 0.0f, 1.0f), 1e-6f);
        }
    }
    // The seed's fits at hand-evaluated points (g = 1, NoV = 0):
    // a0 = (1 - e^-(11.5 * 0.01)) * 1.32 = 0.14340; a1 = min(1 - 2^-(16.11 * 0.025), 1) = 0.24356;
    // a0f = 4.885 * 0.025 * 2 = 0.24425; a1f = 0.4. Tolerance 1e-5.
    EXPECT_NEAR(bo2A0(1.0f, 0.0f), (1.0 - std::exp(-11.5 * 0.01)) * 1.32, 1e-5);
    EXPECT_NEAR(bo2A1(1.0f, 0.0f), 1.0 - std::exp2(-16.11 * 0.025), 1e-5);
    EXPECT_NEAR(bo2A0f(1.0f, 0.0f), 4.885 * 0.025 * 2.0, 1e-5);
    EXPECT_NEAR(bo2A1f(1.0f, 0.0f), 0.4, 1e-6);
}

// Gloss mappings: endpoints, monotonicity, and the choice.
TEST(BlackOps2, GlossMappings) {
    EXPECT_EQ(glossFromRoughnessLinear(0.0f), 1.0f);
    EXPECT_EQ(glossFromRoughnessLinear(1.0f), 0.0f);
    EXPECT_EQ(glossFromRoughnessBlinnPhong(0.0f), 1.0f);
    EXPECT_EQ(glossFromRoughnessBlinnPhong(1.0f), 0.0f);
    // roughness 0.5: alpha^2 = 1/16, n = 30, g = log2(30)/13 = 0.37744 (tolerance 1e-5).
    EXPECT_NEAR(glossFromRoughnessBlinnPhong(0.5f), std::log2(30.0) / 13.0, 1e-5);
    float previous = 2.0f;
    for (float r = 0.0f; r <= 1.0f; r += 0.01f) {
        float g = glossFromRoughnessBlinnPhong(r);
        EXPECT_LE(g, previous);
        EXPECT_GE(g, 0.0f);
        previous = g;
        EXPECT_EQ(bo2GlossFromRoughness(r), g);
    }
}

// Black Ops 2 EnvironmentBRDF against our LUT with both gloss mappings. Measured (64 x 64 grid):
//                                   max     (NoV>=0.25)  rms
//   Blinn-Phong map, f0 = 0.04     0.438    0.030       0.028
//   Blinn-Phong map, f0 = 1        0.435    0.435       0.162
//   g = 1 - r,       f0 = 0.04     0.446    0.041       0.032
//   g = 1 - r,       f0 = 1        0.437    0.437       0.176
// The Blinn-Phong mapping is better on every aggregate, hence the default. The f0 = 1 error is
// structural: a1vf = 0.25 g + 0.75 ignores the energy Smith-Schlick loses at high roughness
// (our A + B is 0.38 at roughness 1, normal incidence). Asserted within 0.95x..1.05x.
TEST(BlackOps2, BoundsAgainstLut) {
    auto check = [](const char* name, float (*gloss)(float), double f0, double mx, double mx25, double rms) {
        ErrorStats s = compareWithLut(f0, [gloss, f0](float r, float nov) {
            return environmentBRDF(gloss(r), nov, glm::vec3(float(f0))).x;
        });
        printStats(name, s);
        EXPECT_LE(s.maxAbs, 1.05 * mx) << name;
        EXPECT_GE(s.maxAbs, 0.95 * mx) << name;
        EXPECT_LE(s.maxAbsNoV25, 1.05 * mx25) << name;
        EXPECT_GE(s.maxAbsNoV25, 0.95 * mx25) << name;
        EXPECT_LE(s.rms, 1.05 * rms) << name;
        EXPECT_GE(s.rms, 0.95 * rms) << name;
        return s;
    };
    ErrorStats bp004 = check("bo2 Blinn-Phong gloss f0=0.04", glossFromRoughnessBlinnPhong, 0.04, 0.438, 0.030, 0.028);
    ErrorStats bp1 = check("bo2 Blinn-Phong gloss f0=1", glossFromRoughnessBlinnPhong, 1.0, 0.435, 0.435, 0.162);
    ErrorStats li004 = check("bo2 1-r gloss f0=0.04", glossFromRoughnessLinear, 0.04, 0.446, 0.041, 0.032);
    ErrorStats li1 = check("bo2 1-r gloss f0=1", glossFromRoughnessLinear, 1.0, 0.437, 0.437, 0.176);
    EXPECT_LT(bp004.rms, li004.rms);
    EXPECT_LT(bp1.rms, li1.rms);
}

// ---------------------------------------------------------------- the CPU LUT image

// Orientation: texel (x, y) is integrateBRDF(roughness = (y+0.5)/size, NoV = (x+0.5)/size)
// bit for bit; the smooth, normal-incidence corner (top right) is ~1 (tolerance 0.01), the
// rough grazing corner (bottom left) is dark. Bilinear lookup returns texels at their centres
// and clamps outside. Bad sizes throw.
TEST(BrdfLut, OrientationAndLookup) {
    const int size = 8, samples = 64;
    gbl::Image lut = computeBrdfLutCpu(size, samples);
    ASSERT_EQ(lut.width, size);
    ASSERT_EQ(lut.height, size);
    ASSERT_EQ(lut.channels, 2);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            glm::vec2 ab = integrateBRDF((y + 0.5f) / size, (x + 0.5f) / size, samples);
            ASSERT_EQ(lut.at(x, y, 0), ab.x);
            ASSERT_EQ(lut.at(x, y, 1), ab.y);
            glm::vec2 s = sampleBrdfLut(lut, (x + 0.5f) / size, (y + 0.5f) / size);
            ASSERT_NEAR(s.x, ab.x, 1e-6f);
            ASSERT_NEAR(s.y, ab.y, 1e-6f);
        }
    }
    EXPECT_NEAR(lut.at(size - 1, 0, 0) + lut.at(size - 1, 0, 1), 1.0f, 0.01f);
    EXPECT_LT(lut.at(0, size - 1, 0) + lut.at(0, size - 1, 1), 0.7f);
    glm::vec2 corner = sampleBrdfLut(lut, 0.0f, 1.0f);
    EXPECT_EQ(corner.x, lut.at(0, size - 1, 0));
    glm::vec2 mid = sampleBrdfLut(lut, 1.0f / size, 0.5f / size);  // half-way between x = 0 and 1, row 0
    EXPECT_NEAR(mid.x, 0.5f * (lut.at(0, 0, 0) + lut.at(1, 0, 0)), 1e-6f);
    EXPECT_THROW(computeBrdfLutCpu(0, 16), std::invalid_argument);
    EXPECT_THROW(computeBrdfLutCpu(4, 0), std::invalid_argument);
}
