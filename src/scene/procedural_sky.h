#pragma once
// The built-in HDR environment used when no --env is given: a coloured sky gradient, a ground,
// and a small, very bright sun disc (so specular highlights and IBL both have a clear key light).
#include <glm/glm.hpp>

#include "environment_map.h"

namespace gbl {

struct SkyParameters {
    glm::vec3 sunDirection = glm::normalize(glm::vec3(-0.4f, 0.6f, 0.5f));  // towards the sun
    glm::vec3 sunRadiance{20000.0f, 18000.0f, 15000.0f};
    float sunAngularRadius = 0.02f;  // radians
    glm::vec3 zenithColor{0.25f, 0.45f, 1.0f};
    glm::vec3 horizonColor{1.0f, 0.9f, 0.75f};
    glm::vec3 groundColor{0.25f, 0.22f, 0.2f};
};

EnvironmentMap makeProceduralSky(int width = 1024, const SkyParameters& params = {});

}  // namespace gbl
