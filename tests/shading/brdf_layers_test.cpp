// Tests of the material layers (src/shading/brdf_layers.h, mirror of shaders/brdf_layers.glsl)
// against implementations written here from the specification texts, in double precision:
//   KHR_materials_clearcoat README ("Layering", "Emission"), glTF 2.0 Appendix B (specular_brdf),
//   KHR_materials_sheen README ("Implementation Notes"), KHR_materials_anisotropy README
//   ("Anisotropy": Burley's D in its closed form; "Implementation": V_GGX_anisotropic).
// The layered direct light is assembled here from the README formulas, not from brdf_layers.cpp:
//   coated   = mix(material, clearcoat_brdf, clearcoat * (0.04 + 0.96 (1 - |V.Nc|)^5))
//   sheened  = sheenColor * sheen_brdf + material * min(1 - max3(c) E(NoV), 1 - max3(c) E(NoL))
// with the project's own base (UE4, brdf.h: unchanged by the layers) as `material`.
// Every tolerance is stated beside its assertion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "brdf.h"
#include "brdf_layers.h"

using namespace gbl::shading;

namespace {

constexpr double kPiD = 3.14159265358979323846;

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        glm::vec3 v(n(rng), n(rng), n(rng));
        float l = glm::length(v);
        if (l > 1e-3f) return v / l;
    }
}

// A unit vector within the hemisphere of N, at least `minCos` from its horizon.
glm::vec3 randomAbove(std::mt19937& rng, glm::vec3 N, float minCos) {
    for (;;) {
        glm::vec3 v = randomUnit(rng);
        if (glm::dot(v, N) < 0.0f) v = -v;
        if (glm::dot(v, N) >= minCos) return v;
    }
}

// ---- the specifications, in double ----

// glTF 2.0 Appendix B: D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2).
double specGgxD(double NoH, double alpha) {
    const double a2 = alpha * alpha;
    const double d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPiD * d * d);
}

// glTF 2.0 Appendix B: the height-correlated G = 2 |NL| |NV| / (|NV| sqrt(a^2 + (1-a^2) NL^2) +
// |NL| sqrt(a^2 + (1-a^2) NV^2)), and the BRDF G D / (4 |NL| |NV|).
double specMicrofacetBrdf(double NoH, double NoV, double NoL, double alpha) {
    const double a2 = alpha * alpha;
    const double G = 2.0 * NoL * NoV / (NoV * std::sqrt(a2 + (1.0 - a2) * NoL * NoL) + NoL * std::sqrt(a2 + (1.0 - a2) * NoV * NoV));
    return G * specGgxD(NoH, alpha) / (4.0 * NoL * NoV);
}

// KHR_materials_sheen: the Charlie D, (2 + 1/r) sin^(1/r) / (2 pi), r = sheenRoughness^2.
double specCharlieD(double NoH, double sheenRoughness) {
    const double r = sheenRoughness * sheenRoughness;
    const double sin2 = std::max(1.0 - NoH * NoH, 0.0);
    return (2.0 + 1.0 / r) * std::pow(sin2, 0.5 / r) / (2.0 * kPiD);
}

double specSheenL(double x, double r) {
    const double t = (1.0 - r) * (1.0 - r);
    auto mix = [&](double a, double b) { return a * (1.0 - t) + b * t; };
    return mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
           mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
}

double specSheenLambda(double c, double r) {
    return std::abs(c) < 0.5 ? std::exp(specSheenL(c, r)) : std::exp(2.0 * specSheenL(0.5, r) - specSheenL(1.0 - c, r));
}

double specCharlieV(double NoV, double NoL, double sheenRoughness) {
    const double r = sheenRoughness * sheenRoughness;
    return 1.0 / ((1.0 + specSheenLambda(NoV, r) + specSheenLambda(NoL, r)) * (4.0 * NoV * NoL));
}

// KHR_materials_anisotropy, "Anisotropy": D(h) = 1 / (pi at ab ((h.t)^2/at^2 + (h.b)^2/ab^2 + (h.n)^2)^2).
double specAnisoD(double NoH, double ToH, double BoH, double at, double ab) {
    const double q = ToH * ToH / (at * at) + BoH * BoH / (ab * ab) + NoH * NoH;
    return 1.0 / (kPiD * at * ab * q * q);
}

