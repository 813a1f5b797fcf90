#pragma once
// Procedural textures of the built-in scene: each one stresses what a G-buffer layout can get
// wrong, and each is deterministic (integer hashing only), so every run renders the same pixels.
#include <vector>

#include "scene.h"

namespace gbl {

// sRGB albedo of saturated hues in small tiles (4 x 4 texels) with 1-texel light grout: chroma
// that changes every few pixels, which chroma subsampling (Crysis 3's checkerboard YCbCr,
// Mavridis & Papaioannou 2012) cannot follow.
Texture makeMosaicAlbedo(int size);

// A panel of 16 x 16-texel tiles, each either metal or dielectric with its own roughness, split
// along sharp edges (the boundaries a metal/dielectric bit or a derived specular colour must
// keep). Returns the tiles' packed occlusion-roughness-metallic texture, as real assets pack it
// (linear; R = occlusion, G = roughness, B = metallic: glTF's occlusionTexture and
// metallicRoughnessTexture may share it): the occlusion darkens the grooves between the tiles, 0.35
// in the groove and 0.7 beside it, 1 elsewhere. Its base colour texture (sRGB; gold, copper,
// silver for metals, saturated paint for dielectrics) is makeTileBaseColor(size) with the same tiles.
Texture makeTileMetalRoughness(int size);
Texture makeTileBaseColor(int size);

// RGBA8 sRGB: a wire fence, alpha 1 on wires 2 texels wide every 16 texels (both directions),
// alpha 0 between: thin alpha-tested detail (glTF alphaMode MASK).
Texture makeFenceAlbedo(int size);

// sRGB emissive stripes (a sign): saturated colours at full and half brightness, black gaps.
Texture makeEmissiveStripes(int size);

// A sphere that shades the ground beneath it.
struct OccludingSphere {
    glm::vec3 centre;
    float radius = 0.0f;
};

// Linear RGBA8, R = the ambient occlusion of the square ground plane y = 0, `groundSize` metres
// wide and centred at the origin (uv as makeGroundPlane: u along +X, v along +Z), under `spheres`
// (G, B, A 255): what a baker writes into an occlusion map. A sphere of radius r whose centre is d
// from the texel and h above the ground hides h r^2 / d^3 of its cosine-weighted sky (the form
// factor of a sphere wholly above the horizon, exact while h >= r); several multiply, each hiding
// its share of what the others leave (exact for one sphere; the usual blend of occluders, as
// Kontkanen and Laine's ambient occlusion fields, 2005, combine them), so spheres stacked above one
// another are not counted twice. 0 where a sphere touches the ground, soft contact shadows around it.
Texture makeGroundOcclusion(int size, float groundSize, const std::vector<OccludingSphere>& spheres);

}  // namespace gbl
