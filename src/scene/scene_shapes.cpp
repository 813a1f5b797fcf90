// UV sphere and ground plane generation.
#include "scene_shapes.h"

#include <cmath>

namespace gbl {

ShapeMesh makeUvSphere(float radius, int segments, int rings) {
    constexpr float kPi = 3.14159265358979f;
    ShapeMesh mesh;
    const uint32_t columns = static_cast<uint32_t>(segments) + 1;  // the seam column is duplicated for uv
    for (int ring = 0; ring <= rings; ++ring) {
        const float v = float(ring) / float(rings);
        const float theta = v * kPi;  // from +Y
        for (int seg = 0; seg <= segments; ++seg) {
            const float u = float(seg) / float(segments);
            const float phi = u * 2.0f * kPi;
            Vertex vertex;
            const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            vertex.normal = n;
            vertex.position = n * radius;
            // dP/du is (cos phi, 0, -sin phi) scaled by sin theta; using the unscaled direction
            // keeps the tangent defined at the poles too.
            vertex.tangent = glm::vec4(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);
            vertex.uv = glm::vec2(u, v);
            mesh.vertices.push_back(vertex);
        }
    }
    for (uint32_t ring = 0; ring < uint32_t(rings); ++ring) {
        for (uint32_t seg = 0; seg < uint32_t(segments); ++seg) {
            const uint32_t a = ring * columns + seg;  // upper left as seen from outside
            const uint32_t b = a + columns;           // lower left
            const uint32_t c = a + 1, d = b + 1;      // upper right, lower right
            if (ring != uint32_t(rings) - 1) mesh.indices.insert(mesh.indices.end(), {a, b, d});
            if (ring != 0) mesh.indices.insert(mesh.indices.end(), {a, d, c});
        }
    }
    return mesh;
}

ShapeMesh makeGroundPlane(float size, int cells) {
    ShapeMesh mesh;
    const uint32_t columns = static_cast<uint32_t>(cells) + 1;
    for (int row = 0; row <= cells; ++row) {
        for (int col = 0; col <= cells; ++col) {
            Vertex vertex;
            vertex.uv = glm::vec2(float(col) / float(cells), float(row) / float(cells));
            vertex.position = glm::vec3((vertex.uv.x - 0.5f) * size, 0.0f, (vertex.uv.y - 0.5f) * size);
            vertex.normal = glm::vec3(0, 1, 0);
            // T = +X (increasing u); B = cross(N, T) = -Z, which is decreasing v: w = +1.
            vertex.tangent = glm::vec4(1, 0, 0, 1);
            mesh.vertices.push_back(vertex);
        }
    }
    for (uint32_t row = 0; row < uint32_t(cells); ++row) {
        for (uint32_t col = 0; col < uint32_t(cells); ++col) {
            const uint32_t p00 = row * columns + col, p10 = p00 + 1;  // p10: +X
            const uint32_t p01 = p00 + columns, p11 = p01 + 1;        // p01: +Z
            mesh.indices.insert(mesh.indices.end(), {p00, p01, p11, p00, p11, p10});
        }
    }
    return mesh;
}

}  // namespace gbl
