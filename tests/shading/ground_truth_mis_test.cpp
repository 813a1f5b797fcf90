// The converged ground truth's CPU twin (specularIBLGroundTruthMis in src/shading/ibl_math.h, twin of
// shaders/ibl_math.glsl) against an independent double-precision integration of a bright cap.
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

// ---- the converged ground truth's CPU twin (specularIBLGroundTruthMis) against an independent integration ----
namespace {

// An environment with one bright cap: radiance `cap` on the equirect texels whose centre lies within
// `halfAngle` of `axis`, `background` elsewhere (grey).
gbl::Image capEnvironment(int W, glm::dvec3 axis, double halfAngle, float cap, float background) {
    gbl::Image img(W, W / 2, 3, background);
    const double cosCap = std::cos(halfAngle);
    for (int j = 0; j < W / 2; ++j)
        for (int i = 0; i < W; ++i) {
            const glm::vec3 d = gbl::equirectUvToDirection(glm::vec2((i + 0.5f) / W, (j + 0.5f) / (W / 2)));
            if (glm::dot(glm::dvec3(d), axis) >= cosCap)
                for (int c = 0; c < 3; ++c) img.at(i, j, c) = cap;
        }
    return img;
}

// What the estimator reads as mip 0: the texel holding the direction (nearest, no filtering).
glm::vec3 nearestTexel(const gbl::Image& img, glm::vec3 dir) {
    const glm::vec2 uv = gbl::directionToEquirectUv(dir);
    const int i = std::min(int(uv.x * float(img.width)), img.width - 1);
    const int j = std::min(int(uv.y * float(img.height)), img.height - 1);
    return {img.at(i, j, 0), img.at(i, j, 1), img.at(i, j, 2)};
}

// Independent reference, all in double and written here from the formulas (not from ibl_math.cpp):
// the integral of L(l) D G F / (4 NoV NoL) NoL over the sphere (NoL > 0), the environment
// piecewise constant per texel, each texel integrated by an s x s midpoint rule in (phi, theta)
// with d omega = sin(theta) d theta d phi. D: GGX with alpha = r^2; G: Smith-Schlick, k = alpha/2;
// F: exact Schlick. Returns the green channel's f0 weighting for f0 = (f0, f0, f0).
double capReference(const gbl::Image& img, double f0, double roughness, glm::dvec3 N, glm::dvec3 V, int s) {
    const double a = roughness * roughness, a2 = a * a, k = a / 2.0;
    const double NoV = glm::dot(N, V);
    const int W = img.width, H = img.height;
    double sum = 0.0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const double L = img.at(i, j, 1);
            if (L == 0.0) continue;
            for (int sj = 0; sj < s; ++sj) {
                const double v = (j + (sj + 0.5) / s) / H, theta = M_PI * v;
                for (int si = 0; si < s; ++si) {
                    const double u = (i + (si + 0.5) / s) / W, phi = (u - 0.5) * 2.0 * M_PI;
                    const glm::dvec3 l(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
                    const double NoL = glm::dot(N, l);
                    if (NoL <= 0.0) continue;
                    const glm::dvec3 h = glm::normalize(l + V);
                    const double NoH = glm::dot(N, h), VoH = glm::dot(V, h);
                    const double t = NoH * NoH * (a2 - 1.0) + 1.0;
                    const double D = a2 / (M_PI * t * t);
                    const double G = NoV / (NoV * (1.0 - k) + k) * NoL / (NoL * (1.0 - k) + k);
                    const double F = f0 + (1.0 - f0) * std::pow(1.0 - VoH, 5.0);
                    const double dOmega = std::sin(theta) * (M_PI / (H * s)) * (2.0 * M_PI / (W * s));
                    sum += L * D * G * F / (4.0 * NoV) * dOmega;
                }
            }
        }
    return sum;
}

}  // namespace

