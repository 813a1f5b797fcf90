#pragma once
// The environment the scene is lit by: an equirectangular (lat-long) linear RGB float image.
// Convention: u = 0.5 + atan2(d.x, -d.z) / (2 pi) ... (see environment_map.cpp: directionToEquirectUv),
// v = acos(d.y) / pi, row 0 = up (+Y).
#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "image.h"

namespace gbl {

struct EnvironmentMap {
    std::string source;  // file path or "built-in procedural sky"
    Image image;         // RGB float, width == 2 * height
    size_t clampedNegativeTexels = 0;  // values in [-kEnvironmentRingingTolerance, 0) set to 0 on load
};

// Lossy EXR compression (DWAA/DWAB: a DCT on half floats) rings around sharp edges and leaves
// small negative values next to black: Blender's bundled world maps hold 3 to ~9000 of them,
// down to about -0.004. Real data is never negative, but texels within this tolerance below 0
// are codec noise, not a broken map, so they are clamped to 0 (and counted) rather than refused.
// 1/64 is ~4x the worst ringing seen and far below any deliberate (e.g. sign-flipped) value.
constexpr float kEnvironmentRingingTolerance = 1.0f / 64.0f;  // 0.015625
// The brightest texel accepted: about the sun's disc in cd/m^2 (1.6e9), far above any captured
// sky, and low enough that sums over a whole map stay far from float overflow.
constexpr float kEnvironmentMaxValue = 1e9f;

// Loads .hdr or .exr and validates it: width must be 2 x height and at least 8x4; NaN, Inf and
// texels below -kEnvironmentRingingTolerance are a UserError naming the file, the first bad
// texel and the count. Negatives within the tolerance are clamped to 0 and counted in
// clampedNegativeTexels (callers may print a note when it is non-zero).
EnvironmentMap loadEnvironmentMap(const std::string& path);

// Checks an in-memory map (used by loadEnvironmentMap, exposed for tests). Negatives within
// kEnvironmentRingingTolerance pass; clampEnvironmentRinging removes them.
void validateEnvironmentImage(const Image& image, const std::string& source);
// Sets every value in [-kEnvironmentRingingTolerance, 0) to 0 (-0.0 is left as is); returns
// how many were changed. Call after validateEnvironmentImage.
size_t clampEnvironmentRinging(Image& image);

// Direction (unit, world space, +Y up) <-> equirect uv in [0,1]^2. Shared convention with
// shaders/environment_map.glsl.
glm::vec2 directionToEquirectUv(glm::vec3 direction);
glm::vec3 equirectUvToDirection(glm::vec2 uv);

// Bilinear lookup (wraps in u, clamps in v).
glm::vec3 sampleEquirect(const Image& image, glm::vec3 direction);

}  // namespace gbl
