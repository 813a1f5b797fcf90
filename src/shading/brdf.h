#pragma once
// The UE4 (SIGGRAPH 2013) shading model on the CPU: the C++ mirror of shaders/brdf.glsl, same
// names, same math, line for line (see that file for the sources of each term, repeated in
// brdf.cpp). Namespace gbl::shading.
//
// Conventions (identical to the GLSL):
//   roughness = UE4 perceptual roughness in [0,1]; alpha = roughness^2.
//   Smith-Schlick k per path:
//     analytic lights (evaluateDirectLight, specularGgx): k = (roughness+1)^2/8
//     IBL (ibl_math: specularIBLGroundTruth, integrateBRDF, the LUT):  k = alpha/2
//   Default Fresnel: FRESNEL_KARIS (UE4's 2013 shipping choice, the most accurate exp2 form).
//
// Measured max |w(c) - (1-c)^5| of the Fresnel weights over c in [0,1] (1e6+1 points; brdf_test
// asserts measured <= bound and >= 0.95 bound, so these figures cannot go stale):
//   FRESNEL_KARIS  3.77e-3 at c = 0.055   [bound 4.0e-3]
//   FRESNEL_SEED   3.88e-2 at c = 0.100   [bound 4.0e-2]   (ten times worse than Karis')
//   (times (1 - f0) for F itself.)
// Float precision: dGgx's d = NoH^2 (alpha^2 - 1) + 1 cancels near NoH = 1; relative error
// ~1.2e-7 / alpha^2 at the peak (7.5e-5 at roughness 0.2, 1.2e-3 at roughness 0.1).
// White furnace of the analytic path (f0 = 1, no diffuse; quadrature over L in brdf_test): the
// (roughness+1)^2/8 remap darkens much more than the IBL k, e.g. directional albedo
//   roughness 0.3: 0.341 / 0.668 / 0.976 at NoV 0.2 / 0.5 / 1
//   roughness 0.5: 0.407 / 0.585 / 0.860;  roughness 1: 0.511 / 0.409 / 0.307 (k = 1/2 both paths).
#include <glm/glm.hpp>

namespace gbl::shading {

// ---- choices (int constants shared with shaders/brdf.glsl; brdf_test checks they agree) ----
inline constexpr int NDF_GGX = 0;
inline constexpr int GEOMETRY_SMITH_SCHLICK_ANALYTIC = 0;
inline constexpr int GEOMETRY_SMITH_SCHLICK_IBL = 1;
inline constexpr int FRESNEL_SCHLICK = 0;
inline constexpr int FRESNEL_KARIS = 1;
inline constexpr int FRESNEL_SEED = 2;
inline constexpr int DIFFUSE_LAMBERT = 0;
inline constexpr int FRESNEL_DEFAULT = FRESNEL_KARIS;
inline constexpr int BRDF_UE4 = 0;
inline constexpr int BRDF_GLTF = 1;

inline constexpr float kPi = 3.14159265358979323846f;
// GLSL's clamp(x, 0, 1), as the shaders write it.
inline float saturate(float x) { return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x; }
// evaluateDirectLight clamps roughness to at least this (GGX is a delta at roughness 0).
inline constexpr float kMinDirectRoughness = 0.045f;
// BRDF_GLTF's roughness floor (the Sample Viewer's anisotropic alpha floor; brdf.glsl says why).
inline constexpr float kMinGltfRoughness = 0.001f;

// GGX D, alpha = roughness^2: alpha^2 / (pi ((n.h)^2 (alpha^2-1) + 1)^2). 0/0 at roughness 0, NoH 1.
float dGgx(float NoH, float roughness);
// k = (roughness+1)^2/8 (analytic lights).
float kSmithSchlickAnalytic(float roughness);
// k = alpha/2 (IBL).
float kSmithSchlickIbl(float roughness);
// G1 = NoX / (NoX (1-k) + k).
float g1SmithSchlick(float NoX, float k);
// G = G1(NoV) G1(NoL).
float gSmithSchlick(float NoV, float NoL, float k);
float gSmithSchlickAnalytic(float roughness, float NoV, float NoL);
float gSmithSchlickIbl(float roughness, float NoV, float NoL);
// G / (4 NoL NoV) = 1 / (4 (NoL(1-k)+k)(NoV(1-k)+k)).
float visSmithSchlick(float NoV, float NoL, float k);

// Fresnel weights w(c), F = f0 + (1 - f0) w(VoH).
float fresnelWeightSchlick(float VoH);
float fresnelWeightKaris(float VoH);
float fresnelWeightSeed(float VoH);
float fresnelWeight(int mode, float VoH);  // FRESNEL_*; unknown -> exact Schlick

glm::vec3 fSchlick(glm::vec3 f0, float VoH);
glm::vec3 fSchlickKaris(glm::vec3 f0, float VoH);
glm::vec3 fSchlickSeed(glm::vec3 f0, float VoH);
glm::vec3 fresnel(int mode, glm::vec3 f0, float VoH);

// Lambert: c_diff / pi.
glm::vec3 diffuseLambert(glm::vec3 diffuseColor);

// D * Vis * F with the analytic k; cosines already in [0,1].
glm::vec3 specularGgx(float NoH, float NoV, float NoL, float VoH, glm::vec3 specularColor, float roughness,
                      int fresnelMode);

// Radiance towards V from one analytic light from L: (Lambert + D Vis F) * lightRadiance * NoL.
// N, V, L unit and pointing away from the surface; roughness clamped to kMinDirectRoughness;
// zero when NoL <= 0.
glm::vec3 evaluateDirectLightMode(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                  glm::vec3 specularColor, float roughness, glm::vec3 lightRadiance,
                                  int fresnelMode);
// evaluateDirectLightMode with FRESNEL_DEFAULT.
glm::vec3 evaluateDirectLight(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                              glm::vec3 specularColor, float roughness, glm::vec3 lightRadiance);

// ---- BRDF_GLTF: the glTF 2.0 specification's BRDF (Appendix B) as the Khronos glTF Sample
// Viewer 1.1.0 computes it (shaders/brdf.glsl cites the viewer's lines) ----
// Height-correlated Smith visibility, alpha = roughness^2: 0.5 / (NoV sqrt(a^2 + (1-a^2) NoL^2) +
// NoL sqrt(a^2 + (1-a^2) NoV^2)); 0 where both cosines are 0.
float visSmithGgxCorrelated(float NoV, float NoL, float roughness);
// The dielectric's Schlick Fresnel with f90 = 1: f0 + (1 - f0)(1 - VoH)^5.
float gltfDielectricFresnel(float dielectricF0, float VoH);
// diffuse_brdf(diffuseColor) (1 - F_dielectric) + D Vis F_Schlick(specularColor), times
// lightRadiance NoL; roughness floored to kMinGltfRoughness; zero when NoL <= 0.
glm::vec3 evaluateDirectLightGltf(glm::vec3 N, glm::vec3 V, glm::vec3 L, glm::vec3 diffuseColor,
                                  glm::vec3 specularColor, float dielectricF0, float roughness,
                                  glm::vec3 lightRadiance);
// KHR_lights_punctual's range window: clamp(1 - (d/range)^4, 0, 1), squared under BRDF_UE4; 1
// where range <= 0.
float lightRangeWindow(float d2, float range, int brdfModel);

}  // namespace gbl::shading