// KHR_materials_anisotropy, "Implementation": V_GGX_anisotropic (clamped to [0, 1] as written there).
double specAnisoV(double NoL, double NoV, double BoV, double ToV, double ToL, double BoL, double at, double ab) {
    const double gv = NoL * std::sqrt(at * at * ToV * ToV + ab * ab * BoV * BoV + NoV * NoV);
    const double gl = NoV * std::sqrt(at * at * ToL * ToL + ab * ab * BoL * BoL + NoL * NoL);
    return std::clamp(0.5 / (gv + gl), 0.0, 1.0);
}

double relErr(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-30); }

}  // namespace

// The coat's visibility is the specification's height-correlated Smith: V D against Appendix B's
// G D / (4 NL NV) in double. Tolerance 1e-4 relative: float D near the peak cancels in 1 - NoH^2
// (brdf.h: ~1.2e-7 / alpha^2 relative, 7.5e-5 at the smallest roughness here, 0.2; measured 2.4e-5).
TEST(Coat, MicrofacetLobeIsAppendixB) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.02f, 1.0f);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const float r = 0.2f + 0.8f * u(rng), NoV = u(rng), NoL = u(rng), NoH = u(rng);
        const double spec = specMicrofacetBrdf(NoH, NoV, NoL, double(r) * r);
        const double ours = double(coatSpecular(NoH, NoV, NoL, r));
        worst = std::max(worst, relErr(ours, spec));
    }
    EXPECT_LT(worst, 1e-4);
    // The coat's Fresnel is Schlick at ior 1.5 with n.v: 0.04 at normal incidence, 1 at grazing.
    EXPECT_FLOAT_EQ(coatFresnel(1.0f), 0.04f);
    EXPECT_FLOAT_EQ(coatFresnel(0.0f), 1.0f);
    EXPECT_NEAR(coatFresnel(0.5f), 0.04 + 0.96 * std::pow(0.5, 5.0), 1e-7);
}

// Charlie D and V against the README's formulas in double. Tolerance 5e-4 relative for D: float
// pow(sin^2, 1 / (2 alpha_g)) carries the exponent's rounding (alpha_g = r^2, its inverse: a few
// 1e-7 relative of an exponent up to 247) times |ln sin^2| (up to ~10 where D is still above 1e-20),
// ~2.5e-4, and the base's (247 x 6e-8); measured 1.9e-4. 1e-4 for V: exp() of the lambda fit
// (arguments up to ~17) amplifies its rounding by the argument (~2e-6); measured 2.8e-6.
TEST(Sheen, CharlieDistributionAndVisibilityAreTheSpecifications) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double worstD = 0.0, worstV = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const float r = std::max(u(rng), kMinSheenRoughness);
        const float NoH = u(rng), NoV = std::max(u(rng), 1e-3f), NoL = std::max(u(rng), 1e-3f);
        const double d = specCharlieD(NoH, r);
        if (d > 1e-20) worstD = std::max(worstD, relErr(dCharlie(NoH, r), d));
        worstV = std::max(worstV, relErr(visCharlie(NoV, NoL, r), specCharlieV(NoV, NoL, r)));
    }
    std::printf("  Charlie D worst relative error %.2e, V %.2e\n", worstD, worstV);
    EXPECT_LT(worstD, 5e-4);
    EXPECT_LT(worstV, 1e-4);
    // The Charlie distribution is normalised: integral of D (n.h) dw = 1 (Conty & Kulla 2017).
    // Midpoint rule in theta_h, 200k steps; tolerance 1e-3 (float D at the sharpest lobe, r = 0.045).
    for (float r : {0.045f, 0.2f, 0.5f, 1.0f}) {
        const int steps = 200000;
        double sum = 0.0;
        for (int k = 0; k < steps; ++k) {
            const double t = (k + 0.5) * 0.5 * kPiD / steps;
            sum += double(dCharlie(float(std::cos(t)), r)) * std::cos(t) * std::sin(t);
        }
        EXPECT_NEAR(2.0 * kPiD * sum * 0.5 * kPiD / steps, 1.0, 1e-3) << "sheen roughness " << r;
    }
}

