#pragma once
// Cameras and KHR_lights_punctual lights placed by glTF nodes, in world space.
#include <optional>
#include <vector>

#include "scene.h"
#include "scene_gltf_context.h"
#include "scene_gltf_nodes.h"

namespace gbl {

// The first node (in traversal order) with a perspective camera. Orthographic cameras are
// skipped: Camera has no orthographic mode. A missing zfar (glTF: infinite projection) becomes
// twice the distance to the farthest corner of `bounds`, so depth stays finite.
std::optional<Camera> cameraFromNodes(const GltfContext& ctx, const std::vector<NodeInstance>& nodes,
                                      const Bounds& bounds);

// Every KHR_lights_punctual light a node places, positioned and aimed by the node's world
// matrix (lights shine down the node's -Z).
std::vector<Light> lightsFromNodes(const GltfContext& ctx, const std::vector<NodeInstance>& nodes);

}  // namespace gbl
