#pragma once
// Surface: every shading attribute the G-buffer pass produces and the lighting pass consumes.
// C++ mirror of shaders/surface.glsl: the same member names in the same order.
#include <glm/glm.hpp>

namespace gbl {

struct Surface {
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  // world space, unit
    glm::vec3 baseColor{0.0f};           // linear
    float metallic = 0.0f;
    float roughness = 0.0f;              // perceptual; GGX alpha = roughness^2
    float specular = 0.0f;               // UE4 scalar specular: dielectric F0 = 0.08 * specular
    glm::vec3 specularColor{0.0f};       // F0, linear
    glm::vec3 diffuseColor{0.0f};        // Lambert albedo = baseColor * (1 - metallic)
    float occlusion = 1.0f;
    glm::vec3 emissive{0.0f};            // linear radiance
    glm::vec3 position{0.0f};            // world space (stored only by layouts that store `position`)
    // The material layers of glTF's PBR extensions (shaders/brdf_layers.glsl). 0 everywhere is "no
    // layer": what a layout that does not store one decodes (coat 0, sheen black, anisotropy 0).
    float coat = 0.0f;                         // KHR_materials_clearcoat: clearcoat, [0,1]
    float coatRoughness = 0.0f;                // clearcoatRoughness, perceptual
    glm::vec3 coatNormal{0.0f};                // unit, in the normal's space; 0: the base normal
    glm::vec3 sheenColor{0.0f};                // KHR_materials_sheen: sheenColor, linear
    float sheenRoughness = 0.0f;               // sheenRoughness, perceptual
    float anisotropyStrength = 0.0f;           // KHR_materials_anisotropy: strength, [0,1]
    glm::vec3 anisotropyDirection{0.0f};       // unit tangent highlights stretch along, in the
                                               // normal's space, orthogonal to the normal; 0: none
    float shadingModel = 0.0f;                 // reserved for the shading-model selector (the
                                               // material's GBL_LAYER_* bits); read by no pass yet
};

}  // namespace gbl
