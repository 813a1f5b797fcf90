#pragma once
// The two inputs every command starts from: a scene (a glTF file or the built-in one) and an
// environment (an .hdr/.exr or the built-in sky). Both are loaded and validated before any
// Vulkan work, so bad input fails fast with nothing written.
#include <string>

#include "environment_map.h"
#include "scene.h"

namespace gbl {

struct SceneInputs {
    Scene scene;
    EnvironmentMap environment;
};

// Empty paths pick the built-in scene / sky. A scene without a camera is framed for `aspect`.
// `gltf` says where the scene's buffers and images may come from (--allow-outside-scene).
SceneInputs loadSceneInputs(const std::string& scenePath, const std::string& environmentPath, float aspect,
                            const GltfLoadOptions& gltf = {});

}  // namespace gbl
