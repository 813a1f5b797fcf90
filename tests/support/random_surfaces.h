#pragma once
// Seeded random Surfaces for the bit tests that hold encoders to each other (gpu_cpu_bits_test,
// layout_export_gpu_test): every member uniform over its range, normals unit and uniform in
// direction, emissive up to 8, positions within +-100 with z mostly in [0, 1] and some outside (a
// stored window depth rides in position.z: wiring_plan.h).
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "surface.h"

namespace gbl::test {

inline std::vector<Surface> randomSurfaces(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Surface> v(count);
    for (Surface& s : v) {
        glm::vec3 n;
        do n = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f - 1.0f;
        while (glm::dot(n, n) > 1.0f || glm::dot(n, n) < 1e-4f);
        s.normal = glm::normalize(n);
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
    }
    return v;
}

}  // namespace gbl::test
