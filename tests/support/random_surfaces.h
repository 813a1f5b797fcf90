#pragma once
// Seeded random Surfaces for the bit tests that hold encoders to each other (gpu_cpu_bits_test,
// layout_export_gpu_test): every member uniform over its range, normals unit and uniform in
// direction, emissive up to 8, positions within +-100 with z mostly in [0, 1] and some outside (a
// stored window depth rides in position.z: wiring_plan.h). The layers (coat, coat roughness, sheen
// colour and roughness, anisotropy strength uniform in [0, 1], the coat normal and the anisotropy
// direction unit and uniform in direction; a quarter of the Surfaces without any layer, all 0)
// come from a stream of their own, so the other members are what they were before the layers.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "surface.h"

namespace gbl::test {

inline glm::vec3 randomUnitVector(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    glm::vec3 n;
    do n = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f;
    while (glm::dot(n, n) > 1.0f || glm::dot(n, n) < 1e-4f);
    return glm::normalize(n);
}

inline std::vector<Surface> randomSurfaces(size_t count, uint32_t seed) {
    std::mt19937 rng(seed), layers(seed ^ 0x9e3779b9u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Surface> v(count);
    for (Surface& s : v) {
        s.normal = randomUnitVector(rng);
        s.baseColor = {u(rng), u(rng), u(rng)};
        s.metallic = u(rng);
        s.roughness = u(rng);
        s.specular = u(rng);
        s.specularColor = {u(rng), u(rng), u(rng)};
        s.diffuseColor = {u(rng), u(rng), u(rng)};
        s.occlusion = u(rng);
        s.emissive = glm::vec3(u(rng), u(rng), u(rng)) * 8.0f;
        s.position = (glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f) * 100.0f;
        s.position.z = u(rng) * 1.2f - 0.1f;
        if (u(layers) < 0.25f) continue;  // no layer
        s.coat = u(layers);
        s.coatRoughness = u(layers);
        s.coatNormal = randomUnitVector(layers);
        s.sheenColor = {u(layers), u(layers), u(layers)};
        s.sheenRoughness = u(layers);
        s.anisotropyStrength = u(layers);
        s.anisotropyDirection = randomUnitVector(layers);
    }
    return v;
}

}  // namespace gbl::test
