// Primitive loading: attributes, indices, validation, then normal and tangent fix-ups.
#include "scene_gltf_geometry.h"

#include <cmath>

#include "scene_gltf_accessor.h"
#include "scene_normals.h"
#include "tangents.h"

namespace gbl {
namespace {

int attributeAccessor(const tinygltf::Primitive& prim, const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

bool allFinite(const std::vector<float>& values, size_t& firstBad) {
    for (size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            firstBad = i;
            return false;
        }
    }
    return true;
}

std::string formatFloat(float v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
    return std::to_string(v);
}

}  // namespace

std::optional<PrimitiveGeometry> loadTrianglePrimitive(const GltfContext& ctx, size_t meshIndex,
                                                       size_t primitiveIndex) {
    const tinygltf::Mesh& mesh = ctx.model.meshes[meshIndex];
    const tinygltf::Primitive& prim = mesh.primitives[primitiveIndex];
    const std::string where = describeItem("mesh", meshIndex, mesh.name) + " primitive " + std::to_string(primitiveIndex);

    // tinygltf leaves mode at -1 when the file omits it; glTF's default is TRIANGLES.
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) return std::nullopt;
    const int positionAccessor = attributeAccessor(prim, "POSITION");
    if (positionAccessor < 0) return std::nullopt;

    const std::vector<float> positions = readAttribute(ctx, positionAccessor, GltfVertexAttribute::Position, where);
    const size_t vertexCount = positions.size() / 3;
    if (vertexCount == 0) return std::nullopt;
    // Non-finite positions are an error, not a dropped primitive: they would poison the bounds
    // and the camera, and silently losing geometry hides the exporter bug.
    if (size_t bad = 0; !allFinite(positions, bad))
        ctx.fail(where + ": POSITION accessor " + std::to_string(positionAccessor),
                 "vertex " + std::to_string(bad / 3) + " has a non-finite coordinate (" + formatFloat(positions[bad]) + ")",
                 "fix or remove the broken vertices in the source model and re-export");

    // Every other attribute must describe the same vertices.
    auto readMatching = [&](const char* name, GltfVertexAttribute kind) -> std::vector<float> {
        const int index = attributeAccessor(prim, name);
        if (index < 0) return {};
        const size_t count = accessorCount(ctx, index, where + ": " + name);
        if (count != vertexCount)
            ctx.fail(where + ": " + name + " accessor " + std::to_string(index),
                     "has " + std::to_string(count) + " elements but POSITION has " + std::to_string(vertexCount),
                     "all attributes of a primitive must have the same count; re-export the file");
        return readAttribute(ctx, index, kind, where);
    };
    const std::vector<float> normals = readMatching("NORMAL", GltfVertexAttribute::Normal);
    const std::vector<float> tangents = readMatching("TANGENT", GltfVertexAttribute::Tangent);
    const std::vector<float> uvs = readMatching("TEXCOORD_0", GltfVertexAttribute::TexCoord);
    // The second set, for textures whose texCoord (or KHR_texture_transform texCoord) is 1.
    const std::vector<float> uvs1 = readMatching("TEXCOORD_1", GltfVertexAttribute::TexCoord);
    for (const auto& [set, values] : {std::pair<const char*, const std::vector<float>*>{"TEXCOORD_0", &uvs},
                                      std::pair<const char*, const std::vector<float>*>{"TEXCOORD_1", &uvs1}})
        if (size_t bad = 0; !allFinite(*values, bad))
            ctx.fail(where + ": " + set + " accessor " + std::to_string(attributeAccessor(prim, set)),
                     "vertex " + std::to_string(bad / 2) + " has a non-finite texture coordinate",
                     "fix the UVs in the source model and re-export");

    PrimitiveGeometry geometry;
    geometry.vertices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) {
        Vertex& v = geometry.vertices[i];
        v.position = glm::vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
        v.normal = normals.empty() ? glm::vec3(0.0f) : glm::vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
        v.tangent = tangents.empty() ? glm::vec4(0.0f)
                                     : glm::vec4(tangents[4 * i], tangents[4 * i + 1], tangents[4 * i + 2], tangents[4 * i + 3]);
        v.uv = uvs.empty() ? glm::vec2(0.0f) : glm::vec2(uvs[2 * i], uvs[2 * i + 1]);
        v.uv1 = uvs1.empty() ? glm::vec2(0.0f) : glm::vec2(uvs1[2 * i], uvs1[2 * i + 1]);
    }

    if (prim.indices >= 0) {
        geometry.indices = readIndices(ctx, prim.indices, where);
        for (size_t i = 0; i < geometry.indices.size(); ++i) {
            if (geometry.indices[i] >= vertexCount)
                ctx.fail(where + ": indices accessor " + std::to_string(prim.indices),
                         "index " + std::to_string(i) + " is " + std::to_string(geometry.indices[i]) +
                             ", out of range for " + std::to_string(vertexCount) + " vertices",
                         "the file is corrupt or its exporter is broken; re-export it");
        }
    } else {
        geometry.indices.resize(vertexCount);  // non-indexed: vertices in order
        for (size_t i = 0; i < vertexCount; ++i) geometry.indices[i] = static_cast<uint32_t>(i);
    }
    if (geometry.indices.size() % 3 != 0)
        ctx.fail(where, std::to_string(geometry.indices.size()) + " vertices/indices do not form whole triangles",
                 "a TRIANGLES primitive needs a multiple of 3; re-export the file");
    if (geometry.indices.empty()) return std::nullopt;

    if (normals.empty()) {
        makeFlatNormals(geometry.vertices, geometry.indices);
    } else {
        repairNormals(geometry.vertices, geometry.indices);  // e.g. zero normals in BoxBadNormals
    }

    bool tangentsUsable = !tangents.empty();
    for (Vertex& v : geometry.vertices) {
        if (!tangentsUsable) break;
        tangentsUsable = orthonormalizeTangent(v.normal, v.tangent);
    }
    // Generated for every primitive without usable tangents, not only normal-mapped ones: the
    // renderer then never sees a zero tangent, and the cost is a few ms on the largest model.
    if (!tangentsUsable) generateTangents(geometry.vertices, geometry.indices);
    return geometry;
}

}  // namespace gbl
