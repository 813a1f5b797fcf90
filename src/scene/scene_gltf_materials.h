#pragma once
// glTF metallic-roughness materials (+ KHR_materials_specular) -> Scene::materials/textures.
#include "scene.h"
#include "scene_gltf_context.h"

namespace gbl {

// Appends one Material per glTF material, in file order (so glTF material i is
// scene.materials[i]), and the textures they use to scene.textures.
void loadMaterials(const GltfContext& ctx, Scene& scene);

// The material glTF prescribes for primitives without one: every property at its default
// (white, metallic 1, roughness 1, no textures).
Material defaultGltfMaterial();

}  // namespace gbl