// Burley's anisotropic D in the specification's sample-implementation form equals its closed form,
// reduces to GGX at strength 0, and stays normalised (integral of D (n.h) dw = 1) at every
// strength: a wrong stretch (alpha_t for alpha_b, or a missing square) fails each.
TEST(Anisotropy, DistributionIsBurleysAndNormalised) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 h = randomUnit(rng);
        h.z = std::abs(h.z);
        const float rough = 0.1f + 0.9f * std::abs(u(rng)), s = std::abs(u(rng));
        const float ab = rough * rough, at = anisotropicAlphaT(rough, s);
        EXPECT_NEAR(at, ab * (1.0 - s * s) + s * s, 1e-6);  // mix(alpha, 1, strength^2)
        worst = std::max(worst, relErr(dGgxAnisotropic(h.z, h.x, h.y, at, ab), specAnisoD(h.z, h.x, h.y, at, ab)));
        // At strength 0 it is GGX: dGgx's float 1 - NoH^2 cancels near the peak (~1.2e-7 / alpha^2
        // relative, brdf.h), Burley's form does not; both against the double closed form.
        const double isoRef = specAnisoD(h.z, h.x, h.y, double(rough) * rough, double(rough) * rough);
        EXPECT_LT(relErr(dGgxAnisotropic(h.z, h.x, h.y, ab, ab), isoRef), 1e-5);
        EXPECT_LT(relErr(dGgx(h.z, rough), isoRef), 5e-7 / (double(ab) * ab) + 1e-5);  // measured 3.0e-7 / alpha^2
    }
    EXPECT_LT(worst, 1e-5);  // float against double, no cancellation in either form
    for (float s : {0.0f, 0.5f, 1.0f}) {
        const float rough = 0.3f, ab = rough * rough, at = anisotropicAlphaT(rough, s);
        // Integral over the hemisphere, midpoint in (cos theta, phi): 2000 x 2000.
        const int n = 2000;
        double sum = 0.0;
        for (int a = 0; a < n; ++a) {
            const double c = (a + 0.5) / n, sn = std::sqrt(1.0 - c * c);
            for (int b = 0; b < n; ++b) {
                const double phi = (b + 0.5) * 2.0 * kPiD / n;
                sum += double(dGgxAnisotropic(float(c), float(sn * std::cos(phi)), float(sn * std::sin(phi)), at, ab)) * c;
            }
        }
        EXPECT_NEAR(sum * (1.0 / n) * (2.0 * kPiD / n), 1.0, 2e-3) << "strength " << s;  // quadrature at the peak
    }
}

// The anisotropic direct light against the specification's BRDF_specularAnisotropicGGX assembled
// here (F with the base's Fresnel mode: Schlick here), and its visibility against the README's.
// Tolerance 1e-4 relative (float against double; the D peak at roughness 0.2 as above).
TEST(Anisotropy, DirectLightIsTheSpecificationsLobe) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double worst = 0.0;
    for (int i = 0; i < 5000; ++i) {
        const glm::vec3 N = randomUnit(rng);
        glm::vec3 T = glm::normalize(glm::cross(N, randomUnit(rng)));
        const glm::vec3 B = glm::cross(N, T);
        const glm::vec3 V = randomAbove(rng, N, 0.05f), L = randomAbove(rng, N, 0.05f);
        const float rough = 0.2f + 0.8f * u(rng), s = u(rng);
        const glm::vec3 f0(0.04f + 0.9f * u(rng), 0.5f, 0.9f), cd(0.3f, 0.2f, 0.1f);
        const glm::vec3 ours = evaluateDirectLightAnisotropicMode(N, V, L, T, B, s, cd, f0, rough, glm::vec3(1.0f),
                                                                  FRESNEL_SCHLICK);
        const glm::dvec3 Hd = glm::normalize(glm::dvec3(V) + glm::dvec3(L));
        const double NoL = glm::dot(glm::dvec3(N), glm::dvec3(L)), NoV = glm::dot(glm::dvec3(N), glm::dvec3(V));
        const double ab = double(rough) * rough, at = ab * (1.0 - double(s) * s) + double(s) * s;
        const double D = specAnisoD(glm::dot(glm::dvec3(N), Hd), glm::dot(glm::dvec3(T), Hd), glm::dot(glm::dvec3(B), Hd), at, ab);
        const double Vis = specAnisoV(NoL, NoV, glm::dot(glm::dvec3(B), glm::dvec3(V)), glm::dot(glm::dvec3(T), glm::dvec3(V)),
                                      glm::dot(glm::dvec3(T), glm::dvec3(L)), glm::dot(glm::dvec3(B), glm::dvec3(L)), at, ab);
        const double VoH = glm::dot(glm::dvec3(V), Hd);
        for (int c = 0; c < 3; ++c) {
            const double F = f0[c] + (1.0 - f0[c]) * std::pow(1.0 - VoH, 5.0);
            const double ref = (cd[c] / kPiD + D * Vis * F) * NoL;
            worst = std::max(worst, relErr(ours[c], ref));
        }
    }
    std::printf("  anisotropic direct light: worst relative error %.2e\n", worst);
    EXPECT_LT(worst, 1e-4);
}

