// C++ mirror of shaders/brdf.glsl. Keep line for line in step with the shader.
//   [Karis13]   B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course notes.
//   [Walter07]  B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", 2007.
//   [Schlick94] C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", 1994.
//   [Seed]      ../shared/seed/000_807e17994f774a43.txt.
#include "brdf.h"

#include <algorithm>
#include <cmath>

namespace gbl::shading {

namespace {
}  // namespace

// GGX / Trowbridge-Reitz [Karis13 eq. 3], [Walter07 eq. 33], alpha = roughness^2.
float dGgx(float NoH, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    float d = NoH * NoH * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

// [Karis13 eq. 4]: k = (roughness + 1)^2 / 8, analytic lights only.
float kSmithSchlickAnalytic(float roughness) {
    float r = roughness + 1.0f;
    return r * r / 8.0f;
}

// [Karis13 p.3]: k = alpha / 2 for image-based lighting.
float kSmithSchlickIbl(float roughness) {
    float a = roughness * roughness;
    return a / 2.0f;
}

// [Schlick94], [Karis13 eq. 4]: G1(v) = n.v / ((n.v)(1 - k) + k).
float g1SmithSchlick(float NoX, float k) { return NoX / (NoX * (1.0f - k) + k); }

// [Karis13 eq. 4]: G = G1(l) G1(v).
float gSmithSchlick(float NoV, float NoL, float k) { return g1SmithSchlick(NoV, k) * g1SmithSchlick(NoL, k); }

// [Karis13 eq. 4], analytic k. Used by evaluateDirectLight.
float gSmithSchlickAnalytic(float roughness, float NoV, float NoL) {
    return gSmithSchlick(NoV, NoL, kSmithSchlickAnalytic(roughness));
}

// [Karis13 p.3], IBL k. Used by ibl_math (ground truth, LUT).
float gSmithSchlickIbl(float roughness, float NoV, float NoL) {
    return gSmithSchlick(NoV, NoL, kSmithSchlickIbl(roughness));
}

// [Karis13 eq. 4] rearranged: G / (4 NoL NoV) with the cosines cancelled.
float visSmithSchlick(float NoV, float NoL, float k) {
    return 0.25f / ((NoL * (1.0f - k) + k) * (NoV * (1.0f - k) + k));
}

// [Schlick94]: (1 - c)^5.
float fresnelWeightSchlick(float VoH) {
    float m = 1.0f - VoH;
    float m2 = m * m;
    return m2 * m2 * m;
}

// [Karis13 eq. 5]: 2^((-5.55473 c - 6.98316) c).
float fresnelWeightKaris(float VoH) { return std::exp2((-5.55473f * VoH - 6.98316f) * VoH); }

// [Seed]: 2^(-9.60232 c^8 - 8.58092 c).
float fresnelWeightSeed(float VoH) {
    float c2 = VoH * VoH;
    float c4 = c2 * c2;
    float c8 = c4 * c4;
    return std::exp2(-9.60232f * c8 - 8.58092f * VoH);
}

float fresnelWeight(int mode, float VoH) {
    if (mode == FRESNEL_KARIS) return fresnelWeightKaris(VoH);
    if (mode == FRESNEL_SEED) return fresnelWeightSeed(VoH);
    return fresnelWeightSchlick(VoH);
}

// [Schlick94].
glm::vec3 fSchlick(glm::vec3 f0, float VoH) { return f0 + (glm::vec3(1.0f) - f0) * fresnelWeightSchlick(VoH); }

// [Karis13 eq. 5].
glm::vec3 fSchlickKaris(glm::vec3 f0, float VoH) { return f0 + (glm::vec3(1.0f) - f0) * fresnelWeightKaris(VoH); }

// [Seed].
glm::vec3 fSchlickSeed(glm::vec3 f0, float VoH) { return f0 + (glm::vec3(1.0f) - f0) * fresnelWeightSeed(VoH); }

glm::vec3 fresnel(int mode, glm::vec3 f0, float VoH) {
    return f0 + (glm::vec3(1.0f) - f0) * fresnelWeight(mode, VoH);
}

// [Karis13 eq. 1]: Lambert.
glm::vec3 diffuseLambert(glm::vec3 diffuseColor) { return diffuseColor / kPi; }

// [Karis13 eq. 2]: Cook-Torrance D F G / (4 NoL NoV) = D Vis F, analytic k.
glm::vec3 specularGgx(float NoH, float NoV, float NoL, float VoH, glm::vec3 specularColor, float roughness,
                      int fresnelMode) {
    float D = dGgx(NoH, roughness);
    float Vis = visSmithSchlick(NoV, NoL, kSmithSchlickAnalytic(roughness));
    glm::vec3 F = fresnel(fresnelMode, specularColor, VoH);
    return D * Vis * F;
}

// [Karis13, "Shading Model"]: Lambert + GGX/Smith-Schlick/Schlick-Fresnel, times radiance NoL.
glm::vec3 evaluateDirectLightMode(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                  glm::vec3 specularColor, float roughness, glm::vec3 lightRadiance,
                                  int fresnelMode) {
    float NoL = saturate(glm::dot(N, L));
    if (NoL <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 Hu = V + L;  // zero when V = -L (then NoH = VoH = 0)
    glm::vec3 H = Hu * (1.0f / std::sqrt(std::max(glm::dot(Hu, Hu), 1e-12f)));
    float NoV = saturate(glm::dot(N, V));
    float NoH = saturate(glm::dot(N, H));
    float VoH = saturate(glm::dot(V, H));
    float r = std::max(roughness, kMinDirectRoughness);
    glm::vec3 brdf = diffuseLambert(diffuseColor) + specularGgx(NoH, NoV, NoL, VoH, specularColor, r, fresnelMode);
    return brdf * lightRadiance * NoL;
}

glm::vec3 evaluateDirectLight(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                              glm::vec3 specularColor, float roughness, glm::vec3 lightRadiance) {
    return evaluateDirectLightMode(N, V, L, diffuseColor, specularColor, roughness, lightRadiance,
                                   FRESNEL_DEFAULT);
}

// ---- BRDF_GLTF ----
//   [glTF-B]  glTF 2.0 Specification, Appendix B "BRDF Implementation".
//   [Viewer]  npm @khronosgroup/gltf-viewer 1.1.0, dist/gltf-viewer.module.js: brdfShader (3802),
//             punctualShader (3810), pbrShader (3800).

// [glTF-B] "Specular BRDF": height-correlated Smith visibility ([Viewer] V_GGX).
float visSmithGgxCorrelated(float NoV, float NoL, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    float gv = NoL * std::sqrt(a2 + (1.0f - a2) * NoV * NoV);
    float gl = NoV * std::sqrt(a2 + (1.0f - a2) * NoL * NoL);
    float d = gv + gl;
    return d > 0.0f ? 0.5f / d : 0.0f;
}

// [glTF-B] "Fresnel", fresnel_mix's fr with f90 = 1.
float gltfDielectricFresnel(float dielectricF0, float VoH) {
    return dielectricF0 + (1.0f - dielectricF0) * fresnelWeightSchlick(VoH);
}

// [glTF-B] "Metal BRDF and Dielectric BRDF", over diffuseColor / specularColor ([Viewer] pbrShader).
glm::vec3 evaluateDirectLightGltf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                  glm::vec3 specularColor, float dielectricF0, float roughness,
                                  glm::vec3 lightRadiance) {
    float NoL = saturate(glm::dot(N, L));
    if (NoL <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 Hu = V + L;
    glm::vec3 H = Hu * (1.0f / std::sqrt(std::max(glm::dot(Hu, Hu), 1e-12f)));
    float NoV = saturate(glm::dot(N, V));
    float NoH = saturate(glm::dot(N, H));
    float VoH = saturate(glm::dot(V, H));
    float r = std::max(roughness, kMinGltfRoughness);
    float D = dGgx(NoH, r);
    float Vis = visSmithGgxCorrelated(NoV, NoL, r);
    glm::vec3 F = fSchlick(specularColor, VoH);
    float Fd = gltfDielectricFresnel(dielectricF0, VoH);
    glm::vec3 brdf = diffuseLambert(diffuseColor) * (1.0f - Fd) + D * Vis * F;
    return brdf * lightRadiance * NoL;
}

// KHR_lights_punctual README "Range Property"; UE4 squares it ([Karis13] eq. 9).
float lightRangeWindow(float d2, float range, int brdfModel) {
    if (range <= 0.0f) return 1.0f;
    float r = d2 / (range * range);
    float window = saturate(1.0f - r * r);
    return brdfModel == BRDF_GLTF ? window : window * window;
}

}  // namespace gbl::shading
