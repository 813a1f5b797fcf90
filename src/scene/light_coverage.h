#pragma once
// How many light volumes cover a pixel: what a deferred renderer that draws light volumes reads
// the G-buffer for (compare --lighting volumes).
#include <cstdint>
#include <vector>

#include "scene.h"

namespace gbl {

// The mean, over a width x height view from `camera`, of the light volumes covering a pixel:
// a directional light, or a point or spot light of infinite range (glTF range 0), is drawn as a
// full-screen pass and covers every pixel; a point or spot light of finite range is drawn as its
// bounding sphere (the range about its position: a spot's cone lies inside it, so the count is an
// upper bound for spots) and covers the pixels whose view ray meets the sphere (all of them when
// the camera is inside). No stencil or depth-bounds culling: the volume's screen footprint.
// Sampled at the centres of a grid of at most 256 x 256 cells of the view.
double meanLightVolumesPerPixel(const std::vector<Light>& lights, const Camera& camera, uint32_t width, uint32_t height);

}  // namespace gbl