// The layered direct light: coat over sheen over base, assembled from the README formulas. The
// base is brdf.h's UE4 (or anisotropic) light, which the layers leave as it is; E(NoV), E(NoL)
// are inputs (arbitrary values here: the layering must use them as given). Tolerance 6e-4 relative
// (float against double: the Charlie D's bound above, 5e-4, plus the base's; measured 3.9e-4).
TEST(Layers, DirectLightIsTheSpecificationsLayering) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double worst = 0.0;
    for (int i = 0; i < 5000; ++i) {
        const glm::vec3 N = randomUnit(rng);
        const glm::vec3 V = randomAbove(rng, N, 0.05f), L = randomAbove(rng, N, 0.05f);
        const glm::vec3 Nc = glm::normalize(N + 0.3f * randomUnit(rng));
        Layers ly;
        ly.coat = i % 3 == 0 ? 0.0f : u(rng);
        ly.coatRoughness = 0.05f + 0.9f * u(rng);
        ly.coatNormal = Nc;
        ly.sheenColor = i % 5 == 0 ? glm::vec3(0.0f) : glm::vec3(u(rng), u(rng), u(rng));
        ly.sheenRoughness = 0.1f + 0.9f * u(rng);
        const float EV = 0.3f * u(rng), EL = 0.3f * u(rng);
        const glm::vec3 cd(0.5f, 0.3f, 0.2f), f0(0.04f);
        const float rough = 0.1f + 0.9f * u(rng);
        const glm::vec3 E(2.0f, 1.5f, 1.0f);
        const glm::vec3 ours = evaluateDirectLightLayeredMode(N, V, L, cd, f0, rough, ly, EV, EL, E, FRESNEL_KARIS);
        // material: the UE4 base (brdf.h), per unit radiance, as BRDF * NoL.
        const glm::dvec3 material = glm::dvec3(evaluateDirectLightMode(N, V, L, cd, f0, rough, glm::vec3(1.0f), FRESNEL_KARIS));
        const glm::dvec3 Hd = glm::normalize(glm::dvec3(V) + glm::dvec3(L));
        glm::dvec3 out = material;
        const double m = std::max({ly.sheenColor.x, ly.sheenColor.y, ly.sheenColor.z});
        if (m > 0.0) {
            const double NoL = glm::dot(glm::dvec3(N), glm::dvec3(L)), NoV = glm::dot(glm::dvec3(N), glm::dvec3(V));
            const double sr = std::max(double(ly.sheenRoughness), double(kMinSheenRoughness));
            const double sheenBrdf = specCharlieD(glm::dot(glm::dvec3(N), Hd), sr) * specCharlieV(NoV, NoL, sr);
            out = glm::dvec3(ly.sheenColor) * sheenBrdf * NoL + material * std::min(1.0 - m * EV, 1.0 - m * EL);
        }
        if (ly.coat > 0.0f) {
            // |V.Nc| (the README's abs(VdotNc)), also in Appendix B's |N.V|.
            const double NcoV = std::abs(glm::dot(glm::dvec3(Nc), glm::dvec3(V))), NcoL = glm::dot(glm::dvec3(Nc), glm::dvec3(L));
            const double weight = ly.coat * (0.04 + 0.96 * std::pow(1.0 - NcoV, 5.0));
            const double cr = std::max(double(ly.coatRoughness), double(kMinDirectRoughness));
            const double coatBrdf =
                NcoL > 0.0 ? specMicrofacetBrdf(glm::dot(glm::dvec3(Nc), Hd), NcoV, NcoL, cr * cr) * NcoL : 0.0;
            out = out * (1.0 - weight) + glm::dvec3(weight * coatBrdf);  // mix(material, clearcoat_brdf, weight)
        }
        out *= glm::dvec3(E);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(ours[c] - out[c]) / std::max(std::abs(out[c]), 1e-3));
    }
    std::printf("  layered direct light: worst relative error %.2e\n", worst);
    EXPECT_LT(worst, 6e-4);
}

