// Tests of the BRDF terms (src/shading/brdf.h, mirror of shaders/brdf.glsl). Every tolerance is stated
// next to its assertion, with why it is that size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include "brdf.h"
#include "ibl_math.h"

using namespace gbl::shading;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Integral over the hemisphere of D(h) (n.h) dw = 2 pi int_0^{pi/2} D(cos t) cos t sin t dt,
// midpoint rule in t, accumulated in double.
double integrateProjectedGgx(float roughness, int steps) {
    double dt = 0.5 * kPiD / steps;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        double t = (i + 0.5) * dt;
        double c = std::cos(t);
        sum += double(dGgx(float(c), roughness)) * c * std::sin(t);
    }
    return 2.0 * kPiD * sum * dt;
}

// Independent double-precision evaluation of the direct-light model, written from the
// formulas in DIGEST.md section 1 (not from brdf.cpp).
glm::dvec3 referenceDirectLight(glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, glm::dvec3 cdiff, glm::dvec3 f0,
                                double roughness, glm::dvec3 radiance, int fresnelMode) {
    double NoL = std::clamp(glm::dot(N, L), 0.0, 1.0);
    if (NoL <= 0.0) return glm::dvec3(0.0);
    double NoV = std::clamp(glm::dot(N, V), 0.0, 1.0);
    glm::dvec3 H = glm::normalize(V + L);
    double NoH = std::clamp(glm::dot(N, H), 0.0, 1.0);
    double VoH = std::clamp(glm::dot(V, H), 0.0, 1.0);
    double r = std::max(roughness, double(kMinDirectRoughness));
    double alpha = r * r;
    double a2 = alpha * alpha;
    double D = a2 / (kPiD * std::pow(NoH * NoH * (a2 - 1.0) + 1.0, 2.0));
    double k = (r + 1.0) * (r + 1.0) / 8.0;
    double G = (NoL / (NoL * (1.0 - k) + k)) * (NoV / (NoV * (1.0 - k) + k));
    double w = 0.0;
    if (fresnelMode == FRESNEL_SCHLICK) w = std::pow(1.0 - VoH, 5.0);
    if (fresnelMode == FRESNEL_KARIS) w = std::pow(2.0, (-5.55473 * VoH - 6.98316) * VoH);
    if (fresnelMode == FRESNEL_SEED) w = std::pow(2.0, -9.60232 * std::pow(VoH, 8.0) - 8.58092 * VoH);
    glm::dvec3 F = f0 + (1.0 - f0) * w;
    glm::dvec3 spec = D * F * G / (4.0 * NoL * NoV);  // callers keep NoV > 0
    return (cdiff / kPiD + spec) * radiance * NoL;
}

glm::dvec3 toD(glm::vec3 v) { return glm::dvec3(v); }

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        glm::vec3 v(n(rng), n(rng), n(rng));
        float l = glm::length(v);
        if (l > 1e-3f) return v / l;
    }
}

std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

// GGX is normalised: int D(h) (n.h) dw = 1 [Walter07 eq. 4]. Tolerance 1e-3: the quadrature
// (400k midpoints, step 3.9e-6 rad, 250x finer than the alpha = 0.01 lobe) is exact to ~1e-9;
// what remains is float D, whose 1 - NoH^2 cancels: ~6e-8 / alpha^2 relative near the peak
// (6e-4 at roughness 0.1; measured -2.3e-4 there, < 2e-5 from roughness 0.2 up).
TEST(Ggx, ProjectedIntegralIsOne) {
    for (float r : {0.1f, 0.2f, 0.35f, 0.5f, 0.75f, 1.0f}) {
        double integral = integrateProjectedGgx(r, 400000);
        std::printf("int D (n.h) dw at roughness %.2f: 1 %+.2e\n", r, integral - 1.0);
        EXPECT_NEAR(integral, 1.0, 1e-3) << "roughness " << r;
    }
}

