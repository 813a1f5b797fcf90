// glTF cameras and punctual lights -> Camera and Light in world space.
#include "scene_gltf_camera_lights.h"

#include <algorithm>
#include <cmath>

namespace gbl {
namespace {

constexpr float kPi = 3.14159265358979f;

bool isUsableDirection(const glm::vec3& v) {
    const float len = glm::length(v);
    return std::isfinite(len) && len > 1e-12f;
}

float farthestCornerDistance(const glm::vec3& eye, const Bounds& b) {
    float farthest = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
        farthest = std::max(farthest, glm::length(corner - eye));
    }
    return farthest;
}

}  // namespace

std::optional<Camera> cameraFromNodes(const GltfContext& ctx, const std::vector<NodeInstance>& nodes,
                                      const Bounds& bounds) {
    const auto& model = ctx.model;
    for (const NodeInstance& instance : nodes) {
        const int cameraIndex = model.nodes[instance.node].camera;
        if (cameraIndex < 0) continue;
        const std::string where = describeItem("node", instance.node, model.nodes[instance.node].name);
        if (static_cast<size_t>(cameraIndex) >= model.cameras.size())
            ctx.fail(where, "refers to camera " + std::to_string(cameraIndex) + ", but the file has " +
                                std::to_string(model.cameras.size()),
                     "the file is corrupt; re-export it");
        const tinygltf::Camera& src = model.cameras[static_cast<size_t>(cameraIndex)];
        if (src.type != "perspective") continue;
        const std::string cameraWhere = describeItem("camera", static_cast<size_t>(cameraIndex), src.name);
        const auto& p = src.perspective;
        if (!(p.yfov > 0.0 && p.yfov < kPi))
            ctx.fail(cameraWhere, "yfov is " + std::to_string(p.yfov) + ", not in (0, pi)", "set a valid field of view");
        if (!(p.znear > 0.0) || !std::isfinite(p.znear))
            ctx.fail(cameraWhere, "znear must be a finite number > 0", "set a positive near plane");
        if (p.zfar != 0.0 && !(p.zfar > p.znear && std::isfinite(p.zfar)))
            ctx.fail(cameraWhere, "zfar must be greater than znear", "fix the far plane or remove it");

        // glTF cameras look down their node's -Z with +Y up.
        const glm::vec3 eye(instance.world[3]);
        const glm::vec3 forward(instance.world * glm::vec4(0, 0, -1, 0));
        const glm::vec3 up(instance.world * glm::vec4(0, 1, 0, 0));
        if (!isUsableDirection(forward) || !isUsableDirection(up) || !std::isfinite(eye.x + eye.y + eye.z))
            ctx.fail(where, "the camera's world transform is degenerate (zero scale)", "fix the node's transform");
        Camera camera;
        camera.position = eye;
        camera.target = eye + glm::normalize(forward);
        camera.up = glm::normalize(up);
        camera.yFovRadians = static_cast<float>(p.yfov);
        camera.zNear = static_cast<float>(p.znear);
        camera.zFar = p.zfar != 0.0 ? static_cast<float>(p.zfar)
                                    : std::max(2.0f * farthestCornerDistance(eye, bounds), 2.0f * camera.zNear);
        camera.fromFile = true;
        return camera;
    }
    return std::nullopt;
}

std::vector<Light> lightsFromNodes(const GltfContext& ctx, const std::vector<NodeInstance>& nodes) {
    const auto& model = ctx.model;
    std::vector<Light> lights;
    for (const NodeInstance& instance : nodes) {
        const tinygltf::Node& node = model.nodes[instance.node];
        const auto ext = node.extensions.find("KHR_lights_punctual");
        if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light")) continue;
        const std::string where = describeItem("node", instance.node, node.name) + " KHR_lights_punctual";
        const tinygltf::Value& ref = ext->second.Get("light");
        const int index = ref.IsNumber() ? ref.GetNumberAsInt() : -1;
        if (index < 0 || static_cast<size_t>(index) >= model.lights.size())
            ctx.fail(where, "refers to light " + std::to_string(index) + ", but the file has " +
                                std::to_string(model.lights.size()),
                     "the file is corrupt; re-export it");
        const tinygltf::Light& src = model.lights[static_cast<size_t>(index)];
        const std::string lightWhere = describeItem("light", static_cast<size_t>(index), src.name);

        Light light;
        if (src.type == "directional") light.type = LightType::Directional;
        else if (src.type == "point") light.type = LightType::Point;
        else if (src.type == "spot") light.type = LightType::Spot;
        else ctx.fail(lightWhere, "has type '" + src.type + "'", "use directional, point or spot");
        if (src.color.size() == 3)
            light.color = glm::max(glm::vec3(float(src.color[0]), float(src.color[1]), float(src.color[2])), 0.0f);
        light.intensity = std::isfinite(src.intensity) ? std::max(0.0f, float(src.intensity)) : 1.0f;
        light.range = std::isfinite(src.range) && src.range > 0.0 ? float(src.range) : 0.0f;
        light.innerConeAngle = float(src.spot.innerConeAngle);
        light.outerConeAngle = float(src.spot.outerConeAngle);
        light.position = glm::vec3(instance.world[3]);
        const glm::vec3 direction(instance.world * glm::vec4(0, 0, -1, 0));
        if (light.type != LightType::Point && !isUsableDirection(direction))
            ctx.fail(where, "the light's world transform is degenerate (zero scale)", "fix the node's transform");
        if (isUsableDirection(direction)) light.direction = glm::normalize(direction);
        lights.push_back(light);
    }
    return lights;
}

}  // namespace gbl
