// The layered ground truth's CPU twin (iblGroundTruthLayeredMis in src/shading/ibl_layers.h, twin of
// shaders/ibl_layers.glsl) against an independent double-precision quadrature of the layered BRDF
// over a smooth environment, and the layers' sampling routines against their pdfs.
//
// The reference integrand is written here from the specification texts (brdf_layers_test.cpp has
// the same formulas, checked point by point): KHR_materials_clearcoat's mix(material,
// clearcoat_brdf, clearcoat * fresnel(NcoV)) with Appendix B's height-correlated GGX lobe;
// KHR_materials_sheen's Charlie lobe and albedo scaling; KHR_materials_anisotropy's Burley D and
// V_GGX_anisotropic; the ground truth's own base lobe (GGX, Smith-Schlick k = alpha / 2, exact
// Schlick: ibl_math.h). The diffuse's share: what the estimator returns besides the SH9 irradiance,
// -(1 - coat fc) integral L c_diff / pi NoL max(m E(NoV), m E(NoL)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "brdf.h"
#include "brdf_layers.h"
#include "environment_map.h"
#include "ibl_layers.h"
#include "ibl_math.h"
#include "ibl_precompute.h"
#include "image.h"

using namespace gbl::shading;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// A smooth environment, positive everywhere.
glm::dvec3 smoothRadiance(glm::dvec3 d) {
    return {1.0 + 0.5 * d.x + 0.3 * d.y * d.y, 0.8 + 0.2 * d.z + 0.6 * std::max(d.y, 0.0), 1.2 - 0.4 * d.y};
}

// The sheen's E as the estimator is handed it (any function will do: the layering must use it as given).
double testAlbedo(double NoX, double r) { return 0.05 + 0.25 * r * (1.0 - 0.5 * NoX); }

struct Material {
    glm::dvec3 diffuse, f0;
    double roughness;
    Layers ly;
};

