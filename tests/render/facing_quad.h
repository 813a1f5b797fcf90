#pragma once
// The smallest scenes the render tests light: a 2 x 2 quad in the z = 0 plane facing a camera at
// (0, 0, 3), uv (0, 0) at its top left, one material sampling texture 0 as its base colour, the
// default sun; and a constant white environment with small IBL maps. srgb_texture_test and
// layers_render_test read single texels and transformed uvs off it.
#include <array>
#include <string>

#include "environment_map.h"
#include "ibl_precompute.h"
#include "scene.h"

namespace gbl::test {

// uv1: the second texture coordinate set at the corners top left, top right, bottom right,
// bottom left (zero when a test does not read TEXCOORD_1).
inline Scene facingQuad(const std::string& source, const std::array<glm::vec2, 4>& uv1 = {}) {
    Scene scene;
    scene.source = source;
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const glm::vec4 t(1.0f, 0.0f, 0.0f, 1.0f);
    scene.vertices = {{{-1, 1, 0}, n, t, {0, 0}, uv1[0]},
                      {{1, 1, 0}, n, t, {1, 0}, uv1[1]},
                      {{1, -1, 0}, n, t, {1, 1}, uv1[2]},
                      {{-1, -1, 0}, n, t, {0, 1}, uv1[3]}};
    scene.indices = {0, 3, 2, 0, 2, 1};
    Draw draw;
    draw.indexCount = 6;
    scene.draws.push_back(draw);
    scene.camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
    scene.camera.target = glm::vec3(0.0f);
    scene.lights.push_back(defaultSun());
    Material m;
    m.baseColorTexture = 0;
    scene.materials = {m};
    return scene;
}

inline EnvironmentMap constantEnvironment(float value) {
    EnvironmentMap env;
    env.source = "constant";
    env.image = Image(64, 32, 3, value);
    return env;
}

// The image-based light of `env` at 32^2 cube faces: enough for a constant environment.
inline IblMaps smallIblMaps(const VulkanContext& ctx, const EnvironmentMap& env) {
    IblSettings is;
    is.sourceFaceSize = 32;
    is.prefilteredFaceSize = 32;
    return computeIblMaps(ctx, env, is);
}

}  // namespace gbl::test
