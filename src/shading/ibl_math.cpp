// C++ mirror of shaders/ibl_math.glsl. Keep in step with the shader.
//   [Karis13]   B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course notes.
//   [Karis14]   B. Karis, "Physically Based Shading on Mobile", 2014.
//   [Lazarov13] D. Lazarov, "Getting More Physical in Call of Duty: Black Ops II", SIGGRAPH 2013.
//   [Heitz18]   E. Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018.
//   [Walter07]  B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007.
//   [KC08]      J. Krivanek, M. Colbert, "Real-time Shading with Filtered Importance Sampling", 2008.
//   [HH64]      J. Hammersley, D. Handscomb, "Monte Carlo Methods", 1964; bit reversal as in
//               H. Warren, "Hacker's Delight", ch. 7.
//   [Walter07]  B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", 2007.
//   [Seed]      ../shared/seed/000_807e17994f774a43.txt.
#include "ibl_math.h"

#include <algorithm>
#include <cmath>

#include "brdf.h"
#include "environment_sampling.h"

namespace gbl::shading {

namespace {


uint32_t reverseBits(uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return bits;
}

// importanceSampleGGX for float (the GLSL mirror) and double (the reference variant).
template <class T>
glm::vec<3, T> importanceSampleGGXT(glm::vec<2, T> Xi, T roughness, glm::vec<3, T> N) {
    using V3 = glm::vec<3, T>;
    T a = roughness * roughness;
    T phi = T(2) * T(3.14159265358979323846) * Xi.x;
    T cosTheta = std::sqrt((T(1) - Xi.y) / (T(1) + (a * a - T(1)) * Xi.y));
    T sinTheta = std::sqrt(std::max(T(1) - cosTheta * cosTheta, T(0)));
    V3 H(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
    V3 up = std::abs(N.z) < T(0.999) ? V3(0, 0, 1) : V3(1, 0, 0);
    V3 tangentX = glm::normalize(glm::cross(up, N));
    V3 tangentY = glm::cross(N, tangentX);
    return tangentX * H.x + tangentY * H.y + N * H.z;
}

}  // namespace

// [HH64], [Warren ch. 7]: reverse the 32 bits, keep the top 24 (exact in float, < 1).
float radicalInverseVdC(uint32_t bits) { return float(reverseBits(bits) >> 8u) * 5.9604644775390625e-8f; }

double radicalInverseVdCDouble(uint32_t bits) { return double(reverseBits(bits)) * 2.3283064365386962890625e-10; }

// [HH64]: (i/N, radical inverse of i).
glm::vec2 hammersley(uint32_t i, uint32_t N) { return glm::vec2(float(i) / float(N), radicalInverseVdC(i)); }

glm::dvec2 hammersleyDouble(uint32_t i, uint32_t N) {
    return glm::dvec2(double(i) / double(N), radicalInverseVdCDouble(i));
}

// [Karis13 ImportanceSampleGGX], [Walter07 eqs. 35-36].
glm::vec3 importanceSampleGGX(glm::vec2 Xi, float roughness, glm::vec3 N) {
    return importanceSampleGGXT<float>(Xi, roughness, N);
}

glm::dvec3 importanceSampleGGXDouble(glm::dvec2 Xi, double roughness, glm::dvec3 N) {
    return importanceSampleGGXT<double>(Xi, roughness, N);
}

// [Karis13 SpecularIBL comment], [Walter07 eq. 14]: D NoH / (4 VoH).
float pdfGgxReflection(float NoH, float VoH, float roughness) { return dGgx(NoH, roughness) * NoH / (4.0f * VoH); }

// [KC08, sec. 3]: lod = 0.5 log2(Os / Op), clamped below at 0.
float filteredSampleLod(float pdf, float numSamples, float faceSize) {
    float omegaS = 1.0f / (numSamples * pdf);
    float omegaP = 4.0f * kPi / (6.0f * faceSize * faceSize);
    return std::max(0.5f * std::log2(omegaS / omegaP), 0.0f);
}

// Our choice (the UE4 slides leave it open [Seed]): linear in roughness.
float mipFromRoughness(float roughness, float mipCount) { return roughness * std::max(mipCount - 1.0f, 0.0f); }

float roughnessFromMip(float mip, float mipCount) { return mipCount > 1.0f ? mip / (mipCount - 1.0f) : 0.0f; }

// [Karis13 IntegrateBRDF], N = (0,0,1), G with k = alpha/2 (IBL).
glm::vec2 integrateBRDF(float roughness, float NoV, uint32_t numSamples) {
    NoV = std::max(NoV, kMinIblNoV);
    glm::vec3 V(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    glm::vec3 N(0.0f, 0.0f, 1.0f);
    float A = 0.0f;
    float B = 0.0f;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi = hammersley(i, numSamples);
        glm::vec3 H = importanceSampleGGX(Xi, roughness, N);
        glm::vec3 L = 2.0f * glm::dot(V, H) * H - V;
        float NoL = saturate(L.z);
        float NoH = saturate(H.z);
        float VoH = saturate(glm::dot(V, H));
        if (NoL > 0.0f) {
            float G = gSmithSchlickIbl(roughness, NoV, NoL);
            float G_Vis = G * VoH / (NoH * NoV);
            float Fc = fresnelWeightSchlick(VoH);
            A += (1.0f - Fc) * G_Vis;
            B += Fc * G_Vis;
        }
    }
    return glm::vec2(A, B) / float(numSamples);
}

// The same estimator, every operation in double (the reference for float and the LUT).
glm::dvec2 integrateBRDFDouble(double roughness, double NoV, uint32_t numSamples) {
    NoV = std::max(NoV, double(kMinIblNoV));
    glm::dvec3 V(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
    glm::dvec3 N(0.0, 0.0, 1.0);
    double k = roughness * roughness / 2.0;  // IBL k = alpha/2
    double A = 0.0;
    double B = 0.0;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::dvec2 Xi = hammersleyDouble(i, numSamples);
        glm::dvec3 H = importanceSampleGGXDouble(Xi, roughness, N);
        glm::dvec3 L = 2.0 * glm::dot(V, H) * H - V;
        double NoL = std::clamp(L.z, 0.0, 1.0);
        double NoH = std::clamp(H.z, 0.0, 1.0);
        double VoH = std::clamp(glm::dot(V, H), 0.0, 1.0);
        if (NoL > 0.0) {
            double G = (NoV / (NoV * (1.0 - k) + k)) * (NoL / (NoL * (1.0 - k) + k));
            double G_Vis = G * VoH / (NoH * NoV);
            double Fc = std::pow(1.0 - VoH, 5.0);
            A += (1.0 - Fc) * G_Vis;
            B += Fc * G_Vis;
        }
    }
    return glm::dvec2(A, B) / double(numSamples);
}

// [Walter07 eq. 34]: exact Smith G1 of GGX (the visible-normal distribution's normalisation).
float g1SmithGgxExact(float NoV, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    return 2.0f * NoV / (NoV + std::sqrt(a2 + (1.0f - a2) * NoV * NoV));
}

// [Heitz18, listing 1], isotropic, tangent frame N = +z, V in the xz plane (T1 = +y).
glm::vec3 importanceSampleVisibleGGX(glm::vec2 Xi, float roughness, glm::vec3 V) {
    float a = roughness * roughness;
    glm::vec3 Vh = glm::normalize(glm::vec3(a * V.x, 0.0f, V.z));
    glm::vec3 T1(0.0f, 1.0f, 0.0f);
    glm::vec3 T2 = glm::cross(Vh, T1);
    float r = std::sqrt(Xi.x);
    float phi = 2.0f * kPi * Xi.y;
    float t1 = r * std::cos(phi);
    float t2 = r * std::sin(phi);
    float s = 0.5f * (1.0f + Vh.z);
    t2 = (1.0f - s) * std::sqrt(std::max(1.0f - t1 * t1, 0.0f)) + s * t2;
    glm::vec3 Nh = t1 * T1 + t2 * T2 + std::sqrt(std::max(1.0f - t1 * t1 - t2 * t2, 0.0f)) * Vh;
    return glm::normalize(glm::vec3(a * Nh.x, a * Nh.y, std::max(Nh.z, 0.0f)));
}

// [Heitz18]: integrateBRDF's integral with visible-normal sampling; weight F G / G1_exact(V).
glm::vec2 integrateBRDFVisible(float roughness, float NoV, uint32_t numSamples) {
    NoV = std::max(NoV, kMinIblNoV);
    glm::vec3 V(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    float g1V = g1SmithGgxExact(NoV, roughness);
    float A = 0.0f;
    float B = 0.0f;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi((float(i) + 0.5f) / float(numSamples), radicalInverseVdC(i));
        glm::vec3 H = importanceSampleVisibleGGX(Xi, roughness, V);
        float VoH = saturate(glm::dot(V, H));
        float NoL = 2.0f * VoH * H.z - NoV;
        if (NoL > 0.0f) {
            float w = gSmithSchlickIbl(roughness, NoV, std::min(NoL, 1.0f)) / g1V;
            float Fc = fresnelWeightSchlick(VoH);
            A += (1.0f - Fc) * w;
            B += Fc * w;
        }
    }
    return glm::vec2(A, B) / float(numSamples);
}

// [Karis13 / Seed EnvBRDF]: the 2% rule.
glm::vec3 envBRDF(glm::vec3 specularColor, glm::vec2 AB) {
    return specularColor * AB.x + saturate(50.0f * specularColor.g) * AB.y;
}

// [Karis14], [Seed EnvBRDFApprox].
glm::vec3 envBRDFApprox(glm::vec3 specularColor, float roughness, float NoV) {
    const glm::vec4 c0(-1.0f, -0.0275f, -0.572f, 0.022f);
    const glm::vec4 c1(1.0f, 0.0425f, 1.04f, -0.04f);
    glm::vec4 r = roughness * c0 + c1;
    float a004 = std::min(r.x * r.x, std::exp2(-9.28f * NoV)) * r.x + r.y;
    glm::vec2 AB = glm::vec2(-1.04f, 1.04f) * a004 + glm::vec2(r.z, r.w);
    return specularColor * AB.x + AB.y;
}

// [Karis14], [Seed EnvBRDFApproxNonmetal].
float envBRDFApproxNonmetal(float roughness, float NoV) {
    const glm::vec2 c0(-1.0f, -0.0275f);
    const glm::vec2 c1(1.0f, 0.0425f);
    glm::vec2 r = roughness * c0 + c1;
    return std::min(r.x * r.x, std::exp2(-9.28f * NoV)) * r.x + r.y;
}

// [Karis14], [Seed]: the fully-rough shortcut.
void envBRDFApproxFullyRough(glm::vec3& diffuseColor, glm::vec3& specularColor) {
    diffuseColor += specularColor * 0.45f;
    specularColor = glm::vec3(0.0f);
}

// [Lazarov13], [Seed]: the Black Ops 2 fits.
float bo2A0(float g, float NoV) {
    float t1 = 11.4f * g * g * g + 0.1f;
    float t2 = NoV + (0.1f - 0.09f * g);
    return (1.0f - std::exp(-t1 * t2)) * 1.32f * std::exp2(-10.3f * NoV);
}

float bo2A1(float g, float NoV) {
    float t1 = std::max(1.336f - 0.486f * g, 1.0f);
    float t2 = 0.06f + 3.25f * g + 12.8f * g * g * g;
    float t3 = NoV + std::min(0.125f - 0.1f * g, 0.1f);
    return std::min(t1 - std::exp2(-t2 * t3), 1.0f);
}

float bo2A0f(float g, float NoV) {
    float t1 = 0.095f + g * (0.6f + 4.19f * g);
    float t2 = NoV + 0.025f;
    return t1 * t2 * std::exp2(1.0f - 14.0f * NoV);
}

float bo2A1f(float g, float NoV) {
    float t1 = 9.5f * g * NoV;
    return 0.4f + 0.6f * (1.0f - std::exp2(-t1));
}

float bo2A004(float g, float NoV) {
    float t = std::min(0.475f * g, std::exp2(-9.28f * NoV));
    return (t + 0.0275f) * g + 0.015f;
}

float bo2A1vf(float g) { return 0.25f * g + 0.75f; }

float bo2A0r(float g, float NoV) { return (bo2A004(g, NoV) - bo2A1vf(g) * 0.04f) / 0.96f; }

// [Lazarov13], [Seed EnvironmentBRDF]: folded form.
glm::vec3 environmentBRDF(float g, float NoV, glm::vec3 rf0) {
    glm::vec4 t(1.0f / 0.96f, 0.475f, (0.0275f - 0.25f * 0.04f) / 0.96f, 0.25f);
    t *= glm::vec4(g, g, g, g);
    t += glm::vec4(0.0f, 0.0f, (0.015f - 0.75f * 0.04f) / 0.96f, 0.75f);
    float a0 = t.x * std::min(t.y, std::exp2(-9.28f * NoV)) + t.z;
    float a1 = t.w;
    return glm::clamp(glm::vec3(a0) + rf0 * (a1 - a0), 0.0f, 1.0f);
}

float glossFromRoughnessLinear(float roughness) { return 1.0f - roughness; }

// [Lazarov13] power 2^(13 g); GGX match n = 2/alpha^2 - 2 ([Walter07] sec. 5.2 / Karis 2013).
float glossFromRoughnessBlinnPhong(float roughness) {
    float a = roughness * roughness;
    float n = 2.0f / std::max(a * a, 1e-8f) - 2.0f;
    return std::clamp(std::log2(std::max(n, 1.0f)) / 13.0f, 0.0f, 1.0f);
}

float bo2GlossFromRoughness(float roughness) { return glossFromRoughnessBlinnPhong(roughness); }

// [Karis13 SpecularIBL]: ground truth, G with k = alpha/2.
glm::vec3 specularIBLGroundTruth(const EnvironmentLodFn& sampleEnvironmentLod, glm::vec3 specularColor,
                                 float roughness, glm::vec3 N, glm::vec3 V, uint32_t numSamples) {
    glm::vec3 specularLighting(0.0f);
    float NoV = std::max(saturate(glm::dot(N, V)), kMinIblNoV);
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi = hammersley(i, numSamples);
        glm::vec3 H = importanceSampleGGX(Xi, roughness, N);
        glm::vec3 L = 2.0f * glm::dot(V, H) * H - V;
        float NoL = saturate(glm::dot(N, L));
        float NoH = saturate(glm::dot(N, H));
        float VoH = saturate(glm::dot(V, H));
        if (NoL > 0.0f) {
            glm::vec3 sampleColor = sampleEnvironmentLod(L, 0.0f);
            float G = gSmithSchlickIbl(roughness, NoV, NoL);
            float Fc = fresnelWeightSchlick(VoH);
            glm::vec3 F = (1.0f - Fc) * specularColor + Fc;
            specularLighting += sampleColor * F * G * VoH / (NoH * NoV);
        }
    }
    return specularLighting / float(numSamples);
}

// [Karis13 PrefilterEnvMap], with the total weight declared.
glm::vec3 prefilterEnvMap(const EnvironmentLodFn& sampleEnvironmentLod, float roughness, glm::vec3 R,
                          uint32_t numSamples) {
    glm::vec3 N = R;
    glm::vec3 V = R;
    glm::vec3 prefilteredColor(0.0f);
    float totalWeight = 0.0f;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi = hammersley(i, numSamples);
        glm::vec3 H = importanceSampleGGX(Xi, roughness, N);
        glm::vec3 L = 2.0f * glm::dot(V, H) * H - V;
        float NoL = saturate(glm::dot(N, L));
        if (NoL > 0.0f) {
            prefilteredColor += sampleEnvironmentLod(L, 0.0f) * NoL;
            totalWeight += NoL;
        }
    }
    return totalWeight > 0.0f ? prefilteredColor / totalWeight : glm::vec3(0.0f);
}