// Point values tie alpha = roughness^2 down (normalisation alone would accept alpha = roughness).
// Tolerance: 2e-6 relative for a handful of float operations, plus the cancellation in
// d = NoH^2 (alpha^2 - 1) + 1 at NoH = 1: (alpha^2 - 1) rounds by up to 6e-8 absolute, i.e.
// 6e-8 / alpha^2 relative in d, doubled by d^2 (7.5e-5 at roughness 0.2).
TEST(Ggx, PointValuesUseAlphaEqualsRoughnessSquared) {
    for (float r : {0.2f, 0.5f, 0.9f}) {
        double alpha = double(r) * r, a2 = alpha * alpha;
        double peak = 1.0 / (kPiD * a2);
        EXPECT_NEAR(dGgx(1.0f, r), peak, (2e-6 + 1.2e-7 / a2) * peak) << r;
        EXPECT_NEAR(dGgx(0.0f, r), a2 / kPiD, 2e-6 * a2 / kPiD) << r;
    }
    // Roughness 0.5, NoH = cos 30 deg, by hand: alpha = 0.25, a2 = 0.0625,
    // d = 0.75 * (0.0625 - 1) + 1 = 0.296875, D = a2 / (pi d^2) = 0.225727.
    double expected = 0.0625 / (kPiD * 0.296875 * 0.296875);
    EXPECT_NEAR(dGgx(float(std::sqrt(0.75)), 0.5f), expected, 2e-6 * expected);
}

// k per path and Smith-Schlick G. Tolerance 1e-6 (exact or one rounding).
TEST(SmithSchlick, KPerPathAndG) {
    EXPECT_FLOAT_EQ(kSmithSchlickAnalytic(0.0f), 0.125f);  // (0+1)^2/8
    EXPECT_FLOAT_EQ(kSmithSchlickAnalytic(1.0f), 0.5f);    // (1+1)^2/8
    EXPECT_FLOAT_EQ(kSmithSchlickIbl(1.0f), 0.5f);         // alpha/2 = 1/2
    EXPECT_FLOAT_EQ(kSmithSchlickIbl(0.5f), 0.125f);       // 0.25/2
    EXPECT_FLOAT_EQ(kSmithSchlickIbl(0.0f), 0.0f);
    for (float r : {0.0f, 0.3f, 0.7f, 1.0f}) {
        for (float nv : {0.01f, 0.2f, 0.5f, 1.0f}) {
            for (float nl : {0.01f, 0.4f, 1.0f}) {
                double ka = (r + 1.0) * (r + 1.0) / 8.0, ki = double(r) * r / 2.0;
                auto g = [](double n, double k) { return n / (n * (1.0 - k) + k); };
                EXPECT_NEAR(gSmithSchlickAnalytic(r, nv, nl), g(nv, ka) * g(nl, ka), 1e-6);
                EXPECT_NEAR(gSmithSchlickIbl(r, nv, nl), g(nv, ki) * g(nl, ki), 1e-6);
                float G = gSmithSchlickAnalytic(r, nv, nl);
                EXPECT_GE(G, 0.0f);
                EXPECT_LE(G, 1.0f + 1e-6f);
                // Vis = G / (4 NoL NoV): 4e-6 relative (a few roundings).
                float vis = visSmithSchlick(nv, nl, kSmithSchlickAnalytic(r));
                EXPECT_NEAR(vis * 4.0f * nl * nv, G, 4e-6f * G) << r << " " << nv << " " << nl;
            }
        }
        EXPECT_NEAR(g1SmithSchlick(1.0f, kSmithSchlickAnalytic(r)), 1.0f, 1e-6f);  // G1(n.v = 1) = 1
    }
}

