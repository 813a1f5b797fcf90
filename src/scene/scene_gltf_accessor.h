#pragma once
// Reads glTF accessors into plain arrays, validating every byte range and type first, so a
// malformed file becomes a UserError instead of an out-of-bounds read.
#include <cstdint>
#include <string>
#include <vector>

#include "scene_gltf_context.h"

namespace gbl {

// Which vertex attribute an accessor feeds; decides the accepted type and component types.
enum class GltfVertexAttribute { Position, Normal, Tangent, TexCoord };

// Components per element for an attribute: 3, 3, 4, 2.
int componentsOf(GltfVertexAttribute kind);

// The accessor's elements as floats (count * componentsOf(kind) values), with glTF's
// normalisation rules applied to normalised integer components and sparse substitution done.
// `where` names the mesh and primitive for error messages.
std::vector<float> readAttribute(const GltfContext& ctx, int accessorIndex, GltfVertexAttribute kind,
                                 const std::string& where);

// An index accessor (SCALAR unsigned byte/short/int) as 32-bit indices.
std::vector<uint32_t> readIndices(const GltfContext& ctx, int accessorIndex, const std::string& where);

// The element count of an accessor, after checking that the index is valid.
size_t accessorCount(const GltfContext& ctx, int accessorIndex, const std::string& where);

}  // namespace gbl
