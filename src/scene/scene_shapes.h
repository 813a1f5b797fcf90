#pragma once
// Procedural meshes for the built-in scene, with exact analytic normals and tangents.
#include <cstdint>
#include <vector>

#include "scene.h"

namespace gbl {

struct ShapeMesh {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // counter-clockwise front faces, as in glTF
};

// A UV sphere centred at the origin: `segments` around (u = 0..1 starting at +Z, going towards
// +X), `rings` from the north pole (v = 0) to the south pole (v = 1). Triangles that collapse at
// the poles are left out. Tangents follow u; the bitangent points to decreasing v (north), the
// same convention generateTangents uses.
ShapeMesh makeUvSphere(float radius, int segments, int rings);

// A horizontal square in the XZ plane at y = 0, facing +Y, `cells` x `cells` quads, uv 0..1 with
// u along +X and v along +Z.
ShapeMesh makeGroundPlane(float size, int cells);

}  // namespace gbl
