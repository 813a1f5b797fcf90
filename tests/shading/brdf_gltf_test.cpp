// Tests of the direct-light BRDF_GLTF (src/shading/brdf.h evaluateDirectLightGltf, brdf_layers.h
// evaluateDirectLightLayeredGltf; mirrors of shaders/brdf.glsl and brdf_layers.glsl) against an
// implementation written here, in double precision, from the specification text alone:
//   glTF 2.0 Specification, Appendix B "BRDF Implementation" (specification/2.0/Specification.adoc):
//     D   = alpha^2 chi+(N.H) / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2)
//     Vis = chi+(H.L) chi+(H.V) / (2 (|N.V| sqrt(alpha^2 + (1 - alpha^2)(N.L)^2)
//                                   + |N.L| sqrt(alpha^2 + (1 - alpha^2)(N.V)^2)))
//     fresnel_w = (1 - |V.H|)^5
//     dielectric_brdf = mix(baseColor / pi, Vis D, 0.04 + 0.96 fresnel_w)
//     metal_brdf = Vis D (baseColor + (1 - baseColor) fresnel_w)
//     material = mix(dielectric_brdf, metal_brdf, metallic),  alpha = roughness^2
//   KHR_lights_punctual README, "Range Property": clamp(1 - (d / range)^4, 0, 1) / d^2.
//   KHR_materials_clearcoat README, "Layering": mix(material, clearcoat_brdf, clearcoat fr(N_c.V)).
// The radiance from a light of intensity E at the point is material E (N.L) (the rendering
// equation with a delta light). Every tolerance is stated beside its assertion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "brdf.h"
#include "brdf_layers.h"

using namespace gbl::shading;

namespace {

constexpr double kPiD = 3.14159265358979323846;
using dvec3 = glm::dvec3;

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        glm::vec3 v(n(rng), n(rng), n(rng));
        float l = glm::length(v);
        if (l > 1e-3f) return v / l;
    }
}

glm::vec3 randomAbove(std::mt19937& rng, glm::vec3 N, float minCos) {
    for (;;) {
        glm::vec3 v = randomUnit(rng);
        if (glm::dot(v, N) < 0.0f) v = -v;
        if (glm::dot(v, N) >= minCos) return v;
    }
}

double chi(double x) { return x > 0.0 ? 1.0 : 0.0; }

// Appendix B's specular_brdf(alpha) = Vis D.
double specularBrdfSpec(dvec3 N, dvec3 V, dvec3 L, double alpha) {
    const dvec3 H = glm::normalize(L + V);
    const double NoH = glm::dot(N, H), NoL = glm::dot(N, L), NoV = glm::dot(N, V);
    const double a2 = alpha * alpha;
    const double D = a2 * chi(NoH) / (kPiD * std::pow(NoH * NoH * (a2 - 1.0) + 1.0, 2.0));
    const double Vis = chi(glm::dot(H, L)) * chi(glm::dot(H, V)) /
                       (2.0 * (std::abs(NoV) * std::sqrt(a2 + (1.0 - a2) * NoL * NoL) +
                               std::abs(NoL) * std::sqrt(a2 + (1.0 - a2) * NoV * NoV)));
    return Vis * D;
}

// Appendix B's material, times E (N.L).
dvec3 materialRadianceSpec(dvec3 N, dvec3 V, dvec3 L, dvec3 base, double metallic, double roughness, dvec3 E) {
    const dvec3 H = glm::normalize(L + V);
    const double w = std::pow(1.0 - std::abs(glm::dot(V, H)), 5.0);
    const double spec = specularBrdfSpec(N, V, L, roughness * roughness);
    const dvec3 diffuse = base / kPiD;
    const double fd = 0.04 + 0.96 * w;
    const dvec3 dielectric = diffuse * (1.0 - fd) + dvec3(spec * fd);
    const dvec3 metal = spec * (base + (dvec3(1.0) - base) * w);
    const dvec3 material = dielectric * (1.0 - metallic) + metal * metallic;
    return material * E * glm::dot(N, L);
}

