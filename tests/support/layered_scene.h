#pragma once
// The sphere grid of the built-in scene with the material layers on every fourth sphere: from the
// second on coated (factor 1, coat roughness 0.15), from the third with sheen (colour
// (0.9, 0.7, 0.4), roughness 0.5), from the fourth anisotropic (strength 0.8, rotation 0.7); the
// others and the ground plain. The tests of the layers' shading, decode and metrics share it.
#include "scene.h"

namespace gbl::test {

inline void addLayersToSphereGrid(Scene& scene) {
    for (size_t i = 0; i + 1 < scene.materials.size(); ++i) {
        Material& m = scene.materials[i];
        if (i % 4 == 1) {
            m.clearcoatFactor = 1.0f;
            m.clearcoatRoughnessFactor = 0.15f;
        } else if (i % 4 == 2) {
            m.sheenColorFactor = glm::vec3(0.9f, 0.7f, 0.4f);
            m.sheenRoughnessFactor = 0.5f;
        } else if (i % 4 == 3) {
            m.anisotropyStrength = 0.8f;
            m.anisotropyRotation = 0.7f;
        }
    }
}

}  // namespace gbl::test
