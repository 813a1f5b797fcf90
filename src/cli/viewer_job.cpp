// The Sample Viewer job file and the coverage mask (viewer_job.h).
#include "viewer_job.h"

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "file_io.h"

namespace gbl {

namespace {
nlohmann::json vec3Json(glm::vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); }

const char* lightTypeName(LightType t) {
    switch (t) {
        case LightType::Point: return "point";
        case LightType::Spot: return "spot";
        default: return "directional";
    }
}
}  // namespace

std::string viewerJobJson(const ViewerJob& job, const Scene& scene) {
    // renderer.cpp computeCameraMatrices: view = lookAt(position, target, up) (right-handed, the
    // camera looking down its -Z with +Y up: the glTF camera convention), so its inverse is the
    // camera's node matrix.
    const glm::mat4 cameraToWorld = glm::inverse(glm::lookAt(job.camera.position, job.camera.target, job.camera.up));
    nlohmann::json matrix = nlohmann::json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) matrix.push_back(cameraToWorld[c][r]);  // column-major
    nlohmann::json lights = nlohmann::json::array();
    for (const Light& l : scene.lights) {
        nlohmann::json j = {{"type", lightTypeName(l.type)},
                            {"color", vec3Json(l.color)},
                            {"intensity", l.intensity},
                            {"position", vec3Json(l.position)},
                            {"direction", vec3Json(l.direction)},
                            {"range", l.range}};
        if (l.type == LightType::Spot) {
            j["inner_cone_angle"] = l.innerConeAngle;
            j["outer_cone_angle"] = l.outerConeAngle;
        }
        lights.push_back(j);
    }
    // The environment's orientation: gbufferlab reads an equirect texel at u = 0.5 + atan2(x, -z) / 2 pi
    // (shaders/environment_map.glsl directionToEquirectUv), the viewer at u = 0.5 + atan2(z', x') / 2 pi
    // of d' = RotY(rotation) d (gltf-viewer.module.js:19227 panoramaToCubeMap dirToUV, :3808
    // u_EnvRotation, :3779 rotateY): a rotation of -90 degrees makes x' = -z, z' = x, the same texel.
    // Measured on a metal sphere (docs/crosscheck.md): 8x8 block means 0.43 apart at -90, 6.5 at +90.
    nlohmann::json ibl = nullptr;
    if (job.ibl) ibl = {{"environment", job.environment}, {"rotation_degrees", -90.0}, {"intensity", 1.0}};
    const nlohmann::json out = {{"gltf", job.gltf},
                                {"width", job.width},
                                {"height", job.height},
                                {"camera",
                                 {{"camera_to_world", matrix},
                                  {"yfov", job.camera.yFovRadians},
                                  {"znear", job.camera.zNear},
                                  {"zfar", job.camera.zFar}}},
                                {"lights", lights},
                                {"exposure", job.exposure},
                                {"ibl", ibl},
                                {"output", job.output}};
    return out.dump(2) + "\n";
}

void writeCoverageMask(const std::string& path, const Image& hdr, const std::vector<uint8_t>& excluded) {
    std::string pgm = "P5\n" + std::to_string(hdr.width) + " " + std::to_string(hdr.height) + "\n255\n";
    pgm.reserve(pgm.size() + size_t(hdr.width) * size_t(hdr.height));
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x) {
            const bool out = !excluded.empty() && excluded[size_t(y) * size_t(hdr.width) + size_t(x)] != 0;
            pgm.push_back(hdr.at(x, y, 3) > 0.5f && !out ? char(255) : char(0));
        }
    writeFileAtomic(path, pgm);
}

}  // namespace gbl