// The integrand of the estimator's part (see the file comment) for light from unit direction l.
glm::dvec3 referenceIntegrand(const Material& m, glm::dvec3 N, glm::dvec3 V, glm::dvec3 l) {
    const Layers& ly = m.ly;
    const glm::dvec3 Nc(ly.coatNormal), T(ly.anisotropyT), B(ly.anisotropyB);
    const double NoV = glm::dot(N, V), NoL = glm::dot(N, l);
    const glm::dvec3 h = glm::normalize(V + l);
    const double VoH = glm::dot(V, h);
    const double NcoV = glm::dot(Nc, V);
    const double fc = ly.coat > 0.0f ? ly.coat * (0.04 + 0.96 * std::pow(1.0 - NcoV, 5.0)) : 0.0;
    const double sheenMax = std::max({ly.sheenColor.x, ly.sheenColor.y, ly.sheenColor.z});
    glm::dvec3 out(0.0);
    if (NoL > 0.0) {
        // base specular (the ground truth's lobe, or the anisotropic one)
        const double F0[3] = {m.f0.x, m.f0.y, m.f0.z};
        double lobe = 0.0;
        const double a = m.roughness * m.roughness;
        if (ly.anisotropy > 0.0f) {
            const double s = ly.anisotropy, at = a * (1.0 - s * s) + s * s, ab = a;
            const double q = std::pow(glm::dot(T, h) / at, 2.0) + std::pow(glm::dot(B, h) / ab, 2.0) + std::pow(glm::dot(N, h), 2.0);
            const double D = 1.0 / (kPiD * at * ab * q * q);
            const double gv = NoL * std::sqrt(std::pow(at * glm::dot(T, V), 2.0) + std::pow(ab * glm::dot(B, V), 2.0) + NoV * NoV);
            const double gl = NoV * std::sqrt(std::pow(at * glm::dot(T, l), 2.0) + std::pow(ab * glm::dot(B, l), 2.0) + NoL * NoL);
            lobe = D * std::clamp(0.5 / (gv + gl), 0.0, 1.0) * NoL;
        } else {
            const double a2 = a * a, NoH = glm::dot(N, h), t = NoH * NoH * (a2 - 1.0) + 1.0, k = a / 2.0;
            const double D = a2 / (kPiD * t * t);
            const double G = NoV / (NoV * (1.0 - k) + k) * NoL / (NoL * (1.0 - k) + k);
            lobe = D * G / (4.0 * NoV);
        }
        double scale = 1.0 - fc;
        if (sheenMax > 0.0)
            scale *= std::min(1.0 - sheenMax * testAlbedo(NoV, ly.sheenRoughness), 1.0 - sheenMax * testAlbedo(NoL, ly.sheenRoughness));
        for (int c = 0; c < 3; ++c) out[c] += scale * lobe * (F0[c] + (1.0 - F0[c]) * std::pow(1.0 - VoH, 5.0));
        // sheen and the diffuse's share of its scaling
        if (sheenMax > 0.0) {
            const double r = std::max(double(ly.sheenRoughness), double(kMinSheenRoughness)), ag = r * r;
            const double NoH = glm::dot(N, h);
            const double D = (2.0 + 1.0 / ag) * std::pow(std::max(1.0 - NoH * NoH, 0.0), 0.5 / ag) / (2.0 * kPiD);
            auto lc = [&](double x) {
                const double t = (1.0 - ag) * (1.0 - ag);
                auto mix = [&](double p, double q) { return p * (1.0 - t) + q * t; };
                return mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
                       mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
            };
            auto lambda = [&](double c) { return c < 0.5 ? std::exp(lc(c)) : std::exp(2.0 * lc(0.5) - lc(1.0 - c)); };
            const double Vs = 1.0 / ((1.0 + lambda(NoV) + lambda(NoL)) * (4.0 * NoV * NoL));
            const double cut = std::max(sheenMax * testAlbedo(NoV, ly.sheenRoughness), sheenMax * testAlbedo(NoL, ly.sheenRoughness));
            out += (1.0 - fc) * (glm::dvec3(ly.sheenColor) * D * Vs * NoL - m.diffuse / kPiD * NoL * cut);
        }
    }
    const double NcoL = glm::dot(Nc, l);
    if (ly.coat > 0.0f && NcoL > 0.0) {
        const double a = double(ly.coatRoughness) * ly.coatRoughness, a2 = a * a, NcoH = glm::dot(Nc, h);
        const double t = NcoH * NcoH * (a2 - 1.0) + 1.0, D = a2 / (kPiD * t * t);
        const double G = 2.0 * NcoL * NcoV / (NcoV * std::sqrt(a2 + (1.0 - a2) * NcoL * NcoL) + NcoL * std::sqrt(a2 + (1.0 - a2) * NcoV * NcoV));
        out += glm::dvec3(fc * G * D / (4.0 * NcoL * NcoV) * NcoL);
    }
    return out;
}

// Midpoint quadrature over the sphere in (theta, phi).
glm::dvec3 referenceIntegral(const Material& m, glm::dvec3 N, glm::dvec3 V, int nTheta) {
    glm::dvec3 sum(0.0);
    const int nPhi = 2 * nTheta;
    for (int a = 0; a < nTheta; ++a) {
        const double th = (a + 0.5) * kPiD / nTheta, st = std::sin(th);
        for (int b = 0; b < nPhi; ++b) {
            const double ph = (b + 0.5) * 2.0 * kPiD / nPhi;
            const glm::dvec3 l(st * std::cos(ph), st * std::sin(ph), std::cos(th));
            sum += referenceIntegrand(m, N, V, l) * smoothRadiance(l) * st;
        }
    }
    return sum * (kPiD / nTheta) * (2.0 * kPiD / nPhi);
}

}  // namespace

