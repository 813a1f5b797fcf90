// Tangent generation: area-weighted accumulation of per-triangle uv derivatives.
#include "tangents.h"

#include <cmath>
#include <vector>

namespace gbl {

glm::vec3 anyPerpendicular(const glm::vec3& n) {
    // Cross with the world axis least aligned with n, so the result never degenerates.
    const glm::vec3 a = std::abs(n.x) < 0.57f ? glm::vec3(1, 0, 0)
                        : std::abs(n.y) < 0.57f ? glm::vec3(0, 1, 0)
                                                : glm::vec3(0, 0, 1);
    return glm::normalize(glm::cross(n, a));
}

bool orthonormalizeTangent(const glm::vec3& n, glm::vec4& tangent) {
    glm::vec3 t(tangent);
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z)) return false;
    t -= n * glm::dot(n, t);
    const float len = glm::length(t);
    if (!(len > 1e-6f)) return false;
    // w is a sign; some exporters write 0 or tiny values. Treat those as +1 (right-handed).
    tangent = glm::vec4(t / len, tangent.w < 0.0f ? -1.0f : 1.0f);
    return true;
}

void generateTangents(std::span<Vertex> vertices, std::span<const uint32_t> indices) {
    std::vector<glm::vec3> tangentSum(vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> bitangentSum(vertices.size(), glm::vec3(0.0f));

    for (size_t tri = 0; tri + 2 < indices.size(); tri += 3) {
        const uint32_t i0 = indices[tri], i1 = indices[tri + 1], i2 = indices[tri + 2];
        const Vertex& v0 = vertices[i0];
        const glm::vec3 e1 = vertices[i1].position - v0.position;
        const glm::vec3 e2 = vertices[i2].position - v0.position;
        const glm::vec2 d1 = vertices[i1].uv - v0.uv;
        const glm::vec2 d2 = vertices[i2].uv - v0.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-12f)) continue;  // uv-degenerate: tells nothing about direction
        // Solve e = dP/du * du + dP/dv * dv for both edges.
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
        const glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) / det;
        const float lu = glm::length(dPdu), lv = glm::length(dPdv);
        if (!(lu > 0.0f) || !(lv > 0.0f) || !std::isfinite(lu) || !std::isfinite(lv)) continue;
        // Weight by area so slivers do not outvote the large triangles around a vertex.
        const float area = 0.5f * glm::length(glm::cross(e1, e2));
        const glm::vec3 t = dPdu / lu * area;
        const glm::vec3 b = -dPdv / lv * area;  // image "up" is decreasing v in glTF
        for (uint32_t i : {i0, i1, i2}) {
            tangentSum[i] += t;
            bitangentSum[i] += b;
        }
    }

    for (size_t i = 0; i < vertices.size(); ++i) {
        const glm::vec3 n = vertices[i].normal;
        glm::vec4 tangent(tangentSum[i], 1.0f);
        if (!orthonormalizeTangent(n, tangent)) {
            vertices[i].tangent = glm::vec4(anyPerpendicular(n), 1.0f);
            continue;
        }
        const float handedness = glm::dot(glm::cross(n, glm::vec3(tangent)), bitangentSum[i]);
        tangent.w = handedness < 0.0f ? -1.0f : 1.0f;
        vertices[i].tangent = tangent;
    }
}

}  // namespace gbl
