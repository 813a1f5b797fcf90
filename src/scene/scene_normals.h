#pragma once
// Vertex normals for meshes that lack them or carry broken ones.
#include <cstdint>
#include <span>
#include <vector>

#include "scene.h"

namespace gbl {

// glTF: "When normals are not specified, client implementations MUST calculate flat normals."
// Flat shading needs one vertex per triangle corner, so this un-shares vertices: afterwards
// vertices has indices.size() entries and indices is 0, 1, 2, ...
void makeFlatNormals(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices);

// Normalises every normal; one that is zero, non-finite or tiny is replaced by the area-weighted
// average of the faces around its vertex (or +Z if those are degenerate too).
// Returns how many were replaced.
size_t repairNormals(std::span<Vertex> vertices, std::span<const uint32_t> indices);

}  // namespace gbl
