#include "scene_inputs.h"

#include "procedural_sky.h"

namespace gbl {

SceneInputs loadSceneInputs(const std::string& scenePath, const std::string& environmentPath, float aspect,
                            const GltfLoadOptions& gltf) {
    SceneInputs in;
    // A file the user named is read before anything is built in code, so bad input fails fast.
    if (!environmentPath.empty()) in.environment = loadEnvironmentMap(environmentPath);
    in.scene = scenePath.empty() ? makeDefaultScene() : loadGltfScene(scenePath, gltf);
    if (!in.scene.camera.fromFile && !scenePath.empty()) in.scene.camera = frameScene(in.scene, aspect);
    if (environmentPath.empty()) in.environment = makeProceduralSky();
    return in;
}

}  // namespace gbl