// Each Fresnel weight against exact Schlick (1-c)^5 over c in [0,1] (1e6+1 points, double
// comparison). Measured max |error|: Karis 3.77e-3 at c = 0.055, seed 3.88e-2 at c = 0.100.
// Asserted upper bound 4.0e-3 / 4.0e-2, and lower bound 3.6e-3 / 3.7e-2 so that the figures
// documented in brdf.h cannot go stale silently.
TEST(Fresnel, ApproximationErrorBounds) {
    double maxKaris = 0.0, maxSeed = 0.0, atKaris = 0.0, atSeed = 0.0;
    for (int i = 0; i <= 1000000; ++i) {
        double c = double(float(i * 1e-6));  // the float argument, exactly
        double exact = std::pow(1.0 - c, 5.0);
        double ek = std::fabs(double(fresnelWeightKaris(float(c))) - exact);
        double es = std::fabs(double(fresnelWeightSeed(float(c))) - exact);
        if (ek > maxKaris) maxKaris = ek, atKaris = c;
        if (es > maxSeed) maxSeed = es, atSeed = c;
        // exact Schlick in float: 1 - c and three products, <= 5 roundings of 6e-8: 3e-7.
        ASSERT_NEAR(fresnelWeightSchlick(float(c)), exact, 3e-7) << c;
    }
    std::printf("Fresnel max |w - (1-c)^5|: Karis %.3e at c=%.4f, seed %.3e at c=%.4f\n", maxKaris, atKaris,
                maxSeed, atSeed);
    EXPECT_LE(maxKaris, 4.0e-3);
    EXPECT_GE(maxKaris, 3.6e-3);
    EXPECT_LE(maxSeed, 4.0e-2);
    EXPECT_GE(maxSeed, 3.7e-2);
    // Endpoints: all weights are 1 at c = 0; at c = 1 exact is 0, Karis 2^-12.53789 = 1.68e-4,
    // seed 2^-18.18324 = 3.37e-6 (tolerance 1e-6 relative).
    EXPECT_FLOAT_EQ(fresnelWeightSchlick(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(fresnelWeightKaris(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(fresnelWeightSeed(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(fresnelWeightSchlick(1.0f), 0.0f);
    EXPECT_NEAR(fresnelWeightKaris(1.0f), std::pow(2.0, -12.53789), 1e-6 * 1.7e-4);
    EXPECT_NEAR(fresnelWeightSeed(1.0f), std::pow(2.0, -18.18324), 1e-6 * 3.4e-6);
}

// F assembly, run-time dispatch, and F(f0 = 1) = 1 for every mode. Tolerance 1e-6.
TEST(Fresnel, AssemblyAndDispatch) {
    glm::vec3 f0(0.04f, 0.5f, 0.95f);
    for (float c : {0.0f, 0.1f, 0.5f, 0.9f, 1.0f}) {
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(fSchlick(f0, c)[ch], f0[ch] + (1 - f0[ch]) * std::pow(1.0 - c, 5.0), 1e-6);
            EXPECT_NEAR(fSchlickKaris(f0, c)[ch], f0[ch] + (1 - f0[ch]) * fresnelWeightKaris(c), 1e-6);
            EXPECT_NEAR(fSchlickSeed(f0, c)[ch], f0[ch] + (1 - f0[ch]) * fresnelWeightSeed(c), 1e-6);
        }
        EXPECT_EQ(fresnel(FRESNEL_SCHLICK, f0, c), fSchlick(f0, c));
        EXPECT_EQ(fresnel(FRESNEL_KARIS, f0, c), fSchlickKaris(f0, c));
        EXPECT_EQ(fresnel(FRESNEL_SEED, f0, c), fSchlickSeed(f0, c));
        EXPECT_EQ(fresnelWeight(99, c), fresnelWeightSchlick(c));  // unknown -> exact Schlick
        for (int mode : {FRESNEL_SCHLICK, FRESNEL_KARIS, FRESNEL_SEED})
            EXPECT_NEAR(fresnel(mode, glm::vec3(1.0f), c).y, 1.0f, 1e-6f);
    }
    EXPECT_EQ(FRESNEL_DEFAULT, FRESNEL_KARIS);  // UE4 2013 shipped Karis' exp2 form
}

// The whole direct-light model against a double-precision reference written from the formulas.
// Tolerance: 2e-5 relative (+1e-7 absolute) for float evaluation, plus GGX's cancellation:
// d = NoH^2 (alpha^2 - 1) + 1 carries ~1.5e-7 absolute error from the float cosines and their
// squares, 3e-7 / d relative in D = a2 / (pi d^2) (d >= alpha^2, so up to 3e-3 at roughness 0.1).
TEST(DirectLight, MatchesDoubleReference) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int checked = 0;
    for (int i = 0; i < 4000; ++i) {
        glm::vec3 N = randomUnit(rng), V = randomUnit(rng), L = randomUnit(rng);
        if (glm::dot(N, V) < 0.0f) V = -V;
        if (glm::dot(N, L) < 0.05f || glm::dot(N, V) < 0.05f) continue;
        glm::vec3 cd(u(rng), u(rng), u(rng)), f0(u(rng), u(rng), u(rng)), rad(u(rng) * 5.0f);
        float r = 0.1f + 0.9f * u(rng);
        int mode = i % 3;
        glm::vec3 got = evaluateDirectLightMode(N, V, L, cd, f0, r, rad, mode);
        glm::dvec3 want = referenceDirectLight(toD(N), toD(V), toD(L), toD(cd), toD(f0), r, toD(rad), mode);
        double noh = glm::dot(toD(N), glm::normalize(toD(V) + toD(L))), a2 = std::pow(double(r), 4.0);
        double d = noh * noh * (a2 - 1.0) + 1.0;
        double rel = 2e-5 + 3e-7 / d;
        for (int c = 0; c < 3; ++c) {
            ASSERT_NEAR(got[c], want[c], rel * std::fabs(want[c]) + 1e-7) << i;
        }
        if (mode == FRESNEL_DEFAULT) {
            ASSERT_EQ(evaluateDirectLight(N, V, L, cd, f0, r, rad), got);
        }
        ++checked;
    }
    EXPECT_GT(checked, 1000);
}

// Below the horizon: zero. V = -L (degenerate half vector): finite. Roughness 0 -> clamped.
TEST(DirectLight, EdgeCases) {
    glm::vec3 N(0, 0, 1), V = glm::normalize(glm::vec3(1, 0, 1));
    EXPECT_EQ(evaluateDirectLight(N, V, glm::vec3(0, 0, -1), glm::vec3(1), glm::vec3(1), 0.5f, glm::vec3(1)),
              glm::vec3(0.0f));
    EXPECT_EQ(evaluateDirectLight(N, V, glm::normalize(glm::vec3(1, 0, -0.001f)), glm::vec3(1), glm::vec3(1), 0.5f,
                                  glm::vec3(1)),
              glm::vec3(0.0f));
    glm::vec3 L = glm::normalize(glm::vec3(-1, 0, 0.2f));
    glm::vec3 back = evaluateDirectLight(N, -L, L, glm::vec3(0.5f), glm::vec3(0.04f), 0.5f, glm::vec3(1));
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(back[c]));
    glm::vec3 mirrorL = glm::normalize(glm::vec3(-1, 0, 1));
    glm::vec3 r0 = evaluateDirectLight(N, V, mirrorL, glm::vec3(0), glm::vec3(1), 0.0f, glm::vec3(1));
    glm::vec3 rMin = evaluateDirectLight(N, V, mirrorL, glm::vec3(0), glm::vec3(1), kMinDirectRoughness, glm::vec3(1));
    EXPECT_TRUE(std::isfinite(r0.x));
    EXPECT_EQ(r0, rMin);
    // Grazing view (NoV = 0) stays finite thanks to the cancelled Vis form.
    glm::vec3 graze = evaluateDirectLight(N, glm::vec3(1, 0, 0), mirrorL, glm::vec3(0), glm::vec3(1), 0.3f,
                                          glm::vec3(1));
    EXPECT_TRUE(std::isfinite(graze.x));
    EXPECT_GT(graze.x, 0.0f);
}

// Helmholtz reciprocity: f(l, v) = f(v, l), so result(N,V,L)/NoL = result(N,L,V)/NoV.
// Linearity in radiance. Tolerance 1e-5 relative.
TEST(DirectLight, ReciprocityAndLinearity) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 N = randomUnit(rng), V = randomUnit(rng), L = randomUnit(rng);
        float nv = glm::dot(N, V), nl = glm::dot(N, L);
        if (nv < 0.05f || nl < 0.05f) continue;
        glm::vec3 cd(u(rng)), f0(u(rng), u(rng), u(rng));
        float r = 0.1f + 0.9f * u(rng);
        int mode = i % 3;
        glm::vec3 a = evaluateDirectLightMode(N, V, L, cd, f0, r, glm::vec3(1), mode) / nl;
        glm::vec3 b = evaluateDirectLightMode(N, L, V, cd, f0, r, glm::vec3(1), mode) / nv;
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-5f * std::fabs(a[c]) + 1e-7f) << i;
        glm::vec3 twice = evaluateDirectLightMode(N, V, L, cd, f0, r, glm::vec3(2), mode);
        glm::vec3 once = evaluateDirectLightMode(N, V, L, cd, f0, r, glm::vec3(1), mode);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(twice[c], 2.0f * once[c], 1e-6f * std::fabs(twice[c]));
    }
    // Lambert alone: albedo / pi * NoL when f0 = 0 and VoH = 1 (V = L: Fresnel weight 0 exactly
    // for exact Schlick, so only diffuse and 0 * spec remain).
    glm::vec3 N(0, 0, 1), L = glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f));
    glm::vec3 got = evaluateDirectLightMode(N, L, L, glm::vec3(0.8f), glm::vec3(0.0f), 0.5f, glm::vec3(1),
                                            FRESNEL_SCHLICK);
    EXPECT_NEAR(got.x, 0.8 / kPiD * L.z, 1e-6);
}

