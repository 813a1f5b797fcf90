// Flat normal generation and repair of unusable supplied normals.
#include "scene_normals.h"

#include <cmath>

namespace gbl {
namespace {

// Cross product of the edges: its length is twice the area, so sums weight by area.
glm::vec3 faceNormalTimesTwiceArea(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    return glm::cross(p1 - p0, p2 - p0);
}

bool usableNormal(const glm::vec3& n) {
    const float len = glm::length(n);
    return std::isfinite(len) && len > 1e-6f;
}

}  // namespace

void makeFlatNormals(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices) {
    std::vector<Vertex> flat;
    flat.reserve(indices.size());
    for (size_t tri = 0; tri + 2 < indices.size(); tri += 3) {
        const Vertex a = vertices[indices[tri]], b = vertices[indices[tri + 1]], c = vertices[indices[tri + 2]];
        const glm::vec3 n = faceNormalTimesTwiceArea(a.position, b.position, c.position);
        // A zero-area triangle covers no pixels; any unit normal keeps later maths finite.
        const glm::vec3 unit = usableNormal(n) ? glm::normalize(n) : glm::vec3(0, 0, 1);
        for (Vertex v : {a, b, c}) {
            v.normal = unit;
            flat.push_back(v);
        }
    }
    vertices = std::move(flat);
    indices.resize(vertices.size());
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
}

size_t repairNormals(std::span<Vertex> vertices, std::span<const uint32_t> indices) {
    std::vector<bool> broken(vertices.size(), false);
    size_t brokenCount = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
        if (usableNormal(vertices[i].normal)) {
            vertices[i].normal = glm::normalize(vertices[i].normal);
        } else {
            broken[i] = true;
            ++brokenCount;
        }
    }
    if (brokenCount == 0) return 0;

    std::vector<glm::vec3> sum(vertices.size(), glm::vec3(0.0f));
    for (size_t tri = 0; tri + 2 < indices.size(); tri += 3) {
        const uint32_t i0 = indices[tri], i1 = indices[tri + 1], i2 = indices[tri + 2];
        const glm::vec3 n = faceNormalTimesTwiceArea(vertices[i0].position, vertices[i1].position,
                                                     vertices[i2].position);
        for (uint32_t i : {i0, i1, i2})
            if (broken[i]) sum[i] += n;
    }
    for (size_t i = 0; i < vertices.size(); ++i) {
        if (!broken[i]) continue;
        vertices[i].normal = usableNormal(sum[i]) ? glm::normalize(sum[i]) : glm::vec3(0, 0, 1);
    }
    return brokenCount;
}

}  // namespace gbl
