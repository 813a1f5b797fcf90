#pragma once
// Turns one glTF mesh primitive into validated vertices and indices with unit normals and
// tangent frames.
#include <cstdint>
#include <optional>
#include <vector>

#include "scene.h"
#include "scene_gltf_context.h"

namespace gbl {

struct PrimitiveGeometry {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // relative to `vertices`, a triangle list
};

// Empty when the primitive draws no triangles and may be skipped: points, lines, strips and
// fans (only mode 4, TRIANGLES, is supported), no POSITION (glTF: clients SHOULD skip those), or
// zero vertices. Anything malformed throws a UserError naming mesh, primitive and accessor.
std::optional<PrimitiveGeometry> loadTrianglePrimitive(const GltfContext& ctx, size_t meshIndex,
                                                       size_t primitiveIndex);

}  // namespace gbl
