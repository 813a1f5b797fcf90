#pragma once
// A procedural tangent-space normal map with detail at several scales, for the built-in ground.
#include "scene.h"

namespace gbl {

// size x size RGBA8, linear (srgb = false), tileable, deterministic (integer hashing only, no
// library random distributions). Height features, largest first: grooves between 8x8 tiles, a
// lattice of small round studs, two octaves of bumps, and a per-texel grain. Normals are glTF
// tangent space: +X towards increasing u, +Y up the image, encoded as n * 0.5 + 0.5.
Texture makeDetailNormalMap(int size);

}  // namespace gbl
