#pragma once
// The environment the scene is lit by: an equirectangular (lat-long) linear RGB float image.
// Convention: u = 0.5 + atan2(d.x, -d.z) / (2 pi) ... (see environment_map.cpp: directionToEquirectUv),
// v = acos(d.y) / pi, row 0 = up (+Y).
#include <string>

#include <glm/glm.hpp>

#include "image.h"

namespace gbl {

struct EnvironmentMap {
    std::string source;  // file path or "built-in procedural sky"
    Image image;         // RGB float, width == 2 * height
};

// Loads .hdr or .exr and validates it: width must be 2 x height and at least 8x4; NaN, Inf and
// negative texels are a UserError naming the file, the first bad texel and the count.
EnvironmentMap loadEnvironmentMap(const std::string& path);

// Checks an in-memory map (used by loadEnvironmentMap, exposed for tests).
void validateEnvironmentImage(const Image& image, const std::string& source);

// Direction (unit, world space, +Y up) <-> equirect uv in [0,1]^2. Shared convention with
// shaders/environment.glsl.
glm::vec2 directionToEquirectUv(glm::vec3 direction);
glm::vec3 equirectUvToDirection(glm::vec2 uv);

// Bilinear lookup (wraps in u, clamps in v).
glm::vec3 sampleEquirect(const Image& image, glm::vec3 direction);

}  // namespace gbl
