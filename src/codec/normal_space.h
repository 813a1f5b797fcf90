#pragma once
// The CPU mirror of shaders/normal_space.glsl: a layout's [space] (layout.h StoredSpace). The
// G-buffer pass transforms the Surface's normal (and position) into the stored space before the
// generated writeGBuffer, and the lighting and decode passes transform back after readGBuffer; the
// codec (cpu_codec.h, wiring_codegen.h) is space-agnostic and sees stored-space values only.
// The axis swap is exact; the view transform is the same float arithmetic as the GLSL (up to the
// order of the matrix product's additions), so tests compare it with a tolerance, not bits.
#include <glm/glm.hpp>

#include "layout.h"

namespace gbl {

// Y-up -> Z-up, right-handed: the +90 degree rotation about X, (x, y, z) -> (x, -z, y).
inline glm::vec3 yUpToZUp(glm::vec3 v) { return {v.x, -v.z, v.y}; }
inline glm::vec3 zUpToYUp(glm::vec3 v) { return {v.x, v.z, -v.y}; }

inline glm::vec3 directionToStored(glm::vec3 n, StoredSpace space, const glm::mat4& view) {
    if (space == StoredSpace::WorldZUp) return yUpToZUp(n);
    if (space == StoredSpace::View) return glm::mat3(view) * n;
    return n;
}
inline glm::vec3 directionFromStored(glm::vec3 n, StoredSpace space, const glm::mat4& view) {
    if (space == StoredSpace::WorldZUp) return zUpToYUp(n);
    if (space == StoredSpace::View) return n * glm::mat3(view);
    return n;
}
inline glm::vec3 pointToStored(glm::vec3 p, StoredSpace space, const glm::mat4& view) {
    if (space == StoredSpace::WorldZUp) return yUpToZUp(p);
    if (space == StoredSpace::View) return glm::vec3(view * glm::vec4(p, 1.0f));
    return p;
}
inline glm::vec3 pointFromStored(glm::vec3 p, StoredSpace space, const glm::mat4& view) {
    if (space == StoredSpace::WorldZUp) return zUpToYUp(p);
    if (space == StoredSpace::View) return (p - glm::vec3(view[3])) * glm::mat3(view);
    return p;
}

}  // namespace gbl