// White furnace for the analytic-light path: with f0 = 1 (F = 1 in every mode), no diffuse and
// unit radiance, the directional albedo int evaluateDirectLight dw_L must stay <= 1. Quadrature
// over L (midpoint, 800 x 1600 in theta x phi; exact to < 1e-4 for roughness >= 0.3 whose lobe is
// > 0.1 rad wide). Tolerance +2e-3 over 1. Measured albedo (analytic k = (r+1)^2/8, which darkens
// more than the IBL k): printed below and recorded in ibl_math.h's furnace table comment.
TEST(DirectLight, WhiteFurnaceAnalyticK) {
    glm::dvec3 N(0, 0, 1);
    const int nt = 800, np = 1600;
    for (float r : {0.3f, 0.5f, 0.75f, 1.0f}) {
        for (double nov : {0.2, 0.5, 1.0}) {
            glm::vec3 V(float(std::sqrt(1.0 - nov * nov)), 0.0f, float(nov));
            double sum = 0.0;
            for (int i = 0; i < nt; ++i) {
                double t = (i + 0.5) * 0.5 * kPiD / nt;
                double st = std::sin(t), ct = std::cos(t);
                for (int j = 0; j < np; ++j) {
                    double p = (j + 0.5) * 2.0 * kPiD / np;
                    glm::vec3 L(float(st * std::cos(p)), float(st * std::sin(p)), float(ct));
                    sum += double(evaluateDirectLight(glm::vec3(N), V, L, glm::vec3(0), glm::vec3(1), r,
                                                      glm::vec3(1)).x) * st;
                }
            }
            double albedo = sum * (0.5 * kPiD / nt) * (2.0 * kPiD / np);
            std::printf("direct furnace r=%.2f NoV=%.1f albedo %.4f\n", r, nov, albedo);
            EXPECT_LE(albedo, 1.0 + 2e-3) << r << " " << nov;
            EXPECT_GT(albedo, 0.2) << r << " " << nov;  // sanity: the lobe was found at all
        }
    }
}

