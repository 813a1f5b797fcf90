#pragma once
// Shared by the IBL tests on lavapipe (ibl_gpu_test.cpp: the pre-computation, the modes, the cache;
// ibl_ground_truth_test.cpp: the converged ground truth): their fixture, the constant environment
// (a white furnace when value = 1), small IBL maps, the furnace's scene and the specular-only
// render settings.
#include <cstdint>

#include "environment_map.h"
#include "ibl_precompute.h"
#include "image.h"
#include "renderer.h"
#include "vk_test_support.h"

namespace gbl::ibl_test {

inline EnvironmentMap constantEnvironment(float value) {
    EnvironmentMap env;
    env.source = "constant";
    env.image = Image(64, 32, 3, value);
    return env;
}

// IBL settings with a pre-filtered cube of face size `prefiltered` and a source cube of `source`
// (0: the default, from the map's width).
inline IblSettings iblSizes(uint32_t prefiltered, uint32_t source = 0) {
    IblSettings s;
    if (source) s.sourceFaceSize = source;
    s.prefilteredFaceSize = prefiltered;
    return s;
}

// `scene` lit by the environment alone, every material a white metal (F0 = 1) without emission.
inline Scene furnaceScene(Scene scene) {
    scene.lights.clear();
    for (Material& m : scene.materials) {
        m.baseColorFactor = glm::vec4(1.0f);
        m.metallicFactor = 1.0f;
        m.emissiveFactor = glm::vec3(0.0f);
    }
    return scene;
}

// A width x height render of the specular IBL alone (no diffuse IBL), in `mode`.
inline RenderSettings specularOnly(uint32_t width, uint32_t height, IblMode mode) {
    RenderSettings rs = test::frame(width, height);
    rs.diffuseIbl = false;
    rs.specularIbl = mode;
    return rs;
}

class IblGpuTest : public test::VulkanTest {};

}  // namespace gbl::ibl_test
