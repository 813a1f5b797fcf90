// C++ mirror of shaders/brdf_layers.glsl. Keep line for line in step with the shader.
//   [glTF-B]  glTF 2.0 Specification, Appendix B "BRDF Implementation".
//   [Coat]    KHR_materials_clearcoat README, "Layering", "Emission".
//   [Sheen]   KHR_materials_sheen README, "Implementation Notes"; Conty & Kulla, "Production
//             Friendly Microfacet Sheen BRDF", Sony Imageworks 2017.
//   [Aniso]   KHR_materials_anisotropy README, "Anisotropy", "Implementation".
#include "brdf_layers.h"

#include <algorithm>
#include <cmath>

#include "brdf.h"

namespace gbl::shading {

namespace {
float mixf(float x, float y, float a) { return x * (1.0f - a) + y * a; }  // GLSL mix
glm::vec3 safeHalf(glm::vec3 V, glm::vec3 L) {
    glm::vec3 Hu = V + L;
    return Hu * (1.0f / std::sqrt(std::max(glm::dot(Hu, Hu), 1e-12f)));
}
}  // namespace

float max3(glm::vec3 v) { return std::max(std::max(v.x, v.y), v.z); }

// [Coat]: |V.Nc|.
float coatNoV(glm::vec3 Nc, glm::vec3 V) { return std::min(std::abs(glm::dot(Nc, V)), 1.0f); }

// [Coat]: 0.04 + 0.96 (1 - NcoV)^5.
float coatFresnel(float NcoV) { return kCoatF0 + (1.0f - kCoatF0) * fresnelWeightSchlick(NcoV); }

// visSmithGgxCorrelated is brdf.h's.
float coatSpecular(float NcoH, float NcoV, float NcoL, float coatRoughness) {
    return dGgx(NcoH, coatRoughness) * visSmithGgxCorrelated(NcoV, NcoL, coatRoughness);
}

// [Sheen]: Charlie D.
float dCharlie(float NoH, float sheenRoughness) {
    float alphaG = sheenRoughness * sheenRoughness;
    float invR = 1.0f / alphaG;
    float sin2h = std::max(1.0f - NoH * NoH, 0.0f);
    return (2.0f + invR) * std::pow(sin2h, invR * 0.5f) / (2.0f * kPi);
}

// [Sheen]: l(x, alpha_g).
float sheenLambdaCurve(float x, float alphaG) {
    float oneMinusAlphaSq = (1.0f - alphaG) * (1.0f - alphaG);
    float a = mixf(21.5473f, 25.3245f, oneMinusAlphaSq);
    float b = mixf(3.82987f, 3.32435f, oneMinusAlphaSq);
    float c = mixf(0.19823f, 0.16801f, oneMinusAlphaSq);
    float d = mixf(-1.97760f, -1.27393f, oneMinusAlphaSq);
    float e = mixf(-4.32054f, -4.85967f, oneMinusAlphaSq);
    return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

float lambdaSheen(float cosTheta, float alphaG) {
    return std::abs(cosTheta) < 0.5f
               ? std::exp(sheenLambdaCurve(cosTheta, alphaG))
               : std::exp(2.0f * sheenLambdaCurve(0.5f, alphaG) - sheenLambdaCurve(1.0f - cosTheta, alphaG));
}

float visCharlie(float NoV, float NoL, float sheenRoughness) {
    float alphaG = sheenRoughness * sheenRoughness;
    return 1.0f / ((1.0f + lambdaSheen(NoV, alphaG) + lambdaSheen(NoL, alphaG)) * (4.0f * NoV * NoL));
}

float sheenBrdf(float NoH, float NoV, float NoL, float sheenRoughness) {
    float r = std::max(sheenRoughness, kMinSheenRoughness);
    return dCharlie(NoH, r) * visCharlie(std::max(NoV, kMinSheenNoV), NoL, r);
}

float sheenAlbedoScaling(glm::vec3 sheenColor, float albedoV, float albedoL) {
    float m = max3(sheenColor);
    return std::min(1.0f - m * albedoV, 1.0f - m * albedoL);
}

// [Aniso].
float anisotropicAlphaT(float roughness, float anisotropy) {
    float a = roughness * roughness;
    return mixf(a, 1.0f, anisotropy * anisotropy);
}

float dGgxAnisotropic(float NoH, float ToH, float BoH, float at, float ab) {
    float a2 = at * ab;
    glm::vec3 f(ab * ToH, at * BoH, a2 * NoH);
    float w2 = a2 / glm::dot(f, f);
    return a2 * w2 * w2 / kPi;
}

float visGgxAnisotropic(float NoL, float NoV, float BoV, float ToV, float ToL, float BoL, float at, float ab) {
    float ggxV = NoL * glm::length(glm::vec3(at * ToV, ab * BoV, NoV));
    float ggxL = NoV * glm::length(glm::vec3(at * ToL, ab * BoL, NoL));
    float v = 0.5f / (ggxV + ggxL);
    return saturate(v);
}

glm::vec3 evaluateDirectLightAnisotropicMode(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 T, glm::vec3 B,
                                             float anisotropy, glm::vec3 diffuseColor, glm::vec3 specularColor,
                                             float roughness, glm::vec3 lightRadiance, int fresnelMode) {
    float NoL = saturate(glm::dot(N, L));
    if (NoL <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 H = safeHalf(V, L);
    float NoV = saturate(glm::dot(N, V));
    float NoH = saturate(glm::dot(N, H));
    float VoH = saturate(glm::dot(V, H));
    float r = std::max(roughness, kMinDirectRoughness);
    float ab = r * r;
    float at = anisotropicAlphaT(r, anisotropy);
    float D = dGgxAnisotropic(NoH, glm::dot(T, H), glm::dot(B, H), at, ab);
    float Vis = visGgxAnisotropic(NoL, NoV, glm::dot(B, V), glm::dot(T, V), glm::dot(T, L), glm::dot(B, L), at, ab);
    glm::vec3 F = fresnel(fresnelMode, specularColor, VoH);
    glm::vec3 brdf = diffuseLambert(diffuseColor) + D * Vis * F;
    return brdf * lightRadiance * NoL;
}

glm::vec3 coatedEmission(glm::vec3 emission, const Layers& ly, glm::vec3 V) {
    if (ly.coat <= 0.0f) return emission;
    return emission * (1.0f - ly.coat * coatFresnel(coatNoV(ly.coatNormal, V)));
}

glm::vec3 anisotropicReflection(glm::vec3 N, glm::vec3 V, glm::vec3 B, float anisotropy, float roughness) {
    glm::vec3 bent = glm::cross(glm::cross(B, V), B);
    bent = glm::dot(bent, bent) > 1e-12f ? glm::normalize(bent) : N;
    float t = 1.0f - anisotropy * (1.0f - roughness);
    float a = t * t * t * t;
    bent = glm::normalize(glm::mix(bent, N, a));
    glm::vec3 R = 2.0f * glm::dot(bent, V) * bent - V;  // reflect(-V, bent)
    return glm::normalize(glm::mix(R, bent, roughness * roughness));
}

// ---- BRDF_GLTF: the layers with the Sample Viewer's clamps (brdf_layers.glsl lists them) ----

float sheenBrdfGltf(float NoH, float NoV, float NoL, float sheenRoughness) {
    float r = std::max(sheenRoughness, kMinGltfSheenRoughness);
    return dCharlie(NoH, r) * std::clamp(visCharlie(NoV, NoL, r), 0.0f, 1.0f);
}

glm::vec3 evaluateDirectLightAnisotropicGltf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 T, glm::vec3 B,
                                             float anisotropy, glm::vec3 diffuseColor, glm::vec3 specularColor,
                                             float dielectricF0, float roughness, glm::vec3 lightRadiance) {
    float NoL = saturate(glm::dot(N, L));
    if (NoL <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 H = safeHalf(V, L);
    float VoH = saturate(glm::dot(V, H));
    float at = anisotropicAlphaT(roughness, anisotropy);
    float ab = std::clamp(roughness * roughness, 0.001f, 1.0f);
    float NoH = std::clamp(glm::dot(N, H), 0.001f, 1.0f);
    float D = dGgxAnisotropic(NoH, glm::dot(T, H), glm::dot(B, H), at, ab);
    float Vis = visGgxAnisotropic(NoL, glm::dot(N, V), glm::dot(B, V), glm::dot(T, V), glm::dot(T, L), glm::dot(B, L),
                                  at, ab);
    glm::vec3 F = fSchlick(specularColor, VoH);
    float Fd = gltfDielectricFresnel(dielectricF0, VoH);
    glm::vec3 brdf = diffuseLambert(diffuseColor) * (1.0f - Fd) + D * Vis * F;
    return brdf * lightRadiance * NoL;
}

float coatNoVGltf(glm::vec3 Nc, glm::vec3 V) { return saturate(glm::dot(Nc, V)); }

// brdf_layers.glsl layerOverBase: the layers over a base lobe's radiance, [Sheen] then [Coat];
// `gltf` picks the Sample Viewer's sheen clamps, the coat's clamped n.v and kMinGltfRoughness.
static glm::vec3 layerOverBase(glm::vec3 color, glm::vec3 N, glm::vec3 V, glm::vec3 L, const Layers& ly, float sheenAlbedoV,
                               float sheenAlbedoL, glm::vec3 lightRadiance, bool gltf) {
    glm::vec3 H = safeHalf(V, L);
    if (max3(ly.sheenColor) > 0.0f) {
        float NoL = saturate(glm::dot(N, L));
        glm::vec3 sheen(0.0f);
        if (NoL > 0.0f) {
            float NoH = saturate(glm::dot(N, H)), NoV = saturate(glm::dot(N, V));
            float lobe = gltf ? sheenBrdfGltf(NoH, NoV, NoL, ly.sheenRoughness) : sheenBrdf(NoH, NoV, NoL, ly.sheenRoughness);
            sheen = ly.sheenColor * (lobe * NoL) * lightRadiance;
        }
        color = sheen + color * sheenAlbedoScaling(ly.sheenColor, sheenAlbedoV, sheenAlbedoL);
    }
    if (ly.coat > 0.0f) {
        glm::vec3 Nc = ly.coatNormal;
        float NcoL = saturate(glm::dot(Nc, L));
        float NcoV = gltf ? coatNoVGltf(Nc, V) : coatNoV(Nc, V);
        float fc = ly.coat * coatFresnel(NcoV);
        float coat = 0.0f;
        if (NcoL > 0.0f)
            coat = coatSpecular(saturate(glm::dot(Nc, H)), NcoV, NcoL,
                                std::max(ly.coatRoughness, gltf ? kMinGltfRoughness : kMinDirectRoughness)) *
                   NcoL;
        color = color * (1.0f - fc) + (fc * coat) * lightRadiance;
    }
    return color;
}

glm::vec3 evaluateDirectLightLayeredMode(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                         glm::vec3 specularColor, float roughness, const Layers& ly,
                                         float sheenAlbedoV, float sheenAlbedoL, glm::vec3 lightRadiance,
                                         int fresnelMode) {
    glm::vec3 color = ly.anisotropy > 0.0f
                          ? evaluateDirectLightAnisotropicMode(N, V, L, ly.anisotropyT, ly.anisotropyB, ly.anisotropy,
                                                               diffuseColor, specularColor, roughness, lightRadiance,
                                                               fresnelMode)
                          : evaluateDirectLightMode(N, V, L, diffuseColor, specularColor, roughness, lightRadiance,
                                                    fresnelMode);
    return layerOverBase(color, N, V, L, ly, sheenAlbedoV, sheenAlbedoL, lightRadiance, false);
}

glm::vec3 evaluateDirectLightLayeredGltf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                         glm::vec3 specularColor, float dielectricF0, float roughness,
                                         const Layers& ly, float sheenAlbedoV, float sheenAlbedoL,
                                         glm::vec3 lightRadiance) {
    glm::vec3 color = ly.anisotropy > 0.0f
                          ? evaluateDirectLightAnisotropicGltf(N, V, L, ly.anisotropyT, ly.anisotropyB, ly.anisotropy,
                                                               diffuseColor, specularColor, dielectricF0, roughness,
                                                               lightRadiance)
                          : evaluateDirectLightGltf(N, V, L, diffuseColor, specularColor, dielectricF0, roughness,
                                                    lightRadiance);
    return layerOverBase(color, N, V, L, ly, sheenAlbedoV, sheenAlbedoL, lightRadiance, true);
}

glm::vec3 coatedEmissionGltf(glm::vec3 emission, const Layers& ly, glm::vec3 V) {
    if (ly.coat <= 0.0f) return emission;
    return emission * (1.0f - ly.coat * coatFresnel(coatNoVGltf(ly.coatNormal, V)));
}

}  // namespace gbl::shading