// The FRESNEL_* / NDF_* / ... int constants, kPi, kMinDirectRoughness (shaders/brdf.glsl vs
// src/shading/brdf.h) and kIblDefaultSamples, kMinIblNoV, kMinMisRoughness (shaders/ibl_math.glsl vs src/shading/ibl_math.h) are written
// twice; they must agree exactly.
TEST(Shared, GlslConstantsMatchCpp) {
    std::string glsl = readText(std::filesystem::path(GBL_SOURCE_SHADER_DIR) / "brdf.glsl");
    ASSERT_FALSE(glsl.empty());
    // "const <type> <name> = <value>;" declarations, one a line.
    std::map<std::string, std::string> found;
    std::istringstream lines(glsl);
    for (std::string line; std::getline(lines, line);) {
        line = line.substr(0, line.find("//"));
        std::istringstream words(line);
        std::string keyword, type, name, eq, value;
        if (!(words >> keyword >> type >> name >> eq >> value) || keyword != "const" || eq != "=") continue;
        if (value.empty() || value.back() != ';') continue;
        value.pop_back();
        found[name] = value;
    }
    std::map<std::string, int> cpp = {
        {"NDF_GGX", NDF_GGX},
        {"GEOMETRY_SMITH_SCHLICK_ANALYTIC", GEOMETRY_SMITH_SCHLICK_ANALYTIC},
        {"GEOMETRY_SMITH_SCHLICK_IBL", GEOMETRY_SMITH_SCHLICK_IBL},
        {"FRESNEL_SCHLICK", FRESNEL_SCHLICK},
        {"FRESNEL_KARIS", FRESNEL_KARIS},
        {"FRESNEL_SEED", FRESNEL_SEED},
        {"DIFFUSE_LAMBERT", DIFFUSE_LAMBERT},
        {"BRDF_UE4", BRDF_UE4},
        {"BRDF_GLTF", BRDF_GLTF},
    };
    for (auto& [name, value] : cpp) {
        ASSERT_TRUE(found.count(name)) << name << " missing from brdf.glsl";
        EXPECT_EQ(std::stoi(found[name]), value) << name;
    }
    ASSERT_TRUE(found.count("FRESNEL_DEFAULT"));
    ASSERT_TRUE(cpp.count(found["FRESNEL_DEFAULT"]));
    EXPECT_EQ(cpp[found["FRESNEL_DEFAULT"]], FRESNEL_DEFAULT);
    ASSERT_TRUE(found.count("kMinDirectRoughness"));
    EXPECT_EQ(std::stof(found["kMinDirectRoughness"]), kMinDirectRoughness);
    ASSERT_TRUE(found.count("kMinGltfRoughness"));
    EXPECT_EQ(std::stof(found["kMinGltfRoughness"]), kMinGltfRoughness);
    ASSERT_TRUE(found.count("kPi"));
    EXPECT_EQ(std::stof(found["kPi"]), kPi);

    std::string ibl = readText(std::filesystem::path(GBL_SOURCE_SHADER_DIR) / "ibl_math.glsl");
    std::istringstream iblLines(ibl);
    for (std::string line; std::getline(iblLines, line);) {
        std::istringstream words(line.substr(0, line.find("//")));
        std::string keyword, type, name, eq, value;
        if ((words >> keyword >> type >> name >> eq >> value) && keyword == "const" && eq == "=") {
            if (name == "kIblDefaultSamples") {
                EXPECT_EQ(std::stoul(value), kIblDefaultSamples);
            }
            if (name == "kMinIblNoV") {
                EXPECT_EQ(std::stof(value), kMinIblNoV);
            }
            if (name == "kMinMisRoughness") {
                EXPECT_EQ(std::stof(value), kMinMisRoughness);
            }
            found[name] = value;
        }
    }
    EXPECT_TRUE(found.count("kIblDefaultSamples"));
    EXPECT_TRUE(found.count("kMinIblNoV"));
    EXPECT_TRUE(found.count("kMinMisRoughness"));
}

