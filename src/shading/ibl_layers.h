#pragma once
// Image-based light on the material layers on the CPU: the C++ mirror of shaders/ibl_layers.glsl
// (same names, same math; sources cited there). Where the GLSL calls the includer's
// sampleEnvironmentLod, environmentSampling[] and sheenAlbedo, the C++ takes them as arguments.
// Namespace gbl::shading.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "brdf_layers.h"
#include "ibl_math.h"

namespace gbl::shading {

// E(NoX, sheenRoughness) of the sheen BRDF (the GLSL includer's sheenAlbedo; sheen_albedo.h).
using SheenAlbedoFn = std::function<float(float NoX, float sheenRoughness)>;

// Anisotropic GGX half vector around N (pdf D_aniso NoH), the slopes of the isotropic sample
// stretched by (at, ab) along (T, B).
glm::vec3 importanceSampleGGXAnisotropic(glm::vec2 Xi, float at, float ab, glm::vec3 N, glm::vec3 T, glm::vec3 B);
// Cosine-weighted direction around N, pdf NoL / pi.
glm::vec3 sampleCosineHemisphere(glm::vec2 Xi, glm::vec3 N);

glm::vec3 prefilteredRadianceInShaderAnisotropic(const EnvironmentLodFn& sampleEnvironmentLod, glm::vec3 N,
                                                 glm::vec3 V, glm::vec3 T, glm::vec3 B, float at, float ab,
                                                 uint32_t numSamples);
glm::vec3 sheenRadianceInShader(const EnvironmentLodFn& sampleEnvironmentLod, glm::vec3 N, glm::vec3 V,
                                float sheenRoughness, uint32_t numSamples);

// The converged ground truth of coat(sheen(base)) without the base's SH diffuse (ibl_layers.glsl).
glm::vec3 iblGroundTruthLayeredMis(const EnvironmentLodFn& sampleEnvironmentLod,
                                   const std::vector<float>& environmentSampling, const SheenAlbedoFn& sheenAlbedo,
                                   glm::vec3 diffuseColor, glm::vec3 specularColor, float roughness, glm::vec3 N,
                                   glm::vec3 V, const Layers& ly, uint32_t numSamples, glm::vec4 shiftsBaseEnv,
                                   glm::vec4 shiftsCoatSheen);

}  // namespace gbl::shading