// Four materials (coat over a rough base; sheen with a diffuse base; an anisotropic base; all three
// together over a tilted coat normal). Each: 32 independent Cranley-Patterson shifts of 1024 steps;
// the mean must land on the quadrature (720 x 1440 nodes, converged to < 1e-4 relative for these
// lobes) within 4 standard errors + 2e-3 relative (the float estimator against double). A wrong
// layering weight, a missing MIS term (double counting the environment samples) or a lost lobe
// moves the mean by far more.
TEST(GroundTruthLayered, MatchesIndependentQuadrature) {
    // The environment sampling table of the smooth radiance, from an equirect image of it.
    gbl::Image equirect(128, 64, 3);
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 128; ++i) {
            const glm::vec3 d = gbl::equirectUvToDirection(glm::vec2((i + 0.5f) / 128.0f, (j + 0.5f) / 64.0f));
            const glm::dvec3 r = smoothRadiance(glm::dvec3(d));
            for (int c = 0; c < 3; ++c) equirect.at(i, j, c) = float(r[c]);
        }
    const std::vector<float> table = gbl::buildEnvironmentSampling(equirect);
    const EnvironmentLodFn env = [](glm::vec3 d, float) { return glm::vec3(smoothRadiance(glm::dvec3(d))); };
    const SheenAlbedoFn albedo = [](float x, float r) { return float(testAlbedo(x, r)); };

    const glm::vec3 N = glm::normalize(glm::vec3(0.2f, 0.3f, 1.0f));
    const glm::vec3 V = glm::normalize(glm::vec3(0.6f, -0.1f, 0.7f));
    const glm::vec3 T = glm::normalize(glm::cross(N, glm::vec3(0.0f, 1.0f, 0.0f)));
    std::vector<std::pair<const char*, Material>> cases;
    {
        Material m{glm::dvec3(0.2, 0.1, 0.05), glm::dvec3(0.04), 0.5, Layers{}};
        m.ly.coat = 0.8f;
        m.ly.coatRoughness = 0.25f;
        m.ly.coatNormal = N;
        cases.push_back({"coat", m});
    }
    {
        Material m{glm::dvec3(0.6, 0.3, 0.2), glm::dvec3(0.04), 0.7, Layers{}};
        m.ly.sheenColor = glm::vec3(0.9f, 0.5f, 0.3f);
        m.ly.sheenRoughness = 0.4f;
        cases.push_back({"sheen", m});
    }
    {
        Material m{glm::dvec3(0.0), glm::dvec3(0.95, 0.64, 0.54), 0.4, Layers{}};
        m.ly.anisotropy = 0.7f;
        m.ly.anisotropyT = T;
        m.ly.anisotropyB = glm::cross(N, T);
        cases.push_back({"anisotropy", m});
    }
    {
        Material m{glm::dvec3(0.3, 0.3, 0.5), glm::dvec3(0.04), 0.45, Layers{}};
        m.ly.coat = 1.0f;
        m.ly.coatRoughness = 0.3f;
        m.ly.coatNormal = glm::normalize(N + glm::vec3(0.1f, -0.05f, 0.0f));
        m.ly.sheenColor = glm::vec3(0.4f, 0.8f, 0.6f);
        m.ly.sheenRoughness = 0.6f;
        m.ly.anisotropy = 0.5f;
        m.ly.anisotropyT = T;
        m.ly.anisotropyB = glm::cross(N, T);
        cases.push_back({"coat + sheen + anisotropy", m});
    }
    for (const auto& [name, m] : cases) {
        const glm::dvec3 ref = referenceIntegral(m, glm::dvec3(N), glm::dvec3(V), 720);
        const int runs = 32;
        std::vector<double> y;
        for (int k = 0; k < runs; ++k) {
            const glm::vec4 a(randomShift(uint32_t(k), 3u, 0u), randomShift(uint32_t(k), 3u, 1u));
            const glm::vec4 b(randomShift(uint32_t(k), 3u, 2u), randomShift(uint32_t(k), 3u, 3u));
            const glm::vec3 e = iblGroundTruthLayeredMis(env, table, albedo, glm::vec3(m.diffuse), glm::vec3(m.f0),
                                                         float(m.roughness), N, V, m.ly, 1024, a, b);
            y.push_back(0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z);
        }
        double mean = 0.0, var = 0.0;
        for (double v : y) mean += v / runs;
        for (double v : y) var += (v - mean) * (v - mean) / (runs - 1);
        const double se = std::sqrt(var / runs);
        const double yr = 0.2126 * ref.x + 0.7152 * ref.y + 0.0722 * ref.z;
        std::printf("  %-26s quadrature %.6f, estimator %.6f +- %.1e (%.2f standard errors)\n", name, yr, mean, se,
                    std::abs(mean - yr) / std::max(se, 1e-12));
        EXPECT_LT(std::abs(mean - yr), 4.0 * se + 2e-3 * std::abs(yr)) << name;
        EXPECT_LT(se, 0.01 * std::abs(yr)) << name << ": too noisy for the comparison to mean anything";
    }
}