// [Karis13 PrefilterEnvMap] + [KC08] per-sample mip.
glm::vec3 prefilterEnvMapFiltered(const EnvironmentLodFn& sampleEnvironmentLod, float roughness, glm::vec3 R,
                                  uint32_t numSamples, float faceSize) {
    if (roughness <= 0.0f) return sampleEnvironmentLod(R, 0.0f);  // D is a delta: pdf undefined
    glm::vec3 N = R;
    glm::vec3 V = R;
    glm::vec3 prefilteredColor(0.0f);
    float totalWeight = 0.0f;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi = hammersley(i, numSamples);
        glm::vec3 H = importanceSampleGGX(Xi, roughness, N);
        glm::vec3 L = 2.0f * glm::dot(V, H) * H - V;
        float NoL = saturate(glm::dot(N, L));
        if (NoL > 0.0f) {
            float NoH = saturate(glm::dot(N, H));
            float pdf = dGgx(NoH, roughness) / 4.0f;
            float lod = filteredSampleLod(pdf, float(numSamples), faceSize);
            prefilteredColor += sampleEnvironmentLod(L, lod) * NoL;
            totalWeight += NoL;
        }
    }
    return totalWeight > 0.0f ? prefilteredColor / totalWeight : glm::vec3(0.0f);
}