// Without layers the layered light is the base light, bit for bit (what keeps a scene without
// layers rendering as before where a layered scene's pass meets a pixel without layers).
TEST(Layers, NoLayerIsTheBaseBitForBit) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 N = randomUnit(rng), V = randomAbove(rng, N, 0.0f), L = randomUnit(rng);
        const glm::vec3 cd(u(rng), u(rng), u(rng)), f0(u(rng), u(rng), u(rng));
        const float r = u(rng);
        const glm::vec3 E(3.0f * u(rng));
        const glm::vec3 base = evaluateDirectLightMode(N, V, L, cd, f0, r, E, FRESNEL_KARIS);
        const glm::vec3 layered = evaluateDirectLightLayeredMode(N, V, L, cd, f0, r, Layers{}, 0.7f, 0.2f, E, FRESNEL_KARIS);
        EXPECT_EQ(std::memcmp(&base, &layered, sizeof(base)), 0) << i;
        const glm::vec3 emission(u(rng), 2.0f, 0.5f), coated = coatedEmission(emission, Layers{}, V);
        EXPECT_EQ(std::memcmp(&emission, &coated, sizeof(emission)), 0);
    }
}

// [Coat] "Emission": emission * (1 - clearcoat * fresnel(NcoV)): 4% less at normal incidence
// under a full coat, all of it at grazing.
TEST(Coat, EmissionIsDarkenedByTheCoatsFresnel) {
    Layers ly;
    ly.coat = 1.0f;
    ly.coatNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 e(1.0f, 2.0f, 4.0f);
    const glm::vec3 head = coatedEmission(e, ly, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(head.y, 2.0f * 0.96f, 1e-6);
    const glm::vec3 grazing = coatedEmission(e, ly, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_NEAR(grazing.z, 0.0f, 1e-6);
    ly.coat = 0.5f;
    const glm::vec3 half = coatedEmission(e, ly, glm::vec3(0.6f, 0.0f, 0.8f));
    EXPECT_NEAR(half.x, 1.0 - 0.5 * (0.04 + 0.96 * std::pow(0.2, 5.0)), 1e-6);
}

// The coat's share of the layered light is its Fresnel weight times its own lobe, whose albedo
// (integral of D V NcoL over the hemisphere of directional lights, quadrature) is at most 1: what
// the layered light adds over (1 - weight) x the base is in (0.8, 1] x weight at coat roughness 0.3
// (height-correlated Smith loses ~5 % there). A layering that adds the coat without darkening
// the base (or darkens it by the wrong weight) leaves the base's ~1.0 albedo in the difference
// and fails the upper bound.
TEST(Coat, LayeringAddsAtMostTheCoatsWeight) {
    const glm::vec3 N(0.0f, 0.0f, 1.0f);
    for (float NoV : {0.2f, 0.6f, 1.0f}) {
        const glm::vec3 V(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
        Layers ly;
        ly.coat = 1.0f;
        ly.coatRoughness = 0.3f;
        ly.coatNormal = N;
        const double weight = ly.coat * coatFresnel(NoV);
        const int n = 400;
        double coated = 0.0, bare = 0.0;
        for (int a = 0; a < n; ++a) {
            const double c = (a + 0.5) / n, s = std::sqrt(1.0 - c * c);
            for (int b = 0; b < n; ++b) {
                const double phi = (b + 0.5) * 2.0 * kPiD / n;
                const glm::vec3 L(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c));
                coated += evaluateDirectLightLayeredMode(N, V, L, glm::vec3(1.0f), glm::vec3(0.0f), 1.0f, ly, 0, 0,
                                                         glm::vec3(1.0f), FRESNEL_SCHLICK).x;
                bare += evaluateDirectLightMode(N, V, L, glm::vec3(1.0f), glm::vec3(0.0f), 1.0f, glm::vec3(1.0f),
                                                FRESNEL_SCHLICK).x;
            }
        }
        const double dw = (1.0 / n) * (2.0 * kPiD / n);
        const double added = (coated - (1.0 - weight) * bare) * dw;
        EXPECT_GT(bare * dw, 0.99) << "NoV " << NoV;  // Lambert white, plus the base's Fresnel
        EXPECT_LE(added, weight * (1.0 + 1e-3)) << "NoV " << NoV;
        EXPECT_GT(added, 0.8 * weight) << "NoV " << NoV;
    }
}
