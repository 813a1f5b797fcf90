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
    // The material layers (codec/surface.h), decoded only for a scene some material of which has
    // layers (GBL_LAYERS); empty otherwise, and then not measured. 0 is "no layer", as the layout
    // that does not store one decodes it. Directions in world space, as the normal; 0: none.
    Image coat;                 // 1: clear coat amount
    Image coatRoughness;        // 1
    Image coatNormal;           // 3: 0 = the base normal
    Image sheenColor;           // 3: linear
    Image sheenRoughness;       // 1
    Image anisotropyStrength;   // 1
    Image anisotropyDirection;  // 3: 0 = no direction
    bool hasLayers() const { return !coat.empty(); }
    // Allocates the seven layer images (zeros), width x height.
    void allocateLayers(int width, int height) {
        coat = Image(width, height, 1);
        coatRoughness = Image(width, height, 1);
        coatNormal = Image(width, height, 3);
        sheenColor = Image(width, height, 3);
        sheenRoughness = Image(width, height, 1);
        anisotropyStrength = Image(width, height, 1);
        anisotropyDirection = Image(width, height, 3);
    }
};

}  // namespace gbl
