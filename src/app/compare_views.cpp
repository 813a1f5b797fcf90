#include "compare_views.h"
#include "compare_temporal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer.h"
#include "view_stats.h"

namespace gbl::compare {


std::vector<CompareView> placedViews(const Scene& scene, const std::vector<Camera>& cameras) {
    std::vector<CompareView> views;
    const glm::vec3 centre = 0.5f * (scene.bounds.min + scene.bounds.max);
    float radius = 0.5f * glm::length(scene.bounds.max - scene.bounds.min);
    if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;
    for (size_t i = 0; i < cameras.size(); ++i) {
        Camera c = cameras[i];
        const float distance = glm::length(c.position - centre);
        c.zNear = std::max(distance - radius, 1e-3f * std::max(distance, radius)) * 0.5f;
        c.zFar = (distance + radius) * 2.0f;
        char buf[200];
        std::snprintf(buf, sizeof(buf), "suite camera %d: position (%g, %g, %g), target (%g, %g, %g)", int(i),
                      double(c.position.x), double(c.position.y), double(c.position.z), double(c.target.x),
                      double(c.target.y), double(c.target.z));
        views.push_back({c, buf});
    }
    return views;
}

std::vector<CompareView> compareViews(const Scene& scene, int count, float aspect) {
    std::vector<CompareView> views;
    const Camera& base = scene.camera;
    views.push_back({base, "scene camera"});
    if (count <= 1) return views;
    const glm::vec3 up = glm::normalize(base.up);
    const glm::vec3 centre = base.fromFile || base.framed ? 0.5f * (scene.bounds.min + scene.bounds.max) : base.target;
    float distance = glm::length(base.position - centre);
    if (!(distance > 0.0f) || !std::isfinite(distance)) distance = 1.0f;
    // The scene camera's horizontal direction from the centre (any horizontal one when it looks straight down).
    glm::vec3 from = base.position - centre;
    from -= up * glm::dot(from, up);
    if (glm::length(from) < 1e-6f * distance) from = std::abs(up.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    from = glm::normalize(from - up * glm::dot(from, up));
    auto place = [&](float azimuthDeg, float elevationDeg, glm::vec3 target) {
        const glm::vec3 h = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(azimuthDeg), up) * glm::vec4(from, 0.0f));
        const float e = glm::radians(elevationDeg);
        Camera c = base;
        c.position = target + distance * (std::cos(e) * h + std::sin(e) * up);
        c.target = target;
        c.up = up;
        c.fromFile = false;
        return c;
    };
    // A framed object is fitted from each view's direction: the orbit's distance would leave a
    // tall object small when seen from above.
    const std::vector<glm::vec3> points = base.framed ? drawnPoints(scene) : std::vector<glm::vec3>{};
    auto fitted = [&](Camera c) {
        if (!base.framed || points.empty()) return c;
        return fitPointsInView(points, c.position - c.target, up, aspect, base.yFovRadians);
    };
    const bool grazing = count >= 3;
    const int orbits = count - 1 - (grazing ? 1 : 0);
    char buf[160];
    for (int k = 0; k < orbits; ++k) {
        const float azimuth = 40.0f + 120.0f * float(k);
        std::snprintf(buf, sizeof(buf), "orbit about the scene's centre: azimuth %+.0f deg, elevation 35 deg",
                      double(azimuth));
        views.push_back({fitted(place(azimuth, 35.0f, centre)), buf});
    }
    if (grazing) {
        // The ground: the plane through the bounds' lowest point along up.
        const glm::vec3 corners[2] = {scene.bounds.min, scene.bounds.max};
        float low = std::numeric_limits<float>::max();
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 p(corners[i & 1].x, corners[(i >> 1) & 1].y, corners[(i >> 2) & 1].z);
            low = std::min(low, glm::dot(p, up));
        }
        const glm::vec3 foot = centre - up * (glm::dot(centre, up) - low);
        // A framed object (a glTF without a camera) has no ground to graze: the low view looks at the
        // centre of its bounds, then is fitted to it like the others.
        if (base.framed)
            views.push_back({fitted(place(-30.0f, 6.0f, centre)), "low view of the object: 6 deg above its centre, azimuth -30 deg"});
        else
            views.push_back({place(-30.0f, 6.0f, foot), "grazing view of the ground: 6 deg above it, azimuth -30 deg"});
    }
    return views;
}

