#pragma once
// The glTF node hierarchy of one scene, flattened to nodes with world matrices.
#include <vector>

#include <glm/glm.hpp>

#include "scene_gltf_context.h"

namespace gbl {

struct NodeInstance {
    size_t node = 0;
    glm::mat4 world{1.0f};
};

// The file's default scene, else scene 0. Throws when there is no scene or it has no nodes.
size_t chooseScene(const GltfContext& ctx);

// Every node reachable from the scene's roots, depth first in file order, with its world
// matrix. glTF requires the hierarchy to be a set of disjoint trees; a node reached twice (a
// cycle, as in RecursiveNodes.gltf, or a node with two parents) throws instead of recursing
// forever. Iterative, so a deep chain cannot overflow the stack.
std::vector<NodeInstance> flattenScene(const GltfContext& ctx, size_t sceneIndex);

}  // namespace gbl
