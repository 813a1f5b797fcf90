// Scene-wide helpers shared by the glTF loader and the built-in scene.
#include "scene.h"

#include <cmath>
#include <limits>

namespace gbl {

glm::mat2 TextureTransform::matrix() const {
    // rotation * scale, the rotation of glTF issue 1563 (scene.h): columns (c, -s) and (s, c).
    const float c = std::cos(rotation), s = std::sin(rotation);
    return glm::mat2(glm::vec2(c, -s) * scale.x, glm::vec2(s, c) * scale.y);
}

int Material::layers() const {
    int bits = 0;
    if (clearcoatFactor > 0.0f) bits |= kLayerCoat;
    if (sheenColorFactor.x > 0.0f || sheenColorFactor.y > 0.0f || sheenColorFactor.z > 0.0f) bits |= kLayerSheen;
    if (anisotropyStrength > 0.0f) bits |= kLayerAnisotropy;
    return bits;
}

Light defaultSun() {
    Light sun;
    sun.type = LightType::Directional;
    // Sits to the upper left in front of the scene, so it travels right, down and away from the
    // viewer: front faces are lit and shadows fall behind objects.
    sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, -0.6f));
    sun.color = glm::vec3(1.0f, 0.95f, 0.87f);  // warm white
    // glTF's lux, scaled for an exposure-free renderer: about what glTF viewers use by default.
    sun.intensity = 3.0f;
    return sun;
}

Bounds worldBounds(const Scene& scene) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    glm::vec3 lo(kInf), hi(-kInf);
    for (const Draw& draw : scene.draws) {
        for (uint32_t i = 0; i < draw.indexCount; ++i) {
            // Through the indices, so vertices no draw references do not widen the bounds.
            const uint32_t v = scene.indices[draw.firstIndex + i] + static_cast<uint32_t>(draw.vertexOffset);
            const glm::vec3 p = glm::vec3(draw.model * glm::vec4(scene.vertices[v].position, 1.0f));
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
    if (lo.x > hi.x) return Bounds{};  // nothing drawn
    return Bounds{lo, hi};
}

}  // namespace gbl
