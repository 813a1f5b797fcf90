#pragma once
// The material layers of glTF 2.0's PBR extensions over the UE4 base BRDF on the CPU: the C++
// mirror of shaders/brdf_layers.glsl, same names, same math, line for line (the sources of each
// formula are cited there and in brdf_layers.cpp). Namespace gbl::shading.
//
//   clear coat  KHR_materials_clearcoat: coated = mix(material, D V (Nc, coat roughness^2),
//               clearcoat (0.04 + 0.96 (1 - |V.Nc|)^5)); emission darkened by the same weight.
//   sheen       KHR_materials_sheen: Charlie D and V (Conty & Kulla 2017), base scaled by
//               min(1 - max3(c) E(NoV), 1 - max3(c) E(NoL)), E from sheen_albedo.h.
//   anisotropy  KHR_materials_anisotropy: at = mix(alpha, 1, strength^2), ab = alpha, Burley's D,
//               the anisotropic height-correlated V; the bent normal for one pre-filtered look-up.
// Order: coat(sheen(base)). A layer of amount 0 leaves the base bit for bit.
#include <glm/glm.hpp>

namespace gbl::shading {

inline constexpr int GBL_LAYER_COAT = 1;
inline constexpr int GBL_LAYER_SHEEN = 2;
inline constexpr int GBL_LAYER_ANISOTROPY = 4;

inline constexpr float kCoatF0 = 0.04f;
inline constexpr float kMinSheenRoughness = 0.045f;
inline constexpr float kMinSheenNoV = 1e-4f;
inline constexpr float kMinGltfSheenRoughness = 0.000001f;  // the Sample Viewer's (brdf_layers.glsl)

struct Layers {
    float coat = 0.0f;
    float coatRoughness = 0.0f;
    glm::vec3 coatNormal{0.0f, 0.0f, 1.0f};
    glm::vec3 sheenColor{0.0f};
    float sheenRoughness = 0.0f;
    float anisotropy = 0.0f;
    glm::vec3 anisotropyT{1.0f, 0.0f, 0.0f};
    glm::vec3 anisotropyB{0.0f, 1.0f, 0.0f};
};

float max3(glm::vec3 v);

float coatNoV(glm::vec3 Nc, glm::vec3 V);  // |V.Nc|, at most 1
float coatFresnel(float NcoV);
float coatSpecular(float NcoH, float NcoV, float NcoL, float coatRoughness);

float dCharlie(float NoH, float sheenRoughness);
float sheenLambdaCurve(float x, float alphaG);
float lambdaSheen(float cosTheta, float alphaG);
float visCharlie(float NoV, float NoL, float sheenRoughness);
float sheenBrdf(float NoH, float NoV, float NoL, float sheenRoughness);
float sheenAlbedoScaling(glm::vec3 sheenColor, float albedoV, float albedoL);

float anisotropicAlphaT(float roughness, float anisotropy);
float dGgxAnisotropic(float NoH, float ToH, float BoH, float at, float ab);
float visGgxAnisotropic(float NoL, float NoV, float BoV, float ToV, float ToL, float BoL, float at, float ab);

glm::vec3 evaluateDirectLightAnisotropicMode(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 T, glm::vec3 B,
                                             float anisotropy, glm::vec3 diffuseColor, glm::vec3 specularColor,
                                             float roughness, glm::vec3 lightRadiance, int fresnelMode);
glm::vec3 evaluateDirectLightLayeredMode(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                         glm::vec3 specularColor, float roughness, const Layers& ly,
                                         float sheenAlbedoV, float sheenAlbedoL, glm::vec3 lightRadiance,
                                         int fresnelMode);
glm::vec3 coatedEmission(glm::vec3 emission, const Layers& ly, glm::vec3 V);
glm::vec3 anisotropicReflection(glm::vec3 N, glm::vec3 V, glm::vec3 B, float anisotropy, float roughness);

// BRDF_GLTF: the same layering over evaluateDirectLightGltf with the Sample Viewer's clamps
// (sheen roughness >= 1e-6 and V_Sheen in [0, 1]; the coat's n.v clamped, not |.|; the anisotropic
// lobe's alpha_b >= 0.001, NoH >= 0.001, NoV unclamped).
float sheenBrdfGltf(float NoH, float NoV, float NoL, float sheenRoughness);
glm::vec3 evaluateDirectLightAnisotropicGltf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 T, glm::vec3 B,
                                             float anisotropy, glm::vec3 diffuseColor, glm::vec3 specularColor,
                                             float dielectricF0, float roughness, glm::vec3 lightRadiance);
float coatNoVGltf(glm::vec3 Nc, glm::vec3 V);
glm::vec3 evaluateDirectLightLayeredGltf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                         glm::vec3 specularColor, float dielectricF0, float roughness,
                                         const Layers& ly, float sheenAlbedoV, float sheenAlbedoL,
                                         glm::vec3 lightRadiance);
glm::vec3 coatedEmissionGltf(glm::vec3 emission, const Layers& ly, glm::vec3 V);

}  // namespace gbl::shading
