// Scene choice, node transforms (matrix or TRS) and hierarchy traversal.
#include "scene_gltf_nodes.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace gbl {
namespace {

constexpr const char* kFixHierarchy = "the node hierarchy must be a tree; fix it in the source file and re-export";

bool finite(const std::vector<double>& values) {
    for (double v : values)
        if (!std::isfinite(v)) return false;
    return true;
}

// glTF: a node has either `matrix` (column-major) or translation/rotation/scale, T * R * S.
glm::mat4 localTransform(const GltfContext& ctx, size_t index) {
    const tinygltf::Node& node = ctx.model.nodes[index];
    const std::string where = describeItem("node", index, node.name);
    auto check = [&](const std::vector<double>& values, size_t wanted, const char* what) {
        if (values.empty()) return false;
        if (values.size() != wanted || !finite(values))
            ctx.fail(where, std::string(what) + " must be " + std::to_string(wanted) + " finite numbers",
                     "fix the node's transform and re-export");
        return true;
    };
    if (check(node.matrix, 16, "matrix")) {
        glm::mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = static_cast<float>(node.matrix[size_t(c * 4 + r)]);
        return m;
    }
    glm::mat4 m(1.0f);
    if (check(node.translation, 3, "translation"))
        m[3] = glm::vec4(float(node.translation[0]), float(node.translation[1]), float(node.translation[2]), 1.0f);
    if (check(node.rotation, 4, "rotation")) {
        // glTF stores x, y, z, w; glm::quat's constructor takes w first. Normalised because
        // exporters write quaternions rounded to a few digits.
        const glm::quat q = glm::normalize(glm::quat(float(node.rotation[3]), float(node.rotation[0]),
                                                     float(node.rotation[1]), float(node.rotation[2])));
        if (!std::isfinite(q.w)) ctx.fail(where, "rotation is a zero quaternion", "fix the node's rotation");
        m = m * glm::mat4_cast(q);
    }
    if (check(node.scale, 3, "scale"))
        m = m * glm::mat4(glm::vec4(float(node.scale[0]), 0, 0, 0), glm::vec4(0, float(node.scale[1]), 0, 0),
                          glm::vec4(0, 0, float(node.scale[2]), 0), glm::vec4(0, 0, 0, 1));
    return m;
}

}  // namespace

size_t chooseScene(const GltfContext& ctx) {
    const auto& model = ctx.model;
    if (model.scenes.empty())
        ctx.fail("scenes", "the file has no scenes, so there is nothing to render",
                 "export the file with a scene that contains the objects");
    size_t index = 0;
    if (model.defaultScene >= 0) {
        if (static_cast<size_t>(model.defaultScene) >= model.scenes.size())
            ctx.fail("scene", "the default scene is " + std::to_string(model.defaultScene) + ", but the file has " +
                                  std::to_string(model.scenes.size()) + " scene(s)",
                     "fix the top-level \"scene\" index");
        index = static_cast<size_t>(model.defaultScene);
    }
    if (model.scenes[index].nodes.empty())
        ctx.fail(describeItem("scene", index, model.scenes[index].name), "the scene has no nodes, so there is nothing to render",
                 "export the file with the objects placed in the scene");
    return index;
}

std::vector<NodeInstance> flattenScene(const GltfContext& ctx, size_t sceneIndex) {
    const auto& model = ctx.model;
    const tinygltf::Scene& scene = model.scenes[sceneIndex];
    std::vector<bool> reached(model.nodes.size(), false);
    std::vector<NodeInstance> out;

    struct Pending {
        int node;
        glm::mat4 parentWorld;
        std::string parent;  // for the error message
    };
    std::vector<Pending> stack;
    const std::string sceneName = describeItem("scene", sceneIndex, scene.name);
    for (auto it = scene.nodes.rbegin(); it != scene.nodes.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f), sceneName});

    while (!stack.empty()) {
        const Pending item = std::move(stack.back());
        stack.pop_back();
        if (item.node < 0 || static_cast<size_t>(item.node) >= model.nodes.size())
            ctx.fail(item.parent, "refers to node " + std::to_string(item.node) + ", but the file has " +
                                      std::to_string(model.nodes.size()),
                     "the file is corrupt; re-export it");
        const size_t index = static_cast<size_t>(item.node);
        const std::string name = describeItem("node", index, model.nodes[index].name);
        if (reached[index])
            ctx.fail(name, "is reached a second time (through " + item.parent + "): the hierarchy has a cycle or a node with two parents",
                     kFixHierarchy);
        reached[index] = true;
        const glm::mat4 world = item.parentWorld * localTransform(ctx, index);
        out.push_back({index, world});
        const auto& children = model.nodes[index].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, world, name});
    }
    return out;
}

}  // namespace gbl