// specularIBLGroundTruthMis (the CPU twin of the GLSL's converged ground truth) against an
// independent double-precision integration, under a sun-like cap (radiance 2000, half-angle 0.1 rad)
// over a sky of 0.5. Each case: 32 independent Cranley-Patterson shifts of 1024 steps; their mean must
// land on the reference within 4 standard errors + 5e-4 relative (float accumulation and the
// texelised cap's midpoint rule), and the standard error must be small enough (< 1% of the value)
// that the comparison means something. The GGX-only estimator of the seed is printed beside it.
TEST(GroundTruthMis, MatchesIndependentIntegrationOfABrightCap) {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(-0.4, 0.6, 0.5));
    const double halfAngle = 0.1;
    const gbl::Image img = capEnvironment(256, axis, halfAngle, 2000.0f, 0.5f);
    // The cap is what we think it is: its texelised solid angle vs 2 pi (1 - cos 0.1) = 0.03139 sr.
    double capOmega = 0.0;
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i)
            if (img.at(i, j, 0) > 1.0f)
                capOmega += (std::cos(M_PI * j / img.height) - std::cos(M_PI * (j + 1) / img.height)) *
                            (2.0 * M_PI / img.width);
    const double exactOmega = 2.0 * M_PI * (1.0 - std::cos(halfAngle));
    std::printf("  cap: texelised solid angle %.5f sr, exact cap %.5f sr\n", capOmega, exactOmega);
    EXPECT_NEAR(capOmega, exactOmega, 0.1 * exactOmega);

    const std::vector<float> table = gbl::buildEnvironmentSampling(img);
    const EnvironmentLodFn env = [&](glm::vec3 d, float) { return nearestTexel(img, d); };
    struct Case {
        double roughness, f0;
        glm::dvec3 N, V;
        const char* what;
    };
    const glm::dvec3 N = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
    auto mirrorOf = [&](glm::dvec3 l) { return glm::normalize(2.0 * glm::dot(N, l) * N - l); };
    const glm::dvec3 off = glm::normalize(glm::dvec3(-0.1, 0.6, 0.9));  // 0.6 rad from the cap
    const std::vector<Case> cases = {
        {0.2, 1.0, N, mirrorOf(axis), "metal r 0.2, cap in the mirror direction"},
        {0.5, 1.0, N, mirrorOf(axis), "metal r 0.5, cap in the mirror direction"},
        {1.0, 0.04, N, mirrorOf(axis), "dielectric r 1.0, cap in the mirror direction"},
        {0.5, 0.04, N, mirrorOf(off), "dielectric r 0.5, cap 0.6 rad off the mirror direction"},
        {0.3, 1.0, glm::dvec3(0, 1, 0), glm::normalize(glm::dvec3(0.95, 0.3, 0.0)), "metal r 0.3, NoV 0.3"},
    };
    for (size_t c = 0; c < cases.size(); ++c) {
        const Case& k = cases[c];
        const double ref = capReference(img, k.f0, k.roughness, k.N, k.V, 8);
        const int runs = 32;
        const uint32_t steps = 1024;
        double mean = 0.0, m2 = 0.0;
        for (int r = 0; r < runs; ++r) {
            const glm::vec3 est = specularIBLGroundTruthMis(
                env, table, glm::vec3(float(k.f0)), float(k.roughness), glm::vec3(k.N), glm::vec3(k.V), steps,
                randomShift(uint32_t(c), uint32_t(r), 0u), randomShift(uint32_t(c), uint32_t(r), 1u));
            const double x = est.y, d = x - mean;
            mean += d / (r + 1);
            m2 += d * (x - mean);
        }
        const double se = std::sqrt(m2 / (runs - 1) / runs);
        const glm::vec3 ggx = specularIBLGroundTruth(env, glm::vec3(float(k.f0)), float(k.roughness), glm::vec3(k.N),
                                                     glm::vec3(k.V), steps * runs);
        std::printf("  %-55s reference %.5f, MIS %.5f (SE %.5f, %.3f%%), seed GGX-only %u spp %.5f (%+.2f%%)\n",
                    k.what, ref, mean, se, 100.0 * se / ref, steps * runs, ggx.y, 100.0 * (ggx.y - ref) / ref);
        EXPECT_NEAR(mean, ref, 4.0 * se + 5e-4 * ref) << k.what;
        EXPECT_LT(se, 0.01 * ref) << k.what;
    }
}
