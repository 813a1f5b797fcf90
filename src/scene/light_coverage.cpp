#include "light_coverage.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace gbl {

double meanLightVolumesPerPixel(const std::vector<Light>& lights, const Camera& camera, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0) return 0.0;
    double full = 0.0;
    std::vector<const Light*> spheres;
    for (const Light& l : lights) {
        if (l.type == LightType::Directional || !(l.range > 0.0f)) full += 1.0;
        else spheres.push_back(&l);
    }
    if (spheres.empty()) return full;
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const double tanHalf = std::tan(double(camera.yFovRadians) * 0.5);
    const double aspect = double(width) / double(height);
    const uint32_t gx = std::min<uint32_t>(width, 256), gy = std::min<uint32_t>(height, 256);
    double covered = 0.0;
    for (uint32_t j = 0; j < gy; ++j) {
        const double ndcY = 1.0 - 2.0 * (double(j) + 0.5) / double(gy);
        for (uint32_t i = 0; i < gx; ++i) {
            const double ndcX = 2.0 * (double(i) + 0.5) / double(gx) - 1.0;
            const glm::dvec3 dir = glm::normalize(glm::dvec3(forward) + glm::dvec3(right) * (ndcX * tanHalf * aspect) +
                                                  glm::dvec3(up) * (ndcY * tanHalf));
            for (const Light* l : spheres) {
                const glm::dvec3 oc = glm::dvec3(camera.position) - glm::dvec3(l->position);
                const double r2 = double(l->range) * double(l->range);
                const double c = glm::dot(oc, oc) - r2;
                if (c <= 0.0) {  // the camera is inside the volume
                    covered += 1.0;
                    continue;
                }
                const double b = glm::dot(oc, dir);
                if (b < 0.0 && b * b - c >= 0.0) covered += 1.0;  // in front of the camera, the ray meets it
            }
        }
    }
    return full + covered / (double(gx) * double(gy));
}

}  // namespace gbl
