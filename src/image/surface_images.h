#pragma once
// A decoded G-buffer as float images, one per Surface attribute (what the lighting pass saw),
// plus depth and coverage. The reference layout's SurfaceImages are the truth that attribute
// errors are measured against.
#include <cstdint>
#include <vector>

#include "image.h"

namespace gbl {

struct SurfaceImages {
    Image normal;         // 3 channels, world space
    Image baseColor;      // 3
    Image diffuseColor;   // 3
    Image specularColor;  // 3 (F0)
    Image roughness;      // 1
    Image metallic;       // 1
    Image occlusion;      // 1
    Image emissive;       // 3
    Image depth;          // 1: the depth buffer's value (as the layout's depth format stored it)
    Image viewDepth;      // 1: linear view-space distance along the view axis, from the depth
    std::vector<uint8_t> coverage;  // 1 where geometry covers the pixel
};

}  // namespace gbl