double maxRel(dvec3 a, dvec3 b) {
    double m = 0.0;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), 1e-6));
    return m;
}

// 20,000 random materials and directions (N.L, N.V >= 0.05, roughness in [0.2, 1]). Tolerance 2e-4
// relative per channel: float against double, dominated by D's cancellation near N.H = 1
// (~1.2e-7 / alpha^2 = 7.5e-5 at roughness 0.2; brdf.h).
TEST(BrdfGltf, DirectLightIsAppendixB) {
    std::mt19937 rng(45);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k) {
        const glm::vec3 N = randomUnit(rng);
        const glm::vec3 V = randomAbove(rng, N, 0.05f), L = randomAbove(rng, N, 0.05f);
        const glm::vec3 base(u(rng), u(rng), u(rng));
        const float metallic = k % 3 == 0 ? 0.0f : k % 3 == 1 ? 1.0f : u(rng);
        const float roughness = 0.2f + 0.8f * u(rng);
        const glm::vec3 E(2.0f, 1.5f, 0.5f);
        const glm::vec3 diffuseColor = base * (1.0f - metallic);
        const glm::vec3 specularColor = glm::mix(glm::vec3(0.04f), base, metallic);
        const glm::vec3 got = evaluateDirectLightGltf(N, V, L, diffuseColor, specularColor, 0.04f, roughness, E);
        const dvec3 want = materialRadianceSpec(N, V, L, base, metallic, roughness, E);
        const double rel = maxRel(dvec3(got), want);
        worst = std::max(worst, rel);
        ASSERT_LT(rel, 2e-4) << "case " << k << " roughness " << roughness << " metallic " << metallic;
    }
    std::printf("  worst relative difference against Appendix B: %.2e\n", worst);
}

// Below the horizon the light contributes nothing (chi+ and N.L clamped), under both BRDFs.
TEST(BrdfGltf, NoLightFromBelowTheHorizon) {
    const glm::vec3 N(0, 0, 1), V = glm::normalize(glm::vec3(0.3f, 0, 1)), L = glm::normalize(glm::vec3(0.2f, 0.1f, -0.5f));
    EXPECT_EQ(evaluateDirectLightGltf(N, V, L, glm::vec3(0.5f), glm::vec3(0.04f), 0.04f, 0.5f, glm::vec3(1.0f)),
              glm::vec3(0.0f));
}

// The choice changes the function: at roughness 0.5 and grazing angles UE4's Smith-Schlick with
// k = (r + 1)^2 / 8 and its undamped Lambert differ from Appendix B by far more than rounding (so a
// render with --brdf gltf that came out as ue4 would fail here). A metal at N.V = N.L = 0.2, mirror
// configuration: G1 Schlick(k = 0.28125) = 0.2 / (0.2 * 0.71875 + 0.28125) = 0.4706 per direction against
// the height-correlated 0.5 / (2 * 0.2 sqrt(0.0625 + 0.9375 * 0.04)) * 4 * 0.04 = 0.632 for both.
TEST(BrdfGltf, DiffersFromTheUe4Choice) {
    const glm::vec3 N(0, 0, 1);
    const float s = std::sqrt(1.0f - 0.04f);
    const glm::vec3 V(s, 0, 0.2f), L(-s, 0, 0.2f);
    const glm::vec3 f0(0.9f, 0.6f, 0.5f);
    const glm::vec3 gltf = evaluateDirectLightGltf(N, V, L, glm::vec3(0.0f), f0, 0.04f, 0.5f, glm::vec3(1.0f));
    const glm::vec3 ue4 = evaluateDirectLightMode(N, V, L, glm::vec3(0.0f), f0, 0.5f, glm::vec3(1.0f), FRESNEL_SCHLICK);
    // Same D and F: the ratio is the visibilities' ratio, 0.4706^2 / 0.632 = 0.350.
    const double ratio = double(ue4.x) / double(gltf.x);
    const double g1 = 0.2 / (0.2 * (1.0 - 0.28125) + 0.28125);
    const double a2 = 0.0625;
    const double g2 = 4.0 * 0.2 * 0.2 * 0.5 / (2.0 * 0.2 * std::sqrt(a2 + (1.0 - a2) * 0.04));
    EXPECT_NEAR(ratio, g1 * g1 / g2, 1e-4);
    EXPECT_LT(ratio, 0.5);
}

