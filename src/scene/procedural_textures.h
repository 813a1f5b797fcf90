#pragma once
// Procedural textures of the built-in scene: each one stresses what a G-buffer layout can get
// wrong, and each is deterministic (integer hashing only), so every run renders the same pixels.
#include "scene.h"

namespace gbl {

// sRGB albedo of saturated hues in small tiles (4 x 4 texels) with 1-texel light grout: chroma
// that changes every few pixels, which chroma subsampling (Crysis 3's checkerboard YCbCr,
// Mavridis & Papaioannou 2012) cannot follow.
Texture makeMosaicAlbedo(int size);

// A panel of 16 x 16-texel tiles, each either metal or dielectric with its own roughness, split
// along sharp edges (the boundaries a metal/dielectric bit or a derived specular colour must
// keep). Returns the glTF metallic-roughness texture (linear; G = roughness, B = metallic); its
// base colour texture (sRGB; gold, copper, silver for metals, saturated paint for dielectrics)
// is makeTileBaseColor(size) with the same tiles.
Texture makeTileMetalRoughness(int size);
Texture makeTileBaseColor(int size);

// RGBA8 sRGB: a wire fence, alpha 1 on wires 2 texels wide every 16 texels (both directions),
// alpha 0 between: thin alpha-tested detail (glTF alphaMode MASK).
Texture makeFenceAlbedo(int size);

// sRGB emissive stripes (a sign): saturated colours at full and half brightness, black gaps.
Texture makeEmissiveStripes(int size);

}  // namespace gbl