// PCG hash [O'Neill 2014; Jarzynski & Olano, JCGT 9(3), 2020], RXS-M-XS: uint32 wrap-around as in GLSL.
uint32_t pcgHash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

glm::vec2 randomShift(uint32_t a, uint32_t b, uint32_t c) {
    uint32_t h = pcgHash(a ^ pcgHash(b ^ pcgHash(c)));
    uint32_t h2 = pcgHash(h);
    return glm::vec2(float(h >> 8u), float(h2 >> 8u)) * 5.9604644775390625e-8f;  // 2^-24
}

// [Veach97, sec. 9.2.4], beta = 2.
float powerHeuristic(float a, float b) {
    float a2 = a * a;
    float d = a2 + b * b;
    return d > 0.0f ? a2 / d : 0.0f;
}

// [Veach97 ch. 9]: one GGX and one environment sample per step, power heuristic (ibl_math.glsl).
glm::vec3 specularIBLGroundTruthMis(const EnvironmentLodFn& sampleEnvironmentLod,
                                    const std::vector<float>& environmentSampling, glm::vec3 specularColor,
                                    float roughness, glm::vec3 N, glm::vec3 V, uint32_t numSamples,
                                    glm::vec2 shiftGgx, glm::vec2 shiftEnv) {
    glm::vec3 sum(0.0f);
    float NoV = std::max(saturate(glm::dot(N, V)), kMinIblNoV);
    bool useEnvironment = roughness >= kMinMisRoughness;
    for (uint32_t i = 0; i < numSamples; i++) {
        glm::vec2 Xi = hammersley(i, numSamples);
        // BRDF technique.
        glm::vec3 H = importanceSampleGGX(fractGlsl(Xi + shiftGgx), roughness, N);
        glm::vec3 L = 2.0f * glm::dot(V, H) * H - V;
        float NoL = saturate(glm::dot(N, L));
        float NoH = saturate(glm::dot(N, H));
        float VoH = saturate(glm::dot(V, H));
        if (NoL > 0.0f && NoH > 0.0f && VoH > 0.0f) {
            float G = gSmithSchlickIbl(roughness, NoV, NoL);
            float Fc = fresnelWeightSchlick(VoH);
            glm::vec3 F = (1.0f - Fc) * specularColor + Fc;
            float w = 1.0f;
            if (useEnvironment)
                w = powerHeuristic(pdfGgxReflection(NoH, VoH, roughness), environmentDirectionPdf(environmentSampling, L));
            sum += w * sampleEnvironmentLod(L, 0.0f) * F * (G * VoH / (NoH * NoV));
        }
        if (!useEnvironment) continue;
        // Environment technique.
        float pdfEnv;
        glm::vec3 Le = sampleEnvironmentDirection(environmentSampling, fractGlsl(Xi + shiftEnv), pdfEnv);
        float NoLe = glm::dot(N, Le);
        if (pdfEnv > 0.0f && NoLe > 0.0f) {
            glm::vec3 He = glm::normalize(V + Le);
            float NoHe = saturate(glm::dot(N, He));
            float VoHe = std::clamp(glm::dot(V, He), 1e-6f, 1.0f);
            float D = dGgx(NoHe, roughness);
            float G = gSmithSchlickIbl(roughness, NoV, std::min(NoLe, 1.0f));
            float Fc = fresnelWeightSchlick(VoHe);
            glm::vec3 F = (1.0f - Fc) * specularColor + Fc;
            float w = powerHeuristic(pdfEnv, D * NoHe / (4.0f * VoHe));
            // f NoL = D G F / (4 NoV)
            sum += w * sampleEnvironmentLod(Le, 0.0f) * F * (D * G / (4.0f * NoV * pdfEnv));
        }
    }
    return sum / float(numSamples);
}

}  // namespace gbl::shading
