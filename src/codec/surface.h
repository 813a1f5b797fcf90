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
};

}  // namespace gbl