// The anisotropic sampler draws H with density D_aniso(H) NoH: the histogram of NoH over 2^18
// samples against the integral of that density per bin (midpoint quadrature). At strength 0 it is
// importanceSampleGGX's lobe. Tolerance: 5 standard errors of a bin count + 2e-3.
TEST(GroundTruthLayered, AnisotropicSamplerFollowsItsPdf) {
    const glm::vec3 N(0.0f, 0.0f, 1.0f), T(1.0f, 0.0f, 0.0f), B(0.0f, 1.0f, 0.0f);
    const float rough = 0.5f, ab = rough * rough, at = anisotropicAlphaT(rough, 0.8f);
    const int bins = 10, n = 1 << 18;
    std::vector<double> hist(bins, 0.0), histTx(bins, 0.0);
    for (int i = 0; i < n; ++i) {
        const glm::vec3 H = importanceSampleGGXAnisotropic(hammersley(uint32_t(i), uint32_t(n)), at, ab, N, T, B);
        hist[std::min(int(H.z * bins), bins - 1)] += 1.0 / n;
        histTx[std::min(int(std::abs(H.x) * bins), bins - 1)] += 1.0 / n;
    }
    // Expected: integral over the bin of D NoH dw, in (cos theta, phi), 400 x 800 per bin.
    std::vector<double> expect(bins, 0.0), expectTx(bins, 0.0);
    const int m = 4000, mp = 800;
    for (int a = 0; a < m; ++a) {
        const double c = (a + 0.5) / m, s = std::sqrt(1.0 - c * c);
        for (int b = 0; b < mp; ++b) {
            const double ph = (b + 0.5) * 2.0 * kPiD / mp;
            const double hx = s * std::cos(ph), hy = s * std::sin(ph);
            const double w = double(dGgxAnisotropic(float(c), float(hx), float(hy), at, ab)) * c * (1.0 / m) * (2.0 * kPiD / mp);
            expect[std::min(int(c * bins), bins - 1)] += w;
            expectTx[std::min(int(std::abs(hx) * bins), bins - 1)] += w;
        }
    }
    for (int k = 0; k < bins; ++k) {
        const double se = std::sqrt(expect[k] * (1.0 - expect[k]) / n), seTx = std::sqrt(expectTx[k] * (1.0 - expectTx[k]) / n);
        EXPECT_NEAR(hist[k], expect[k], 5.0 * se + 2e-3) << "NoH bin " << k;
        EXPECT_NEAR(histTx[k], expectTx[k], 5.0 * seTx + 2e-3) << "|T.H| bin " << k;
    }
    // Strength 0: the isotropic GGX sampler's directions, to float rounding.
    for (int i = 0; i < 64; ++i) {
        const glm::vec2 xi = hammersley(uint32_t(i), 64u);
        const glm::vec3 a = importanceSampleGGXAnisotropic(xi, ab, ab, N, glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(-1.0f, 0.0f, 0.0f));
        const glm::vec3 b = importanceSampleGGX(xi, rough, N);
        EXPECT_NEAR(a.z, b.z, 2e-5) << i;  // the same polar angle (the azimuth's frame differs)
    }
}
