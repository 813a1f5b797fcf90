#include "scene_inputs.h"

#include "procedural_sky.h"

namespace gbl {

SceneInputs loadSceneInputs(const std::string& scenePath, const std::string& environmentPath, float aspect) {
    SceneInputs in;
    in.scene = scenePath.empty() ? makeDefaultScene() : loadGltfScene(scenePath);
    if (!in.scene.camera.fromFile && !scenePath.empty()) in.scene.camera = frameBounds(in.scene.bounds, aspect);
    in.environment = environmentPath.empty() ? makeProceduralSky() : loadEnvironmentMap(environmentPath);
    return in;
}

}  // namespace gbl