// shaders/brdf.glsl + shaders/ibl_math.glsl compile for Vulkan 1.2, with and without the environment
// hook (GBL_IBL_HAS_ENVIRONMENT). Skipped when glslangValidator is not installed.
TEST(Shared, GlslCompiles) {
    if (std::system("command -v glslangValidator > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "glslangValidator not installed";
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("gbl_brdf_glsl_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string head =
        "#version 450\n#extension GL_GOOGLE_include_directive : require\nlayout(local_size_x = 1) in;\n";
    const std::string withEnv = head + R"(
layout(std430, binding = 0) buffer Out { vec4 v[]; } outBuf;
layout(binding = 1) uniform samplerCube env;
vec3 sampleEnvironmentLod(vec3 dir, float lod) { return textureLod(env, dir, lod).rgb; }
#define GBL_IBL_HAS_ENVIRONMENT
#include "brdf.glsl"
#include "ibl_math.glsl"
void main() {
    vec3 N = vec3(0, 0, 1), V = normalize(vec3(1, 0, 1)), L = normalize(vec3(-1, 0.2, 1));
    vec3 s = evaluateDirectLight(N, V, L, vec3(0.5), vec3(0.04), 0.5, vec3(1));
    s += evaluateDirectLightMode(N, V, L, vec3(0.5), vec3(0.04), 0.5, vec3(1), FRESNEL_SEED);
    s += fSchlick(vec3(0.04), 0.3) + fSchlickKaris(vec3(0.04), 0.3) + fSchlickSeed(vec3(0.04), 0.3);
    s.x += gSmithSchlickAnalytic(0.3, 0.5, 0.5) + gSmithSchlickIbl(0.3, 0.5, 0.5);
    vec2 ab = integrateBRDF(0.5, 0.5) + integrateBRDF(0.5, 0.5, 64u);
    s += envBRDF(vec3(0.04), ab) + envBRDFApprox(vec3(0.04), 0.5, 0.5);
    s.x += envBRDFApproxNonmetal(0.5, 0.5);
    vec3 d = vec3(0.5), sp = vec3(0.04);
    envBRDFApproxFullyRough(d, sp);
    s += d + sp;
    float g = bo2GlossFromRoughness(0.5) + glossFromRoughnessLinear(0.5) + glossFromRoughnessBlinnPhong(0.5);
    s += environmentBRDF(g, 0.5, vec3(0.04));
    s.x += bo2A0(g, 0.5) + bo2A1(g, 0.5) + bo2A0f(g, 0.5) + bo2A1f(g, 0.5) + bo2A0r(g, 0.5);
    s += specularIBLGroundTruth(vec3(1), 0.5, N, V) + specularIBLGroundTruth(vec3(1), 0.5, N, V, 16u);
    s += prefilterEnvMap(0.5, N) + prefilterEnvMap(0.5, N, 16u) + prefilterEnvMapFiltered(0.5, N, 32u, 256.0);
    s.x += filteredSampleLod(1.0, 32.0, 256.0) + mipFromRoughness(0.5, 8.0) + roughnessFromMip(3.0, 8.0);
    s.x += pdfGgxReflection(0.9, 0.8, 0.5) + dGgx(0.9, 0.5) + visSmithSchlick(0.5, 0.5, 0.1);
    outBuf.v[gl_GlobalInvocationID.x] = vec4(s, hammersley(3u, 16u).y + radicalInverseVdC(5u));
}
)";
    const std::string noEnv = head + R"(
layout(std430, binding = 0) buffer Out { vec2 v[]; } outBuf;
#include "brdf.glsl"
#include "ibl_math.glsl"
void main() { outBuf.v[gl_GlobalInvocationID.x] = integrateBRDF(0.5, 0.5); }
)";
    int index = 0;
    for (const std::string* src : {&withEnv, &noEnv}) {
        fs::path comp = dir / ("wrapper" + std::to_string(index) + ".comp");
        fs::path spv = dir / ("wrapper" + std::to_string(index) + ".spv");
        fs::path log = dir / ("wrapper" + std::to_string(index) + ".log");
        std::ofstream(comp) << *src;
        std::string cmd = "glslangValidator -V --target-env vulkan1.2 -S comp -I\"" +
                          std::string(GBL_SOURCE_SHADER_DIR) + "\" \"" + comp.string() + "\" -o \"" + spv.string() +
                          "\" > \"" + log.string() + "\" 2>&1";
        int rc = std::system(cmd.c_str());
        EXPECT_EQ(rc, 0) << "wrapper " << index << ":\n" << readText(log);
        ++index;
    }
    fs::remove_all(dir);
}