// KHR_lights_punctual's range window: the README's under BRDF_GLTF, its square under BRDF_UE4
// ([Karis13] eq. 9); 1 without a range. Tolerance 1e-6 absolute (float).
TEST(BrdfGltf, RangeWindowIsTheReadmes) {
    for (double d : {0.1, 0.5, 0.9, 0.99, 1.0, 1.5}) {
        const double range = 1.0;
        const double spec = std::clamp(1.0 - std::pow(d / range, 4.0), 0.0, 1.0);
        EXPECT_NEAR(lightRangeWindow(float(d * d), float(range), BRDF_GLTF), spec, 1e-6) << d;
        EXPECT_NEAR(lightRangeWindow(float(d * d), float(range), BRDF_UE4), spec * spec, 1e-6) << d;
        EXPECT_EQ(lightRangeWindow(float(d * d), 0.0f, BRDF_GLTF), 1.0f);
    }
}

// Without layers the layered function is the base, bit for bit; with a coat it is the README's
// mix(material, clearcoat_brdf, clearcoat (0.04 + 0.96 (1 - N_c.V)^5)) over Appendix B's material,
// clearcoat_brdf = specular_brdf(N_c, clearcoatRoughness^2) (N_c.L). 5,000 cases, tolerance 2e-4
// relative as above (coat roughness >= 0.2).
TEST(BrdfGltf, CoatLayeringIsTheReadmes) {
    std::mt19937 rng(451);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < 5000; ++k) {
        const glm::vec3 N = randomUnit(rng);
        const glm::vec3 V = randomAbove(rng, N, 0.1f), L = randomAbove(rng, N, 0.1f);
        const glm::vec3 base(u(rng), u(rng), u(rng));
        const float metallic = u(rng), roughness = 0.2f + 0.8f * u(rng);
        const glm::vec3 diffuseColor = base * (1.0f - metallic);
        const glm::vec3 specularColor = glm::mix(glm::vec3(0.04f), base, metallic);
        Layers none;
        none.coatNormal = N;
        const glm::vec3 plain = evaluateDirectLightGltf(N, V, L, diffuseColor, specularColor, 0.04f, roughness, glm::vec3(1.0f));
        ASSERT_EQ(evaluateDirectLightLayeredGltf(N, V, L, diffuseColor, specularColor, 0.04f, roughness, none, 0.0f, 0.0f,
                                                 glm::vec3(1.0f)),
                  plain);
        Layers ly;
        ly.coat = u(rng);
        ly.coatRoughness = 0.2f + 0.8f * u(rng);
        ly.coatNormal = N;  // the coat normal map's tilt is tested in brdf_layers_test
        const glm::vec3 got = evaluateDirectLightLayeredGltf(N, V, L, diffuseColor, specularColor, 0.04f, roughness, ly,
                                                             0.0f, 0.0f, glm::vec3(1.0f));
        const dvec3 material = materialRadianceSpec(N, V, L, base, metallic, roughness, dvec3(1.0));
        const double NcoV = glm::dot(dvec3(N), dvec3(V));
        const double fr = 0.04 + 0.96 * std::pow(1.0 - NcoV, 5.0);
        const double coat = specularBrdfSpec(N, V, L, double(ly.coatRoughness) * ly.coatRoughness) * glm::dot(dvec3(N), dvec3(L));
        const dvec3 want = material * (1.0 - ly.coat * fr) + dvec3(ly.coat * fr * coat);
        ASSERT_LT(maxRel(dvec3(got), want), 2e-4) << "case " << k;
    }
}

}  // namespace
