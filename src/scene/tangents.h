#pragma once
// Per-vertex tangent frames for normal mapping when a mesh does not supply TANGENT.
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "scene.h"

namespace gbl {

// Fills vertices[].tangent for an indexed triangle list (indices relative to `vertices`).
// Per triangle, the tangent is the direction of increasing u and the bitangent the direction of
// decreasing v (glTF's uv origin is the image's top-left, and its normal maps have +Y pointing
// up the image); these are accumulated per vertex, weighted by triangle area, then made
// orthogonal to the normal (Gram-Schmidt). w = +1 or -1 so that B = cross(N, T) * w, glTF's
// convention. A vertex with no usable uv derivative (no uvs, degenerate or zero-area
// triangles) gets an arbitrary unit tangent perpendicular to its normal.
// Normals must be unit length.
void generateTangents(std::span<Vertex> vertices, std::span<const uint32_t> indices);

// A unit vector perpendicular to the unit vector n (stable for every direction).
glm::vec3 anyPerpendicular(const glm::vec3& n);

// Makes a supplied tangent unit and orthogonal to the unit normal n, and its w exactly +-1.
// Returns false when it cannot (non-finite, zero or parallel to n).
bool orthonormalizeTangent(const glm::vec3& n, glm::vec4& tangent);

}  // namespace gbl