void finishViews(RunReport& run, const std::vector<std::string>& viewNotMeasured) {
    if (run.views.size() > 1) averageViews(run);
    else run.views.clear();
    finishSingleFrameViews(run);
    size_t left = 0;
    for (size_t v = 0; v < viewNotMeasured.size(); ++v) {
        if (viewNotMeasured[v].empty()) continue;
        run.notMeasured += (run.notMeasured.empty() ? "" : "; ") + ("view " + std::to_string(v) + ": " + viewNotMeasured[v]);
        ++left;
    }
    if (left && left == viewNotMeasured.size() && run.status == RunStatus::Ok) {
        clearMeasurements(run);
        run.status = RunStatus::NotMeasured;
    }
}

void clearMeasurements(RunReport& run) {
    run.attributes = {};
    run.image.reset();
    if (run.singleFrame) {
        run.singleFrame->attributes = {};
        run.singleFrame->image.reset();
    }
}

std::vector<FigureBall> findFigureBalls(const Scene& scene, uint32_t width, uint32_t height) {
    std::vector<std::pair<float, FigureBall>> metals, dielectrics;
    const CameraMatrices cam = computeCameraMatrices(scene.camera, float(width) / float(height), false);
    for (const Draw& d : scene.draws) {
        if (d.material < 0 || size_t(d.material) >= scene.materials.size()) continue;
        const std::string& name = scene.materials[size_t(d.material)].name;
        const bool metal = name.rfind("metal roughness", 0) == 0;
        if (!metal && name.rfind("dielectric roughness", 0) != 0) continue;
        const glm::vec3 centre(d.model[3]);
        float radius = 0.0f;
        for (uint32_t k = 0; k < d.indexCount; ++k) {
            const Vertex& v = scene.vertices[size_t(d.vertexOffset) + scene.indices[d.firstIndex + k]];
            radius = std::max(radius, glm::length(glm::vec3(d.model * glm::vec4(v.position, 1.0f)) - centre));
        }
        const glm::vec4 clip = cam.viewProj * glm::vec4(centre, 1.0f);
        if (clip.w <= 0.0f) continue;
        const float px = (clip.x / clip.w * 0.5f + 0.5f) * float(width);
        const float py = (clip.y / clip.w * 0.5f + 0.5f) * float(height);
        const float dist = glm::length(centre - scene.camera.position);
        const float rpx = radius / (dist * std::tan(scene.camera.yFovRadians * 0.5f)) * 0.5f * float(height);
        FigureBall b;
        b.size = std::max(4, int(std::ceil(2.2f * rpx)));
        b.x = int(std::floor(px - 0.5f * float(b.size)));
        b.y = int(std::floor(py - 0.5f * float(b.size)));
        // The ball's pixels: the camera ray through each crop pixel's centre hits the sphere.
        // radius is the farthest vertex; the tessellated silhouette lies up to ~1.5% inside it.
        const float inscribed = 0.985f * radius;
        const glm::mat4 inverseViewProj = glm::inverse(cam.viewProj);
        b.mask.assign(size_t(b.size) * size_t(b.size), 0);
        for (int my = 0; my < b.size; ++my)
            for (int mx = 0; mx < b.size; ++mx) {
                const float nx = (float(b.x + mx) + 0.5f) / float(width) * 2.0f - 1.0f;
                const float ny = (float(b.y + my) + 0.5f) / float(height) * 2.0f - 1.0f;
                const glm::vec4 a = inverseViewProj * glm::vec4(nx, ny, 0.0f, 1.0f);
                const glm::vec4 e = inverseViewProj * glm::vec4(nx, ny, 1.0f, 1.0f);
                const glm::vec3 origin = glm::vec3(a) / a.w;
                const glm::vec3 dir = glm::normalize(glm::vec3(e) / e.w - origin);
                const glm::vec3 oc = centre - origin;
                const float along = glm::dot(oc, dir);
                b.mask[size_t(my) * size_t(b.size) + size_t(mx)] =
                    along > 0.0f && glm::dot(oc, oc) - along * along <= inscribed * inscribed ? 1 : 0;
            }
        b.metal = metal;
        const float r = scene.materials[size_t(d.material)].roughnessFactor;
        char label[48];
        std::snprintf(label, sizeof(label), "%s r=%.2f", metal ? "metal" : "dielectric", double(r));
        b.label = label;
        (metal ? metals : dielectrics).push_back({centre.x, b});
    }
    std::vector<FigureBall> balls;
    for (auto* group : {&metals, &dielectrics}) {
        std::sort(group->begin(), group->end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [x, b] : *group) balls.push_back(b);
    }
    return balls;
}


}  // namespace gbl::compare
