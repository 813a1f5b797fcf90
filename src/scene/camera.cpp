// Default framing for scenes without a camera of their own.
#include <algorithm>
#include <cmath>
#include <limits>

#include "scene.h"

namespace gbl {

namespace {

// Each axis of the frame keeps this share free around the points' projection (5% of the
// half-extent), so silhouettes do not touch the image border.
constexpr float kFrameMargin = 1.05f;

// From the front (+Z), a little above, so tops of objects read as 3D.
glm::vec3 defaultTowardCamera() { return glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f)); }

}  // namespace

Camera fitPointsInView(const std::vector<glm::vec3>& points, glm::vec3 towardCamera, glm::vec3 up, float aspect,
                       float yFovRadians) {
    Camera camera;
    camera.yFovRadians = yFovRadians;
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) aspect = 1.0f;
    if (!(glm::length(towardCamera) > 0.0f)) towardCamera = defaultTowardCamera();
    const glm::vec3 forward = -glm::normalize(towardCamera);
    glm::vec3 right = glm::cross(forward, up);
    if (glm::length(right) < 1e-6f) right = glm::cross(forward, std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    right = glm::normalize(right);
    const glm::vec3 upOrtho = glm::cross(right, forward);

    // In the camera's basis about the points' first point, x right, y up, z forward (depth). A
    // camera at origin + cx right + cy up - t forward sees point p when |x - cx| <= tx (z + t) and
    // |y - cy| <= ty (z + t), tx and ty the frame's half-extents per unit depth. Per axis that is
    // max(x - tx z) - tx t <= cx <= min(x + tx z) + tx t: the closest camera is
    // t = (max(x - tx z) - min(x + tx z)) / (2 tx), with cx midway, the tightest fit of a
    // perspective frustum to a point set (the projected extent touches the margin on the binding
    // axis; the other is then centred in the image).
    const float ty = std::tan(0.5f * yFovRadians) / kFrameMargin;
    const float tx = std::tan(0.5f * yFovRadians) * aspect / kFrameMargin;
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const glm::vec3 origin = points.empty() ? glm::vec3(0.0f) : points.front();
    float loX = kInf, hiX = -kInf, loY = kInf, hiY = -kInf, minZ = kInf, maxZ = -kInf, extent = 0.0f;
    for (const glm::vec3& p : points) {
        const glm::vec3 d = p - origin;
        const float x = glm::dot(d, right), y = glm::dot(d, upOrtho), z = glm::dot(d, forward);
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
        hiX = std::max(hiX, x - tx * z);
        loX = std::min(loX, x + tx * z);
        hiY = std::max(hiY, y - ty * z);
        loY = std::min(loY, y + ty * z);
        minZ = std::min(minZ, z);
        maxZ = std::max(maxZ, z);
        extent = std::max(extent, glm::length(d));
    }
    if (!(minZ <= maxZ)) {  // no finite point: a unit view of the origin
        loX = hiX = loY = hiY = minZ = maxZ = 0.0f;
    }
    if (!(extent > 0.0f)) extent = 1.0f;  // a single point still gets a usable camera
    const float t = std::max({(hiX - loX) / (2.0f * tx), (hiY - loY) / (2.0f * ty), 0.05f * extent - minZ});
    // Within each axis's feasible interval [hi - t tan, lo + t tan] (a single point on the binding
    // axis), the offset that centres the projected extent in the image: max((x - c) / depth) +
    // min((x - c) / depth) falls as c grows, so bisection finds its zero.
    auto centre = [&](const glm::vec3& axis, float hi, float lo, float tanHalf) {
        float a = hi - tanHalf * t, b = lo + tanHalf * t;
        if (!(a < b)) return 0.5f * (a + b);
        for (int i = 0; i < 40; ++i) {
            const float c = 0.5f * (a + b);
            float most = -kInf, least = kInf;
            for (const glm::vec3& p : points) {
                const glm::vec3 d = p - origin;
                const float depth = glm::dot(d, forward) + t;
                if (!(depth > 0.0f) || !std::isfinite(depth)) continue;
                const float v = (glm::dot(d, axis) - c) / depth;
                most = std::max(most, v);
                least = std::min(least, v);
            }
            if (!(most >= least)) break;
            (most + least > 0.0f ? a : b) = c;
        }
        return 0.5f * (a + b);
    };
    const float cx = centre(right, hiX, loX, tx), cy = centre(upOrtho, hiY, loY, ty);
    const glm::vec3 lateral = origin + cx * right + cy * upOrtho;
    camera.position = lateral - t * forward;
    // The target lies on the view axis at the depth of the points' middle.
    camera.target = lateral + 0.5f * (minZ + maxZ) * forward;
    if (!(glm::length(camera.target - camera.position) > 0.0f)) camera.target = camera.position + forward;
    camera.up = upOrtho;
    // Near and far hug the points, so depth precision scales with the scene: a 6 cm model gets
    // a millimetre-scale near plane, a 100 m one a metre-scale one.
    const float nearest = minZ + t, farthest = maxZ + t;
    camera.zNear = std::max(nearest, 1e-3f * farthest) * 0.5f;
    camera.zFar = farthest * 2.0f;
    camera.fromFile = false;
    camera.framed = true;
    return camera;
}

Camera frameBounds(const Bounds& bounds, float aspect) {
    std::vector<glm::vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back(i & 1 ? bounds.max.x : bounds.min.x, i & 2 ? bounds.max.y : bounds.min.y,
                             i & 4 ? bounds.max.z : bounds.min.z);
    return fitPointsInView(corners, defaultTowardCamera(), glm::vec3(0, 1, 0), aspect, Camera{}.yFovRadians);
}

std::vector<glm::vec3> drawnPoints(const Scene& scene) {
    std::vector<glm::vec3> points;
    for (const Draw& draw : scene.draws)
        for (uint32_t i = 0; i < draw.indexCount; ++i) {
            const uint32_t v = scene.indices[draw.firstIndex + i] + static_cast<uint32_t>(draw.vertexOffset);
            points.push_back(glm::vec3(draw.model * glm::vec4(scene.vertices[v].position, 1.0f)));
        }
    return points;
}

Camera frameScene(const Scene& scene, float aspect) {
    const std::vector<glm::vec3> points = drawnPoints(scene);
    if (points.empty()) return frameBounds(scene.bounds, aspect);
    return fitPointsInView(points, defaultTowardCamera(), glm::vec3(0, 1, 0), aspect, Camera{}.yFovRadians);
}

}  // namespace gbl
