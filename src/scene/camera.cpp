// Default framing for scenes without a camera of their own.
#include <algorithm>
#include <cmath>

#include "scene.h"

namespace gbl {

Camera frameBounds(const Bounds& bounds, float aspect) {
    Camera camera;
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) aspect = 1.0f;

    const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
    float radius = 0.5f * glm::length(bounds.max - bounds.min);
    // A point or empty scene still needs a usable camera; anything finite and positive will do.
    if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;

    // Fit the bounding sphere into the narrower of the two fields of view.
    const float halfY = 0.5f * camera.yFovRadians;
    const float halfX = std::atan(std::tan(halfY) * aspect);
    const float halfFov = std::min(halfX, halfY);
    const float distance = radius / std::sin(halfFov) * 1.05f;  // 5% margin around the sphere

    // From the front (+Z), a little above, so tops of objects read as 3D.
    const glm::vec3 viewDir = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));
    camera.position = centre + viewDir * distance;
    camera.target = centre;
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    // Near and far hug the bounding sphere, so depth precision scales with the scene: a 6 cm
    // model gets a millimetre-scale near plane, a 100 m one a metre-scale one.
    camera.zNear = std::max(distance - radius, 1e-3f * distance) * 0.5f;
    camera.zFar = (distance + radius) * 2.0f;
    camera.fromFile = false;
    camera.framed = true;
    return camera;
}

}  // namespace gbl
